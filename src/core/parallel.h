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
#include <sanitizer/tsan_interface.h>
#endif

namespace spindrift {

/// The two ordering edges of a parallel loop, told to ThreadSanitizer. oneTBB
/// from Debian is not built with it, so the synchronisation by which a loop
/// hands chunks to its threads and joins them is invisible: every value a
/// chunk read from the caller's stack, once the caller reuses the slot,
/// reads as a race. TBB guarantees exactly these edges: what the caller did
/// before the loop happens before every chunk, and every chunk before the
/// loop returns. Chunks get no edge between them, so a race between two
/// chunks is still reported (docs/fuzzing.md, "ThreadSanitizer"). Without
/// the sanitizer every call is empty.
class LoopEdges {
public:
    void beforeLoop() { release(&start_); }
    void chunkBegins() { acquire(&start_); }
    void chunkEnds() { release(&end_); }
    void afterLoop() { acquire(&end_); }

private:
    static void release([[maybe_unused]] char* p) {
#if defined(__SANITIZE_THREAD__)
        __tsan_release(p);
#endif
    }
    static void acquire([[maybe_unused]] char* p) {
#if defined(__SANITIZE_THREAD__)
        __tsan_acquire(p);
#endif
    }
    char start_ = 0;
    char end_ = 0;
};

class WorkerPool {
public:
    /// threads == 0: all hardware threads.
    explicit WorkerPool(unsigned threads)
        : arena_(std::make_unique<tbb::task_arena>(threads == 0 ? tbb::task_arena::automatic
                                                                : static_cast<int>(threads))) {}
    int concurrency() const { return arena_->max_concurrency(); }

    /// Calls fn(chunk, begin, end) for every chunk [begin, end) of `grain` items.
    template <class Fn>
    void forChunks(std::size_t count, std::size_t grain, Fn&& fn) {
        std::size_t chunks = chunkCount(count, grain);
        if (chunks == 0) {
            return;
        }
        LoopEdges edges;
        edges.beforeLoop();
        arena_->execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                              [&](const tbb::blocked_range<std::size_t>& r) {
                                  edges.chunkBegins();
                                  for (std::size_t c = r.begin(); c != r.end(); ++c) {
                                      std::size_t begin = c * grain;
                                      std::size_t end = begin + grain < count ? begin + grain : count;
                                      fn(c, begin, end);
                                  }
                                  edges.chunkEnds();
                              },
                              tbb::simple_partitioner());
        });
        edges.afterLoop();
    }

    static std::size_t chunkCount(std::size_t count, std::size_t grain) {
        return (count + grain - 1) / grain;
    }

private:
    std::unique_ptr<tbb::task_arena> arena_;
};

}  // namespace spindrift
