// Effective restitution statistics (Barrat & Trizac 2002, Sec. III E): for every collision, the
// effective one-dimensional restitution along a chosen component, alpha_1d = -v'_12,a / v_12,a
// (Eq. (9)), which can exceed 1 because energy flows between components; its distribution on a
// linear axis and, for the large-alpha tail (~alpha^-2), on logarithmic bins; the conditional
// distribution of alpha_1d in bins of g_a = |v_12,a| / sqrt(2T) (T: mixture temperature of the
// previous sample); and the energy restitution |v'_12| / |v_12| (Eq. (10)), which exceeds 1 only
// through rotation. Densities are normalised by all recorded collisions.
#include <fmt/format.h>

#include <boost/histogram.hpp>
#include <cmath>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "observables/blocked_histogram.hpp"

namespace gran {
namespace {

namespace bh = boost::histogram;
using Linear = decltype(bh::make_histogram(bh::axis::regular<>(1, 0.0, 1.0)));
using Logarithmic =
    decltype(bh::make_histogram(bh::axis::regular<double, bh::axis::transform::log>(1, 1.0, 2.0)));

template <class H>
void write_histogram(ResultGroup& g, const std::string& name, const H& h, double total) {
    const auto& axis = h.axis();
    const auto nb = static_cast<std::size_t>(axis.size());
    std::vector<double> edges(nb + 1), density(nb), error(nb);
    for (std::size_t k = 0; k <= nb; ++k) edges[k] = axis.bin(int(k)).lower();
    for (std::size_t k = 0; k < nb; ++k) {
        const double w = edges[k + 1] - edges[k];
        const double c = h.at(int(k));
        density[k] = total > 0 ? c / (total * w) : 0.0;
        error[k] = total > 0 ? std::sqrt(c) / (total * w)
                             : 0.0;  // counting error (collisions are nearly independent)
    }
    g.histogram(name + "/", edges, density, error);
}

template <int D>
class RestitutionStatistics final : public Observable<D>, public CollisionSink<D> {
  public:
    RestitutionStatistics(const Params& p, const SceneInfo& info)
        : table_(*info.species),
          linear_(bh::make_histogram(linear_axis(p))),
          tail_(bh::make_histogram(
              bh::axis::regular<double, bh::axis::transform::log>(40, 1.0, 1000.0))),
          energy_(bh::make_histogram(bh::axis::regular<>(100, 0.0, 2.0))) {
        const std::string c = p.str("component");
        component_ = c == "x" ? 0 : (c == "y" ? 1 : 2);
        if (component_ >= D)
            p.fail("component", "component " + c + " does not exist in this dimension");
        for (double g : p.reals("conditional_g")) {
            conditional_g_.push_back(g);
            conditional_.push_back(bh::make_histogram(linear_axis(p)));
            conditional_total_.push_back(0);
        }
        width_g_ = p.real("conditional_width");
    }

    // The alpha_1d axis [min, max]: refused unless min < max with a finite width (found by
    // `make fuzz`: min = max and max = 1e308, min = -1e308 escaped as Boost.Histogram errors).
    static bh::axis::regular<> linear_axis(const Params& p) {
        const double lo = p.real("min"), hi = p.real("max");
        if (!(hi > lo) || !std::isfinite(hi - lo)) {
            p.fail("max",
                   fmt::format("[min, max] = [{:g}, {:g}] is not an interval of finite width "
                               "with min < max",
                               lo, hi));
        }
        return bh::axis::regular<>(unsigned(p.integer("bins")), lo, hi);
    }

    CollisionSink<D>* collision_sink() override { return this; }

    void on_collision(const CollisionRecord<D>& c) override {
        if (!measuring_) return;
        const Vec<D> g = c.vi - c.vj;
        const Vec<D> g_after = c.vi_after - c.vj_after;
        if (g[component_] == 0.0) return;  // alpha_1d undefined
        const double a1d = -g_after[component_] / g[component_];
        ++total_;
        if (a1d > 1) ++above_one_;
        linear_(a1d);
        tail_(a1d);
        energy_(g_after.norm() / g.norm());
        if (temperature_ > 0) {
            const double gx = std::abs(g[component_]) / std::sqrt(2 * temperature_);
            for (std::size_t k = 0; k < conditional_g_.size(); ++k) {
                if (std::abs(gx - conditional_g_[k]) < 0.5 * width_g_) {
                    conditional_[k](a1d);
                    ++conditional_total_[k];
                }
            }
        }
    }

    void sample(const SampleContext<D>& ctx) override {
        measuring_ = ctx.measuring;
        // Mixture temperature for the conditional distributions.
        const auto& p = ctx.engine.particles();
        double e = 0;
        for (std::size_t i = 0; i < p.size(); ++i)
            e += table_.species[p.species[i]].mass * p.v[i].squaredNorm();
        temperature_ = e / (D * double(p.size()));
    }

    void write(ResultGroup& g) const override {
        const double total = double(total_);
        g.value("collisions", total_);
        g.attr("component", std::string(component_name(component_)));
        write_histogram(g, "alpha_1d", linear_, total);
        write_histogram(g, "alpha_1d_tail", tail_, total);
        write_histogram(g, "energy_restitution", energy_, total);
        for (std::size_t k = 0; k < conditional_g_.size(); ++k) {
            const std::string name = "conditional/g_" + std::to_string(k);
            write_histogram(g, name, conditional_[k], double(conditional_total_[k]));
            g.attr_on(name, "g", conditional_g_[k]);
        }
        const double f = total > 0 ? double(above_one_) / total : 0;
        g.estimate("fraction_above_one",
                   Estimate{f, total > 0 ? std::sqrt(f * (1 - f) / total) : 0}, "");
    }

    // The histograms' axes come from the parameters: only their counts are archived.
    void checkpoint(StateArchive& ar) override {
        ar.section("restitution_statistics");
        checkpoint_counts(ar, linear_);
        checkpoint_counts(ar, tail_);
        checkpoint_counts(ar, energy_);
        for (auto& h : conditional_) checkpoint_counts(ar, h);
        ar.io(conditional_total_);
        ar.io(temperature_);
        ar.io(measuring_);
        ar.io(total_);
        ar.io(above_one_);
    }

  private:
    const SpeciesTable& table_;
    int component_ = 0;
    Linear linear_;
    Logarithmic tail_;
    Linear energy_;
    std::vector<double> conditional_g_;
    std::vector<Linear> conditional_;
    std::vector<std::uint64_t> conditional_total_;
    double width_g_ = 0.1;
    double temperature_ = 0;
    bool measuring_ = false;
    std::uint64_t total_ = 0, above_one_ = 0;
};

const char* const kDescription =
    R"md(
Per collision, the effective restitution along one component, alpha_1d = -v'_12,a / v_12,a
(Barrat & Trizac 2002, Eq. (9)): its distribution `alpha_1d/{edges,density,error}`, the tail on
logarithmic bins from 1 to 1000 (`alpha_1d_tail`, decays as alpha_1d^-2), conditional
distributions given g_a = |v_12,a| / sqrt(2T) (`conditional/g_k`, attribute `g`), the energy
restitution |v'_12| / |v_12| (Eq. (10), `energy_restitution`) and `fraction_above_one`. Needs
binary collision records: refused on the dem engine.)md";

const bool registered = register_plugin<Observable, RestitutionStatistics>(
    "restitution_statistics",
    "effective restitution alpha_1d = -v'_12,a / v_12,a per collision (Eq. 9), its tail, "
    "conditional "
    "distributions given g_a, and the energy restitution (Eq. 10)",
    {choice("component", "x", {"x", "y", "z"},
            "component a of the projected collisions (x: across the injection)"),
     integer("bins", "120", "bins of the linear histograms", 4, 100000),
     real("min", "-1", "", "lower end of the linear alpha_1d histograms"),
     real("max", "5", "", "upper end of the linear alpha_1d histograms"),
     [] {
         ParamSpec s =
             real("conditional_g", "[0.1, 0.5, 1.0]", "",
                  "values of g_a = |v_12,a|/sqrt(2T) for the conditional distributions", 0, 1e308);
         s.type = ParamType::RealList;
         return s;
     }(),
     real("conditional_width", "0.1", "",
          "width of the g_a window of each conditional distribution", 0, 1e308, true)},
    kDescription);

}  // namespace
}  // namespace gran
