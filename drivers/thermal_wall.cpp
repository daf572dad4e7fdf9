// Thermal wall at temperature T0 (Barrat & Trizac 2002, Sec. III A; Grossman, Zhou & Ben-Naim
// 1997): a reflected particle leaves with a normal speed drawn from the flux distribution
// P(v) = (m v / T0) exp(-m v^2 / (2 T0)), v > 0, by inversion v = sqrt(-2 T0 ln(1 - U) / m);
// tangential components are kept (the paper's rule) or redrawn from the Maxwellian at T0. The
// rule replaces the contact: a thermal wall has no contact law.
#include <cmath>

#include "drivers/wall_driver.hpp"
#include "libgran/core/random.hpp"

namespace gran {
namespace {

template <int D>
class ThermalWall final : public WallDriver<D>, private WallReflection<D> {
  public:
    ThermalWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, "thermal"),
          temperature_(p.real("temperature")),
          redraw_tangential_(p.str("tangential") == "redraw"),
          rng_(make_rng(info.seed + 7919ull * (info.index + 1), Stream::Driver)) {
        this->replace_contact(this);
    }

    void checkpoint(StateArchive& ar) override {
        WallDriver<D>::checkpoint(ar);
        ar.io(rng_);
    }

  private:
    void reflect(Vec<D>& v, int axis, double inward, double /*u: a static wall*/,
                 double mass) override {
        const double u = uniform01(rng_);
        v[axis] = inward * std::sqrt(-2.0 * temperature_ * std::log1p(-u) / mass);
        if (redraw_tangential_) {
            const double sd = std::sqrt(temperature_ / mass);
            for (int a = 0; a < D; ++a) {
                if (a != axis) v[a] = sd * gaussian(rng_);
            }
        }
    }

    double temperature_;
    bool redraw_tangential_;
    Rng rng_;
};

const char* const kDescription =
    R"md(
Barrat & Trizac 2002, Sec. III A: the outgoing normal velocity is drawn from the flux
distribution (m v / T0) exp(-m v^2 / (2 T0)); the tangential velocity is unaffected (the paper's
rule) or redrawn from the Maxwellian at T0.)md";

const bool registered = register_plugin<Driver, ThermalWall>(
    "thermal_wall",
    "thermal wall: outgoing normal velocity from the flux distribution at temperature T0",
    wall_schema(
        {real("temperature", "", "energy", "wall temperature T0", 0, 1e308, true),
         choice("tangential", "keep", {"keep", "redraw"},
                "tangential velocity: unaffected (as in Barrat & Trizac 2002) or redrawn at T0")}),
    wall_description(kDescription, /*contacts=*/false));

}  // namespace
}  // namespace gran
