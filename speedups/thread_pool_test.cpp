#include "speedups/thread_pool.h"

#include <gtest/gtest.h>
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace povrayfc {
namespace {

// A function that sets `finished` after a while, long enough that returning early shows.
std::function<void()> SlowFunction(std::atomic<bool> &finished) {
    return [&finished] {
        std::this_thread::sleep_for(std::chrono::milliseconds(40));
        finished = true;
    };
}

TEST(PooledThread, JoinWaitsForTheFunction) {
    std::atomic<bool> finished{false};
    auto t = PooledThread::Start(SlowFunction(finished), 0);
    t->Join();
    EXPECT_TRUE(finished);
    t->Join();  // again: returns at once
}

TEST(PooledThread, AFinishedThreadRunsTheNextFunction) {
    pthread_t first{}, second{};
    auto a = PooledThread::Start([&] { first = pthread_self(); }, 1 << 20);
    a->Join();
    const std::size_t created = PooledThread::ThreadsCreated();
    auto b = PooledThread::Start([&] { second = pthread_self(); }, 1 << 20);
    b->Join();
    EXPECT_EQ(PooledThread::ThreadsCreated(), created);
    EXPECT_TRUE(pthread_equal(first, second));
    EXPECT_NE(first, pthread_self());
}

TEST(PooledThread, ConcurrentFunctionsGetThreadsOfTheirOwn) {
    // Four functions that each wait for all four to be running: on fewer threads they
    // would wait forever (the test's timeout would say so).
    std::atomic<int> running{0};
    std::vector<std::unique_ptr<PooledThread>> threads;
    for (int i = 0; i < 4; ++i)
        threads.push_back(PooledThread::Start([&] {
            ++running;
            while (running < 4) std::this_thread::yield();
        }, 0));
    for (auto &t : threads) t->Join();
    EXPECT_EQ(running, 4);
    EXPECT_GE(PooledThread::ThreadsIdle(), 4u);
}

TEST(PooledThread, GivesAtLeastTheStackAskedFor) {
    const std::size_t big = 16u << 20;
    std::size_t got = 0;
    auto t = PooledThread::Start([&] {
        pthread_attr_t attr;
        ASSERT_EQ(pthread_getattr_np(pthread_self(), &attr), 0);
        pthread_attr_getstacksize(&attr, &got);
        pthread_attr_destroy(&attr);
    }, big);
    t->Join();
    EXPECT_GE(got, big);
}

TEST(PooledThread, DestroyingTheHandleWaitsForTheFunction) {
    std::atomic<bool> finished{false};
    { auto t = PooledThread::Start(SlowFunction(finished), 0); }
    EXPECT_TRUE(finished);
}

}  // namespace
}  // namespace povrayfc
