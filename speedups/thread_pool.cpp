// PooledThread: threads kept across POV-Ray's tasks (thread_pool.h says why).
#include "speedups/thread_pool.h"

#include <pthread.h>

#include <condition_variable>
#include <mutex>
#include <system_error>
#include <utility>
#include <vector>

namespace povrayfc {

struct PooledThread::Done {
    std::mutex mutex;
    std::condition_variable returned;
    bool done = false;
};

namespace {

// One kept thread: its next function, or none while it waits.
struct Worker {
    std::size_t stackSize = 0;
    std::function<void()> function;
    std::shared_ptr<PooledThread::Done> done;
    std::condition_variable wake;
};

// Never destroyed: waiting workers hold its mutex's condition at exit.
struct Pool {
    std::mutex mutex;
    std::vector<Worker *> idle;
    std::size_t created = 0;
};

Pool &ThePool() {
    static Pool *pool = new Pool;
    return *pool;
}

void *WorkerLoop(void *arg) {
    Worker *worker = static_cast<Worker *>(arg);
    Pool &pool = ThePool();
    for (;;) {
        std::function<void()> function;
        std::shared_ptr<PooledThread::Done> done;
        {
            std::unique_lock<std::mutex> lock(pool.mutex);
            worker->wake.wait(lock, [worker] { return bool(worker->function); });
            function = std::move(worker->function);
            worker->function = nullptr;
            done = std::move(worker->done);
        }
        function();
        function = nullptr;  // what it holds goes before the joiner goes on
        {
            // Idle again before the joiner hears of it: a task started right after the
            // join finds this thread.
            std::lock_guard<std::mutex> lock(pool.mutex);
            pool.idle.push_back(worker);
        }
        {
            std::lock_guard<std::mutex> lock(done->mutex);
            done->done = true;
        }
        done->returned.notify_all();
    }
    return nullptr;
}

}  // namespace

std::unique_ptr<PooledThread> PooledThread::Start(std::function<void()> function, std::size_t stackSize) {
    auto done = std::make_shared<Done>();
    Pool &pool = ThePool();
    {
        std::lock_guard<std::mutex> lock(pool.mutex);
        // The most recently idle thread with enough stack (its stack is likeliest cached).
        for (std::size_t i = pool.idle.size(); i-- > 0;) {
            Worker *worker = pool.idle[i];
            if (worker->stackSize < stackSize) continue;
            pool.idle.erase(pool.idle.begin() + long(i));
            worker->function = std::move(function);
            worker->done = done;
            worker->wake.notify_one();
            return std::unique_ptr<PooledThread>(new PooledThread(done));
        }
        ++pool.created;
    }
    Worker *worker = new Worker;
    worker->stackSize = stackSize;
    worker->function = std::move(function);
    worker->done = done;
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    if (stackSize > 0) pthread_attr_setstacksize(&attr, stackSize);
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    pthread_t id;
    const int err = pthread_create(&id, &attr, WorkerLoop, worker);
    pthread_attr_destroy(&attr);
    if (err != 0) {
        // As boost::thread does (thread_resource_error is a system_error too).
        delete worker;
        std::lock_guard<std::mutex> lock(pool.mutex);
        --pool.created;
        throw std::system_error(err, std::generic_category(), "cannot create a thread");
    }
    return std::unique_ptr<PooledThread>(new PooledThread(done));
}

PooledThread::~PooledThread() { Join(); }

void PooledThread::Join() {
    std::unique_lock<std::mutex> lock(done_->mutex);
    done_->returned.wait(lock, [this] { return done_->done; });
}

std::size_t PooledThread::ThreadsCreated() {
    std::lock_guard<std::mutex> lock(ThePool().mutex);
    return ThePool().created;
}

std::size_t PooledThread::ThreadsIdle() {
    std::lock_guard<std::mutex> lock(ThePool().mutex);
    return ThePool().idle.size();
}

}  // namespace povrayfc
