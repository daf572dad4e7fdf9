// Velocity distributions per species and component: raw P(v_a) and rescaled P(c_a) with
// c_a = (v_a - U_a) / sqrt(T_{s,a}/m_s) using the instantaneous species-component temperature (so
// the rescaled PDF is meaningful in cooling states too; Barrat & Trizac 2002 Figs. 6-7, 17).
// Histograms are Boost.Histogram regular axes. Error bars: the measurement is split into `blocks`
// consecutive blocks; the error of each bin is the standard error of the block densities. The
// kurtosis <c_a^4>/<c_a^2>^2 (3 for a Gaussian) is reported with a jackknife error.
#include <boost/histogram.hpp>
#include <cmath>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "observables/block_clock.hpp"
#include "observables/blocked_histogram.hpp"
#include "observables/local_flow.hpp"

namespace gran {
namespace {

template <int D>
class VelocityPdf final : public Observable<D> {
  public:
    VelocityPdf(const Params& p, const SceneInfo& info)
        : table_(*info.species),
          bins_(static_cast<unsigned>(p.integer("bins"))),
          range_(p.real("range")),
          nblocks_(static_cast<std::size_t>(p.integer("blocks"))),
          raw_range_(p.has("raw_range") ? p.real("raw_range") : 0.0) {
        per_.resize(table_.size());
        if (p.has("flow_cell")) {
            std::size_t n = 0;
            for (const auto& sp : table_.species) n += sp.count;
            check_flow_cell(p.real("flow_cell"), info.box_length, n, D,
                            [&](const std::string& why) { p.fail("flow_cell", why); });
            flow_ = LocalFlow<D>(p.real("flow_cell"), info.box_length, table_.size());
            local_ = true;
        }
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const auto& p = ctx.engine.particles();
        const std::size_t ns = table_.size();
        if (!initialised_) init(ctx);
        const BlockClock::Place place =
            clock_.place(samples_, ctx.expected_samples, ctx.open_ended);
        const std::size_t block = place.block;
        ++samples_;
        const Vec<D> u = centre_of_mass_velocity<D>(p, table_);
        if (local_) flow_.compute(p, table_);
        const auto peculiar = [&](std::size_t i) -> Vec<D> {
            return p.v[i] - (local_ ? flow_.flow_of(i) : u);
        };
        // Instantaneous per-species, per-component variance for rescaling.
        std::vector<Vec<D>> var(ns, Vec<D>::Zero());
        std::vector<double> cnt(ns, 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Vec<D> c = peculiar(i);
            var[p.species[i]] += c.cwiseProduct(c);
            cnt[p.species[i]] += 1;
        }
        // Standard deviations per species and component, once per sample (not per particle).
        std::vector<Vec<D>> sd(ns);
        for (std::size_t s = 0; s < ns; ++s) {
            for (int a = 0; a < D; ++a) sd[s][a] = std::sqrt(var[s][a] / cnt[s]);
        }
        // About the local flow each particle has its own spread, sqrt(sum_t G_it v_t) (the
        // fewer grains in its cell, the smaller): rescaled by it, Gaussian velocities stay
        // Gaussian (local_flow.hpp).
        const std::vector<Vec<D>> v_local =
            local_ ? local_variances(p, var) : std::vector<Vec<D>>();
        std::vector<Vec<D>> m2(ns, Vec<D>::Zero()), m4(ns, Vec<D>::Zero());
        std::vector<double> used = cnt;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            auto& q = per_[s];
            const Vec<D> c = peculiar(i);
            Vec<D> spread = sd[s];
            if (local_) {
                spread = own_spread(i, s, v_local);
                // Alone in its cell: no velocity about the cell's mean to measure.
                if (!(spread[0] > 0)) {
                    used[s] -= 1;
                    continue;
                }
            }
            for (int a = 0; a < D; ++a) {
                const double x = c[a] / spread[a];
                q.raw[a].blocks[block](c[a]);
                q.scaled[a].blocks[block](x);
                m2[s][a] += x * x;
                m4[s][a] += x * x * x * x;
            }
        }
        for (std::size_t s = 0; s < ns; ++s) {
            for (int a = 0; a < D; ++a) {
                per_[s].raw[a].entries[block] += used[s];
                per_[s].scaled[a].entries[block] += used[s];
                per_[s].c2[a].push(m2[s][a] / used[s]);
                per_[s].c4[a].push(m4[s][a] / used[s]);
            }
        }
        if (place.merge_after) {
            for (auto& q : per_) {
                for (int a = 0; a < D; ++a) {
                    q.raw[a].merge_pairs();
                    q.scaled[a].merge_pairs();
                }
            }
        }
    }

    void write(ResultGroup& g) const override {
        if (!initialised_) return;
        for (std::size_t s = 0; s < table_.size(); ++s) {
            ResultGroup gs = g.group(table_.species[s].name);
            for (int a = 0; a < D; ++a) {
                ResultGroup gc = gs.group(component_name(a));
                per_[s].raw[a].write(gc, "raw_", 1.0, "velocity");
                per_[s].scaled[a].write(gc, "scaled_", 1.0, "sqrt(T_{s,a}/m_s)");
                const Estimate k =
                    jackknife({per_[s].c4[a].values(), per_[s].c2[a].values()},
                              [](std::span<const double> m) { return m[0] / (m[1] * m[1]); });
                gc.estimate("kurtosis", k, "");
            }
        }
        g.attr("blocks", static_cast<std::int64_t>(nblocks_));
        g.attr("normalisation", "density: integral over all bins plus out-of-range mass equals 1");
    }

    // The histograms' axes are archived with them (the raw range is set at the first sample).
    void checkpoint(StateArchive& ar) override {
        ar.section("velocity_pdf");
        ar.io(initialised_);
        ar.io(samples_);
        ar.io(per_);
        clock_.checkpoint(ar);
    }

  private:
    // Per-component variances v_{t,a} = T_{t,a} / m_t about the local flow: the solution of
    // sum_t G_st v_{t,a} = sum_{i in s} c_{i,a}^2 (`sum2`).
    std::vector<Vec<D>> local_variances(const Particles<D>& p,
                                        const std::vector<Vec<D>>& sum2) const {
        const std::size_t ns = table_.size();
        std::vector<double> g(ns * ns, 0.0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            flow_.add_variance_weights(i, s, table_.species[s].mass, &g[s * ns]);
        }
        std::vector<Vec<D>> v(ns);
        for (int a = 0; a < D; ++a) {
            std::vector<double> rhs(ns);
            for (std::size_t s = 0; s < ns; ++s) rhs[s] = sum2[s][a];
            const std::vector<double> x = solve_small(g, rhs);
            for (std::size_t s = 0; s < ns; ++s) v[s][a] = x[s];
        }
        return v;
    }

    Vec<D> own_spread(std::size_t i, std::uint32_t s, const std::vector<Vec<D>>& v) const {
        std::vector<double> g(table_.size(), 0.0);
        flow_.add_variance_weights(i, s, table_.species[s].mass, g.data());
        Vec<D> out = Vec<D>::Zero();
        for (std::size_t t = 0; t < g.size(); ++t) out += g[t] * v[t];
        for (int a = 0; a < D; ++a) out[a] = std::sqrt(out[a]);
        return out;
    }

    struct PerSpecies {
        std::array<BlockedHistogram, D> raw, scaled;
        std::array<Series, D> c2, c4;

        void checkpoint(StateArchive& ar) {
            ar.io(raw);
            ar.io(scaled);
            ar.io(c2);
            ar.io(c4);
        }
    };

    void init(const SampleContext<D>& ctx) {
        namespace bh = boost::histogram;
        for (std::size_t s = 0; s < table_.size(); ++s) {
            const double m = table_.species[s].mass;
            // Default raw range: 6 thermal velocities of the first measured sample's temperature.
            double t = 0;
            std::size_t c = 0;
            const auto& p = ctx.engine.particles();
            for (std::size_t i = 0; i < p.size(); ++i) {
                if (p.species[i] == s) {
                    t += m * p.v[i].squaredNorm() / D;
                    ++c;
                }
            }
            const double vr = raw_range_ > 0
                                  ? raw_range_
                                  : 6.0 * std::sqrt(t / double(std::max<std::size_t>(c, 1)) / m);
            for (int a = 0; a < D; ++a) {
                per_[s].raw[a].blocks.assign(
                    nblocks_, bh::make_histogram(bh::axis::regular<>(bins_, -vr, vr)));
                per_[s].raw[a].entries.assign(nblocks_, 0);
                per_[s].scaled[a].blocks.assign(
                    nblocks_, bh::make_histogram(bh::axis::regular<>(bins_, -range_, range_)));
                per_[s].scaled[a].entries.assign(nblocks_, 0);
            }
        }
        initialised_ = true;
    }

    const SpeciesTable& table_;
    unsigned bins_;
    double range_;
    std::size_t nblocks_;
    BlockClock clock_{nblocks_};
    double raw_range_;
    bool initialised_ = false;
    std::size_t samples_ = 0;
    std::vector<PerSpecies> per_;
    bool local_ = false;  // velocities about the local flow (`flow_cell`)
    LocalFlow<D> flow_;
};

const char* const kDescription =
    R"md(
Per species and component: raw P(v_a) and rescaled P(c_a), c_a = v_a / sqrt(T_{s,a}/m_s), with
block error bars (consecutive blocks of samples); kurtosis <c^4>/<c^2>^2. Velocities are taken
about the centre-of-mass velocity, or with `flow_cell` about the mean velocity of their cell of
the local flow, each rescaled by its own expected spread about its cell's mean (smaller in cells
of few grains; observables/local_flow.hpp), so that Gaussian velocities stay Gaussian. The cell's
mean still mixes in the other grains of the cell, which pulls a non-Gaussian kurtosis towards 3
by about 1/n for n grains per cell; `temperatures` with the same `flow_cell` gives a2 corrected for
it.)md";

const bool registered = register_plugin<Observable, VelocityPdf>(
    "velocity_pdf",
    "velocity distributions per species and component, raw and rescaled by sqrt(T), with kurtosis",
    {integer("bins", "60", "histogram bins", 4, 100000),
     real("range", "6", "sqrt(T/m)", "rescaled histograms cover c in [-range, range]", 0, 1e6,
          true),
     optional(real(
         "raw_range", "", "velocity",
         "raw histograms cover v in [-raw_range, raw_range] (default: 6 thermal velocities at the "
         "first sample)",
         0, 1e300, true)),  // [-1e308, 1e308] would be an axis of infinite width
     integer("blocks", "16", "blocks for the error bars of the densities", 2, 1000),
     optional(real("flow_cell", "", "length",
                   "measure velocities about the local flow: the mean velocity of cells of about "
                   "this size (default: about the centre-of-mass velocity)",
                   0, 1e308, true))},
    kDescription);

}  // namespace
}  // namespace gran
