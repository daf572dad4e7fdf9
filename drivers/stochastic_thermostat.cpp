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
//
// When the kicks come (key `kicks`):
//  - every_interval: every particle at once, every `interval`. Each kick changes every velocity,
//    so the engine re-predicts every event: 8 passes over all particles per mean free time at the
//    default interval, 2-6x the cost of the unheated gas.
//  - at_collisions: each particle is kicked right after each of its collisions with the noise
//    accumulated since its previous kick, variance rate * (t - t_last) per component
//    (libgran/plugins/collision_noise.hpp): the same injected variance per unit time, applied
//    where the particle's next event is predicted anyway. The mean kick of the particles is
//    removed every `kDriftIntervalsInMeanFreeTimes` mean free times by one pass over all.
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
        : at_collisions_(p.str("kicks") == "at_collisions"),
          interval_(p.has("interval") ? p.real("interval") : default_interval(info)),
          strength_(p.real("strength")),
          equal_force_(p.str("noise") == "equal_force_variance"),
          remove_drift_(p.boolean("remove_drift")),
          next_(interval_),
          rng_(make_rng(info.seed + 1000003ull * info.index, Stream::Driver)) {
        if (at_collisions_) {
            set_up_collision_noise(p, info);
            return;
        }
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
    CollisionNoise* collision_noise() override { return at_collisions_ ? &noise_ : nullptr; }

    void kick(Particles<D>& p, const SpeciesTable& species) override {
        if (at_collisions_) {
            remove_noise_drift(p, species);
            return;
        }
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
        if (at_collisions_) ar.io(noise_);
    }

    void write(ResultGroup& g) const override {
        g.text("kicks_at", at_collisions_ ? "at_collisions" : "every_interval");
        if (at_collisions_) {
            g.value("kicks", noise_.kicks);  // particle kicks
            g.value("drift_removals", count_);
            g.value("injected_energy", injected_ + noise_.injected_energy, "energy");
            return;
        }
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
    // Mean free times between two removals of the kicks' mean momentum (kicks: at_collisions):
    // each removal is one pass over all particles (~1% of the cost of the collisions in between),
    // and the centre of mass drifts meanwhile by a velocity of variance ~ 10 xi^2 t_mf / N.
    static constexpr double kDriftIntervalsInMeanFreeTimes = 10;

    void set_up_collision_noise(const Params& p, const SceneInfo& info) {
        if (p.has("interval")) {
            p.fail("interval",
                   "with kicks: at_collisions each particle is kicked at its own collisions; "
                   "`interval` sets the common clock of kicks: every_interval");
        }
        if (info.species->total_count() < 2) {
            p.fail("kicks",
                   "at_collisions needs collisions, and one particle has none: use kicks: "
                   "every_interval");
        }
        for (const auto& s : info.species->species) {
            noise_.variance_rate.push_back(equal_force_ ? strength_ / (s.mass * s.mass)
                                                        : strength_);
            noise_.mass.push_back(s.mass);
        }
        noise_.rng = rng_;
        interval_ = kDriftIntervalsInMeanFreeTimes * 8.0 * default_interval(info);
        next_ = remove_drift_ ? interval_ : kInf;
    }

    // Subtracts the kicks' mean momentum since the last removal from every particle (total
    // momentum of the kicks back to zero, as every_interval does at each kick).
    void remove_noise_drift(Particles<D>& p, const SpeciesTable& species) {
        double mass = 0;
        for (std::size_t i = 0; i < p.size(); ++i) mass += species.species[p.species[i]].mass;
        Vec<D> drift;
        for (int a = 0; a < D; ++a) drift[a] = noise_.momentum[std::size_t(a)] / mass;
        double de = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double m = species.species[p.species[i]].mass;
            de += m * (0.5 * drift.squaredNorm() - p.v[i].dot(drift));
            p.v[i] -= drift;
        }
        injected_ += de;
        noise_.momentum = {};
        ++count_;
        next_ += interval_;
    }

    bool at_collisions_;
    CollisionNoise noise_;
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
time.

`kicks: at_collisions` kicks each particle right after each of its collisions instead, with the
noise accumulated since its previous kick (variance strength * elapsed time per component): the
same energy injection per unit time without re-predicting every event at every kick, so a heated
gas costs about what the unheated one does. `interval` does not apply; with `remove_drift` the mean
momentum of the kicks is removed every 10 mean free times. Its accuracy against every_interval
is measured in docs/physics.md.)md";

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
             "subtract the mass-weighted mean kick so total momentum stays zero"),
     choice("kicks", "every_interval", {"every_interval", "at_collisions"},
            "when the kicks come: every particle every `interval`, or each particle right after "
            "each of its collisions with the noise accumulated since its previous kick (no "
            "re-prediction of every event; see docs/physics.md)")},
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
