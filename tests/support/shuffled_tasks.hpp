// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A hostile stand-in for a game's job system (xeno::TaskSystem): the world's result must not
// depend on how its parallel work is cut or ordered (docs/parallel.md). Shared by the determinism
// program and tests/robustness/parallel_test.cpp.
#pragma once

#include <xeno/task_system.hpp>

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <random>
#include <thread>
#include <utility>
#include <vector>

namespace xeno::test {

/// A job system as a game might plug in, made hostile: every parallel_for is cut into ranges of
/// random lengths (ignoring the hint) that run in a shuffled order on `threads` threads. Any cut
/// and order must give the hashes of one thread.
class ShuffledTasks final : public TaskSystem {
public:
    explicit ShuffledTasks(unsigned threads) : threads_(threads) {
        for (unsigned t = 1; t < threads; ++t) pool_.emplace_back([this] { serve(); });
    }
    ~ShuffledTasks() override {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : pool_) t.join();
    }
    unsigned workers() const override { return threads_; }
    void parallel_for(std::uint32_t count, std::uint32_t, RangeTask task) override {
        std::unique_lock<std::mutex> lock(mutex_);
        ranges_.clear();
        for (std::uint32_t begin = 0; begin < count;) {
            const std::uint32_t end = std::min(count, begin + 1 + static_cast<std::uint32_t>(random_() % 40));
            ranges_.emplace_back(begin, end);
            begin = end;
        }
        std::shuffle(ranges_.begin(), ranges_.end(), random_);
        task_ = task;
        next_ = 0;
        pending_ = ranges_.size();
        wake_.notify_all();
        run(lock);
        done_.wait(lock, [&] { return pending_ == 0; });
    }

private:
    void run(std::unique_lock<std::mutex>& lock) {
        while (next_ < ranges_.size()) {
            const std::pair<std::uint32_t, std::uint32_t> r = ranges_[next_++];
            lock.unlock();
            task_(r.first, r.second);
            lock.lock();
            if (--pending_ == 0) done_.notify_all();
        }
    }
    void serve() {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            wake_.wait(lock, [&] { return stopping_ || next_ < ranges_.size(); });
            if (stopping_) return;
            run(lock);
        }
    }

    unsigned threads_;
    std::mt19937 random_{12345};
    std::vector<std::thread> pool_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges_;
    std::size_t next_ = 0, pending_ = 0;
    RangeTask task_{};
    bool stopping_ = false;
};

}  // namespace xeno::test
