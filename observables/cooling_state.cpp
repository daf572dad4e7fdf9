// The homogeneous cooling state (HCS) of a freely cooling gas, measured directly (issue 16).
//
// In free cooling the temperature falls without bound (Haff's law), so time averages of T mix
// every temperature of the run; what is stationary in the scaling state are scale-free quantities
// as functions of the collisions per particle tau = 2 N_coll / N (the number of collisions a
// particle has had; tau = integral of the collision frequency, the natural scaled time of the
// HCS): the temperature ratios gamma_s = T_s / T_ref, the Sonine coefficients a2_s, and the
// cooling rate per collision zeta* = -d ln T / d tau (Gaussian, one species:
// (1 - alpha^2) / d; Brilliantov & Poeschel 2004). This observable records them at every sample,
// finds the end of the transient (MSER-5 truncation of each series, libgran/run/equilibration.hpp),
// watches the longest wavelengths for the breakdown of homogeneity (the shear instability and
// clustering: the density mode |rho_k|^2 / N and the momentum mode |j_k|^2 / sum m^2 c^2 at
// k = 2 pi / L, both about 1 in a homogeneous gas), and averages over the scaling state between
// the two. Velocities are taken about the centre-of-mass velocity.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "libgran/run/equilibration.hpp"

namespace gran {
namespace {

template <int D>
class CoolingState final : public Observable<D> {
  public:
    CoolingState(const Params& p, const SceneInfo& info)
        : table_(*info.species), threshold_(p.real("breakdown_threshold")) {
        if (info.driven) {
            p.fail("type",
                   "cooling_state measures a freely cooling gas: remove the scene's drivers "
                   "(the temperatures observable measures a driven steady state)");
        }
        const std::string ref =
            p.has("reference_species") ? p.str("reference_species") : table_.species[0].name;
        ref_ = table_.index_of(ref);
        if (ref_ == table_.size()) p.fail("reference_species", "unknown species '" + ref + "'");
        for (int a = 0; a < D; ++a) length_[std::size_t(a)] = info.box_length[std::size_t(a)];
        const std::size_t ns = table_.size();
        t_.resize(ns);
        a2_.resize(ns);
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const auto& p = ctx.engine.particles();
        const std::size_t ns = table_.size();
        const Vec<D> u = centre_of_mass_velocity<D>(p, table_);
        std::vector<double> sum2(ns, 0), sum4(ns, 0), count(ns, 0);
        double e = 0, n = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            const double c2 = (p.v[i] - u).squaredNorm();
            sum2[s] += c2;
            sum4[s] += c2 * c2;
            count[s] += 1;
            e += table_.species[s].mass * c2;
            n += 1;
        }
        tau_.push_back(2.0 * double(ctx.engine.collisions()) / n);
        time_.push_back(ctx.time);
        steps_.push_back(ctx.step);
        t_mix_.push_back(e / (D * n));
        for (std::size_t s = 0; s < ns; ++s) {
            const double v2 = sum2[s] / count[s];
            t_[s].push_back(table_.species[s].mass * v2 / D);
            a2_[s].push_back(double(D) / (D + 2.0) * (sum4[s] / count[s]) / (v2 * v2) - 1.0);
        }
        const auto [density, momentum] = long_wavelength_modes(p, u);
        density_mode_.push_back(density);
        momentum_mode_.push_back(momentum);
    }

    void write(ResultGroup& g) const override {
        const std::size_t n = tau_.size();
        if (n < 2) return;
        const auto steps = std::span<const std::int64_t>(steps_);
        g.time_series("series/collisions_per_particle", steps, time_, tau_, "");
        const std::string clock = g.path() + "/series/collisions_per_particle";
        auto series = [&](const std::string& name, std::span<const double> v, const char* unit) {
            g.time_series("series/" + name, steps, time_, v, unit, clock);
        };
        series("T_mixture", t_mix_, "energy");
        series("scaled_time", scaled_time(), "time");
        series("cooling_rate", cooling_rates(), "");
        series("density_mode", density_mode_, "");
        series("momentum_mode", momentum_mode_, "");
        for (std::size_t s = 0; s < table_.size(); ++s) {
            const std::string name = table_.species[s].name;
            series(name + "/T", t_[s], "energy");
            series(name + "/sonine_a2", a2_[s], "");
            if (s != ref_) series(name + "/gamma", gamma(s), "");
        }
        write_scaling_state(g);
        g.attr("reference_species", table_.species[ref_].name);
        g.attr("breakdown_threshold", threshold_);
        g.attr("definition",
               "tau = 2 N_coll / N; zeta* = -d ln T / d tau per sample interval; gamma = T_s / "
               "T_ref; velocities about the centre-of-mass velocity");
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("cooling_state");
        ar.io(tau_);
        ar.io(time_);
        ar.io(steps_);
        ar.io(t_mix_);
        ar.io(t_);
        ar.io(a2_);
        ar.io(density_mode_);
        ar.io(momentum_mode_);
    }

  private:
    // |rho_k|^2 / N and the largest |j_k,b|^2 / sum_i m_i^2 c_{i,b}^2 over the axes a of k
    // (k = 2 pi / L_a along a) and the components b of the momentum: 1 on average for
    // independent positions and velocities; their growth is the loss of homogeneity.
    std::pair<double, double> long_wavelength_modes(const Particles<D>& p, const Vec<D>& u) const {
        double density = 0, momentum = 0;
        for (int a = 0; a < D; ++a) {
            const double k = 2 * std::numbers::pi / length_[std::size_t(a)];
            std::complex<double> rho = 0;
            std::array<std::complex<double>, D> j{};
            std::array<double, D> norm{};
            for (std::size_t i = 0; i < p.size(); ++i) {
                const std::complex<double> phase = std::polar(1.0, k * p.r[i][a]);
                const double m = table_.species[p.species[i]].mass;
                const Vec<D> c = p.v[i] - u;
                rho += phase;
                for (int b = 0; b < D; ++b) {
                    j[std::size_t(b)] += m * c[b] * phase;
                    norm[std::size_t(b)] += m * m * c[b] * c[b];
                }
            }
            density = std::max(density, std::norm(rho) / double(p.size()));
            for (int b = 0; b < D; ++b)
                momentum = std::max(momentum, std::norm(j[std::size_t(b)]) / norm[std::size_t(b)]);
        }
        return {density, momentum};
    }

    std::vector<double> gamma(std::size_t s) const {
        std::vector<double> g(tau_.size());
        for (std::size_t k = 0; k < g.size(); ++k) g[k] = t_[s][k] / t_[ref_][k];
        return g;
    }

    // The scaled time s = int sqrt(T(t) / T_1) dt from the first sample (trapezoids; T_1 the
    // mixture temperature then): the time a gas kept at T_1 would take for the same collisions.
    // In Haff's regime s = t0 ln(1 + t / t0): linear in the collisions per particle.
    std::vector<double> scaled_time() const {
        std::vector<double> s(tau_.size(), 0.0);
        for (std::size_t k = 1; k < s.size(); ++k) {
            const double a = std::sqrt(t_mix_[k - 1] / t_mix_[0]),
                         b = std::sqrt(t_mix_[k] / t_mix_[0]);
            s[k] = s[k - 1] + 0.5 * (a + b) * (time_[k] - time_[k - 1]);
        }
        return s;
    }

    // zeta* of each sample interval (the first sample has none: NaN).
    std::vector<double> cooling_rates() const {
        std::vector<double> z(tau_.size(), std::nan(""));
        for (std::size_t k = 1; k < z.size(); ++k) {
            const double dtau = tau_[k] - tau_[k - 1];
            if (dtau > 0) z[k] = -std::log(t_mix_[k] / t_mix_[k - 1]) / dtau;
        }
        return z;
    }

    // The first sample at which a long-wavelength mode exceeds the threshold (n: none).
    std::size_t breakdown() const {
        for (std::size_t k = 0; k < tau_.size(); ++k) {
            if (density_mode_[k] > threshold_ || momentum_mode_[k] > threshold_) return k;
        }
        return tau_.size();
    }

    // End of the transient: the largest MSER-5 truncation over the scale-free series (gamma of
    // every species, a2 of every species, the cooling rate) before the breakdown.
    std::size_t transient_end(std::size_t end) const {
        std::size_t cut = 0;
        // The samples [from, end) of a series; a truncation d of them ends the transient at
        // sample from + d.
        auto consider = [&](std::span<const double> v, std::size_t from = 0) {
            if (end <= from) return;
            const std::size_t d = mser_truncation(v.subspan(from, end - from));
            if (d > 0) cut = std::max(cut, from + d);
        };
        const std::vector<double> z = cooling_rates();  // z[0] is NaN: no interval before it
        consider(z, 1);
        for (std::size_t s = 0; s < table_.size(); ++s) {
            consider(a2_[s]);
            if (s != ref_) {
                const std::vector<double> g = gamma(s);
                consider(g);
            }
        }
        return cut;
    }

    void write_scaling_state(ResultGroup& g) const {
        const std::size_t n = tau_.size(), end = breakdown();
        const std::size_t start = transient_end(end);
        const bool broke = end < n;
        if (broke) {
            spdlog::warn(
                "cooling_state: the homogeneous cooling state broke down at {:.4g} collisions per "
                "particle (a mode at the longest wavelength holds {:.3g} times its homogeneous "
                "share: shear instability or clustering); the scaling-state values average "
                "{:.4g} to {:.4g} only",
                tau_[end], std::max(density_mode_[end], momentum_mode_[end]), tau_[start],
                tau_[end]);
        }
        g.value("transient_end", tau_[std::min(start, n - 1)], "collisions per particle");
        g.value("breakdown", broke ? tau_[end] : std::nan(""), "collisions per particle");
        g.flag("homogeneous", !broke);
        if (end < start + kMinSamplesForError) {
            g.text("scaling_state",
                   "too short: fewer than 8 samples between the transient and "
                   "the breakdown");
            return;
        }
        const auto window = [&](std::span<const double> v) {
            return v.subspan(start, end - start);
        };
        ResultGroup sg = g.group("scaling_state");
        // zeta*: the fall of ln T over the window per collision, a ratio of sums.
        std::vector<double> dlog, dtau;
        for (std::size_t k = start + 1; k < end; ++k) {
            dlog.push_back(-std::log(t_mix_[k] / t_mix_[k - 1]));
            dtau.push_back(tau_[k] - tau_[k - 1]);
        }
        sg.estimate("cooling_rate", ratio_of_means(dlog, dtau), "");
        for (std::size_t s = 0; s < table_.size(); ++s) {
            const std::string name = table_.species[s].name;
            sg.estimate(name + "/sonine_a2", block_average(window(a2_[s])), "");
            if (s != ref_) {
                const std::vector<double> gs = gamma(s);
                sg.estimate(name + "/gamma", block_average(window(gs)), "");
            }
        }
        sg.value("from", tau_[start], "collisions per particle");
        sg.value("to", tau_[end - 1], "collisions per particle");
    }

    const SpeciesTable& table_;
    double threshold_;
    std::size_t ref_ = 0;
    std::array<double, D> length_{};
    std::vector<double> tau_, time_, t_mix_, density_mode_, momentum_mode_;
    std::vector<std::int64_t> steps_;
    std::vector<std::vector<double>> t_, a2_;  // per species, per sample
};

const char* const kDescription =
    R"md(
The homogeneous cooling state of a freely cooling gas, as a function of the collisions per
particle tau = 2 N_coll / N (the scaled time of the state). Time series (`series/...`, each with
`series/collisions_per_particle` as its clock): the mixture temperature, per species T, the Sonine
coefficient a2 and gamma = T_s / T_ref, `scaled_time` s = int sqrt(T / T_1) dt (the time at the
first sample's temperature T_1; t0 ln(1 + t / t0) in Haff's regime), the cooling rate per
collision zeta* = -d ln T / d tau of each sample interval (for one species in the Gaussian approximation (1 - alpha^2) / d), and the
longest-wavelength modes: `density_mode` |rho_k|^2 / N and `momentum_mode` |j_k|^2 / sum m^2 c^2
at k = 2 pi / L (about 1 while the gas is homogeneous). `transient_end`: the end of the initial
transient, the largest MSER-5 truncation over the scale-free series. `breakdown`: the first sample
at which a mode exceeds `breakdown_threshold` (shear instability, clustering), with a warning;
`homogeneous` is false then. `scaling_state/`: gamma, a2 and zeta* averaged from the end of the
transient to the breakdown (blocking errors; zeta* as a ratio of sums). Pool the replicas of a
study in `<study>.pooled.csv` (docs/studies.md). Velocities are taken about the centre-of-mass
velocity. Sample often enough (every collision per particle or so) for the transient to be
resolved. A scene with a driver is refused (use `temperatures` for a driven steady state).)md";

const bool registered = register_plugin<Observable, CoolingState>(
    "cooling_state",
    "homogeneous cooling state: gamma, a2, cooling rate against collisions per particle, end of "
    "the transient, breakdown of homogeneity, scaling-state values",
    {optional(text("reference_species", "",
                   "species whose temperature divides the ratios (default: first)")),
     real("breakdown_threshold", "20", "",
          "a longest-wavelength mode this many times its homogeneous value ends the "
          "homogeneous state",
          1, 1e308, true)},
    kDescription);

}  // namespace
}  // namespace gran
