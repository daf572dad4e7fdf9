// Pressure of the whole box: the volume average of the pressure tensor's diagonal (Irving &
// Kirkwood, J. Chem. Phys. 18, 817 (1950)), per species and total, and the compressibility factor
// Z = P / (n T). No slabs: the observable of a homogeneous box (an equation of state), and in any
// box the mean over its volume.
//
//   P_aa = (1/V) sum_i m_i c_{i,a}^2  +  P_aa^coll,       c = v - U (U: centre-of-mass velocity)
//
// The interaction part is what the engine has:
//   * binary collisions (event-driven): the collisional momentum transfer per unit time,
//     P_aa^coll = (1 / (V dt)) sum_collisions J sigma_ij n_a^2, J the normal impulse on i and n
//     the unit vector from j to i at contact (Barrat & Trizac 2002, Eq. (B1)), counted between
//     consecutive samples;
//   * soft contacts (DEM): the contact virial at each sample,
//     P_aa^coll = (1/V) sum_contacts (r_i - r_j)_a F_a (EngineView::contact_virial).
// A species' partial pressure has its own kinetic part and half of every collision or contact of
// its grains, so the partial pressures add up to P. Wall forces and gravity are external: they
// are not in the volume average (at a wall the kinetic and collisional parts carry the flux).
//
// Z = P / (n T) with n = N / V and T the mixture temperature (the same c); Z_enskog is the Enskog
// equation of state of the mixture (Barrat & Trizac 2002, Eq. (4)) at the measured partial
// temperatures, with the scene's nominal restitution and the contact values of
// libgran/core/kinetic_theory.hpp (Henderson / Jenkins-Mancini in 2D, Carnahan-Starling /
// Boublik-Mansoori in 3D): for elastic grains the usual hard-disk and hard-sphere equations of
// state.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "libgran/core/kinetic_theory.hpp"
#include "libgran/plugins/observable.hpp"

namespace gran {
namespace {

template <int D>
class Pressure final : public Observable<D>, public CollisionSink<D> {
  public:
    Pressure(const Params&, const SceneInfo& info)
        : table_(*info.species), info_(info), collisions_(info.binary_collisions) {
        volume_ = 1;
        for (int a = 0; a < D; ++a) volume_ *= info.box_length[std::size_t(a)];
        const std::size_t ns = table_.size();
        kinetic_.resize(ns * D);
        transfer_.resize(ns * D);
        pending_.assign(ns * D, 0.0);
        count_.assign(ns, 0);
    }

    CollisionSink<D>* collision_sink() override { return collisions_ ? this : nullptr; }

    // The transfer J sigma n_a^2 of one collision, half to the species of each partner.
    void on_collision(const CollisionRecord<D>& c) override {
        if (!started_) return;
        for (int a = 0; a < D; ++a) {
            const double t = 0.5 * c.impulse * c.contact_distance * c.n[a] * c.n[a];
            pending_[c.si * D + std::size_t(a)] += t;
            pending_[c.sj * D + std::size_t(a)] += t;
        }
    }

    // One sample: the kinetic sums now, and the interaction part with its weight. Collisions:
    // the transfer since the previous sample and the time it took; the collisional pressure is
    // the ratio of their means (samples taken every so many collisions end their intervals on a
    // collision: the mean of per-interval rates would be biased by about 1/(collisions per
    // interval)). Contacts: the virial now, weight 1.
    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const double dt = ctx.time - last_time_;
        if (collisions_ && (!started_ || !(dt > 0))) {
            // The first sample opens the first interval of collisions: nothing to average yet.
            started_ = true;
            last_time_ = ctx.time;
            std::fill(pending_.begin(), pending_.end(), 0.0);
            return;
        }
        const std::vector<double> kin = kinetic_sums(ctx.engine.particles());
        const std::vector<double> inter = collisions_ ? pending_ : ctx.engine.contact_virial();
        for (std::size_t k = 0; k < kinetic_.size(); ++k) {
            kinetic_[k].push(kin[k] / volume_);
            transfer_[k].push(inter.empty() ? 0.0 : inter[k] / volume_);
        }
        weight_.push(collisions_ ? dt : 1.0);
        std::fill(pending_.begin(), pending_.end(), 0.0);
        time_.push(ctx.time);
        steps_.push_back(ctx.step);
        last_time_ = ctx.time;
        started_ = true;
    }

    void write(ResultGroup& g) const override {
        if (weight_.size() == 0) return;
        const std::string pu = "energy/length^" + std::to_string(D);
        const std::size_t ns = table_.size();
        std::vector<std::size_t> all(ns);
        for (std::size_t s = 0; s < ns; ++s) all[s] = s;
        const Sums total = sums(all, -1);
        g.estimate("P", total.pressure(), pu);
        for (int a = 0; a < D; ++a) g.estimate(component("P_", a), sums(all, a).pressure(), pu);
        g.estimate("P_kinetic", block_average(total.kin), pu);
        g.estimate("P_collisional", ratio_of_means(total.inter, weight_.values()), pu);
        g.estimate("Z", total.compressibility(), "");
        g.estimate("Z_enskog", enskog_z(), "");
        const auto steps = std::span<const std::int64_t>(steps_);
        g.time_series("series/P", steps, time_.values(), total.instantaneous(), pu);
        for (std::size_t s = 0; s < ns; ++s) {
            const std::string name = table_.species[s].name;
            ResultGroup gs = g.group(name, {"species", name});
            gs.estimate("P", sums({s}, -1).pressure(), pu);
            for (int a = 0; a < D; ++a)
                gs.estimate(component("P_", a), sums({s}, a).pressure(), pu);
        }
        g.attr("volume", volume_);
        g.attr("interaction_part",
               std::string(collisions_ ? "collisional momentum transfer between samples"
                                       : "contact virial at each sample"));
        g.attr("definition",
               "P_aa = (1/V) sum m c_a^2 + interaction part, c = v - U (centre-of-mass velocity); "
               "Z = P / (n T)");
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("pressure");
        ar.io(kinetic_);
        ar.io(transfer_);
        ar.io(weight_);
        ar.io(time_);
        ar.io(steps_);
        ar.io(pending_);
        ar.io(count_);
        ar.io(last_time_);
        ar.io(started_);
    }

  private:
    // Per-sample sums over some species and axes (trace over D for all axes): the kinetic part,
    // the interaction numerator, with the weights of the interaction part.
    struct Sums {
        std::vector<double> kin, inter;
        std::span<const double> weight;
        Estimate pressure() const {
            return jackknife({kin, inter, weight},
                             [](std::span<const double> m) { return m[0] + m[1] / m[2]; });
        }
        // Z = P / (n T) = 1 + P_coll / P_kin (n T = P_kin with the same velocities).
        Estimate compressibility() const {
            return jackknife({kin, inter, weight},
                             [](std::span<const double> m) { return 1 + m[1] / (m[2] * m[0]); });
        }
        std::vector<double> instantaneous() const {
            std::vector<double> p(kin.size());
            for (std::size_t t = 0; t < p.size(); ++t) p[t] = kin[t] + inter[t] / weight[t];
            return p;
        }
    };

    Sums sums(const std::vector<std::size_t>& species, int axis) const {
        Sums out{std::vector<double>(weight_.size(), 0.0), std::vector<double>(weight_.size(), 0.0),
                 weight_.values()};
        const double share = axis < 0 ? 1.0 / D : 1.0;
        for (std::size_t s : species) {
            for (int a = 0; a < D; ++a) {
                if (axis >= 0 && a != axis) continue;
                const auto k = kinetic_[s * D + std::size_t(a)].values();
                const auto i = transfer_[s * D + std::size_t(a)].values();
                for (std::size_t t = 0; t < out.kin.size(); ++t) {
                    out.kin[t] += share * k[t];
                    out.inter[t] += share * i[t];
                }
            }
        }
        return out;
    }

    static std::string component(const char* prefix, int a) {
        return std::string(prefix) + component_name(a) + component_name(a);
    }

    // Per species and axis: sum m c_a^2, c about the centre-of-mass velocity; counts per species.
    std::vector<double> kinetic_sums(const Particles<D>& p) {
        const Vec<D> u = centre_of_mass_velocity<D>(p, table_);
        std::vector<double> k(table_.size() * D, 0.0);
        std::fill(count_.begin(), count_.end(), 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            const double m = table_.species[s].mass;
            const Vec<D> c = p.v[i] - u;
            for (int a = 0; a < D; ++a) k[s * D + std::size_t(a)] += m * c[a] * c[a];
            ++count_[s];
        }
        return k;
    }

    // Z of the Enskog equation of state at the measured partial temperatures T_s = P_kin,s / n_s
    // (jackknife over the samples).
    Estimate enskog_z() const {
        const std::size_t ns = table_.size();
        std::vector<double> n(ns), m(ns), sigma(ns), x(ns), alpha(ns * ns);
        double n_total = 0, phi = 0;
        const double vd = theory::unit_ball_volume(D);
        for (std::size_t s = 0; s < ns; ++s) {
            n[s] = double(count_[s]) / volume_;
            m[s] = table_.species[s].mass;
            sigma[s] = table_.species[s].diameter;
            n_total += n[s];
            phi += n[s] * vd * std::pow(sigma[s], D);
            for (std::size_t r = 0; r < ns; ++r)
                alpha[s * ns + r] = info_.nominal_restitution_of(s, r);
        }
        for (std::size_t s = 0; s < ns; ++s) x[s] = n[s] / n_total;
        const std::vector<double> chi = theory::contact_values_mixture(D, phi, sigma, x);
        std::vector<std::vector<double>> kin;
        for (std::size_t s = 0; s < ns; ++s) kin.push_back(sums({s}, -1).kin);
        std::vector<std::span<const double>> series(kin.begin(), kin.end());
        return jackknife(series, [&](std::span<const double> pk) {
            std::vector<double> T(ns, 0.0);
            double nt = 0;
            for (std::size_t s = 0; s < ns; ++s) {
                T[s] = n[s] > 0 ? pk[s] / n[s] : 0.0;
                nt += pk[s];
            }
            return theory::enskog_pressure(D, n, T, m, sigma, alpha, chi) / nt;
        });
    }

    const SpeciesTable& table_;
    SceneInfo info_;
    bool collisions_ = true;
    double volume_ = 1;
    // Per species s and axis a at [s * D + a], one value per sample: sum m c_a^2 / V, and the
    // interaction part's numerator (collisions: transfer over the interval / V; contacts:
    // virial / V); weight_: the interval (collisions) or 1 (contacts).
    std::vector<Series> kinetic_, transfer_;
    Series weight_, time_;
    std::vector<std::int64_t> steps_;
    std::vector<double> pending_;  // collisional transfer since the last sample, species x axis
    std::vector<std::size_t> count_;
    double last_time_ = 0;
    bool started_ = false;
};

const char* const kDescription =
    R"md(
Pressure of the whole box, without slabs: `P` (the trace over D), `P_xx`, `P_yy` (, `P_zz`),
its kinetic and interaction parts `P_kinetic`, `P_collisional`, per species (`<species>/P`,
`<species>/P_xx`, ...: the species' kinetic part plus half of each of its collisions or contacts,
so they add up to `P`), the compressibility factor `Z` = P / (n T) (n = N / V, T the mixture
temperature), and `Z_enskog`, the Enskog equation of state at the measured partial temperatures
(Barrat & Trizac 2002, Eq. (4), with the scene's nominal restitution and the Henderson (2D) or
Carnahan-Starling (3D) contact values; for elastic spheres Carnahan-Starling is itself 0.26% low
at packing fraction 0.3); `series/P` is the pressure at each sample. Velocities are taken about
the centre-of-mass velocity. The interaction part is the collisional momentum transfer on the
event-driven engine (Eq. (B1) of the paper: the transfer between samples over the time it took,
a ratio of sums), and the contact virial at each sample on the DEM engine (instantaneous: sample
at intervals of about a contact duration to average it well). Wall forces and gravity are
external and not included: in a box with walls or gravity `P` is the mean of the pressure tensor
over the box. Errors: jackknife over blocks of samples.)md";

const bool registered = register_plugin<Observable, Pressure>(
    "pressure",
    "pressure tensor of the whole box (kinetic + collisional or contact virial), per species, "
    "compressibility factor Z = P/(nT) and the Enskog equation of state",
    {}, kDescription);

}  // namespace
}  // namespace gran
