// The soft-contact laws' fidelity knob for `gran tradeoff` (libgran/study/knob.hpp): the normal
// stiffness, or the contact time that sets it (species/soft_contact.hpp: stiffness = 0 means
// "from contact_time").
#include <cmath>

#include "libgran/study/knob.hpp"

namespace gran {
namespace {

KnobOutcome stiffness(const KnobContext& c) {
    if (knobs::engine_type(c) != "dem") return "hard spheres are infinitely stiff";
    const YAML::Node contacts = c.resolved["interactions"];
    if (knobs::real_at(contacts, "stiffness") > 0) {
        return knobs::scaled("stiffness",
                             "normal spring stiffness k_n: stiffer is harder spheres, shorter "
                             "contacts, smaller steps",
                             "interactions.stiffness", knobs::real_at(contacts, "stiffness"),
                             {0.01, 0.1, 1, 10});
    }
    return knobs::scaled("stiffness", "contact time t_c (shorter is stiffer)",
                         "interactions.contact_time", knobs::real_at(contacts, "contact_time"),
                         {10, std::sqrt(10.0), 1, 1 / std::sqrt(10.0)});
}

const bool registered = register_knob(
    "stiffness", 20,
    "DEM interactions.stiffness x 1/100, 1/10, 1, 10, or contact_time x 10, sqrt(10), 1, "
    "1/sqrt(10) when the stiffness follows from it",
    stiffness);

}  // namespace
}  // namespace gran
