// Arithmetic throughput on 1 and 2 threads (eight independent chains of 4-wide fused
// multiply-adds per thread, no memory traffic): whether the machine's two vCPUs are two cores or
// one core's two hardware threads, which would share the arithmetic units and cap what a second
// DEM thread can gain (docs/performance.md, "The spatial sort"). Best of 5 rounds.
//   g++ -O2 -mavx2 -mfma -fopenmp bench/core_throughput.cpp -o /tmp/core_throughput &&
//   /tmp/core_throughput
#include <immintrin.h>
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <initializer_list>

namespace {

// Fused multiply-adds per second of one thread's loop; `sink` keeps the result alive.
double fma_loop(long iterations, double& sink) {
    __m256d a0 = _mm256_set1_pd(1.0), a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0;
    const __m256d m = _mm256_set1_pd(0.9999999), c = _mm256_set1_pd(1e-7);
    const auto t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < iterations; ++i) {
        a0 = _mm256_fmadd_pd(a0, m, c);
        a1 = _mm256_fmadd_pd(a1, m, c);
        a2 = _mm256_fmadd_pd(a2, m, c);
        a3 = _mm256_fmadd_pd(a3, m, c);
        a4 = _mm256_fmadd_pd(a4, m, c);
        a5 = _mm256_fmadd_pd(a5, m, c);
        a6 = _mm256_fmadd_pd(a6, m, c);
        a7 = _mm256_fmadd_pd(a7, m, c);
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const __m256d t = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(a0, a1), _mm256_add_pd(a2, a3)),
                                    _mm256_add_pd(_mm256_add_pd(a4, a5), _mm256_add_pd(a6, a7)));
    double out[4];
    _mm256_storeu_pd(out, t);
    sink += out[0];
    return double(iterations) * 8 * 4 / s;
}

}  // namespace

int main() {
    const long iterations = 200000000;
    double sink = 0;
    for (int threads : {1, 2}) {
        double best = 0;  // per thread
        for (int round = 0; round < 5; ++round) {
            double slowest = 1e300;
#pragma omp parallel num_threads(threads) reduction(min : slowest) reduction(+ : sink)
            {
                double s = 0;
                const double rate = fma_loop(iterations, s);
                slowest = rate < slowest ? rate : slowest;
                sink += s;
            }
            best = slowest > best ? slowest : best;
        }
        std::printf("%d thread(s): %.1f GFMA/s per thread, %.1f in all\n", threads, best / 1e9,
                    threads * best / 1e9);
    }
    return sink == 12345.0;  // never: keeps the loops
}
