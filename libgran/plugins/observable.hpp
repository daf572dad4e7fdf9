#pragma once
// Measurements. An observable is sampled at the run's sampling times and may subscribe to
// collisions (collision records are built only when some observable does). Results go through a
// ResultGroup to /observables/<name> in the HDF5 file and to the run summary.
#include <cmath>
#include <cstdint>
#include <string>

#include "libgran/core/collision_record.hpp"
#include "libgran/core/registry.hpp"
#include "libgran/core/state_archive.hpp"
#include "libgran/core/statistics.hpp"
#include "libgran/plugins/engine_view.hpp"
#include "libgran/plugins/scene_info.hpp"
#include "libgran/run/result_sink.hpp"

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
    std::int64_t step = 0;  // the engine's events or steps so far (H5MD `step` of time series)
    // The measurement has no fixed length (a run with a target): expected_samples is that of the
    // next look only (observables/block_clock.hpp).
    bool open_ended = false;
};

template <int D>
class Observable {
  public:
    virtual ~Observable() = default;
    // Non-null to receive every collision (costs a record per collision; only when asked). Only an
    // engine with binary collisions makes collision records (SceneInfo::binary_collisions): a scene
    // that needs them on another engine is refused.
    virtual CollisionSink<D>* collision_sink() { return nullptr; }
    virtual void sample(const SampleContext<D>& ctx) = 0;
    // Results under /observables/<name> and the summary's observables.<name>
    // (libgran/run/result_sink.hpp).
    virtual void write(ResultGroup& out) const = 0;
    // Every member that changes during the run (accumulators, series, counters, random streams),
    // in one function for saving and loading (libgran/core/state_archive.hpp): a checkpoint
    // restores it and the resumed run must continue bit for bit. Members set from the scene at
    // construction need not be listed.
    virtual void checkpoint(StateArchive& ar) = 0;
};

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

using ObservableRegistry = Registry<DimensionalPlugin<Observable>>;

// Introduction of the observables in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kObservablesDescription =
    R"md(
Each entry of the scene's `observables` list is `{type: <name>, ...parameters}`; an optional
`name` sets the result group `/observables/<name>` (default: the type). Scalars are datasets with
`error` and `unit` attributes, and `n_eff` (effectively independent samples), `tau_int` (integrated
autocorrelation time in samples), `samples` and `converged` (0: no blocking plateau, the error is a
lower bound); the summary gives `{value, error, unit, n_eff}` (docs/physics.md, "Error bars").)md";

inline const char* component_name(int a) {
    return a == 0 ? "x" : (a == 1 ? "y" : "z");
}

}  // namespace gran
