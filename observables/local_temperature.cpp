// Granular temperature of a vibrated bed as Bhateja, Sharma & Singh, Phys. Fluids 28, 043301
// (2016) define it (issue #5):
//   Eq. (5)  T = (m / (2 d_f)) (<u^2> + <v^2> + <w^2>) =: (T_x + T_y + T_z) / d_f,
// so T_a = m <c_a^2> / 2 per component (half the usual m <c_a^2>), with c the fluctuation
// velocity; the paper's headline quantity is T_z / (m V_p^2), V_p = A omega, against
// W = V_p^2 / (d g).
//
// Fluctuation: about the local mean velocity u(z, phase), the mass-weighted mean of the grains in
// the same slab (depth `bin_width`, one diameter by default, as the paper's local temperature,
// Sec. VI) at the same phase of the drive (`phase_bins` per period of the fastest moving wall).
// A bed riding on the base has no temperature in this definition (the paper's T rises from 0 at
// W ~ 1); about a single mean velocity it would have T_z ~ m V_p^2 / 4.
//
// Reported:
//   local profiles  T_a(z) = sum m c_a^2 / (2 count) per slab, the same about the centre-of-mass
//                   velocity (T_a_plain_profile), volume fraction phi(z), grains per slab; z
//                   measured from the mean position of the lower wall of the axis;
//   particle average  T_a = sum over all grains m c_a^2 / (2 count): each grain counts once;
//   volume average    T_a^vol = mean of T_a(z) over the slabs of the bed, the paper's
//                     T = int T(r) dV / V (Eq. 1); the bed is the slabs from the lowest one a grain
//                     visited to the highest holding at least `min_occupancy` grains on average
//                     (the paper does not say where its V ends);
//   plain average     T_a^plain = sum m (v_a - V_a)^2 / (2 count), V the instantaneous
//                     centre-of-mass velocity of all grains: the fluctuation about "the mean
//                     velocity" without any local resolution (it keeps the collective motion of
//                     the layers relative to each other);
//   all scaled by m V_p^2 (T_*_scaled), and W.
// Error bars: jackknife over `blocks` consecutive blocks of the measurement (the local means are
// recomputed without each block).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "observables/block_clock.hpp"

namespace gran {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <int D>
class LocalTemperature final : public Observable<D> {
  public:
    LocalTemperature(const Params& p, const SceneInfo& info)
        : table_(*info.species),
          nblocks_(static_cast<std::size_t>(p.integer("blocks"))),
          phases_(static_cast<std::size_t>(p.integer("phase_bins"))),
          min_occupancy_(p.real("min_occupancy")),
          peak_velocity_(info.peak_velocity),
          period_(info.drive_period) {
        axis_ = D - 1;
        if (p.has("axis")) {
            const std::string a = p.str("axis");
            axis_ = a == "x" ? 0 : (a == "y" ? 1 : 2);
            if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", a, D));
        }
        length_ = info.box_length[std::size_t(axis_)];
        bounded_ = !info.periodic[std::size_t(axis_)];
        width_ = p.has("bin_width") ? p.real("bin_width") : table_.max_diameter();
        slabs_ = static_cast<std::size_t>(std::ceil(length_ / width_ - 1e-9));
        if (slabs_ > 100000) p.fail("bin_width", "more than 1e5 slabs: increase bin_width");
        cross_section_ = 1;
        for (int a = 0; a < D; ++a) {
            if (a != axis_) cross_section_ *= info.box_length[std::size_t(a)];
        }
        if (!(period_ > 0)) phases_ = 1;  // nothing to resolve
        double m = 0, d = 0, n = 0;
        for (const auto& s : table_.species) {
            m += double(s.count) * s.mass;
            d += double(s.count) * s.diameter;
            n += double(s.count);
        }
        mass_ = m / n;
        diameter_ = d / n;
        g_ = std::abs(info.gravity[std::size_t(axis_)]);
        stride_ = 3 + 2 * D;  // count, volume, mass, sum m v_a (D), sum m v_a^2 (D)
        sums_.assign(nblocks_ * slabs_ * phases_ * stride_, 0.0);
        plain_.assign(nblocks_ * (D + 1), 0.0);
        plain_slab_.assign(nblocks_ * slabs_ * D, 0.0);
        instant_slab_.assign(nblocks_ * slabs_ * D, 0.0);
        instant_.assign(slabs_ * (2 * D + 1), 0.0);
        samples_in_block_.assign(nblocks_, 0);
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        if (samples_ == 0) base_ = base_position(ctx);
        const auto& p = ctx.engine.particles();
        const BlockClock::Place place =
            clock_.place(samples_, ctx.expected_samples, ctx.open_ended);
        const std::size_t block = place.block;
        ++samples_in_block_[block];
        ++samples_;
        std::size_t phase = 0;
        if (phases_ > 1) {
            const double f = ctx.time / period_ - std::floor(ctx.time / period_);
            phase = std::min(phases_ - 1, static_cast<std::size_t>(f * double(phases_)));
        }
        const double vd = D == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
        const Vec<D> vcm = centre_of_mass_velocity<D>(p, table_);
        double* q = &plain_[block * (D + 1)];
        q[D] += double(p.size());
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double m = table_.species[p.species[i]].mass;
            for (int a = 0; a < D; ++a) q[a] += m * (p.v[i][a] - vcm[a]) * (p.v[i][a] - vcm[a]);
        }
        for (std::size_t i = 0; i < p.size(); ++i) {
            double z = p.r[i][axis_];
            if (!bounded_) z -= length_ * std::floor(z / length_);
            const auto slab =
                std::min(slabs_ - 1, static_cast<std::size_t>(std::max(0.0, z) / width_));
            const auto& sp = table_.species[p.species[i]];
            double* s = &sums_[((block * slabs_ + slab) * phases_ + phase) * stride_];
            double* ps = &plain_slab_[(block * slabs_ + slab) * D];
            for (int a = 0; a < D; ++a)
                ps[a] += sp.mass * (p.v[i][a] - vcm[a]) * (p.v[i][a] - vcm[a]);
            double* in = &instant_[slab * (2 * D + 1)];
            in[0] += sp.mass;
            for (int a = 0; a < D; ++a) {
                in[1 + a] += sp.mass * p.v[i][a];
                in[1 + D + a] += sp.mass * p.v[i][a] * p.v[i][a];
            }
            s[0] += 1;
            s[1] += vd * std::pow(sp.diameter, D);
            s[2] += sp.mass;
            for (int a = 0; a < D; ++a) {
                s[3 + a] += sp.mass * p.v[i][a];
                s[3 + D + a] += sp.mass * p.v[i][a] * p.v[i][a];
            }
        }
        // About the slab's mean velocity at this sample: sum m (v - w)^2 = sum m v^2 - (sum m v)^2
        // / sum m (a slab of one grain has none).
        for (std::size_t j = 0; j < slabs_; ++j) {
            double* in = &instant_[j * (2 * D + 1)];
            if (in[0] > 0) {
                double* out = &instant_slab_[(block * slabs_ + j) * D];
                for (int a = 0; a < D; ++a)
                    out[a] += std::max(0.0, in[1 + D + a] - in[1 + a] * in[1 + a] / in[0]);
            }
            std::fill(in, in + 2 * D + 1, 0.0);
        }
        if (place.merge_after) {
            merge_block_pairs(instant_slab_, nblocks_);
            merge_block_pairs(sums_, nblocks_);
            merge_block_pairs(plain_, nblocks_);
            merge_block_pairs(plain_slab_, nblocks_);
            merge_block_pairs(samples_in_block_, nblocks_);
        }
    }

    void write(ResultGroup& g) const override {
        if (samples_ == 0) return;
        ResultGroup settings = g.file_only();
        write_slabs(g, settings);
        const Jackknife jack = jackknife();
        const std::vector<std::size_t> bed = bed_slabs(jack.all);
        settings.value("bed_slabs", bed.size());
        write_density(g, jack);
        const double scale = mass_ * peak_velocity_ * peak_velocity_;
        for (int a = 0; a < D; ++a) write_component(g, jack, bed, a, scale);
        write_total(g, jack, bed, scale);
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("local_temperature");
        ar.io(samples_);
        ar.io(base_);
        ar.io(sums_);
        ar.io(plain_);
        ar.io(plain_slab_);
        ar.io(instant_slab_);
        ar.io(samples_in_block_);
        clock_.checkpoint(ar);
    }

  private:
    // Sums over a set of blocks, reduced over drive phases where the local mean allows it.
    struct Totals {
        std::size_t samples = 0;
        std::array<double, D + 1> plain_sums{};  // sum m (v_a - V_a)^2, count
        double plain(int a) const {
            return plain_sums[D] > 0 ? 0.5 * plain_sums[std::size_t(a)] / plain_sums[D] : kNaN;
        }
        std::vector<double> count, volume;
        std::vector<std::array<double, D>> sum_mc2;      // per slab: sum m c_a^2 about u(z, phase)
        std::vector<std::array<double, D>> plain_mc2;    // per slab: sum m (v_a - V_a)^2
        std::vector<std::array<double, D>> instant_mc2;  // sum m (v_a - w_a(z, t))^2
        double instant_local(std::size_t j, int a) const {
            return count[j] > 0 ? 0.5 * instant_mc2[j][std::size_t(a)] / count[j] : kNaN;
        }
        double plain_local(std::size_t j, int a) const {
            return count[j] > 0 ? 0.5 * plain_mc2[j][std::size_t(a)] / count[j] : kNaN;
        }
        double local(std::size_t j, int a) const {
            return count[j] > 0 ? 0.5 * sum_mc2[j][std::size_t(a)] / count[j] : kNaN;
        }
        double particle_average(int a) const {
            double num = 0, den = 0;
            for (std::size_t j = 0; j < count.size(); ++j) {
                num += sum_mc2[j][std::size_t(a)];
                den += count[j];
            }
            return den > 0 ? 0.5 * num / den : kNaN;
        }
        double volume_average(const std::vector<std::size_t>& bed, int a) const {
            double x = 0;
            std::size_t k = 0;
            for (std::size_t j : bed) {
                if (count[j] > 0) {
                    x += local(j, a);
                    ++k;
                }
            }
            return k > 0 ? x / double(k) : kNaN;
        }
    };

    // All blocks except `skip` (skip = nblocks_: all).
    Totals totals(std::size_t skip) const {
        Totals t;
        t.count.assign(slabs_, 0);
        t.volume.assign(slabs_, 0);
        t.sum_mc2.assign(slabs_, std::array<double, D>{});
        t.plain_mc2.assign(slabs_, std::array<double, D>{});
        t.instant_mc2.assign(slabs_, std::array<double, D>{});
        std::vector<double> cell(stride_);
        for (std::size_t b = 0; b < nblocks_; ++b) {
            if (b == skip) continue;
            t.samples += samples_in_block_[b];
            for (int k = 0; k <= D; ++k)
                t.plain_sums[std::size_t(k)] += plain_[b * (D + 1) + std::size_t(k)];
            for (std::size_t j = 0; j < slabs_; ++j) {
                for (int a = 0; a < D; ++a) {
                    t.plain_mc2[j][std::size_t(a)] +=
                        plain_slab_[(b * slabs_ + j) * D + std::size_t(a)];
                    t.instant_mc2[j][std::size_t(a)] +=
                        instant_slab_[(b * slabs_ + j) * D + std::size_t(a)];
                }
            }
        }
        for (std::size_t j = 0; j < slabs_; ++j) {
            for (std::size_t ph = 0; ph < phases_; ++ph) {
                std::fill(cell.begin(), cell.end(), 0.0);
                for (std::size_t b = 0; b < nblocks_; ++b) {
                    if (b == skip) continue;
                    const double* s = &sums_[((b * slabs_ + j) * phases_ + ph) * stride_];
                    for (std::size_t k = 0; k < stride_; ++k) cell[k] += s[k];
                }
                if (cell[0] == 0) continue;
                t.count[j] += cell[0];
                t.volume[j] += cell[1];
                // sum m (v - u)^2 = sum m v^2 - (sum m v)^2 / sum m, u the mass-weighted mean.
                for (int a = 0; a < D; ++a) {
                    const double mv = cell[3 + std::size_t(a)];
                    t.sum_mc2[j][std::size_t(a)] +=
                        std::max(0.0, cell[3 + D + std::size_t(a)] - mv * mv / cell[2]);
                }
            }
        }
        return t;
    }

    // Each estimate is a function of the sums with some blocks left out (jackknife): the sums
    // over all blocks and those without each block that holds samples.
    struct Jackknife {
        Totals all;
        std::vector<Totals> without;
        std::size_t samples = 0;

        template <class F>
        Estimate operator()(F f) const {
            Estimate e{f(all), kNaN};  // block sums only: tau_int, n_eff unknown (NaN)
            e.samples = samples;
            const double k = double(without.size());
            if (k < 2) return e;
            std::vector<double> r;
            for (const auto& t : without) r.push_back(f(t));
            double mean = 0;
            for (double x : r) mean += x / k;
            double var = 0;
            for (double x : r) var += (x - mean) * (x - mean);
            e.error = std::sqrt((k - 1) / k * var);
            return e;
        }
    };

    Jackknife jackknife() const {
        Jackknife j{totals(nblocks_), {}, samples_};
        for (std::size_t b = 0; b < nblocks_; ++b) {
            if (samples_in_block_[b] > 0) j.without.push_back(totals(b));
        }
        return j;
    }

    // Attributes, settings and the slab centres z.
    void write_slabs(ResultGroup& g, ResultGroup& settings) const {
        g.attr("axis", std::string(component_name(axis_)));
        g.attr("convention",
               "T_a = m <c_a^2> / 2 (Bhateja et al. 2016, Eq. 5), c = v - u(z, drive phase)");
        settings.value("bin_width", width_);
        settings.value("phase_bins", phases_);
        settings.value("base_position", base_);
        std::vector<double> z(slabs_);
        for (std::size_t j = 0; j < slabs_; ++j) z[j] = (double(j) + 0.5) * width_ - base_;
        g.array("z", z, "length");
    }

    // Slabs of the bed (for the volume average): from the lowest slab a grain visited up to the
    // highest slab holding at least min_occupancy grains on average. Contiguous: the few hot
    // grains just above the base belong to the bed however rarely they are there (a per-slab
    // occupancy cut would drop that slab or not from one W to the next).
    std::vector<std::size_t> bed_slabs(const Totals& all) const {
        std::vector<std::size_t> bed;
        std::size_t lo = slabs_, hi = 0;
        for (std::size_t j = 0; j < slabs_; ++j) {
            if (all.count[j] > 0 && lo == slabs_) lo = j;
            if (all.count[j] / double(samples_) >= min_occupancy_) hi = j;
        }
        for (std::size_t j = lo; j <= hi && j < slabs_; ++j) {
            if (all.count[j] > 0) bed.push_back(j);
        }
        return bed;
    }

    // Volume fraction phi(z) and grains per slab.
    void write_density(ResultGroup& g, const Jackknife& jack) const {
        const double slab_volume = cross_section_ * width_;
        std::vector<double> number(slabs_), phi(slabs_), phi_err(slabs_);
        for (std::size_t j = 0; j < slabs_; ++j) {
            const Estimate e = jack(
                [&](const Totals& t) { return t.volume[j] / (double(t.samples) * slab_volume); });
            phi[j] = e.value;
            phi_err[j] = e.error;
            number[j] = jack.all.count[j] / double(samples_);
        }
        g.profile("phi", phi, phi_err);
        g.array("grains_per_slab", number);
    }

    // The profiles and averages of T_a for one component a.
    void write_component(ResultGroup& g, const Jackknife& jack, const std::vector<std::size_t>& bed,
                         int a, double scale) const {
        const std::string c = component_name(a);
        std::vector<double> val(slabs_), err(slabs_);
        for (std::size_t j = 0; j < slabs_; ++j) {
            const Estimate e = jack([&](const Totals& t) { return t.local(j, a); });
            val[j] = e.value;
            err[j] = e.error;
        }
        g.profile("T_" + c + "_profile", val, err, "energy");
        for (std::size_t j = 0; j < slabs_; ++j) {
            const Estimate e = jack([&](const Totals& t) { return t.plain_local(j, a); });
            val[j] = e.value;
            err[j] = e.error;
        }
        g.profile("T_" + c + "_plain_profile", val, err, "energy");
        for (std::size_t j = 0; j < slabs_; ++j) {
            const Estimate e = jack([&](const Totals& t) { return t.instant_local(j, a); });
            val[j] = e.value;
            err[j] = e.error;
        }
        g.profile("T_" + c + "_instantaneous_profile", val, err, "energy");
        const Estimate tp = jack([&](const Totals& t) { return t.particle_average(a); });
        const Estimate tv = jack([&](const Totals& t) { return t.volume_average(bed, a); });
        const Estimate tb = jack([&](const Totals& t) { return t.plain(a); });
        g.estimate("T_" + c, tp, "energy");
        g.estimate("T_" + c + "_plain", tb, "energy");
        g.estimate("T_" + c + "_volume", tv, "energy");
        if (scale > 0) {
            g.estimate("T_" + c + "_scaled", tp.affine(1 / scale), "");
            g.estimate("T_" + c + "_volume_scaled", tv.affine(1 / scale), "");
            g.estimate("T_" + c + "_plain_scaled", tb.affine(1 / scale), "");
        }
    }

    // Total T = (T_x + ... ) / d_f with jackknife over the same blocks; the scale V_p and W.
    void write_total(ResultGroup& g, const Jackknife& jack, const std::vector<std::size_t>& bed,
                     double scale) const {
        const Estimate tt = jack([&](const Totals& t) {
            double x = 0;
            for (int a = 0; a < D; ++a) x += t.particle_average(a) / D;
            return x;
        });
        const Estimate ttv = jack([&](const Totals& t) {
            double x = 0;
            for (int a = 0; a < D; ++a) x += t.volume_average(bed, a) / D;
            return x;
        });
        g.estimate("T", tt, "energy");
        g.estimate("T_volume", ttv, "energy");
        if (scale > 0) {
            g.estimate("T_scaled", tt.affine(1 / scale), "");
            g.estimate("T_volume_scaled", ttv.affine(1 / scale), "");
            g.value("peak_velocity", peak_velocity_);
            if (g_ > 0) g.value("W", peak_velocity_ * peak_velocity_ / (diameter_ * g_));
        }
    }

    // Mean position of the lower wall of the axis over one drive period (0 on a periodic axis).
    double base_position(const SampleContext<D>& ctx) const {
        return bounded_ ? ctx.engine.mean_wall_position(2 * axis_, ctx.time, period_) : 0.0;
    }

    const SpeciesTable& table_;
    std::size_t nblocks_, phases_;
    BlockClock clock_{nblocks_};
    double min_occupancy_, peak_velocity_, period_;
    int axis_ = D - 1;
    double length_ = 1, width_ = 1, cross_section_ = 1, base_ = 0;
    bool bounded_ = true;
    std::size_t slabs_ = 1, stride_ = 1, samples_ = 0;
    double mass_ = 1, diameter_ = 1, g_ = 0;
    std::vector<double> sums_;
    std::vector<double> plain_;       // per block: sum m (v_a - V_a)^2 (D), count
    std::vector<double> plain_slab_;  // per block and slab: sum m (v_a - V_a)^2 (D)
    // Per block and slab: sum m (v_a - w_a)^2, w the slab's mean velocity at each sample (D).
    std::vector<double> instant_slab_;
    std::vector<double> instant_;  // this sample's per-slab sum m, m v_a, m v_a^2 (scratch)
    std::vector<std::size_t> samples_in_block_;
};

const char* const kDescription =
    R"md(
Granular temperature of a vibrated bed as Bhateja, Sharma & Singh 2016 define it (Eq. 5):
T_a = m <c_a^2> / 2 per component (half the usual m <c_a^2>), T = (T_x + T_y (+ T_z)) / d_f, with c
the fluctuation about the local mean velocity u(z, phase): the mass-weighted mean of the grains in
the same slab (depth `bin_width`; the paper: one diameter) at the same phase of the drive
(`phase_bins` per period of the fastest moving wall).

Writes the profiles `z` (slab centres measured from the mean position of the lower wall),
`T_x_profile`, ... with `_error`, the same about the centre-of-mass velocity `T_x_plain_profile`,
..., about the mean velocity of the slab's grains at each sample `T_x_instantaneous_profile`, ...
(no phase binning; a slab holding one grain at a sample adds nothing: sparse slabs read low),
`phi` (volume fraction) and `grains_per_slab`; the scalars `T_x`, `T_y`, (`T_z`), `T` as
particle averages (each grain counts once), `T_x_volume`, ... `T_volume` as volume averages (the
mean of T_a(z) over the slabs of the bed, the paper's T = int T dV / V), `T_x_plain`, ... as plain
averages about the instantaneous centre-of-mass velocity of all grains (no local resolution: the
layers' collective motion counts as temperature), and, with a moving wall, the same scaled by
m V_p^2 (`T_z_scaled`, `T_z_volume_scaled`, ...), `peak_velocity` V_p and `W` = V_p^2 / (d g).

The volume average runs over the slabs from the lowest one a grain visited to the highest holding
at least `min_occupancy` grains on average (the paper does not say where its volume ends).)md";

const bool registered = register_plugin<Observable, LocalTemperature>(
    "local_temperature",
    "granular temperature of a vibrated bed (Bhateja et al. 2016): T_a = m <c_a^2> / 2 about the "
    "local mean velocity of each slab and drive phase; profiles T_a(z) and phi(z), particle and "
    "volume averages, scaled by m V_p^2, and W = V_p^2 / (d g)",
    {optional(choice("axis", "", {"x", "y", "z"},
                     "vibration axis (default: the last axis, y in 2D, z in 3D)")),
     optional(real("bin_width", "", "length", "slab depth (default: the largest diameter)", 0,
                   1e308, true)),
     integer("phase_bins", "16",
             "drive phases resolved in the local mean velocity (1 without a moving wall)", 1, 1000),
     real("min_occupancy", "0.1", "grains",
          "top of the bed for the volume average: the highest slab with at least this many grains "
          "on average (the bed starts at the lowest slab a grain visited)",
          0, 1e308),
     integer("blocks", "16", "blocks of samples for the jackknife error bars", 2, 1000)},
    kDescription);

}  // namespace
}  // namespace gran
