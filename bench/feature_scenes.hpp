#pragma once
// The scenes of `gran_bench_features`: the bare monodisperse smooth elastic gas in a periodic box,
// and the same scene with one feature added (a law, a driver, an observable, trajectory output),
// each compared with a named baseline scene that differs from it by that feature alone (walls
// against the bare gas, gravity against walls, a vibrating floor against gravity, ...). Scenes are
// YAML documents, run by the same code as `gran run`.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

namespace gran::bench {

struct Geometry {
    int dim = 2;
    double phi = 0.1;
    std::size_t n = 10000;
    double box_length() const {  // edge of the cubic box at this packing fraction (diameter 1)
        const double vd = dim == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
        return std::pow(double(n) * vd / phi, 1.0 / dim);
    }
    const char* last_axis() const { return dim == 2 ? "y" : "z"; }
};

// Run length of every scene: the event-driven scenes in collisions per particle (2 N_coll / N),
// the DEM scenes in time; `samples` samples in the measurement (observables pay per sample).
struct RunLength {
    double ed_equilibration = 20;
    double ed_measurement = 100;
    double dem_measurement = 1;  // [time]: 5000 steps (dt = contact_time / 50)
    int samples = 100;
};

struct Feature {
    std::string key;       // short name (CSV, --only)
    std::string what;      // what is added, for the table
    std::string baseline;  // key of the scene it is compared with ("" for the bare scenes)
    std::string engine;    // event_driven or dem
    // Turns the baseline scene into this one.
    std::function<void(YAML::Node&, const Geometry&)> add;
};

// Collision frequency per particle of the bare gas (measured), used to balance the thermostat
// against inelastic cooling at T = 1.
struct Calibration {
    double omega = 1;
};

YAML::Node bare_scene(const std::string& engine, const Geometry& g, const RunLength& run);
std::vector<Feature> features(const Calibration& cal);
// The scene of feature `key`: the bare scene with the additions of its baseline chain.
YAML::Node feature_scene(const std::vector<Feature>& all, const std::string& key, const Geometry& g,
                         const RunLength& run);

}  // namespace gran::bench
