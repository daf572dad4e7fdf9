#pragma once
// What a DEM run actually achieves for one kind of contact: an isolated head-on collision run on
// the DEM engine itself (same law, parameters and time step), reported next to what was requested
// (issue #5: "the run reports dt/t_c and the restitution actually achieved in isolated
// collisions"). The closed forms are those of species/contact_laws.hpp (linear: t_c = pi / omega_d,
// e = exp(-zeta pi / sqrt(1 - zeta^2))).
#include <string>

#include "libgran/core/species.hpp"
#include "libgran/plugins/law.hpp"

namespace gran {

struct DemProbeResult {
    double requested_restitution = 1;
    double restitution = 1;           // -(normal relative velocity after) / (before)
    double closed_form_duration = 0;  // t_c of the resolved contact
    double duration = 0;              // measured: steps with overlap x dt
    double dt_over_tc = 0;            // dt / closed-form t_c
};

// Grain-grain: species a and b of `table` meet head-on at relative speed `speed`.
// Throws std::invalid_argument (from the engine) for an impossible dt.
template <int D>
DemProbeResult probe_pair_collision(const SpeciesTable& species, const ContactTable& table,
                                    std::size_t a, std::size_t b, double speed, double dt);

// Grain-wall: species s hits a static wall of wall partner `wall` at normal speed `speed`.
template <int D>
DemProbeResult probe_wall_collision(const SpeciesTable& species, const ContactTable& table,
                                    std::size_t s, std::size_t wall, double speed, double dt);

}  // namespace gran
