// Profiles along one axis (slabs): per species number density, packing fraction, temperatures T,
// T_a per component and T_rot, the anisotropy A = (T_y - T_x) / (2T) of the mixture (for axis y;
// generally (T_axis - mean of the others) / (2T)), and temperature ratios gamma(y) = T_s / T_ref
// per component (Barrat & Trizac 2002, Figs. 1-3, 13-16); plus the same quantities in a central
// window
// ("middle of the system", Tables I and II). Temperatures are m <v_a^2> over the particles in a
// slab (no mean flow in these steady states). Error bars: jackknife over `blocks` consecutive
// blocks of samples, so ratios of sums are estimated without bias.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "libgran/core/kinetic_theory.hpp"
#include "libgran/plugins/observable.hpp"
#include "observables/block_clock.hpp"
#include "observables/local_flow.hpp"

namespace gran {
namespace {

template <int D>
class Profiles final : public Observable<D>, public CollisionSink<D> {
  public:
    Profiles(const Params& p, const SceneInfo& info)
        : table_(*info.species),
          info_(info),
          bins_(static_cast<std::size_t>(p.integer("bins"))),
          nblocks_(static_cast<std::size_t>(p.integer("blocks"))),
          window_(p.real("middle_window")) {
        const std::string axis = p.str("axis");
        axis_ = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
        if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", axis, D));
        length_ = info.box_length[std::size_t(axis_)];
        cross_section_ = 1;
        for (int a = 0; a < D; ++a) {
            if (a != axis_) cross_section_ *= info.box_length[std::size_t(a)];
        }
        const std::string ref =
            p.has("reference_species") ? p.str("reference_species") : table_.species[0].name;
        ref_ = table_.index_of(ref);
        if (ref_ == table_.size()) p.fail("reference_species", "unknown species '" + ref + "'");
        rotating_ = info.rotating;
        if (p.has("flow_cell")) {
            std::size_t n = 0;
            for (const auto& sp : table_.species) n += sp.count;
            check_flow_cell(p.real("flow_cell"), info.box_length, n, D,
                            [&](const std::string& why) { p.fail("flow_cell", why); });
            flow_ = LocalFlow<D>(p.real("flow_cell"), info.box_length, table_.size());
            local_ = true;
        }
        // Per block, per (bin + 1 middle row), per species: count, sum m v_a^2 (D), sum I w^2;
        // about the local flow also G_st (local_flow.hpp), t = 0 .. ns - 1.
        stride_ = 2 + D + (local_ ? table_.size() : 0);
        sums_.assign(nblocks_ * (bins_ + 1) * table_.size() * stride_, 0.0);
        samples_in_block_.assign(nblocks_, 0);
        // The collisional virial needs binary collision records: event-driven runs only.
        pressure_ = p.boolean("pressure") && info.binary_collisions;
        coll_.assign(nblocks_ * (bins_ + 1) * D, 0.0);
        block_time_.assign(nblocks_, 0.0);
    }

    CollisionSink<D>* collision_sink() override { return pressure_ ? this : nullptr; }

    // Collisional (virial) momentum flux, Irving–Kirkwood style: the transfer impulse * sigma *
    // n_a^2 of the diagonal component a is shared among the slabs crossed by the segment joining
    // the centres, in proportion to the length inside each (Barrat & Trizac 2002, Eq. (B1)).
    void on_collision(const CollisionRecord<D>& c) override {
        if (!started_) return;
        const double sigma = c.contact_distance;
        double yi = c.ri[axis_];
        yi -= length_ * std::floor(yi / length_);
        const double yj = yi - sigma * c.n[axis_];
        const double lo = std::min(yi, yj), hi = std::max(yi, yj), span = hi - lo;
        std::array<double, D> flux;
        for (int a = 0; a < D; ++a) flux[std::size_t(a)] = c.impulse * sigma * c.n[a] * c.n[a];
        const double w = length_ / double(bins_);
        auto deposit = [&](std::size_t row, double fraction) {
            double* t = &coll_[(current_block_ * (bins_ + 1) + row) * D];
            for (int a = 0; a < D; ++a) t[a] += flux[std::size_t(a)] * fraction;
        };
        auto share = [&](double a, double b) {  // fraction of [lo, hi] inside [a, b]
            if (span <= 1e-300) return (lo >= a && lo < b) ? 1.0 : 0.0;
            return std::max(0.0, std::min(hi, b) - std::max(lo, a)) / span;
        };
        // The segment may stick out of [0, L) on a periodic axis: visit the images it touches.
        const long first = static_cast<long>(std::floor(lo / w)),
                   last = static_cast<long>(std::floor(hi / w));
        for (long k = first; k <= last; ++k) {
            const double f = share(double(k) * w, double(k + 1) * w);
            if (f <= 0) continue;
            const long wrapped = ((k % long(bins_)) + long(bins_)) % long(bins_);
            deposit(std::size_t(wrapped), f);
        }
        // The central window and its periodic images: a segment that sticks out of [0, L) on one
        // side has its other part in the window's image (a window of the whole box must receive
        // every collision whole). On a bounded axis the segment lies inside and the images are
        // empty.
        const double mlo = 0.5 * (1 - window_) * length_, mhi = 0.5 * (1 + window_) * length_;
        double fm = 0;
        for (long k = long(std::floor(lo / length_)); k <= long(std::floor(hi / length_)); ++k)
            fm += share(mlo + double(k) * length_, mhi + double(k) * length_);
        if (fm > 0) deposit(bins_, fm);
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const auto& p = ctx.engine.particles();
        const BlockClock::Place place =
            clock_.place(samples_, ctx.expected_samples, ctx.open_ended);
        const std::size_t block = place.block;
        // Collision fluxes since the previous sample belong to this sample's block.
        if (started_) block_time_[block] += ctx.time - last_time_;
        started_ = true;
        last_time_ = ctx.time;
        ++samples_;
        ++samples_in_block_[block];
        const double lo = 0.5 * (1 - window_) * length_, hi = 0.5 * (1 + window_) * length_;
        if (local_) flow_.compute(p, table_);
        for (std::size_t i = 0; i < p.size(); ++i) {
            double y = p.r[i][axis_];
            y -= length_ * std::floor(y / length_);  // periodic images (bounded axes stay inside)
            const auto bin =
                std::min(bins_ - 1, static_cast<std::size_t>(y / length_ * double(bins_)));
            const std::uint32_t s = p.species[i];
            add(block, bin, s, p, i, ctx);
            if (y >= lo && y < hi) add(block, bins_, s, p, i, ctx);
        }
        if (place.merge_after) {
            merge_block_pairs(sums_, nblocks_);
            merge_block_pairs(samples_in_block_, nblocks_);
            merge_block_pairs(coll_, nblocks_);
            merge_block_pairs(block_time_, nblocks_);
        }
        // The collisions until the next sample go to that sample's block.
        current_block_ = clock_.next_block(samples_, ctx.expected_samples, ctx.open_ended);
    }

    void write(ResultGroup& g) const override {
        if (samples_ == 0) return;
        std::vector<double> centres(bins_);
        for (std::size_t b = 0; b < bins_; ++b)
            centres[b] = (double(b) + 0.5) * length_ / double(bins_);
        g.array("position", centres, "length");
        g.attr("axis", std::string(component_name(axis_)));
        g.attr("middle_window", window_);
        for (std::size_t s = 0; s < table_.size(); ++s) {
            write_species(g, s);
            if (s != ref_) write_ratios(g, s);
        }
        profile(g, "mixture/T", "energy",
                [](const Acc& a, double) { return a.mixture_temperature(); });
        profile(g, "mixture/anisotropy", "",
                [this](const Acc& a, double) { return a.anisotropy(axis_); });
        write_eos(g);
        if (pressure_) write_pressure(g);
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("profiles");
        ar.io(sums_);
        ar.io(samples_in_block_);
        ar.io(coll_);
        ar.io(block_time_);
        ar.io(last_time_);
        ar.io(started_);
        ar.io(current_block_);
        clock_.checkpoint(ar);
        ar.io(samples_);
    }

  private:
    // Sums of one row (a bin or the middle window) over a set of blocks.
    struct Acc {
        const Profiles* self;
        std::vector<double> v;  // per species: count, m v_a^2 (D), I w^2
        std::size_t samples = 0;
        std::array<double, D> coll{};  // collisional momentum flux sums per diagonal component
        double time = 0;
        double kinetic(int c) const {  // sum over species of m v_c^2
            double k = 0;
            for (std::size_t s = 0; s < self->table_.size(); ++s)
                k += v[s * self->stride_ + 1 + std::size_t(c)];
            return k;
        }
        double count(std::size_t s) const { return v[s * self->stride_]; }
        double component(std::size_t s, int c) const {
            if (self->local_) return local_components(c)[s];
            return v[s * self->stride_ + 1 + std::size_t(c)] / v[s * self->stride_];
        }
        // T_{s,c} of every species about the local flow: sum_t G_st v_t = sum_{i in s} c_i^2.
        std::vector<double> local_components(int c) const {
            const std::size_t ns = self->table_.size(), st = self->stride_;
            std::vector<double> g(ns * ns), rhs(ns);
            for (std::size_t s = 0; s < ns; ++s) {
                const double m = self->table_.species[s].mass;
                rhs[s] = v[s * st + 1 + std::size_t(c)] / m;
                for (std::size_t t = 0; t < ns; ++t) g[s * ns + t] = v[s * st + 2 + D + t];
            }
            std::vector<double> x = solve_small(g, rhs);
            for (std::size_t s = 0; s < ns; ++s) x[s] *= self->table_.species[s].mass;
            return x;
        }
        double temperature(std::size_t s) const {
            double t = 0;
            for (int c = 0; c < D; ++c) t += component(s, c) / D;
            return t;
        }
        double rotational(std::size_t s) const {
            return v[s * self->stride_ + 1 + D] / v[s * self->stride_] / (D == 2 ? 1.0 : 3.0);
        }
        double mixture_temperature() const {
            if (self->local_) return local_mixture(-1);
            double e = 0, n = 0;
            for (std::size_t s = 0; s < self->table_.size(); ++s) {
                for (int c = 0; c < D; ++c) e += v[s * self->stride_ + 1 + std::size_t(c)];
                n += count(s);
            }
            return e / (D * n);
        }
        // Mixture temperature about the local flow (component c, or the mean over all if c < 0).
        double local_mixture(int c) const {
            double e = 0, n = 0;
            for (int a = 0; a < D; ++a) {
                if (c >= 0 && a != c) continue;
                const std::vector<double> t = local_components(a);
                for (std::size_t s = 0; s < self->table_.size(); ++s) e += count(s) * t[s];
            }
            for (std::size_t s = 0; s < self->table_.size(); ++s) n += count(s);
            return e / (n * (c < 0 ? D : 1));
        }
        double anisotropy(int axis) const {
            if (self->local_) {
                const double along = local_mixture(axis), t = local_mixture(-1);
                const double across = (D * t - along) / (D - 1);
                return (along - across) / (2 * t);
            }
            double along = 0, across = 0, n = 0;
            for (std::size_t s = 0; s < self->table_.size(); ++s) {
                for (int c = 0; c < D; ++c) {
                    (c == axis ? along : across) += v[s * self->stride_ + 1 + std::size_t(c)];
                }
                n += count(s);
            }
            along /= n;
            across /= n * (D - 1);
            const double t = (along + (D - 1) * across) / D;
            return (along - across) / (2 * t);
        }
    };

    // Each quantity is a function of the (species, row) sums; evaluated on all blocks and on the
    // leave-one-block-out sums (jackknife): the profile over the slabs and its middle value.
    template <class F>
    void profile(ResultGroup& g, const std::string& name, const std::string& unit,
                 const F& f) const {
        const double slab_volume = cross_section_ * length_ / double(bins_);
        const double middle_volume = cross_section_ * length_ * window_;
        std::vector<double> val(bins_), err(bins_);
        for (std::size_t b = 0; b < bins_; ++b) {
            const Estimate e = jack(b, f, b < bins_ ? slab_volume : middle_volume);
            val[b] = e.value;
            err[b] = e.error;
        }
        g.profile(name, val, err, unit);
        g.estimate("middle/" + name, jack(bins_, f, middle_volume), unit);
    }

    // Number density, packing fraction and temperatures of species s.
    void write_species(ResultGroup& g, std::size_t s) const {
        const double vd = D == 2 ? std::numbers::pi / 4 : std::numbers::pi / 6;
        const std::string sn = table_.species[s].name;
        const double sig = table_.species[s].diameter;
        profile(
            g, sn + "/number_density", "1/length^" + std::to_string(D),
            [s, this](const Acc& a, double vol) { return a.count(s) / (double(a.samples) * vol); });
        profile(g, sn + "/packing_fraction", "", [s, sig, vd, this](const Acc& a, double vol) {
            return a.count(s) * vd * std::pow(sig, D) / (double(a.samples) * vol);
        });
        profile(g, sn + "/T", "energy", [s](const Acc& a, double) { return a.temperature(s); });
        for (int c = 0; c < D; ++c) {
            profile(g, sn + "/T_" + component_name(c), "energy",
                    [s, c](const Acc& a, double) { return a.component(s, c); });
        }
        if (rotating_)
            profile(g, sn + "/T_rot", "energy",
                    [s](const Acc& a, double) { return a.rotational(s); });
    }

    // Temperature ratios gamma of species s over the reference species.
    void write_ratios(ResultGroup& g, std::size_t s) const {
        const std::string r =
            "ratios/" + table_.species[s].name + "_over_" + table_.species[ref_].name;
        const std::size_t q = ref_;
        profile(g, r + "/gamma", "",
                [s, q](const Acc& a, double) { return a.temperature(s) / a.temperature(q); });
        for (int c = 0; c < D; ++c) {
            profile(g, r + "/gamma_" + component_name(c), "", [s, q, c](const Acc& a, double) {
                return a.component(s, c) / a.component(q, c);
            });
        }
        if (rotating_) {
            profile(g, r + "/gamma_rot", "",
                    [s, q](const Acc& a, double) { return a.rotational(s) / a.rotational(q); });
        }
    }

    // Equation of state from the local densities and temperatures (Eq. (4); Eq. (7) when
    // monodisperse): the ideal part and with the Enskog collisional part, using the full T
    // (isotropic P) or the component along the axis (P_aa, the paper's Fig. 4b).
    void write_eos(ResultGroup& g) const {
        const std::string ax = std::string(component_name(axis_));
        const std::string pu = "energy/length^" + std::to_string(D);
        profile(g, "eos/P_ideal", pu,
                [this](const Acc& a, double vol) { return eos(a, vol, -1, false); });
        profile(g, "eos/P_enskog", pu,
                [this](const Acc& a, double vol) { return eos(a, vol, -1, true); });
        profile(g, "eos/P_ideal_" + ax + ax, pu,
                [this](const Acc& a, double vol) { return eos(a, vol, axis_, false); });
        profile(g, "eos/P_enskog_" + ax + ax, pu,
                [this](const Acc& a, double vol) { return eos(a, vol, axis_, true); });
    }

    // Measured pressure tensor (diagonal): kinetic sum m v_a^2 per volume plus the collisional
    // flux per volume and time.
    void write_pressure(ResultGroup& g) const {
        const std::string pu = "energy/length^" + std::to_string(D);
        for (int c = 0; c < D; ++c) {
            const std::string cc = std::string(component_name(c)) + component_name(c);
            profile(g, "pressure/P_" + cc, pu, [c](const Acc& a, double vol) {
                return a.kinetic(c) / (double(a.samples) * vol) +
                       a.coll[std::size_t(c)] / (a.time * vol);
            });
            profile(g, "pressure/P_" + cc + "_collisional", pu, [c](const Acc& a, double vol) {
                return a.coll[std::size_t(c)] / (a.time * vol);
            });
        }
    }

    // Pressure from the equation of state in a slab: component < 0 uses the total temperatures.
    double eos(const Acc& a, double vol, int component, bool enskog) const {
        const std::size_t ns = table_.size();
        std::vector<double> n(ns), T(ns), m(ns), sigma(ns), x(ns), alpha(ns * ns, 0.0),
            chi(ns * ns, 0.0);
        // No samples (a run stopped in its first block: the leave-one-out sums are empty).
        if (a.samples == 0) return std::nan("");
        double n_total = 0, phi = 0;
        const double vd = theory::unit_ball_volume(D);
        for (std::size_t s = 0; s < ns; ++s) {
            n[s] = a.count(s) / (double(a.samples) * vol);
            T[s] = a.count(s) > 0 ? (component < 0 ? a.temperature(s) : a.component(s, component))
                                  : 0.0;
            m[s] = table_.species[s].mass;
            sigma[s] = table_.species[s].diameter;
            n_total += n[s];
            phi += n[s] * vd * std::pow(sigma[s], D);
        }
        if (n_total == 0) return 0;
        for (std::size_t s = 0; s < ns; ++s) x[s] = n[s] / n_total;
        if (enskog) {
            chi = theory::contact_values_mixture(D, phi, sigma, x);
            for (std::size_t i = 0; i < ns; ++i) {
                for (std::size_t j = 0; j < ns; ++j)
                    alpha[i * ns + j] = info_.nominal_restitution_of(i, j);
            }
        }
        return theory::enskog_pressure(D, n, T, m, sigma, alpha, chi);
    }

    void add(std::size_t block, std::size_t row, std::uint32_t s, const Particles<D>& p,
             std::size_t i, const SampleContext<D>& ctx) {
        double* a = &sums_[((block * (bins_ + 1) + row) * table_.size() + s) * stride_];
        const double m = table_.species[s].mass;
        a[0] += 1;
        if (local_) {
            const Vec<D> c = p.v[i] - flow_.flow_of(i);
            for (int k = 0; k < D; ++k) a[1 + k] += m * c[k] * c[k];
            flow_.add_variance_weights(i, s, m, a + 2 + D);
        } else {
            for (int c = 0; c < D; ++c) a[1 + c] += m * p.v[i][c] * p.v[i][c];
        }
        if (rotating_) a[1 + D] += ctx.engine.species_inertia(s) * ang_squared<D>(p.w[i]);
    }

    Acc row_sums(std::size_t row, std::size_t skip_block) const {
        Acc acc{this, std::vector<double>(table_.size() * stride_, 0.0), 0};
        for (std::size_t b = 0; b < nblocks_; ++b) {
            if (b == skip_block) continue;
            const double* a = &sums_[(b * (bins_ + 1) + row) * table_.size() * stride_];
            for (std::size_t k = 0; k < acc.v.size(); ++k) acc.v[k] += a[k];
            acc.samples += samples_in_block_[b];
            const double* t = &coll_[(b * (bins_ + 1) + row) * D];
            for (int c = 0; c < D; ++c) acc.coll[std::size_t(c)] += t[c];
            acc.time += block_time_[b];
        }
        return acc;
    }

    template <class F>
    Estimate jack(std::size_t row, const F& f, double volume) const {
        const double full = f(row_sums(row, nblocks_), volume);
        std::vector<double> loo;
        for (std::size_t b = 0; b < nblocks_; ++b) {
            // Only blocks whose removal leaves samples (not the only one filled yet).
            if (samples_in_block_[b] == 0 || samples_in_block_[b] == samples_) continue;
            loo.push_back(f(row_sums(row, b), volume));
        }
        // Only block sums are kept, so tau_int and n_eff stay unknown (NaN).
        Estimate e{full, std::nan("")};
        e.samples = samples_;
        const double nb = double(loo.size());
        if (nb < 2) return e;
        double mean = 0;
        for (double x : loo) mean += x / nb;
        double var = 0;
        for (double x : loo) var += (x - mean) * (x - mean);
        e.error = std::sqrt(var * (nb - 1) / nb);
        return e;
    }

    const SpeciesTable& table_;
    SceneInfo info_;  // the nominal restitution of each species pair, for the Enskog pressure
    std::size_t bins_, nblocks_;
    BlockClock clock_{nblocks_};
    double window_;
    int axis_ = 1;
    double length_ = 1, cross_section_ = 1;
    std::size_t ref_ = 0;
    bool rotating_ = false;
    std::size_t stride_ = 0;
    std::vector<double> sums_;
    std::vector<std::size_t> samples_in_block_;
    bool pressure_ = true;
    std::vector<double> coll_;
    std::vector<double> block_time_;
    double last_time_ = 0;
    bool started_ = false;
    std::size_t current_block_ = 0;
    std::size_t samples_ = 0;
    bool local_ = false;  // temperatures about the local flow (`flow_cell`)
    LocalFlow<D> flow_;
};

const char* const kDescription =
    R"md(
Slab profiles along one axis, per species: `number_density`, `packing_fraction`, `T`, `T_x`, `T_y`
(`T_z`), `T_rot`, and ratios `gamma`, `gamma_x`, ... `gamma_rot` against the reference species; for
the mixture, `T` and the anisotropy (T_axis - T_across)/(2T), which is A(y) = (T_y - T_x)/(2T) of
Barrat & Trizac 2002 for axis y. Every profile has an `_error` array (jackknife over blocks) and a
`middle/...` scalar: the same quantity over the central window (Tables I and II of the paper).
`eos/P_ideal`, `eos/P_enskog` and `eos/P_ideal_yy`, `eos/P_enskog_yy` (for axis y) give the
pressure predicted by the equation of state, Eq. (4) of the paper (Eq. (7) for one species), from
the local densities and the total or axial temperatures, without and with the Enskog collisional
part (contact values of Henderson / Carnahan–Starling type). The Enskog part takes a species-pair
matrix per slab when written: memory and time grow with the square of the number of species.

With `pressure` it measures the diagonal pressure tensor `pressure/P_xx`, `P_yy` (, `P_zz`): the
kinetic part plus the collisional (virial) momentum flux shared among the slabs crossed by each
collision (Irving–Kirkwood); `..._collisional` holds the latter alone. This subscribes to collisions
(event_driven engine only; not measured on the dem engine).

With `flow_cell` the temperatures (and the anisotropy, gamma and the equation of state built on
them) are taken about the local flow: each particle's velocity about the mean velocity of its cell
(cells of about `flow_cell`), with the cells' own-mean correction of `temperatures`. The measured
pressure keeps the velocities as they are.)md";

const bool registered = register_plugin<Observable, Profiles>(
    "profiles",
    "profiles along an axis (slabs): density, packing fraction, temperatures, anisotropy, "
    "gamma(y); "
    "middle-of-the-system values",
    {choice("axis", "y", {"x", "y", "z"}, "profile direction"),
     integer("bins", "20", "number of slabs", 1, 100000),
     real("middle_window", "0.2", "",
          "width of the central window, as a fraction of the box length", 0, 1, true, false),
     integer("blocks", "16", "blocks of samples for the jackknife error bars", 2, 1000),
     boolean("pressure", "true",
             "measure the pressure tensor (kinetic + collisional virial); subscribes to collisions "
             "(event_driven engine; not measured on the dem engine)"),
     optional(text("reference_species", "",
                   "species whose temperature divides the ratios (default: first)")),
     optional(real("flow_cell", "", "length",
                   "temperatures about the local flow: the mean velocity of cells of about this "
                   "size, corrected for the cells' own mean (default: the velocities as they are)",
                   0, 1e308, true))},
    kDescription);

}  // namespace
}  // namespace gran
