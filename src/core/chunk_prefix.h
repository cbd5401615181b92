// The finished prefix of a parallel pass's chunks and what it has counted:
// whether chunks 0 .. k, all finished, already reached a bound. A pass that
// keeps the first `bound` items in chunk order (a step's events) can then let
// every chunk not yet finished skip building its items, since none of them
// can be kept, whatever order the chunks run in (forChunks): the result is
// the same for any thread count.
#pragma once

#include <atomic>
#include <cstddef>
#include <limits>
#include <mutex>
#include <vector>

namespace spindrift {

class ChunkPrefix {
public:
    ChunkPrefix(std::size_t chunks, std::size_t bound) : counts_(chunks, kUnfinished), bound_(bound) {
        full_.store(bound == 0, std::memory_order_relaxed);
    }

    /// True once finished chunks 0 .. k counted at least the bound. A chunk
    /// that is not finished lies past that prefix: its items come after the
    /// bound in chunk order.
    bool full() const { return full_.load(std::memory_order_acquire); }

    /// Chunk c is finished, having counted `count` items (built or skipped).
    /// Under a lock: a pass finishes a few hundred chunks.
    void finish(std::size_t c, std::size_t count) {
        std::lock_guard<std::mutex> lock(mutex_);
        counts_[c] = count;
        while (next_ < counts_.size() && counts_[next_] != kUnfinished) {
            sum_ += counts_[next_++];
        }
        if (sum_ >= bound_) {
            full_.store(true, std::memory_order_release);
        }
    }

private:
    static constexpr std::size_t kUnfinished = std::numeric_limits<std::size_t>::max();
    std::mutex mutex_;
    std::vector<std::size_t> counts_;  // per chunk, kUnfinished until finish()
    std::size_t next_ = 0;             // the first chunk not in the finished prefix
    std::size_t sum_ = 0;              // counted by chunks 0 .. next_ - 1
    std::size_t bound_;
    std::atomic<bool> full_{false};
};

}  // namespace spindrift
