#pragma once
// One simulation of one scene: the object the command-line program, the tests, and (next) the
// Python module and checkpoints stand on. Scene in (validated by load_scene / parse_scene), engine
// chosen by the scene, advance by time, collisions or engine work, read-only views of the
// particles and of the observables' state.
//
//   gran::Simulation sim(gran::load_scene("scene.yaml"));
//   sim.advance({.time = 10});              // to t = 10
//   sim.advance({.collisions = 1000});      // 1000 more collisions
//   const std::vector<double> r = sim.positions();   // N x D, placement order
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "libgran/plugins/engine.hpp"
#include "libgran/scene/scene.hpp"

namespace gran {

// The parts of a running simulation of dimension D, for library code that works on them (the run
// loop writes the drivers', observables' and engine's results).
template <int D>
struct SimulationState {
    DriverList<D> drivers;
    ObservableList<D> observables;
    std::unique_ptr<EngineRunner<D>> runner;
};

// How far to advance: to a simulated time, by a number of collisions, or by a number of the
// engine's work units (events, steps); the first reached ends the advance. All absent: nothing.
struct Until {
    double time = std::numeric_limits<double>::infinity();  // absolute
    std::uint64_t collisions = 0;                           // more collisions (0: no limit)
    std::uint64_t work = 0;                                 // more events / steps (0: no limit)
};

class Simulation {
  public:
    // Places the particles and builds drivers, observables and the engine (SceneError for a
    // placement that fails). `interrupt` (optional) stops an advance when it becomes true.
    explicit Simulation(Scene scene, const std::atomic<bool>* interrupt = nullptr);
    ~Simulation();
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    const Scene& scene() const { return *scene_; }
    int dimension() const { return scene_->dimension; }
    std::size_t size() const { return scene_->species.total_count(); }
    double time() const;
    std::uint64_t collisions() const;
    std::uint64_t work() const;
    const char* work_unit() const;  // "events" or "steps"

    // Advances; the state is current at time() afterwards (positions and velocities synchronised).
    Advance advance(const Until& until);
    // Why the watchdog stopped the last advance (empty: it did not).
    const std::string& failure() const;

    // Copies in placement order (particle k is the k-th placed, whatever the engine's storage):
    // N x D row-major positions and velocities, N species indices, N x (1 in 2D, 3 in 3D)
    // angular velocities (empty unless the grains rotate).
    std::vector<double> positions() const;
    std::vector<double> velocities() const;
    std::vector<std::uint32_t> species() const;
    std::vector<double> angular_velocities() const;

    // Samples every observable at the current state (`measuring`: a measurement sample;
    // `expected_samples`: how many the measurement will take, for observables that size buffers).
    void sample(bool measuring, std::size_t expected_samples);

    // Typed access to drivers, observables and engine, for library code of that dimension.
    template <int D>
    SimulationState<D>& state();
    template <int D>
    const SimulationState<D>& state() const;

  private:
    struct Base;
    template <int D>
    struct Impl;
    std::unique_ptr<Scene> scene_;  // stable address: runners and plugins refer to it
    const std::atomic<bool>* interrupt_ = nullptr;
    std::unique_ptr<Base> impl_;
};

}  // namespace gran
