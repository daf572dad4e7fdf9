#pragma once
// What observables may read of a running simulation, whichever engine runs it: the event-driven
// hard-particle engine or the time-stepped soft-sphere DEM engine (scene key engine.type); each
// engine implements it next to its runner (libgran/run/*_runner.cpp). One virtual call per
// quantity per sample; nothing here is on a hot path.
//
// Counts mean the same physical thing on both engines where they can: a "collision" of the
// event-driven engine is a binary collision, of the DEM engine a particle-particle contact that
// formed; a "wall hit" is an instantaneous wall collision or a particle-wall contact that formed;
// the wall impulse is sum m |v_n' - v_n| or the time integral of the wall's normal contact force.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/particles.hpp"
#include "libgran/core/species.hpp"

namespace gran {

template <int D>
class EngineView {
  public:
    virtual ~EngineView() = default;
    // "event_driven" or "dem".
    virtual const char* engine_name() const = 0;
    // Positions and velocities at now() (the run synchronises before every sample).
    virtual const Particles<D>& particles() const = 0;
    // Original (placement) index of the particle stored at k.
    virtual std::uint32_t id(std::size_t k) const = 0;
    virtual double now() const = 0;
    virtual double species_inertia(std::uint32_t s) const = 0;
    virtual const Vec<D>& gravity() const = 0;
    // Binary collisions, or DEM contacts formed, since the start.
    virtual std::uint64_t collisions() const = 0;
    // Per unordered species pair (index min * ns + max); empty if the engine does not count them.
    virtual const std::vector<std::uint64_t>& pair_collisions() const = 0;
    // Per wall (index 2 * axis + side).
    virtual const std::array<std::uint64_t, 2 * D>& wall_hits() const = 0;
    virtual const std::array<double, 2 * D>& wall_impulse() const = 0;
    std::uint64_t total_wall_hits() const {
        std::uint64_t s = 0;
        for (auto h : wall_hits()) s += h;
        return s;
    }
    // Total kinetic energy (translational + rotational) per particle at now(), in the lab frame.
    double kinetic_energy_per_particle(const SpeciesTable& table) const {
        const auto& p = particles();
        double e = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            e += 0.5 * table.species[s].mass * p.v[i].squaredNorm();
            if (p.rotating()) e += 0.5 * species_inertia(s) * ang_squared<D>(p.w[i]);
        }
        return e / double(p.size());
    }
    // The pair virial of soft contacts at now(), per species s and axis a at [s * D + a]:
    // sum over the grain-grain contacts of (r_i - r_j)_a F_a, half to each partner's species.
    // Empty for an engine of binary collisions (their momentum transfer reaches observables as
    // collision records).
    virtual std::vector<double> contact_virial() const { return {}; }
    // Surface position of a wall at time t (index 2 * axis + side), e.g. a vibrating base.
    virtual double wall_position(int code, double t) const = 0;
    // Mean surface position of a wall over one period of its motion from t (period <= 0: at t),
    // e.g. the mean height of a vibrating base that heights are measured from.
    double mean_wall_position(int code, double t, double period) const {
        if (!(period > 0)) return wall_position(code, t);
        constexpr int k = 64;
        double x = 0;
        for (int i = 0; i < k; ++i) x += wall_position(code, t + period * i / k) / k;
        return x;
    }
};

}  // namespace gran
