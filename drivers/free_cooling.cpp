// No energy injection: the gas cools freely (Haff's law in the homogeneous regime).
#include "libgran/plugins/driver.hpp"

namespace gran {
namespace {

template <int D>
class FreeCooling final : public Driver<D> {
  public:
    FreeCooling(const Params&, const SceneInfo&) {}
    void checkpoint(StateArchive& ar) override { ar.section("free cooling"); }
};

const bool registered = register_plugin<Driver, FreeCooling>(
    "none", "no energy injection: free cooling (the default when `drivers` is empty)", {});

}  // namespace
}  // namespace gran
