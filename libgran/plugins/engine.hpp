#pragma once
// Engines as plugins of the same registry (`engine.type`): an engine declares its numerical
// settings (the `engine` section's keys), checks at load that it can run a scene (every refusal
// is a SceneError naming file, line and key), and builds the runner that advances the scene's
// state for the run loop (libgran/run/). The engines themselves are in libgran/engines/; their
// runners and registrations in libgran/run/*_runner.cpp.
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "libgran/core/registry.hpp"
#include "libgran/core/wall_motion.hpp"
#include "libgran/plugins/driver.hpp"
#include "libgran/plugins/engine_view.hpp"
#include "libgran/plugins/observable.hpp"
#include "libgran/plugins/run_cost.hpp"
#include "libgran/run/result_sink.hpp"

namespace gran {

struct Scene;  // libgran/scene/scene.hpp

template <int D>
using DriverList = std::vector<std::unique_ptr<Driver<D>>>;
template <int D>
using ObservableList = std::vector<std::unique_ptr<Observable<D>>>;

// How an advance ended: at its target, interrupted (SIGINT/SIGTERM), with no events left, or
// stopped by the watchdog (EngineRunner::failure() says why).
enum class Advance { Reached, Interrupted, Stalled, Watchdog };

// An engine in the run loop: advances to a time or a collision count, keeps the drivers' kicks and
// the watchdog's windows, and reports its performance.
template <int D>
class EngineRunner {
  public:
    virtual ~EngineRunner() = default;
    virtual const char* work_unit() const = 0;  // "events", "steps"
    virtual const EngineView<D>& view() const = 0;
    virtual double now() const = 0;
    virtual std::uint64_t collisions() const = 0;
    virtual std::uint64_t work() const = 0;
    // Up to time t_target, total collision count c_target or total work (events, steps) w_target,
    // whichever comes first.
    virtual Advance advance(double t_target, std::uint64_t c_target, std::uint64_t w_target,
                            const std::atomic<bool>* interrupt) = 0;
    // Positions and velocities current at now() (before observables read them).
    virtual void synchronize() = 0;
    virtual const std::string& failure() const = 0;
    // The engine's own counters and figures under /performance (and the summary's performance).
    virtual void write_performance(ResultGroup& perf, double cpu) const = 0;
    // The engine's whole dynamic state (particles and their clocks, pending events, cells,
    // neighbour lists and contact history, counters, watchdog windows), saved or loaded
    // (libgran/core/state_archive.hpp) between two events or steps: the loaded runner continues
    // bit for bit as the saved one would have.
    virtual void checkpoint(StateArchive& ar) = 0;
};

// What a scene's drivers and observables ask of an engine, without the dimension: the engine's
// check at load refuses what it cannot do, at the key that asked for it.
struct EngineDemands {
    struct Wall {
        std::size_t driver = 0;  // index in scene.drivers
        std::string partner;
        int axis = 0, side = 0;
        WallMotion motion;
        std::string motion_key;
        bool replaces_contact = false;  // a rule instead of a contact (a thermal wall)
    };
    std::vector<Wall> walls;
    std::vector<std::size_t> kick_drivers;           // drivers with kick events
    std::vector<double> first_kicks;                 // their first kick times (~ the interval)
    std::vector<std::size_t> collision_observables;  // observables asking for collision records
};

struct EnginePlugin : PluginInfo {
    bool binary_collisions = true;  // makes binary collision records (SceneInfo)
    // Rotating grains start with Maxwellian angular velocities at the initial temperature (else
    // at rest in rotation; the engine allocates them).
    bool thermal_initial_spin = true;
    std::function<void(const Scene&, const EngineDemands&)> check;
    // Optional: the work a scene will take and a line saying so, for `gran check` (the check above
    // refuses what could never finish).
    std::function<RunCost(const Scene&, const EngineDemands&)> estimate;
    std::function<std::unique_ptr<EngineRunner<2>>(const Scene&, DriverList<2>&,
                                                   ObservableList<2>&)>
        make2;
    std::function<std::unique_ptr<EngineRunner<3>>(const Scene&, DriverList<3>&,
                                                   ObservableList<3>&)>
        make3;

    template <int D>
    std::unique_ptr<EngineRunner<D>> make(const Scene& s, DriverList<D>& d,
                                          ObservableList<D>& o) const {
        if constexpr (D == 2) {
            return make2(s, d, o);
        } else {
            return make3(s, d, o);
        }
    }
};

// Sets make2 and make3 to build Runner<2> and Runner<3> (each constructible from the scene, the
// drivers and the observables).
template <template <int> class Runner>
void set_runner(EnginePlugin& p) {
    p.make2 = [](const Scene& s, DriverList<2>& d, ObservableList<2>& o) {
        return std::unique_ptr<EngineRunner<2>>(std::make_unique<Runner<2>>(s, d, o));
    };
    p.make3 = [](const Scene& s, DriverList<3>& d, ObservableList<3>& o) {
        return std::unique_ptr<EngineRunner<3>>(std::make_unique<Runner<3>>(s, d, o));
    };
}

using EngineRegistry = Registry<EnginePlugin>;

// Introduction of the engines in docs/scene-reference.md (`gran list --markdown`).
inline constexpr const char* kEnginesDescription =
    R"md(
`engine.type` chooses the engine; the rest of the `engine` section are its numerical settings
(contact physics is in `interactions`). The same scene runs on either engine where the physics
allows: a frictionless soft-contact law runs on `event_driven` as its hard limit.)md";

}  // namespace gran
