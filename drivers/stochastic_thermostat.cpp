// Homogeneous stochastic thermostat (white-noise heating): at every interval dt all particles
// receive independent Gaussian velocity kicks. The continuum limit is the Fokker–Planck term
// (xi_i^2 / 2) Laplacian_v f_i of the heated Boltzmann/Enskog equation (van Noije & Ernst, Granular
// Matter 1, 57 (1998); Barrat & Trizac, Granular Matter 4, 57 (2002)).
//
// Noise conventions (key `noise`):
//  - equal_velocity_variance: every particle gets velocity kicks of the same variance
//    xi^2 dt per component, whatever its mass (m_i dv = F dt with <F F> proportional to m_i^2).
//    This is the convention of the homogeneously heated mixture studies cited above (Barrat &
//    Trizac 2002, Granular Matter; also Pagnani, Marconi & Puglisi PRE 66, 051304 (2002)).
//  - equal_force_variance: every particle feels random forces of the same variance, so its
//    velocity kick has variance strength * dt / m_i^2 per component (lighter particles are
//    shaken harder).
// The mass-weighted mean kick is removed (key `remove_drift`) so that total momentum stays
// zero: otherwise the centre of mass performs an undamped random walk whose kinetic energy grows
// linearly in time. The correction changes each kick by O(1/N).
#include <fmt/format.h>

#include <cmath>

#include "libgran/core/kinetic_theory.hpp"
#include "libgran/core/random.hpp"
#include "libgran/plugins/driver.hpp"
#include "libgran/study/knob.hpp"

namespace gran {
namespace {

template <int D>
class StochasticThermostat final : public Driver<D> {
  public:
    StochasticThermostat(const Params& p, const SceneInfo& info)
        : interval_(p.has("interval") ? p.real("interval") : default_interval(info)),
          strength_(p.real("strength")),
          equal_force_(p.str("noise") == "equal_force_variance"),
          remove_drift_(p.boolean("remove_drift")),
          next_(interval_),
          rng_(make_rng(info.seed + 1000003ull * info.index, Stream::Driver)) {
        // Kicks touch every particle and reschedule every event: an interval many orders below
        // the mean free time makes a run that cannot finish (1e-300 does not even advance the
        // time), refused here rather than left to run.
        const double mean_free_time = 8.0 * default_interval(info);
        if (p.has("interval") && interval_ < kMinIntervalOverMeanFreeTime * mean_free_time) {
            p.fail("interval",
                   fmt::format("{:.3g} is below {:.0e} of the mean free time at the initial "
                               "temperature ({:.3g}): over {:.0e} kicks, each touching every "
                               "particle, per collision; use an interval well below the mean free "
                               "time but not this far (default: {:.3g})",
                               interval_, kMinIntervalOverMeanFreeTime, mean_free_time,
                               1 / kMinIntervalOverMeanFreeTime, mean_free_time / 8));
        }
    }
    static constexpr double kMinIntervalOverMeanFreeTime = 1e-6;

    double next_kick() const override { return next_; }

    void kick(Particles<D>& p, const SpeciesTable& species) override {
        const std::size_t n = p.size();
        kicks_.resize(n);
        Vec<D> dp = Vec<D>::Zero();
        double mass = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double m = species.species[p.species[i]].mass;
            const double sd = equal_force_ ? std::sqrt(strength_ * interval_) / m
                                           : std::sqrt(strength_ * interval_);
            for (int a = 0; a < D; ++a) kicks_[i][a] = sd * gaussian(rng_);
            dp += m * kicks_[i];
            mass += m;
        }
        const Vec<D> drift = remove_drift_ ? Vec<D>(dp / mass) : Vec<D>::Zero();
        double de = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double m = species.species[p.species[i]].mass;
            const Vec<D> v_new = p.v[i] + kicks_[i] - drift;
            de += 0.5 * m * (v_new.squaredNorm() - p.v[i].squaredNorm());
            p.v[i] = v_new;
        }
        injected_ += de;
        ++count_;
        next_ += interval_;
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("stochastic_thermostat");
        ar.io(next_);
        ar.io(rng_);
        ar.io(injected_);
        ar.io(count_);
    }

    void write(ResultGroup& g) const override {
        g.value("kicks", count_);
        g.value("interval", interval_, "time");
        g.value("injected_energy", injected_, "energy");
    }

    // 1/8 of the Enskog mean free time of the mixture at the initial temperature: close enough to
    // white noise for the tested temperature ratios (docs/physics.md), and ~4 rescheduling passes
    // per collision per particle.
    static double default_interval(const SceneInfo& info) {
        const SpeciesTable& t = *info.species;
        double volume = 1;
        for (double l : info.box_length) volume *= l;
        std::vector<double> sigma, x;
        double phi = 0;
        const double n_total = double(t.total_count());
        for (const auto& s : t.species) {
            sigma.push_back(s.diameter);
            x.push_back(double(s.count) / n_total);
            phi += double(s.count) * theory::unit_ball_volume(D) * std::pow(s.diameter, D) / volume;
        }
        const theory::MixtureContactValues chi(D, phi, sigma, x);
        double omega = 0;  // mean collision frequency per particle
        const double T = info.initial_temperature;
        for (std::size_t a = 0; a < t.size(); ++a) {
            for (std::size_t b = 0; b < t.size(); ++b) {
                const double sab = 0.5 * (sigma[a] + sigma[b]);
                omega +=
                    x[a] * theory::enskog_pair_collision_frequency(
                               D, double(t.species[b].count) / volume, sab, chi(sigma[a], sigma[b]),
                               T, t.species[a].mass, T, t.species[b].mass);
            }
        }
        return 1.0 / (8.0 * omega);
    }

  private:
    double interval_;
    double strength_;
    bool equal_force_;
    bool remove_drift_;
    double next_;
    Rng rng_;
    std::vector<Vec<D>> kicks_;
    double injected_ = 0;
    std::uint64_t count_ = 0;
};

const char* const kDescription =
    R"md(
Homogeneous white-noise heating: every `interval`, every particle receives an independent
Gaussian velocity kick. Keep `interval` well below the mean free time; the summary reports the
reschedules per collision per particle.

Noise conventions (`noise`, docs/physics.md): with `equal_velocity_variance` the velocity-kick
variance per component is strength * interval, whatever the mass (`strength` in velocity^2/time);
with `equal_force_variance` every particle feels random forces of the same variance, so its kick has
variance strength * interval / m^2 (`strength` in force^2 * time; lighter particles are shaken
harder). `remove_drift` subtracts the mass-weighted mean kick (a change of O(1/N) per kick): without
it the centre of mass performs an undamped random walk whose kinetic energy grows linearly in
time.)md";

const bool registered = register_plugin<Driver, StochasticThermostat>(
    "stochastic_thermostat",
    "homogeneous white-noise heating: Gaussian velocity kicks to every particle at a fixed "
    "interval",
    {optional(real("interval", "", "time",
                   "time between kicks (default: 1/8 of the Enskog mean free time at the initial "
                   "temperature); keep it well below the mean free time",
                   0, 1e308, true)),
     real("strength", "1",
          "velocity^2/time (equal_velocity_variance) or force^2*time (equal_force_variance)",
          "noise strength: velocity-kick variance per component is strength*interval "
          "(divided by m_i^2 for equal_force_variance)",
          0, 1e308, true),
     choice("noise", "equal_velocity_variance", {"equal_velocity_variance", "equal_force_variance"},
            "noise amplitude convention (see docs/scene-reference.md)"),
     boolean("remove_drift", "true",
             "subtract the mass-weighted mean kick so total momentum stays zero")},
    kDescription);

// `gran tradeoff`'s knob of the thermostat (libgran/study/knob.hpp): the time between kicks, the
// discretisation of the white noise, on the first stochastic_thermostat of the scene.
KnobOutcome kick_interval(const KnobContext& c) {
    const YAML::Node drivers = c.resolved["drivers"];
    for (std::size_t i = 0; drivers && i < drivers.size(); ++i) {
        if (drivers[i]["type"] && drivers[i]["type"].Scalar() == "stochastic_thermostat") {
            return knobs::scaled("kick_interval", "time between thermostat kicks",
                                 fmt::format("drivers.{}.interval", i),
                                 knobs::real_at(drivers[i], "interval"), {4, 2, 1, 0.5});
        }
    }
    return "no stochastic_thermostat driver";
}

const bool registered_knob = register_knob(
    "kick_interval", 40, "stochastic_thermostat interval x 4, 2, 1, 1/2", kick_interval);

}  // namespace
}  // namespace gran
