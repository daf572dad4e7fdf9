#pragma once
// Measurements. An observable is sampled at the run's sampling times and may subscribe to
// collisions (collision records are built only when some observable does). Results go to
// /observables/<name> in the HDF5 file, scalars as datasets with `error` and `unit` attributes.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "libgran/core/h5.hpp"
#include "libgran/core/registry.hpp"
#include "libgran/core/statistics.hpp"
#include "libgran/engines/engine_view.hpp"
#include "libgran/scene/scene_info.hpp"

namespace gran {

// At a sample every particle is brought to ctx.time (positions and velocities current): read
// particles().r and .v directly. (Per-particle clocks are internal, relative to a moving origin.)
template <int D>
struct SampleContext {
    double time = 0;
    bool measuring = false;            // false during equilibration
    std::size_t expected_samples = 0;  // samples the measurement phase will take
    const EngineView<D>& engine;       // either engine (libgran/engine_view.hpp)
    const SpeciesTable& species;
};

template <int D>
class Observable {
  public:
    virtual ~Observable() = default;
    // Non-null to receive every collision (costs a record per collision; only when asked). Only the
    // event-driven engine makes collision records: a scene that needs them on the dem engine is
    // refused.
    virtual CollisionSink<D>* collision_sink() { return nullptr; }
    virtual void sample(const SampleContext<D>& ctx) = 0;
    virtual void write(h5::Group& group, YAML::Node& summary) const = 0;
};

// Writes a scalar estimate as a dataset with attributes `error`, `unit`, and what the error rests
// on (libgran/statistics.hpp): `n_eff` (effectively independent samples), `tau_int` (integrated
// autocorrelation time in samples), `samples`, `converged` (0: no blocking plateau, the error is a
// lower bound); NaN n_eff/tau_int when unknown. The summary node stays short:
// {value, error, unit, n_eff}, plus `converged: false` only when the error is a lower bound.
inline void write_estimate(h5::Group& g, const std::string& name, const Estimate& e,
                           const std::string& unit, YAML::Node& summary) {
    g.write_scalar(name, e.value);
    g.attr_on(name, "error", e.error);
    g.attr_on(name, "unit", unit);
    g.attr_on(name, "n_eff", e.n_eff);
    g.attr_on(name, "tau_int", e.tau_int);
    g.attr_on(name, "samples", static_cast<std::int64_t>(e.samples));
    g.attr_on(name, "converged", static_cast<std::int64_t>(e.converged ? 1 : 0));
    YAML::Node s;
    s["value"] = e.value;
    s["error"] = e.error;
    if (!unit.empty()) s["unit"] = unit;
    if (std::isfinite(e.n_eff)) s["n_eff"] = std::round(e.n_eff);
    if (!e.converged) s["converged"] = false;
    summary[name] = s;
}

// Mass-weighted mean velocity: temperatures are defined from velocities relative to it.
template <int D>
Vec<D> centre_of_mass_velocity(const Particles<D>& p, const SpeciesTable& table) {
    Vec<D> momentum = Vec<D>::Zero();
    double mass = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double m = table.species[p.species[i]].mass;
        momentum += m * p.v[i];
        mass += m;
    }
    return momentum / mass;
}

inline const char* component_name(int a) {
    return a == 0 ? "x" : (a == 1 ? "y" : "z");
}

// Introduction of the observables in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kObservablesDescription =
    R"md(
Each entry of the scene's `observables` list is `{type: <name>, ...parameters}`; an optional
`name` sets the result group `/observables/<name>` (default: the type). Scalars are datasets with
`error` and `unit` attributes, and `n_eff` (effectively independent samples), `tau_int` (integrated
autocorrelation time in samples), `samples` and `converged` (0: no blocking plateau, the error is a
lower bound); the summary gives `{value, error, unit, n_eff}` (docs/physics.md, "Error bars").)md";

}  // namespace gran
