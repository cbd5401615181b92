// parallelFor on oneTBB with a fixed partition: the work is cut into chunks of
// `grain` items whatever the thread count, so per-chunk results combined in
// chunk order are identical for 1 or N threads (docs/design.md, "Determinism").
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <memory>

#if defined(__SANITIZE_THREAD__)
#include "core/plain_threads.h"
#endif

namespace spindrift {

class WorkerPool {
public:
    /// threads == 0: all hardware threads.
    explicit WorkerPool(unsigned threads)
        : arena_(std::make_unique<tbb::task_arena>(threads == 0 ? tbb::task_arena::automatic
                                                                : static_cast<int>(threads)))
#if defined(__SANITIZE_THREAD__)
        , plain_(std::make_unique<PlainThreads>(static_cast<unsigned>(arena_->max_concurrency())))
#endif
    {
    }
    int concurrency() const { return arena_->max_concurrency(); }

    /// Calls fn(chunk, begin, end) for every chunk [begin, end) of `grain` items.
    template <class Fn>
    void forChunks(std::size_t count, std::size_t grain, Fn&& fn) {
        std::size_t chunks = chunkCount(count, grain);
        if (chunks == 0) {
            return;
        }
        auto chunk = [&](std::size_t c) {
            std::size_t begin = c * grain;
            std::size_t end = begin + grain < count ? begin + grain : count;
            fn(c, begin, end);
        };
#if defined(__SANITIZE_THREAD__)
        // ThreadSanitizer cannot see oneTBB's synchronisation (plain_threads.h).
        plain_->run(chunks, chunk);
#else
        arena_->execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                              [&](const tbb::blocked_range<std::size_t>& r) {
                                  for (std::size_t c = r.begin(); c != r.end(); ++c) chunk(c);
                              },
                              tbb::simple_partitioner());
        });
#endif
    }

    static std::size_t chunkCount(std::size_t count, std::size_t grain) {
        return (count + grain - 1) / grain;
    }

private:
    std::unique_ptr<tbb::task_arena> arena_;
#if defined(__SANITIZE_THREAD__)
    std::unique_ptr<PlainThreads> plain_;
#endif
};

}  // namespace spindrift
