#include "exactpixels/fast/worker_pool.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <memory>

namespace exactpixels {

namespace {

/// How long a waiting thread keeps looking before it sleeps. Waking a sleeping thread
/// costs the system a scheduler round trip (on a virtual machine, waking an idle virtual
/// CPU); a renderer called frame after frame starts its next run well within this.
constexpr auto awake_time = std::chrono::microseconds(200);

/// Returns once `value` is no longer `old`: polling (and yielding the CPU to any other
/// thread that wants it) for awake_time, then asleep in std::atomic::wait.
template <class T> void await_change(const std::atomic<T>& value, T old) {
    const auto give_up = std::chrono::steady_clock::now() + awake_time;
    while (value.load(std::memory_order_acquire) == old) {
        if (std::chrono::steady_clock::now() > give_up) {
            value.wait(old, std::memory_order_acquire);
            return;
        }
        std::this_thread::yield();
    }
}

} // namespace

//> worker-pool
WorkerPool::WorkerPool(int threads) {
    if (threads < 1 || threads > max_threads) {
        throw Error(
            fmt::format("thread count {} is outside 1 .. {}", threads, max_threads));
    }
    errors_.resize(static_cast<std::size_t>(threads));
    try {
        for (int t = 1; t < threads; ++t) {
            workers_.emplace_back([this, t] { work(t); });
        }
    } catch (...) { // could not start a thread: stop the ones that run, then report
        stop();
        throw;
    }
}

WorkerPool::~WorkerPool() {
    stop();
}

void WorkerPool::stop() {
    stopping_.store(true, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release); // wakes every worker: stop
    generation_.notify_all();
    for (std::thread& w : workers_) {
        w.join();
    }
    workers_.clear();
}

void WorkerPool::work(int index) {
    std::uint64_t seen = 0;
    for (;;) {
        await_change(generation_, seen); // until a new run
        seen = generation_.load(std::memory_order_acquire);
        if (stopping_.load(std::memory_order_relaxed)) {
            return;
        }
        try {
            (*job_)(index);
        } catch (...) {
            errors_[static_cast<std::size_t>(index)] = std::current_exception();
        }
        if (busy_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            busy_.notify_one(); // the last worker out wakes the caller
        }
    }
}

void WorkerPool::run(const std::function<void(int)>& f) {
    assert(busy_.load() == 0 && "WorkerPool::run is not reentrant");
    std::fill(errors_.begin(), errors_.end(), nullptr);
    job_ = &f;
    busy_.store(size() - 1, std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release); // publishes job_ and busy_
    generation_.notify_all();
    try {
        f(0); // the caller is thread 0
    } catch (...) {
        errors_[0] = std::current_exception();
    }
    for (int left = busy_.load(std::memory_order_acquire); left != 0;
         left = busy_.load(std::memory_order_acquire)) {
        await_change(busy_, left);
    }
    job_ = nullptr;
    for (const std::exception_ptr& e : errors_) {
        if (e) {
            std::rethrow_exception(e);
        }
    }
}
//< worker-pool

void run_on_shared_pool(int threads, const std::function<void(int)>& f) {
    static std::atomic<bool> in_use{false}; // one caller at a time runs on `shared`
    static std::unique_ptr<WorkerPool> shared;
    if (in_use.exchange(true, std::memory_order_acquire)) { // busy: a pool of its own
        WorkerPool(threads).run(f);
        return;
    }
    struct Release { // however this call ends
        ~Release() { in_use.store(false, std::memory_order_release); }
    } release;
    if (!shared || shared->size() != threads) {
        shared.reset(); // its threads joined before new ones start
        shared = std::make_unique<WorkerPool>(threads);
    }
    shared->run(f);
}

} // namespace exactpixels
