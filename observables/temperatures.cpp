// Per-species, per-component translational temperatures T_{s,a} = m_s <(v_a - U_a)^2> (U:
// centre-of- mass velocity), rotational temperatures (I <w^2> per rotational degree of freedom),
// the mixture temperature, temperature ratios gamma = T_s / T_ref (total, per component,
// rotational; Barrat & Trizac 2002 Tables I-II) and the Sonine coefficient a2 = d/(d+2)
// <c^4>/<c^2>^2 - 1 per species. Ratios and a2 are ratios of time averages with jackknife errors
// over decorrelated blocks.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "libgran/plugins/observable.hpp"
#include "observables/local_flow.hpp"

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
        // Free cooling: no driver and some contact dissipates (an elastic gas is stationary).
        cooling_ = !info.driven &&
                   std::any_of(info.nominal_restitution.begin(), info.nominal_restitution.end(),
                               [](double e) { return e < 1; });
        if (p.has("flow_cell")) {
            const double cell = p.real("flow_cell");
            if (table_.size() > kMaxFlowSpecies)
                p.fail("flow_cell", fmt::format("velocities about the local flow are measured for "
                                                "at most {} species; this scene has {}",
                                                kMaxFlowSpecies, table_.size()));
            std::size_t n = 0;
            for (const auto& sp : table_.species) n += sp.count;
            check_flow_cell(cell, info.box_length, n, D,
                            [&](const std::string& why) { p.fail("flow_cell", why); });
            flow_ = LocalFlow<D>(cell, info.box_length, table_.size());
            local_ = true;
            flow_cell_ = cell;
        }
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        const auto& p = ctx.engine.particles();
        const std::size_t ns = table_.size();
        const Vec<D> u = centre_of_mass_velocity<D>(p, table_);
        if (local_) flow_.compute(p, table_);
        std::vector<Vec<D>> sum2(ns, Vec<D>::Zero());
        std::vector<double> sum4(ns, 0), sumr(ns, 0), sumv2(ns, 0);
        std::vector<std::size_t> count(ns, 0);
        LocalSums local(local_ ? ns : 0);
        for (std::size_t i = 0; i < p.size(); ++i) {
            const std::uint32_t s = p.species[i];
            const Vec<D> c = p.v[i] - (local_ ? flow_.flow_of(i) : u);
            const Vec<D> c2 = c.cwiseProduct(c);
            sum2[s] += c2;
            const double v2 = c2.sum();
            sumv2[s] += v2;
            sum4[s] += v2 * v2;
            if (rotating_) sumr[s] += ang_squared<D>(p.w[i]);
            ++count[s];
            if (local_) local.add(flow_, i, s, table_.species[s].mass);
        }
        // About the local flow, the per-component variances v_{s,a} = T_{s,a} / m_s solve
        // sum_t G_st v_{t,a} = sum_{i in s} c_{i,a}^2 (local_flow.hpp).
        std::vector<Vec<D>> var(ns);
        if (local_) {
            for (int a = 0; a < D; ++a) {
                std::vector<double> rhs(ns);
                for (std::size_t s = 0; s < ns; ++s) rhs[s] = sum2[s][a];
                const std::vector<double> v = solve_small(local.g, rhs);
                for (std::size_t s = 0; s < ns; ++s) var[s][a] = v[s];
            }
        }
        double t_mix = 0;
        std::size_t n_mix = 0;
        std::vector<double> t_species(ns);
        for (std::size_t s = 0; s < ns; ++s) {
            auto& q = per_species_[s];
            const double m = table_.species[s].mass;
            const double n = double(count[s]);
            double t_total = 0;
            for (int a = 0; a < D; ++a) {
                // (m * sum / n about the centre of mass: the order of operations of the
                // regression references)
                const double t = local_ ? m * var[s][a] : m * sum2[s][a] / n;
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
            t_species[s] = t_total;
        }
        mixture_.push(t_mix / double(n_mix));
        time_.push(ctx.time);
        steps_.push_back(ctx.step);
        if (local_) push_local(local, sum4, p, u, t_species);
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
            if (local_) {
                gs.estimate("sonine_a2", local_sonine_a2(s), "");
            } else if (q.v2.size() > 0) {
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
        if (cooling_) {
            // Free cooling: these are averages over a state that keeps changing.
            g.attr("whole_run_average",
                   std::string("free cooling: T, gamma and a2 average the whole measurement, "
                               "transient included; the cooling_state observable measures the "
                               "scaling state"));
            spdlog::warn(
                "temperatures: free cooling, so T, gamma and a2 average the whole run, "
                "transient included; add the cooling_state observable for the scaling "
                "state");
        }
        if (local_) {
            write_flow(g);
        } else {
            g.attr("definition",
                   "T_{s,a} = m_s <(v_a - U_a)^2>, U centre-of-mass velocity; gamma = T_s / T_ref");
        }
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("temperatures");
        ar.io(per_species_);
        ar.io(mixture_);
        ar.io(time_);
        ar.io(steps_);
        if (local_) {
            ar.io(quartic_);
            ar.io(quartic_weights_);
            ar.io(variance_products_);
            ar.io(flow_share_);
            ar.io(uncorrelated_share_);
        }
    }

  private:
    static constexpr std::size_t kMaxFlowSpecies = 8;

    // One sample's sums over the particles of each species s (local flow): G_st = sum G_{i,t}
    // (ns x ns), W_st = sum W_{i,t}, H_stu = sum G_{i,t} G_{i,u} (ns^3); local_flow.hpp.
    struct LocalSums {
        std::size_t ns;
        std::vector<double> g, w, h;
        explicit LocalSums(std::size_t n)
            : ns(n), g(n * n, 0.0), w(n * n, 0.0), h(n * n * n, 0.0) {}
        void add(const LocalFlow<D>& flow, std::size_t i, std::uint32_t s, double m) {
            std::array<double, kMaxFlowSpecies> gi{}, wi{};
            flow.add_variance_weights(i, s, m, gi.data());
            flow.add_quartic_weights(i, s, m, wi.data());
            for (std::size_t t = 0; t < ns; ++t) {
                g[s * ns + t] += gi[t];
                w[s * ns + t] += wi[t];
                for (std::size_t u = 0; u < ns; ++u) h[(s * ns + t) * ns + u] += gi[t] * gi[u];
            }
        }
    };

    // The series the local-flow Sonine coefficients and the flow diagnostic need.
    void push_local(const LocalSums& local, const std::vector<double>& sum4, const Particles<D>& p,
                    const Vec<D>& u, const std::vector<double>& t_species) {
        const std::size_t ns = table_.size();
        quartic_.resize(ns);
        quartic_weights_.resize(ns * ns);
        variance_products_.resize(ns * ns * ns);
        for (std::size_t s = 0; s < ns; ++s) quartic_[s].push(sum4[s]);
        for (std::size_t k = 0; k < ns * ns; ++k) quartic_weights_[k].push(local.w[k]);
        for (std::size_t k = 0; k < ns * ns * ns; ++k) variance_products_[k].push(local.h[k]);
        double e = 0;
        for (std::size_t i = 0; i < p.size(); ++i)
            e += 0.5 * table_.species[p.species[i]].mass * (p.v[i] - u).squaredNorm();
        flow_share_.push(flow_.flow_energy(u) / e);
        uncorrelated_share_.push(flow_.uncorrelated_flow_energy(t_species) / e);
    }

    // a2 of species s about the local flow (local_flow.hpp): with v_t = <T_t> / m_t,
    //   sum_t <W_st> v_t^2 a2_t = <Q4_s> / (D (D + 2)) - sum_tu v_t v_u <H_stu>,
    // Q4_s = sum_{i in s} |c_i|^4; jackknife over the samples of every series involved.
    Estimate local_sonine_a2(std::size_t species) const {
        const std::size_t ns = table_.size();
        std::vector<std::span<const double>> series;
        for (std::size_t t = 0; t < ns; ++t) series.push_back(per_species_[t].t.values());
        for (std::size_t t = 0; t < ns; ++t) series.push_back(quartic_[t].values());
        for (const Series& x : quartic_weights_) series.push_back(x.values());
        for (const Series& x : variance_products_) series.push_back(x.values());
        return jackknife(series, [this, ns, species](std::span<const double> m) {
            std::vector<double> v(ns), a(ns * ns), rhs(ns);
            for (std::size_t t = 0; t < ns; ++t) v[t] = m[t] / table_.species[t].mass;
            const double* q4 = m.data() + ns;
            const double* w = q4 + ns;
            const double* h = w + ns * ns;
            for (std::size_t s = 0; s < ns; ++s) {
                double r = q4[s] / (D * (D + 2.0));
                for (std::size_t t = 0; t < ns; ++t) {
                    a[s * ns + t] = w[s * ns + t] * v[t] * v[t];
                    for (std::size_t x = 0; x < ns; ++x)
                        r -= v[t] * v[x] * h[(s * ns + t) * ns + x];
                }
                rhs[s] = r;
            }
            return solve_small(a, rhs)[species];
        });
    }

    // The flow's share of the kinetic energy (about the centre of mass), what independent
    // velocities would give at the measured temperatures, and their difference: the collective
    // flow.
    void write_flow(ResultGroup& g) const {
        ResultGroup f = g.group("flow");
        f.estimate("energy_share", flow_share_.estimate(), "");
        f.estimate("uncorrelated_share", uncorrelated_share_.estimate(), "");
        std::vector<double> diff(flow_share_.size());
        for (std::size_t k = 0; k < diff.size(); ++k)
            diff[k] = flow_share_.values()[k] - uncorrelated_share_.values()[k];
        f.estimate("collective_share", block_average(diff), "");
        f.attr("cells", static_cast<std::int64_t>(flow_.cells()));
        g.attr("flow_cell", flow_cell_);
        g.attr("definition",
               "T_{s,a} = m_s <(v_a - U_a)^2>, U the mass-weighted mean velocity of the particle's "
               "flow cell, corrected for the cell's own mean (local_flow.hpp); gamma = T_s / "
               "T_ref");
    }

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
    // Velocities about the local flow (`flow_cell`), and the series that needs.
    bool cooling_ = false;  // no driver and dissipative contacts: the gas cools freely
    bool local_ = false;
    double flow_cell_ = 0;
    LocalFlow<D> flow_;
    std::vector<Series> quartic_, quartic_weights_, variance_products_;
    Series flow_share_, uncorrelated_share_;
};

const char* const kDescription =
    R"md(
Per species: T, T_x, T_y (T_z), T_rot (rough particles), Sonine a2, with errors and time series
(`series/<quantity>` as H5MD {step, time, value}, sharing one step and time);
ratios gamma = T_s / T_ref (total, per component, rotational); the mixture temperature.

Velocities are taken about the centre-of-mass velocity, or with `flow_cell` about the local flow:
the mass-weighted mean velocity of the particle's cell, cells of about `flow_cell` along each axis.
The cell's own mean also removes part of each particle's thermal motion (all of it in a cell of
one); T and a2 are corrected for that exactly if the velocities within a cell are independent
(observables/local_flow.hpp), so they do not depend on the cell size through it. Then `flow/`
gives the flow's share of the kinetic energy (`energy_share`), what independent velocities would
give (`uncorrelated_share`) and the difference (`collective_share`): the collective flow on scales
above the cell. No a2 time series about the local flow.)md";

const bool registered = register_plugin<Observable, Temperatures>(
    "temperatures",
    "per-species and per-component temperatures, rotational temperatures, ratios gamma = "
    "T_s/T_ref, "
    "Sonine a2",
    {optional(text("reference_species", "",
                   "species whose temperature divides the ratios (default: first)")),
     optional(real("flow_cell", "", "length",
                   "measure velocities about the local flow: the mean velocity of cells of about "
                   "this size (default: about the centre-of-mass velocity)",
                   0, 1e308, true))},
    kDescription);

}  // namespace
}  // namespace gran
