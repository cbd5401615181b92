// Parallel loops on plain threads, for ThreadSanitizer builds only
// (core/parallel.h). Debian's oneTBB is not built with ThreadSanitizer, so the
// synchronisation inside its scheduler (a task handed to the thread that steals
// it, the join at the end of a loop) is invisible to it and every parallel
// loop reads as racing: on the task objects, on the caller's stack slots the
// chunks read. Here chunks are handed out under a mutex and the loop is joined
// with a condition variable, which the sanitizer sees. Chunks still run on
// several threads in any order, so a race between two chunks is still found.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace spindrift {

class PlainThreads {
public:
    /// `threads` in all, the caller's included (at least 1).
    explicit PlainThreads(unsigned threads) {
        for (unsigned t = 1; t < threads; ++t) workers_.emplace_back([this] { work(); });
    }
    ~PlainThreads() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : workers_) t.join();
    }
    PlainThreads(const PlainThreads&) = delete;
    PlainThreads& operator=(const PlainThreads&) = delete;

    int concurrency() const { return static_cast<int>(workers_.size()) + 1; }

    /// Calls body(c) for every c in [0, chunks) and returns when all are done.
    void run(std::size_t chunks, const std::function<void(std::size_t)>& body) {
        std::unique_lock<std::mutex> lock(mutex_);
        body_ = &body;
        chunks_ = chunks;
        next_ = 0;
        finished_ = 0;
        ++generation_;
        wake_.notify_all();
        drain(lock);
        done_.wait(lock, [this] { return finished_ == chunks_; });
        body_ = nullptr;
    }

private:
    /// Runs chunks until none is left to start; `lock` held on entry and exit.
    void drain(std::unique_lock<std::mutex>& lock) {
        const std::function<void(std::size_t)>* body = body_;
        while (next_ < chunks_) {
            const std::size_t c = next_++;
            lock.unlock();
            (*body)(c);
            lock.lock();
            if (++finished_ == chunks_) done_.notify_all();
        }
    }

    void work() {
        std::unique_lock<std::mutex> lock(mutex_);
        std::size_t seen = generation_;
        for (;;) {
            wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
            drain(lock);
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t)>* body_ = nullptr;
    std::size_t chunks_ = 0;
    std::size_t next_ = 0;
    std::size_t finished_ = 0;
    std::size_t generation_ = 0;
    bool stop_ = false;
    std::vector<std::thread> workers_;
};

}  // namespace spindrift
