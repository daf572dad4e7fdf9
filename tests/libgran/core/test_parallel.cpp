// Chunking of threaded loops (libgran/core/parallel.hpp).
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <vector>

#include "libgran/core/parallel.hpp"

namespace gran {
namespace {

// The chunks of a loop cover [0, n) once, in order, with sizes differing by at most one.
TEST(ParallelChunks, ChunksCoverTheRangeOnceInOrder) {
    for (std::size_t n : {0u, 1u, 7u, 100u, 1001u}) {
        for (std::size_t parts : {1u, 2u, 3u, 8u}) {
            std::size_t expected = 0;
            for (std::size_t p = 0; p < parts; ++p) {
                std::size_t b = 0, e = 0;
                chunk_bounds(n, p, parts, b, e);
                EXPECT_EQ(b, expected) << n << " " << parts;
                EXPECT_LE(e - b, n / parts + 1);
                EXPECT_GE(e - b, n / parts);
                expected = e;
            }
            EXPECT_EQ(expected, n);
        }
    }
}

// Every index is visited once whatever the thread count, and the part numbers are below it.
TEST(ParallelChunks, EveryIndexIsVisitedOnceOnAnyThreadCount) {
    for (int threads : {1, 2, 3}) {
        std::vector<int> visits(1000, 0);
        std::atomic<bool> part_in_range{true};
        parallel_chunks(threads, visits.size(),
                        [&](std::size_t part, std::size_t b, std::size_t e) {
                            if (part >= std::size_t(threads)) part_in_range = false;
                            for (std::size_t i = b; i < e; ++i) ++visits[i];
                        });
        for (int v : visits) ASSERT_EQ(v, 1) << threads << " threads";
        EXPECT_TRUE(part_in_range.load());
    }
}

// Given a partition with one range per thread, each part gets its own range (a stage can then
// touch the elements another stage touched on the same thread); with a partition of another
// size, or on one thread, every index is still visited once.
TEST(ParallelRanges, EachPartTakesItsRangeOfThePartitionAndEveryIndexOnce) {
    const std::vector<std::size_t> bounds = {0, 13, 700, 1000};  // three unequal ranges
    for (int threads : {1, 2, 3}) {
        std::vector<int> visits(1000, 0);
        std::vector<std::size_t> begin_of(3, 1u << 30), end_of(3, 1u << 30);
        std::atomic<bool> part_in_range{true};
        parallel_ranges(threads, bounds, [&](std::size_t part, std::size_t b, std::size_t e) {
            if (part >= std::size_t(threads)) {
                part_in_range = false;
                return;
            }
            begin_of[part] = b;
            end_of[part] = e;
            for (std::size_t i = b; i < e; ++i) ++visits[i];
        });
        for (int v : visits) ASSERT_EQ(v, 1) << threads << " threads";
        EXPECT_TRUE(part_in_range.load());
#ifdef _OPENMP
        if (threads == 3) {  // as many threads as ranges (if the runtime grants them)
            for (std::size_t p = 0; p < 3 && begin_of[2] != (1u << 30); ++p) {
                EXPECT_EQ(begin_of[p], bounds[p]);
                EXPECT_EQ(end_of[p], bounds[p + 1]);
            }
        }
#endif
    }
}

}  // namespace
}  // namespace gran
