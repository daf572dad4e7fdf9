#pragma once
// Portable, reproducible random numbers: Boost.Random generators and distributions give the same
// streams on every platform and standard library, unlike std:: distributions.
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_01.hpp>
#include <cstdint>

namespace gran {

using Rng = boost::random::mt19937_64;

// Independent streams of one scene seed (placement, velocities, thermostat, ...).
enum class Stream : std::uint64_t { Placement = 1, Velocities = 2, Driver = 3, Observables = 4 };

inline Rng make_rng(std::uint64_t seed, Stream stream) {
    // SplitMix64 of (seed, stream) so neighbouring seeds give unrelated states.
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (static_cast<std::uint64_t>(stream) + 1);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return Rng(z);
}

inline double uniform01(Rng& rng) {
    return boost::random::uniform_01<double>()(rng);
}
inline double gaussian(Rng& rng) {
    return boost::random::normal_distribution<double>()(rng);
}

}  // namespace gran
