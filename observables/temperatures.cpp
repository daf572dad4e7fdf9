// Per-species, per-component translational temperatures T_{s,a} = m_s <(v_a - U_a)^2> (U:
// centre-of- mass velocity), rotational temperatures (I <w^2> per rotational degree of freedom),
// the mixture temperature, temperature ratios gamma = T_s / T_ref (total, per component,
// rotational; Barrat & Trizac 2002 Tables I-II) and the Sonine coefficient a2 = d/(d+2)
// <c^4>/<c^2>^2 - 1 per species. Ratios and a2 are ratios of time averages with jackknife errors
// over decorrelated blocks.
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "libgran/plugins/observable.hpp"

namespace gran {
namespace {

template <int D>
class Temperatures final : public Observable<D> {
  public:
    Temperatures(const Params& p, const SceneInfo& info) : table_(*info.species) {
        const std::string ref =
            p.has("reference_species") ? p.str("reference_species") : table_.species[0].name;
        ref_ = table_.index_of(ref);
        if (ref_ == table_.size()) p.fail("reference_species", "unknown species '" + ref + "'");
        per_species_.resize(table_.size());
        rotating_ = info.rotating;
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const auto& p = ctx.engine.particles();
        const std::size_t ns = table_.size();
        const Vec<D> u = centre_of_mass_velocity<D>(p, table_);
        std::vector<Vec<D>> sum2(ns, Vec<D>::Zero());
        std::vector<double> sum4(ns, 0), sumr(ns, 0), sumv2(ns, 0);
        std::vector<std::size_t> count(ns, 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            const Vec<D> c = p.v[i] - u;
            const Vec<D> c2 = c.cwiseProduct(c);
            sum2[s] += c2;
            const double v2 = c2.sum();
            sumv2[s] += v2;
            sum4[s] += v2 * v2;
            if (rotating_) sumr[s] += ang_squared<D>(p.w[i]);
            ++count[s];
        }
        double t_mix = 0;
        std::size_t n_mix = 0;
        for (std::size_t s = 0; s < ns; ++s) {
            auto& q = per_species_[s];
            const double m = table_.species[s].mass;
            const double n = double(count[s]);
            double t_total = 0;
            for (int a = 0; a < D; ++a) {
                const double t = m * sum2[s][a] / n;
                q.t_comp[a].push(t);
                t_total += t / D;
            }
            q.t.push(t_total);
            q.v2.push(sumv2[s] / n);
            q.v4.push(sum4[s] / n);
            if (rotating_) {
                const double inertia = table_.species[s].inertia_factor * m *
                                       table_.species[s].diameter * table_.species[s].diameter / 4;
                q.t_rot.push(inertia * sumr[s] / n / (D == 2 ? 1.0 : 3.0));
            }
            t_mix += t_total * n;
            n_mix += count[s];
        }
        mixture_.push(t_mix / double(n_mix));
        time_.push(ctx.time);
        steps_.push_back(ctx.step);
    }

    void write(ResultGroup& g) const override {
        const std::string tunit = "energy";
        g.estimate("T_mixture", mixture_.estimate(), tunit);
        // H5MD time series {step, time, value}; every series shares the mixture's step and time.
        const auto steps = std::span<const std::int64_t>(steps_);
        const auto times = time_.values();
        g.time_series("series/T_mixture", steps, times, mixture_.values(), tunit);
        const std::string clock = g.path() + "/series/T_mixture";
        auto series = [&](ResultGroup& at, const std::string& name, std::span<const double> v,
                          const std::string& unit) {
            at.time_series("series/" + name, steps, times, v, unit, clock);
        };
        for (std::size_t s = 0; s < table_.size(); ++s) {
            const auto& q = per_species_[s];
            const std::string name = table_.species[s].name;
            ResultGroup gs = g.group(name, {"species", name});
            gs.estimate("T", q.t.estimate(), tunit);
            series(gs, "T", q.t.values(), tunit);
            for (int a = 0; a < D; ++a) {
                const std::string c = std::string("T_") + component_name(a);
                gs.estimate(c, q.t_comp[a].estimate(), tunit);
                series(gs, c, q.t_comp[a].values(), tunit);
            }
            if (rotating_) {
                gs.estimate("T_rot", q.t_rot.estimate(), tunit);
                series(gs, "T_rot", q.t_rot.values(), tunit);
            }
            if (q.v2.size() > 0) {
                const double k_factor = double(D) / (D + 2.0);
                const Estimate a2 = jackknife({q.v4.values(), q.v2.values()},
                                              [k_factor](std::span<const double> m) {
                                                  return k_factor * m[0] / (m[1] * m[1]) - 1.0;
                                              });
                gs.estimate("sonine_a2", a2, "");
                // Instantaneous a2 of each sample: scale-free, so usable in cooling states where
                // time averages of moments mix temperatures.
                std::vector<double> inst(q.v2.size());
                for (std::size_t k = 0; k < inst.size(); ++k) {
                    inst[k] =
                        k_factor * q.v4.values()[k] / (q.v2.values()[k] * q.v2.values()[k]) - 1.0;
                }
                series(gs, "sonine_a2", inst, "");
            }
            if (s == ref_) continue;
            const auto& r = per_species_[ref_];
            ResultGroup gr = g.group("ratios").group(name + "_over_" + table_.species[ref_].name);
            gr.estimate("gamma", ratio_of_means(q.t.values(), r.t.values()), "");
            for (int a = 0; a < D; ++a) {
                gr.estimate(std::string("gamma_") + component_name(a),
                            ratio_of_means(q.t_comp[a].values(), r.t_comp[a].values()), "");
            }
            if (rotating_)
                gr.estimate("gamma_rot", ratio_of_means(q.t_rot.values(), r.t_rot.values()), "");
        }
        g.attr("reference_species", table_.species[ref_].name);
        g.attr("definition",
               "T_{s,a} = m_s <(v_a - U_a)^2>, U centre-of-mass velocity; gamma = T_s / T_ref");
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("temperatures");
        ar.io(per_species_);
        ar.io(mixture_);
        ar.io(time_);
        ar.io(steps_);
    }

  private:
    struct PerSpecies {
        Series t;
        std::array<Series, D> t_comp;
        Series t_rot;
        Series v2, v4;

        void checkpoint(StateArchive& ar) {
            ar.io(t);
            ar.io(t_comp);
            ar.io(t_rot);
            ar.io(v2);
            ar.io(v4);
        }
    };
    const SpeciesTable& table_;
    std::size_t ref_ = 0;
    bool rotating_ = false;
    std::vector<PerSpecies> per_species_;
    Series mixture_;
    Series time_;
    std::vector<std::int64_t> steps_;  // the engine's events or steps at each sample
};

const char* const kDescription =
    R"md(
Per species: T, T_x, T_y (T_z), T_rot (rough particles), Sonine a2, with errors and time series
(`series/<quantity>` as H5MD {step, time, value}, sharing one step and time);
ratios gamma = T_s / T_ref (total, per component, rotational); the mixture temperature.)md";

const bool registered = register_plugin<Observable, Temperatures>(
    "temperatures",
    "per-species and per-component temperatures, rotational temperatures, ratios gamma = "
    "T_s/T_ref, "
    "Sonine a2",
    {optional(text("reference_species", "",
                   "species whose temperature divides the ratios (default: first)"))},
    kDescription);

}  // namespace
}  // namespace gran
