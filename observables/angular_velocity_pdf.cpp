// Angular-velocity distributions of rough particles (Barrat & Trizac 2002, Fig. 7b): per species
// and rotation component (the single component w_z in 2D, x, y, z in 3D), the rescaled P(c_w) with
// c_w = w_a / sqrt(T_rot,s / I_s), T_rot,s the instantaneous rotational temperature per degree of
// freedom of the species and I_s its moment of inertia; error bars from blocks of the measurement,
// kurtosis <c^4>/<c^2>^2 (3 for a Gaussian) with a jackknife error. Smooth particles have no
// angular velocities: the observable then records only that (so studies may sweep beta to -1).
#include <boost/histogram.hpp>
#include <cmath>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "observables/block_clock.hpp"
#include "observables/blocked_histogram.hpp"

namespace gran {
namespace {

template <int D>
class AngularVelocityPdf final : public Observable<D> {
    static constexpr int kComponents = D == 2 ? 1 : 3;

  public:
    AngularVelocityPdf(const Params& p, const SceneInfo& info)
        : table_(*info.species),
          rotating_(info.rotating),
          bins_(static_cast<unsigned>(p.integer("bins"))),
          range_(p.real("range")),
          nblocks_(static_cast<std::size_t>(p.integer("blocks"))) {
        namespace bh = boost::histogram;
        per_.resize(table_.size());
        for (auto& s : per_) {
            for (auto& h : s.scaled) {
                h.blocks.assign(nblocks_,
                                bh::make_histogram(bh::axis::regular<>(bins_, -range_, range_)));
                h.entries.assign(nblocks_, 0);
            }
        }
    }

    static double component(const AngVec<D>& w, int a) {
        if constexpr (D == 2) {
            (void)a;
            return w;
        } else {
            return w[a];
        }
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring || !rotating_) return;
        const auto& p = ctx.engine.particles();
        const std::size_t ns = table_.size();
        const BlockClock::Place place =
            clock_.place(samples_, ctx.expected_samples, ctx.open_ended);
        const std::size_t block = place.block;
        ++samples_;
        std::vector<double> w2(ns, 0), cnt(ns, 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            w2[p.species[i]] += ang_squared<D>(p.w[i]);
            cnt[p.species[i]] += kComponents;
        }
        std::vector<double> m2(ns, 0), m4(ns, 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            const double sd = std::sqrt(w2[s] / cnt[s]);  // sqrt(T_rot / I) per component
            if (!(sd > 0)) continue;
            for (int a = 0; a < kComponents; ++a) {
                const double x = component(p.w[i], a) / sd;
                per_[s].scaled[std::size_t(a)].blocks[block](x);
                per_[s].scaled[std::size_t(a)].entries[block] += 1;
                m2[s] += x * x;
                m4[s] += x * x * x * x;
            }
        }
        for (std::size_t s = 0; s < ns; ++s) {
            if (cnt[s] == 0) continue;
            per_[s].c2.push(m2[s] / cnt[s]);
            per_[s].c4.push(m4[s] / cnt[s]);
        }
        if (place.merge_after) {
            for (auto& q : per_) {
                for (auto& h : q.scaled) h.merge_pairs();
            }
        }
    }

    void write(ResultGroup& out) const override {
        if (!rotating_) {
            out.text("note", "smooth particles (every beta = -1): no angular velocities");
            return;
        }
        if (samples_ == 0) return;
        for (std::size_t s = 0; s < table_.size(); ++s) {
            const std::string name = table_.species[s].name;
            ResultGroup gs = out.group(name);
            for (int a = 0; a < kComponents; ++a) {
                const std::string comp = D == 2 ? "z" : component_name(a);
                ResultGroup gc = gs.group(comp);
                per_[s].scaled[std::size_t(a)].write(gc, "scaled_", 1.0, "sqrt(T_rot,s/I_s)");
            }
            if (per_[s].c2.size() < 2) continue;
            const Estimate k =
                jackknife({per_[s].c4.values(), per_[s].c2.values()},
                          [](std::span<const double> m) { return m[0] / (m[1] * m[1]); });
            gs.estimate("kurtosis", k, "");
        }
        out.attr("blocks", static_cast<std::int64_t>(nblocks_));
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("angular_velocity_pdf");
        ar.io(samples_);
        ar.io(per_);
        clock_.checkpoint(ar);
    }

  private:
    struct PerSpecies {
        std::array<BlockedHistogram, kComponents> scaled;
        Series c2, c4;

        void checkpoint(StateArchive& ar) {
            ar.io(scaled);
            ar.io(c2);
            ar.io(c4);
        }
    };
    const SpeciesTable& table_;
    bool rotating_ = false;  // the grains carry angular velocities
    unsigned bins_;
    double range_;
    std::size_t nblocks_;
    BlockClock clock_{nblocks_};
    std::size_t samples_ = 0;
    std::vector<PerSpecies> per_;
};

const char* const kDescription =
    R"md(
Angular-velocity distributions of rough particles (some pair with beta != -1; with smooth particles
only a note is written; Barrat & Trizac 2002, Fig. 7b): per species and component (`z` in 2D; `x`,
`y`, `z` in 3D), the density of c = w_a / sqrt(T_rot,s / I_s) with the instantaneous rotational
temperature, error bars from blocks, and the kurtosis per species (3 for a Gaussian) with a
jackknife error.)md";

const bool registered = register_plugin<Observable, AngularVelocityPdf>(
    "angular_velocity_pdf",
    "angular-velocity distributions of rough particles per species, rescaled by sqrt(T_rot/I), "
    "with kurtosis",
    {integer("bins", "60", "histogram bins", 4, 100000),
     real("range", "6", "sqrt(T_rot/I)", "histograms cover c in [-range, range]", 0, 1e6, true),
     integer("blocks", "16", "blocks for the error bars of the densities", 2, 1000)},
    kDescription);

}  // namespace
}  // namespace gran
