// Memory bandwidth on 1 and 2 threads (a STREAM-like triad a = b + s c over three arrays of n
// doubles, best of 20): whether a second thread gets its own bandwidth on this machine, the
// question behind the DEM engine's thread scaling (docs/performance.md).
//   g++ -O3 -fopenmp bench/stream_triad.cpp -o /tmp/stream_triad && /tmp/stream_triad 20000000
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
    const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 20000000;
    std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 3.0);
    for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        double best = 1e9;
        for (int round = 0; round < 20; ++round) {
            const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
            for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + 1.5 * c[i];
            const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
            if (dt.count() < best) best = dt.count();
        }
        std::printf("n = %zu doubles, %d thread(s): %.1f GB/s\n", n, threads,
                    3.0 * double(n) * 8.0 / best / 1e9);
    }
    return a[n / 2] == 0.0;  // keeps the loop
}
