// Several hard-sphere laws in one scene (e.g. r(v) for one pair, constant restitution for the
// others): each contact keeps its own law's restitution functions and parameters, called through a
// function pointer (one indirect call per collision, paid only by scenes that mix laws).
#include <array>
#include <cstring>
#include <stdexcept>

#include "libgran/engines/register_law.hpp"

namespace gran {

namespace {

struct MixedHardSphere {
    struct Pair {
        double (*restitution)(const void* law, double impact_speed) = nullptr;
        double beta = -1;
        double nominal = 1;
        bool rotates = false;
        alignas(16) std::array<unsigned char, 96> law{};  // the contact's own law's Pair
    };
    static constexpr bool impact_dependent = true;

    static Pair resolve(const Params& p, const ContactPartner&, const ContactPartner&,
                        const LawContext&) {
        p.fail("law", "the mixed law is built from the laws of each contact, never named");
    }
    static double normal_restitution(const Pair& c, double impact_speed) {
        return c.restitution(c.law.data(), impact_speed);
    }
    static double tangential_restitution(const Pair& c) { return c.beta; }
    static double nominal_restitution(const Pair& c) { return c.nominal; }
    static bool rotates(const Pair& c) { return c.rotates; }
};

}  // namespace

const LawPlugin& mixed_hard_sphere_law() {
    static const LawPlugin law = make_law_plugin<MixedHardSphere>(
        "(laws mixed per contact)", "each contact with its own hard-sphere law", {});
    return law;
}

void set_mixed_contact(LawTableBase& table, std::size_t index, const LawPlugin::HardSphere& form,
                       const void* pair, double nominal_restitution, bool rotates) {
    MixedHardSphere::Pair c;
    if (form.pair_size > c.law.size()) {
        throw std::invalid_argument("a law's parameters are too large to be mixed per contact");
    }
    c.restitution = form.normal_restitution;
    c.beta = form.tangential_restitution(pair);
    c.nominal = nominal_restitution;
    c.rotates = rotates;
    std::memcpy(c.law.data(), pair, form.pair_size);
    static_cast<LawTable<MixedHardSphere>&>(table).contacts[index] = c;
}

}  // namespace gran
