// The knobs of every scene for `gran tradeoff` (libgran/study/knob.hpp): the number of particles
// at the same density (finite-size effects) and the length of the measurement (statistical
// error).
#include <fmt/format.h>

#include <cmath>

#include "libgran/study/knob.hpp"

namespace gran {
namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;

// How the scene gives its particle number and its density, and what N scales with them.
struct SizeOf {
    bool by_fraction = false;  // box.packing_fraction: the box follows the particle number
    bool by_total = false;     // `particles` (else the species' counts)
    YAML::Node species, lengths, periodic;
    int n_periodic = 0;
};

SizeOf size_of(const KnobContext& c) {
    const YAML::Node& raw = c.raw;
    const YAML::Node& r = c.resolved;
    SizeOf s;
    s.by_fraction = (raw["box"] && raw["box"]["packing_fraction"]) ||
                    knobs::has_set(c.request.sets, "box.packing_fraction");
    s.by_total = bool(raw["particles"]) || knobs::has_set(c.request.sets, "particles");
    s.species.reset(r["species"]);
    s.lengths.reset(r["box"]["lengths"]);
    s.periodic.reset(r["box"]["periodic"]);
    for (std::size_t a = 0; s.periodic && a < s.periodic.size(); ++a)
        s.n_periodic += s.periodic[a].as<bool>() ? 1 : 0;
    return s;
}

// The particle counts at fraction f of the scene's; false when too few particles are left.
bool scale_counts(const SizeOf& s, const YAML::Node& r, double f, Sets& set) {
    if (s.by_total) {
        const long n = std::lround(f * r["particles"].as<double>());
        set.emplace_back("particles", std::to_string(n));
        return n >= 8;
    }
    bool enough = true;
    for (std::size_t k = 0; k < s.species.size(); ++k) {
        const long n = std::lround(f * s.species[k]["count"].as<double>());
        enough = enough && n >= 4;
        set.emplace_back(fmt::format("species.{}.count", k), std::to_string(n));
    }
    return enough;
}

// The same density at fraction f of the particles: scale the periodic (lateral) lengths, or
// every length of a closed box.
void scale_lengths(const SizeOf& s, double f, Sets& set) {
    const int dims = int(s.lengths.size());
    const int scaled = s.n_periodic > 0 ? s.n_periodic : dims;
    const double g = std::pow(f, 1.0 / scaled);
    for (int a = 0; a < dims; ++a) {
        if (s.n_periodic > 0 && !s.periodic[std::size_t(a)].as<bool>()) continue;
        set.emplace_back(fmt::format("box.lengths.{}", a),
                         knobs::number(s.lengths[std::size_t(a)].as<double>() * g));
    }
}

KnobOutcome particle_number(const KnobContext& c) {
    Knob k{"N", "number of particles at the same density (finite-size effects)", {}, -1};
    const SizeOf s = size_of(c);
    for (double f : {0.125, 0.25, 0.5, 1.0}) {
        KnobLevel lv{knobs::fraction_label(f), {}};
        if (f != 1) {
            if (!scale_counts(s, c.resolved, f, lv.set)) continue;
            if (!s.by_fraction) scale_lengths(s, f, lv.set);
        }
        if (f == 1) k.base = int(k.levels.size());
        k.levels.push_back(lv);
    }
    if (k.levels.size() > 1) return k;
    return "too few particles to scale down";
}

KnobOutcome measurement(const KnobContext& c) {
    const double m = knobs::real_at(c.resolved["run"], "measurement");
    Knob k{"measurement", "length of the measurement (statistical error)", {}, -1};
    for (double f : {0.125, 0.25, 0.5, 1.0}) {
        if (f == 1) k.base = int(k.levels.size());
        k.levels.push_back({knobs::fraction_label(f),
                            f == 1 ? Sets{} : Sets{{"run.measurement", knobs::number(m * f)}}});
    }
    return k;
}

const bool registered_n = register_knob(
    "N", 50, "particles x 1/8, 1/4, 1/2, 1 at the same density (periodic lengths scaled)",
    particle_number);
const bool registered_measurement =
    register_knob("measurement", 60, "run.measurement x 1/8, 1/4, 1/2, 1", measurement);

}  // namespace
}  // namespace gran
