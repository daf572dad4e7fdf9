// Velocity distributions in slabs across the system (Barrat & Trizac 2002, Figs. 6-7, 17): for each
// slab (centre and width as fractions of the box length along `axis`), species and component, the
// raw distribution P(v_a) and the distribution of c_a = v_a / sqrt(T_{s,a}(slab)/m_s) rescaled by
// the slab's time-averaged temperature (an exact change of variable of the raw histogram), with
// block error bars and the kurtosis <v_a^4>/<v_a^2>^2 (3 for a Gaussian). Near a sawtooth wall the
// normal-velocity distribution has two peaks (incoming and outgoing particles).
#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "observables/block_clock.hpp"
#include "observables/blocked_histogram.hpp"

namespace gran {
namespace {

template <int D>
class SlabVelocityPdf final : public Observable<D> {
  public:
    SlabVelocityPdf(const Params& p, const SceneInfo& info)
        : table_(*info.species),
          centres_(p.reals("slabs")),
          width_(p.real("width")),
          bins_(static_cast<unsigned>(p.integer("bins"))),
          range_(p.real("range")),
          nblocks_(static_cast<std::size_t>(p.integer("blocks"))) {
        const std::string axis = p.str("axis");
        axis_ = axis == "x" ? 0 : (axis == "y" ? 1 : 2);
        if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", axis, D));
        length_ = info.box_length[std::size_t(axis_)];
        for (double c : centres_) {
            if (c < 0 || c > 1)
                p.fail("slabs", "slab centres are fractions of the box length, in [0, 1]");
        }
        cells_.resize(centres_.size() * table_.size() * D);
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const auto& p = ctx.engine.particles();
        if (!initialised_) init(p);
        const BlockClock::Place place =
            clock_.place(samples_, ctx.expected_samples, ctx.open_ended);
        const std::size_t block = place.block;
        ++samples_;
        for (std::size_t i = 0; i < p.size(); ++i) {
            double y = p.r[i][axis_];
            y = y / length_ - std::floor(y / length_);
            for (std::size_t k = 0; k < centres_.size(); ++k) {
                if (std::abs(y - centres_[k]) >= 0.5 * width_) continue;
                for (int a = 0; a < D; ++a) {
                    Cell& c = cell(k, p.species[i], a);
                    const double v = p.v[i][a];
                    c.hist.blocks[block](v);
                    c.hist.entries[block] += 1;
                    c.n += 1;
                    c.m2 += v * v;
                    c.m4 += v * v * v * v;
                }
            }
        }
        if (place.merge_after) {
            for (Cell& c : cells_) c.hist.merge_pairs();
        }
    }

    void write(ResultGroup& g) const override {
        if (!initialised_) return;
        g.attr("axis", std::string(component_name(axis_)));
        g.attr("width", width_);
        for (std::size_t k = 0; k < centres_.size(); ++k) {
            ResultGroup slab = g.group("slab_" + std::to_string(k));
            slab.attr("centre", centres_[k]);
            for (std::size_t s = 0; s < table_.size(); ++s) {
                for (int a = 0; a < D; ++a) {
                    const Cell& c = cell(k, s, a);
                    if (c.n == 0) continue;
                    ResultGroup gc = slab.group(table_.species[s].name).group(component_name(a));
                    const double var = c.m2 / c.n;
                    c.hist.write(gc, "raw_");
                    c.hist.write(gc, "scaled_", std::sqrt(var));
                    gc.file_only().value("temperature", table_.species[s].mass * var);
                    gc.value("kurtosis", (c.m4 / c.n) / (var * var));
                }
            }
        }
    }

    // The histograms' axes are archived with them (the raw range is set at the first sample).
    void checkpoint(StateArchive& ar) override {
        ar.section("slab_velocity_pdf");
        ar.io(initialised_);
        ar.io(samples_);
        ar.io(cells_);
        clock_.checkpoint(ar);
    }

  private:
    struct Cell {
        BlockedHistogram hist;
        double n = 0, m2 = 0, m4 = 0;

        void checkpoint(StateArchive& ar) {
            ar.io(hist);
            ar.io(n);
            ar.io(m2);
            ar.io(m4);
        }
    };
    Cell& cell(std::size_t k, std::size_t s, int a) {
        return cells_[(k * table_.size() + s) * D + std::size_t(a)];
    }
    const Cell& cell(std::size_t k, std::size_t s, int a) const {
        return cells_[(k * table_.size() + s) * D + std::size_t(a)];
    }

    void init(const Particles<D>& p) {
        namespace bh = boost::histogram;
        // Raw range: `range` thermal velocities of the first sample's mean kinetic energy, per
        // species.
        for (std::size_t s = 0; s < table_.size(); ++s) {
            double e = 0, n = 0;
            for (std::size_t i = 0; i < p.size(); ++i) {
                if (p.species[i] == s) {
                    e += p.v[i].squaredNorm() / D;
                    n += 1;
                }
            }
            const double vmax = range_ * std::sqrt(e / std::max(n, 1.0));
            for (std::size_t k = 0; k < centres_.size(); ++k) {
                for (int a = 0; a < D; ++a) {
                    Cell& c = cell(k, s, a);
                    c.hist.blocks.assign(
                        nblocks_, bh::make_histogram(bh::axis::regular<>(bins_, -vmax, vmax)));
                    c.hist.entries.assign(nblocks_, 0);
                }
            }
        }
        initialised_ = true;
    }

    const SpeciesTable& table_;
    std::vector<double> centres_;
    double width_;
    unsigned bins_;
    double range_;
    std::size_t nblocks_;
    BlockClock clock_{nblocks_};
    int axis_ = 1;
    double length_ = 1;
    bool initialised_ = false;
    std::size_t samples_ = 0;
    std::vector<Cell> cells_;
};

const char* const kDescription =
    R"md(
Velocity distributions in chosen slabs: per slab (`slab_k`, attribute `centre`), species and
component, raw `raw_{edges,density,error}` and rescaled by the slab's time-averaged temperature
`scaled_{edges,density,error}`, with `temperature` and `kurtosis`. Next to a sawtooth wall the
normal component is double-peaked (Barrat & Trizac 2002, Fig. 6).)md";

const bool registered = register_plugin<Observable, SlabVelocityPdf>(
    "slab_velocity_pdf",
    "velocity distributions in slabs across the system, raw and rescaled by the slab temperature, "
    "with kurtosis",
    {choice("axis", "y", {"x", "y", "z"}, "direction across the slabs"),
     [] {
         ParamSpec s = real("slabs", "[0.05, 0.25, 0.5]", "",
                            "slab centres as fractions of the box length", 0, 1);
         s.type = ParamType::RealList;
         return s;
     }(),
     real("width", "0.1", "", "slab width as a fraction of the box length", 0, 1, true, false),
     integer("bins", "80", "histogram bins", 4, 100000),
     real("range", "8", "thermal velocities",
          "raw histograms cover +-range thermal velocities of the first sample", 0, 1e6, true),
     integer("blocks", "16", "blocks for the error bars", 2, 1000)},
    kDescription);

}  // namespace
}  // namespace gran
