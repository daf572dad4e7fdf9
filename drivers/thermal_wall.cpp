// Thermal wall at temperature T0: reflected particles leave with a normal velocity drawn from the
// flux distribution at T0; tangential components kept (Barrat & Trizac 2002) or redrawn.
#include "drivers/wall_driver.hpp"

namespace gran {
namespace {

template <int D>
class ThermalWall final : public WallDriver<D> {
  public:
    ThermalWall(const Params& p, const SceneInfo& info)
        : WallDriver<D>(p, info, &thermal_wall_rule<D>, make(p), "thermal") {}

  private:
    static WallParams make(const Params& p) {
        WallParams w;
        w.temperature = p.real("temperature");
        w.redraw_tangential = p.str("tangential") == "redraw";
        return w;
    }
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
    wall_description(kDescription, /*restitution_keys=*/false));

}  // namespace
}  // namespace gran
