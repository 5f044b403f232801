// PooledThread: a thread for one function, taken from threads kept for the process's life.
//
// POV-Ray starts a new thread for every task (parser, bounding, each render thread) and
// for its scene's and view's control loops, and joins it when the task ends: five threads
// a frame for a one-thread render. Creating and joining one cost 40-46 us of CPU here (a
// 4 MiB stack, cgroups), about a tenth of the fixed cost of a frame that a frame-division
// slave's renderer pays whatever its tiles. A finished function's thread waits here for
// the next one instead of exiting.
//
// Join semantics as boost::thread's: Start runs `function` on a thread of at least
// `stackSize` bytes of stack; Join waits until it has returned; the destructor joins too
// (POV-Ray always joins before it deletes, and a function still running must not outlive
// its handle). A function must not throw (POV-Ray's thread functions catch everything;
// one that escapes terminates the process, as on a thread of its own). Threads that wait
// for work block at exit, which ends them; they are never destroyed.
#ifndef SPEEDUPS_THREAD_POOL_H
#define SPEEDUPS_THREAD_POOL_H

#include <cstddef>
#include <functional>
#include <memory>

namespace povrayfc {

class PooledThread {
  public:
    static std::unique_ptr<PooledThread> Start(std::function<void()> function, std::size_t stackSize);
    ~PooledThread();
    PooledThread(const PooledThread &) = delete;
    PooledThread &operator=(const PooledThread &) = delete;

    // Wait until the function has returned (at once if it has).
    void Join();
    // boost::thread's spelling, so that POV-Ray's code joins a pooled thread unchanged.
    void join() { Join(); }

    // Threads made so far and threads waiting for work (for tests).
    static std::size_t ThreadsCreated();
    static std::size_t ThreadsIdle();

    struct Done;  // whether the function returned (thread_pool.cpp)

  private:
    explicit PooledThread(std::shared_ptr<Done> done) : done_(std::move(done)) {}
    std::shared_ptr<Done> done_;
};

}  // namespace povrayfc

#endif
