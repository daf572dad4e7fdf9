#pragma once
// Splitting a loop over [0, n) into one contiguous chunk per thread (OpenMP from the toolchain).
// The chunking is only a schedule: callers make their results independent of it (each index
// writes its own slots; sums run in a fixed order afterwards), so a run gives the same bits for
// any thread count. One thread calls the body directly: no runtime call, no outlined function,
// the serial code exactly as written.
#include <cstddef>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gran {

// Chunk `part` of `parts` of [0, n): the first n % parts chunks are one longer.
inline void chunk_bounds(std::size_t n, std::size_t part, std::size_t parts, std::size_t& begin,
                         std::size_t& end) {
    const std::size_t base = n / parts, extra = n % parts;
    begin = part * base + (part < extra ? part : extra);
    end = begin + base + (part < extra ? 1 : 0);
}

// body(part, begin, end) for every chunk, on `threads` threads (at most; fewer if the runtime
// grants fewer). `part` indexes per-thread scratch (at most `threads` parts).
template <class Body>
void parallel_chunks(int threads, std::size_t n, Body&& body) {
#ifdef _OPENMP
    if (threads > 1) {
#pragma omp parallel num_threads(threads)
        {
            const auto parts = static_cast<std::size_t>(omp_get_num_threads());
            const auto part = static_cast<std::size_t>(omp_get_thread_num());
            std::size_t begin = 0, end = 0;
            chunk_bounds(n, part, parts, begin, end);
            body(part, begin, end);
        }
        return;
    }
#else
    (void)threads;
#endif
    body(std::size_t(0), std::size_t(0), n);
}

// body(part, begin, end) for the ranges [bounds[part], bounds[part + 1]) of a partition of
// [0, bounds.back()), one per thread: for a stage that should touch the same elements on the
// same threads as another stage, so that their cache lines stay in one core. If the runtime
// grants another number of threads than the partition has ranges, equal chunks instead (a
// schedule only, as for parallel_chunks). One thread, or a partition of one range: body(0, 0, n).
template <class Body>
void parallel_ranges(int threads, const std::vector<std::size_t>& bounds, Body&& body) {
    const std::size_t n = bounds.empty() ? 0 : bounds.back();
#ifdef _OPENMP
    if (threads > 1 && bounds.size() > 2) {
#pragma omp parallel num_threads(threads)
        {
            const auto parts = static_cast<std::size_t>(omp_get_num_threads());
            const auto part = static_cast<std::size_t>(omp_get_thread_num());
            std::size_t begin = 0, end = 0;
            if (parts + 1 == bounds.size()) {
                begin = bounds[part];
                end = bounds[part + 1];
            } else {
                chunk_bounds(n, part, parts, begin, end);
            }
            body(part, begin, end);
        }
        return;
    }
#else
    (void)threads;
#endif
    body(std::size_t(0), std::size_t(0), n);
}

// body(part, parts) once per thread of one parallel region of at most `threads` threads (the
// runtime may grant fewer: `parts` is what it granted, the same for every thread). Phases inside
// the body are separated by parts_barrier(), which every part must reach equally often. One
// thread calls body(0, 1) directly.
template <class Body>
void parallel_parts(int threads, Body&& body) {
#ifdef _OPENMP
    if (threads > 1) {
#pragma omp parallel num_threads(threads)
        body(static_cast<std::size_t>(omp_get_thread_num()),
             static_cast<std::size_t>(omp_get_num_threads()));
        return;
    }
#else
    (void)threads;
#endif
    body(std::size_t(0), std::size_t(1));
}

// Every part of the enclosing parallel_parts region waits here for the others (and sees their
// writes). Outside a region, or on one thread, it does nothing.
inline void parts_barrier() {
#ifdef _OPENMP
#pragma omp barrier
#endif
}

}  // namespace gran
