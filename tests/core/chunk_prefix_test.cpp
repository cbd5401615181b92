#include "core/chunk_prefix.h"

#include <gtest/gtest.h>

namespace spindrift {
namespace {

// full() may turn true only once chunks 0 .. k have all finished and counted
// the bound between them: a later chunk finishing first, however much it
// counted, says nothing about where the bound falls in chunk order.
TEST(ChunkPrefix, FullOnlyOnceAFinishedPrefixReachesTheBound) {
    ChunkPrefix p(4, 10);
    EXPECT_FALSE(p.full());
    p.finish(2, 100);  // after the bound or not, depending on chunks 0 and 1
    EXPECT_FALSE(p.full());
    p.finish(0, 6);
    EXPECT_FALSE(p.full());  // prefix 0: 6 < 10
    p.finish(1, 3);
    EXPECT_TRUE(p.full());  // prefix 0..2: 109 >= 10
}

TEST(ChunkPrefix, ExactlyTheBoundIsFull) {
    ChunkPrefix p(3, 10);
    p.finish(0, 4);
    p.finish(1, 5);
    EXPECT_FALSE(p.full());  // 9
    p.finish(2, 1);
    EXPECT_TRUE(p.full());  // 10
}

// No room at all: every item of every chunk lies past it.
TEST(ChunkPrefix, ZeroBoundIsFullFromTheStart) {
    ChunkPrefix p(2, 0);
    EXPECT_TRUE(p.full());
}

}  // namespace
}  // namespace spindrift
