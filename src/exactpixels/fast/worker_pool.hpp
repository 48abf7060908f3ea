// worker_pool.hpp: a fixed number of threads, started once and kept, that run one job
// together and wait for each other, so that a renderer called many times a second does
// not pay for starting and joining threads on every call.
//
// Usage:
//   WorkerPool pool(2);                      // the caller and one worker thread
//   pool.run([&](int t) { work_on(slice(t)); }); // f(0) on the caller, f(1) on the
//                                             // worker; returns when both are done
//
// size() threads take part in every run: the calling thread is thread 0, the pool's own
// std::threads are 1 .. size() - 1 (a pool of one starts no thread). run() returns
// once every thread has finished f; if some threads threw, the exception of the lowest
// thread index is rethrown on the caller (the others are dropped), after all have
// finished. One run at a time: run() is not reentrant and must be called from one
// thread. The destructor stops and joins the workers.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <vector>
#ifndef __wasi__
#include <thread>
#endif

namespace exactpixels {

/// The most threads a WorkerPool (and so any renderer built on one) accepts.
inline constexpr int max_threads = 64;

#ifndef __wasi__ // WebAssembly without threads (the live figures) has no pool
/// Threads started once that run jobs together: f(thread_index) on each, then wait.
class WorkerPool {
  public:
    /// A pool of `threads` threads in all, the caller included (1 .. max_threads);
    /// throws Error for any other count before starting a thread.
    explicit WorkerPool(int threads);
    /// Stops and joins the worker threads.
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    /// The number of threads that take part in a run, the caller included.
    int size() const { return static_cast<int>(workers_.size()) + 1; }

    /// Runs f(t) for t = 0 .. size() - 1, f(0) on the calling thread, and returns when
    /// all have returned; rethrows the exception of the lowest t that threw.
    void run(const std::function<void(int)>& f);

  private:
    /// Asks every worker to stop, wakes them and joins them.
    void stop();
    /// A worker's loop: sleep until a run starts, run job_, report, again, until
    /// stopping_ is set.
    void work(int index);

    const std::function<void(int)>* job_ = nullptr; ///< the running job
    std::atomic<std::uint64_t> generation_{0}; ///< bumped to start a run (or to stop)
    std::atomic<int> busy_{0};                 ///< workers still in the current job
    std::atomic<bool> stopping_{false};        ///< set once, by stop()
    std::vector<std::exception_ptr> errors_;   ///< per thread, for the current run
    /// Threads 1 .. size() - 1. std::thread and a flag of our own rather than
    /// std::jthread and its stop token, which LLVM's libc++ 14 lacks.
    std::vector<std::thread> workers_;
};
#endif

/// Thread t's first item when `count` items are split evenly among `threads` threads:
/// thread t takes items thread_share(count, t, threads) up to (not including)
/// thread_share(count, t + 1, threads).
inline std::size_t thread_share(std::size_t count, int t, int threads) {
    return count * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
}

/// Thread t's stretch of a list made of sizes[0] items, then sizes[1] items, ..., split
/// evenly among `threads` threads (thread_share): f(i, first, end) for each list i the
/// stretch meets, in order, with its items first .. end - 1 of list i.
template <class F>
void for_thread_stretch(const std::vector<std::size_t>& sizes, int t, int threads, F f) {
    std::size_t all = 0;
    for (const std::size_t size : sizes) {
        all += size;
    }
    const std::size_t first = thread_share(all, t, threads);
    const std::size_t end = thread_share(all, t + 1, threads);
    std::size_t start = 0; // of list i in the whole
    for (std::size_t i = 0; i < sizes.size() && start < end; start += sizes[i++]) {
        const std::size_t a = first > start ? first : start;
        const std::size_t b = end < start + sizes[i] ? end : start + sizes[i];
        if (a < b) {
            f(i, a - start, b - start);
        }
    }
}

/// Runs f(t) for t = 0 .. threads - 1 (1 .. max_threads) and returns when all have
/// returned, rethrowing as WorkerPool::run does: on a process-wide WorkerPool of
/// `threads` threads, made on first use, kept from call to call (a renderer drawing frame
/// after frame starts no thread) and made anew when the count changes; its threads
/// sleep between calls and are joined at exit. A call made while that pool runs (from
/// another thread, or from inside f) gets a pool of its own for the call. Without
/// threads (WebAssembly) f(0), f(1), ... run one after another on the caller.
#ifndef __wasi__
void run_on_shared_pool(int threads, const std::function<void(int)>& f);
#else
inline void run_on_shared_pool(int threads, const std::function<void(int)>& f) {
    for (int t = 0; t < threads; ++t) {
        f(t);
    }
}
#endif

} // namespace exactpixels
