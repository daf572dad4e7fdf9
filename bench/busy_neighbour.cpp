// A neighbour that takes a share of one core: busy for BUSY milliseconds, asleep for SLEEP, until
// killed. Pinned beside a threaded DEM run (taskset -c 0), it makes that core slower for the
// run's thread there, as another tenant's process does on a shared machine: the case
// DemSettings::balance_threads is for (docs/performance.md, "Shares that follow the threads'
// speeds").
// g++ -std=c++20 -O2 bench/busy_neighbour.cpp -o /tmp/busy_neighbour
// taskset -c 0 /tmp/busy_neighbour 0.2 0.3 &     (BUSY SLEEP in ms)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s BUSY_MS SLEEP_MS\n", argv[0]);
        return 2;
    }
    using clock = std::chrono::steady_clock;
    const std::chrono::duration<double, std::milli> busy(std::atof(argv[1])),
        asleep(std::atof(argv[2]));
    volatile double x = 0;
    for (;;) {
        const auto start = clock::now();
        while (clock::now() - start < busy) x = x + 1;
        std::this_thread::sleep_for(asleep);
    }
}
