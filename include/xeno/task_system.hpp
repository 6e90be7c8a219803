// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// How xeno spreads a step over threads (docs/parallel.md). The world never starts a thread of its
// own accord: it hands ranges of independent work ("these 4,000 pairs", "the groups of colour 3")
// to a TaskSystem and waits. A game plugs in its own job system by implementing parallel_for (the
// shape of Box2D v3's enqueue/finish callbacks and Jolt's JobSystem, reduced to the one call the
// world needs); ThreadPool is the default, a few std::threads that spin briefly between the many
// short ranges of a step and sleep between steps.
//
// Every range the world hands out writes only to its own items, so the result does not depend on
// how the ranges are cut, in what order they run or on which thread: a step gives the same bits
// for any worker count (tests/robustness/parallel_test.cpp).
#pragma once

#include "config.hpp"
#include "error.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>
#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
#include <emmintrin.h>  // _mm_pause (not <immintrin.h>: every AVX-512 header, a tenth of a user file's parse)
#endif

namespace xeno {

/// A range function: run(context, begin, end) processes items [begin, end).
struct RangeTask {
    void (*run)(const void* context, std::uint32_t begin, std::uint32_t end);
    const void* context;
    void operator()(std::uint32_t begin, std::uint32_t end) const { run(context, begin, end); }
};

namespace detail {

/// One turn of a wait loop: the CPU's spin-wait hint, and every 64th turn a yield to the OS
/// (a thread the OS would rather run, or the one being waited for on a busy machine). A yield
/// every turn made each wait a system call, which costs microseconds on a virtual machine.
inline void spin_pause(unsigned spin) {
#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
    _mm_pause();
#elif defined(__aarch64__) && (defined(__GNUC__) || defined(__clang__))
    __asm__ __volatile__("yield");
#endif
    if (spin % 64 == 0) std::this_thread::yield();
}

}  // namespace detail

/// What the world needs from a job system.
class TaskSystem {
public:
    virtual ~TaskSystem() = default;
    /// Calls task on ranges that cover [0, count) without overlapping, from any threads in any
    /// order, and returns when all have finished. min_range is a hint: ranges shorter than it
    /// cost more to hand out than they save (so the default pool runs count <= min_range on the
    /// caller), but any cut gives the same result. count > 0. Called only from the thread
    /// stepping the world, never from inside a task. A task may throw (xeno's do only on a
    /// bug or a failed allocation): finish or skip the other ranges, then rethrow one of the
    /// exceptions to the caller (ThreadPool rethrows the first).
    virtual void parallel_for(std::uint32_t count, std::uint32_t min_range, RangeTask task) = 0;
    /// Threads that may run ranges at once, the caller included (the world sizes ranges by it).
    virtual unsigned workers() const = 0;
};

/// Runs f(begin, end) over [0, count) through `tasks`, or on the caller when there is no task
/// system or it has one worker.
template <class F>
void parallel_for(TaskSystem* tasks, std::uint32_t count, std::uint32_t min_range, const F& f) {
    if (count == 0) return;
    if (tasks == nullptr || tasks->workers() <= 1) {
        f(std::uint32_t(0), count);
        return;
    }
    const RangeTask task{[](const void* c, std::uint32_t b, std::uint32_t e) { (*static_cast<const F*>(c))(b, e); }, &f};
    tasks->parallel_for(count, std::max<std::uint32_t>(min_range, 1u), task);
}

/// The default task system: workers − 1 std::threads plus the caller. A parallel_for cuts the
/// work into two to four ranges per worker (so a worker delayed by the OS is covered by the others,
/// at most 32) and each thread first claims the ranges of its own share, the k-th of `workers`
/// equal shares, then any left: the world hands out items in body order, so a thread keeps
/// touching the same bodies call after call (colour after colour, substep after substep) and
/// their cache lines stay in its core instead of moving between cores. After a call the threads
/// spin for up to 200 µs (a step issues hundreds of short calls, one per colour and substep) and
/// then sleep on a condition variable, so an idle pool costs nothing.
class ThreadPool final : public TaskSystem {
public:
    static constexpr unsigned max_workers = 256;

    /// InvalidArgument unless 1 <= workers <= max_workers.
    explicit ThreadPool(unsigned workers) : workers_(workers) {
        if (workers < 1 || workers > max_workers)
            detail::report_invalid("ThreadPool", "workers must be between 1 and 256", static_cast<double>(workers));
        threads_.reserve(workers - 1);
        for (unsigned i = 1; i < workers; ++i) threads_.emplace_back([this, i] { work(i); });
    }
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;
    ~ThreadPool() override {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : threads_) t.join();
    }

    unsigned workers() const override { return workers_; }

    void parallel_for(std::uint32_t count, std::uint32_t min_range, RangeTask task) override {
        if (count <= min_range || workers_ == 1) {
            task(0, count);
            return;
        }
        // Two to four ranges per worker: 75 items in ranges of 32 would be 3 ranges, and one of
        // two workers would do two thirds; one range each leaves the caller waiting whenever the
        // OS pauses the other worker.
        const std::uint32_t ranges =
            std::min<std::uint32_t>({count, max_ranges, 4u * workers_, std::max(2u * workers_, count / min_range)});
        task_ = task;
        count_ = count;
        ranges_ = ranges;
        done_.store(0, std::memory_order_relaxed);
        // Publishing the new generation with its ranges unclaimed (the bits past them set) opens
        // the job; a thread can only claim a range of the generation it saw, so a late thread
        // never runs a stale job.
        const std::uint64_t generation = (state_.load(std::memory_order_relaxed) >> 32) + 1;
        const std::uint64_t past_ranges = ranges == max_ranges ? 0u : closed << ranges & closed;
        state_.store(generation << 32 | past_ranges, std::memory_order_release);
        {
            std::lock_guard<std::mutex> lock(mutex_);  // orders the store before a sleeper's check
        }
        wake_.notify_all();
        run_ranges(generation, 0);
        for (unsigned spin = 1; done_.load(std::memory_order_acquire) != ranges; ++spin) detail::spin_pause(spin);
        // Closed: a thread still holding this generation's state fails its claim, so the job
        // fields can be rewritten for the next call.
        state_.store(generation << 32 | closed, std::memory_order_release);
#if XENO_HAS_EXCEPTIONS
        std::exception_ptr error;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            std::swap(error, error_);  // (not error.swap: libc++'s exception_ptr has no such member)
        }
        if (error) std::rethrow_exception(error);
#endif
    }

private:
    static constexpr std::uint32_t max_ranges = 32;       ///< one bit each in the state word
    static constexpr std::uint64_t closed = 0xffffffffu;  ///< every range claimed
    static constexpr std::chrono::microseconds spin_time{200};

    /// Claims and runs ranges of `generation` until none is left, thread `thread`'s share first
    /// (the caller is thread 0); reports how many it ran once, at the end (the caller waits on
    /// that count, and each report moves its cache line between cores).
    void run_ranges(std::uint64_t generation, unsigned thread) {
        std::uint32_t ran = 0;
        std::uint64_t state = state_.load(std::memory_order_acquire);
        while ((state >> 32) == generation && (state & closed) != closed) {
            // A stale ranges_ (a newer call's) only picks where to look: the claim below fails
            // because the generation moved on.
            const std::uint32_t r = ranges_.load(std::memory_order_relaxed);
            const std::uint32_t index = next_range(static_cast<std::uint32_t>(state), r, thread);
            if (!state_.compare_exchange_weak(state, state | std::uint64_t(1) << index, std::memory_order_acq_rel,
                                              std::memory_order_acquire))
                continue;
            const std::uint64_t n = count_;
            run_range(static_cast<std::uint32_t>(n * index / r), static_cast<std::uint32_t>(n * (index + 1) / r));
            ++ran;
            state = state_.load(std::memory_order_acquire);
        }
        if (ran > 0) done_.fetch_add(ran, std::memory_order_acq_rel);
    }

    /// Runs [begin, end) of the job. A range that throws still counts as run, and the caller
    /// rethrows the first error once every range is done: thrown out of a worker it ended the
    /// process, and thrown out of the caller it left the workers running on a job being torn down.
    void run_range(std::uint32_t begin, std::uint32_t end) {
#if XENO_HAS_EXCEPTIONS
        try {
            task_(begin, end);
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex_);
            if (!error_) error_ = std::current_exception();
        }
#else
        task_(begin, end);
#endif
    }

    /// The range `thread` claims next among `r` given the claimed bits (not all set): the first
    /// of its own share, else the last one left, so that a thread that finished early takes
    /// from the far end of a late thread's share and not the ranges it is about to claim.
    std::uint32_t next_range(std::uint32_t claimed, std::uint32_t r, unsigned thread) const {
        const auto share = [&](unsigned t) { return static_cast<std::uint32_t>(std::uint64_t(t) * r / workers_); };
        for (std::uint32_t i = share(thread); i < share(thread + 1); ++i)
            if (!(claimed >> i & 1u)) return i;
        std::uint32_t i = max_ranges - 1;
        while (claimed >> i & 1u) --i;  // ends: some bit is clear
        return i;
    }

    void work(unsigned thread) {
        std::uint64_t seen = 0;
        for (;;) {
            // Spin, yielding, for up to spin_time: the gaps between a step's calls are mostly
            // microseconds (colour after colour); past it, sleep until the next call, so the pool
            // does not hold a core between steps.
            std::uint64_t generation = state_.load(std::memory_order_acquire) >> 32;
            const auto until = std::chrono::steady_clock::now() + spin_time;
            for (unsigned spin = 1; generation == seen; ++spin) {
                if (spin % 64 == 0 && std::chrono::steady_clock::now() > until) break;
                detail::spin_pause(spin);
                generation = state_.load(std::memory_order_acquire) >> 32;
            }
            if (generation == seen) {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || (state_.load(std::memory_order_acquire) >> 32) != seen; });
                if (stopping_) return;
                generation = state_.load(std::memory_order_acquire) >> 32;
            }
            seen = generation;
            run_ranges(generation, thread);
        }
    }

    unsigned workers_;
    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::exception_ptr error_;             ///< the first exception a range of this call threw (guarded by mutex_)
    std::atomic<std::uint64_t> state_{0};  ///< generation << 32 | a bit per range, set once claimed
    std::atomic<std::uint32_t> done_{0};   ///< ranges finished in this generation
    // The job: written by the caller before it publishes a generation, read by a thread only
    // after it claimed a range of that generation (the caller waits for every range, so the
    // job cannot change under it). Atomics so that ThreadSanitizer sees the hand-over.
    RangeTask task_{};
    std::atomic<std::uint32_t> count_{0}, ranges_{0};
};

namespace detail {

/// Where a World's parallel work runs: a ThreadPool it owns (World::set_workers), the game's
/// TaskSystem (not owned), or nowhere (the stepping thread). A copied world gets a pool of its
/// own with as many workers, so two worlds never share xeno's pool, and shares the game's system;
/// a moved-from world steps on one thread.
class WorldTasks {
public:
    WorldTasks() = default;
    WorldTasks(const WorldTasks& other) { *this = other; }
    WorldTasks(WorldTasks&& other) noexcept : pool_(std::move(other.pool_)), tasks_(other.tasks_) { other.tasks_ = nullptr; }
    WorldTasks& operator=(const WorldTasks& other) {
        if (this == &other) return *this;
        if (other.pool_) own(other.pool_->workers());
        else use(other.tasks_);
        return *this;
    }
    WorldTasks& operator=(WorldTasks&& other) noexcept {
        pool_ = std::move(other.pool_);
        tasks_ = other.tasks_;
        other.tasks_ = nullptr;
        return *this;
    }

    /// A pool of `workers` (1: none); the old one is kept if creating threads throws.
    void own(unsigned workers) {
        std::unique_ptr<ThreadPool> pool = workers > 1 ? std::make_unique<ThreadPool>(workers) : nullptr;
        pool_ = std::move(pool);
        tasks_ = pool_.get();
    }
    void use(TaskSystem* tasks) {
        pool_.reset();
        tasks_ = tasks;
    }
    TaskSystem* get() const { return tasks_; }

private:
    std::unique_ptr<ThreadPool> pool_;
    TaskSystem* tasks_ = nullptr;
};

}  // namespace detail
}  // namespace xeno
