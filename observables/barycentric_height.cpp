// Barycentric height of a vibrated bed, h_cm = sum m z / sum m, measured from the mean position of
// the lower wall of the axis (the vibrating base), and its change from rest
// Delta h_cm = h_cm - h_rest (Bhateja, Sharma & Singh 2016, Sec. V and Table II; several
// experiments inferred T from Delta h_cm, assuming T ~ Delta h_cm). h_rest is the barycentric
// height of the same grains settled on a static base, measured by a run of its own (the study
// runs one) and given as `rest_height`.
#include <fmt/format.h>

#include <cmath>

#include "libgran/plugins/observable.hpp"

namespace gran {
namespace {

template <int D>
class BarycentricHeight final : public Observable<D> {
  public:
    BarycentricHeight(const Params& p, const SceneInfo& info)
        : table_(*info.species), period_(info.drive_period) {
        axis_ = D - 1;
        if (p.has("axis")) {
            const std::string a = p.str("axis");
            axis_ = a == "x" ? 0 : (a == "y" ? 1 : 2);
            if (axis_ >= D) p.fail("axis", fmt::format("axis {} does not exist in {}D", a, D));
        }
        if (info.periodic[std::size_t(axis_)]) {
            p.fail("axis", "the barycentric height is measured from the wall of a bounded axis");
        }
        if (p.has("rest_height")) rest_ = p.real("rest_height");
    }

    void sample(const SampleContext<D>& ctx) override {
        if (!ctx.measuring) return;
        // Heights from the mean position of the lower wall over one drive period.
        if (h_.size() == 0) base_ = ctx.engine.mean_wall_position(2 * axis_, ctx.time, period_);
        const auto& p = ctx.engine.particles();
        double mz = 0, m = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double mi = table_.species[p.species[i]].mass;
            mz += mi * p.r[i][axis_];
            m += mi;
        }
        h_.push(mz / m - base_);
    }

    void write(ResultGroup& out) const override {
        if (h_.size() == 0) return;
        out.attr("axis", std::string(component_name(axis_)));
        out.file_only().value("base_position", base_);
        const Estimate h = h_.estimate();
        out.estimate("h_cm", h, "length");
        if (!std::isnan(rest_)) {
            out.file_only().value("rest_height", rest_);
            out.estimate("delta_h_cm", h.affine(1, -rest_), "length");
        }
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("barycentric_height");
        ar.io(base_);
        ar.io(h_);
    }

  private:
    const SpeciesTable& table_;
    double period_;
    int axis_ = D - 1;
    double base_ = 0;
    double rest_ = std::nan("");
    Series h_;
};

const char* const kDescription =
    R"md(
`h_cm`: the height of the centre of mass above the mean position of the lower wall of the axis (the
vibrating base), time-averaged over the measurement; with `rest_height`, `delta_h_cm` = h_cm - h_rest
(Bhateja et al. 2016, Table II). The study measures h_rest with a run of the settled bed.)md";

const bool registered = register_plugin<Observable, BarycentricHeight>(
    "barycentric_height",
    "height of the centre of mass above the mean base position, h_cm, and its change from rest "
    "(Bhateja et al. 2016)",
    {optional(choice("axis", "", {"x", "y", "z"},
                     "vibration axis, bounded (default: the last axis, y in 2D, z in 3D)")),
     optional(real("rest_height", "", "length",
                   "h_cm of the grains at rest on the static base (from a run of its own): "
                   "delta_h_cm = h_cm - rest_height",
                   -1e308, 1e308))},
    kDescription);

}  // namespace
}  // namespace gran
