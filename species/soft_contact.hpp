#pragma once
// What the soft-contact laws (linear_dashpot, cundall_strack, hertz_mindlin) share: their common
// keys and how a contact's request (restitution, stiffness or contact time, friction, tangential
// damping) is read from them for two partners. The laws' own files resolve the rest.
//
// Masses: the damping that yields a requested restitution depends on the reduced mass
// m_eff = m_i m_j / (m_i + m_j) (Bhateja et al. 2016, Eq. A9); a wall has infinite mass, m_eff =
// m_i (taken as it is, not as 1 / (1/m_i + 0), which may round). The contact distance is R_i + R_j,
// or R_i against a wall.
#include <fmt/format.h>

#include <string>

#include "libgran/core/params.hpp"
#include "libgran/plugins/law.hpp"
#include "species/contact_laws.hpp"

namespace gran::soft_contact {

// The keys every soft-contact law has, with the scene's defaults.
inline Schema common_schema() {
    return {
        real("restitution", "1", "",
             "normal restitution e of the contact (Bhateja et al. 2016: e_p, e_w), from which the "
             "normal dashpot follows (Eq. A9)",
             0, 1, true, false),
        real("stiffness", "0", "mass/time^2",
             "normal stiffness k_n (hertz_mindlin: coefficient of delta^(3/2), "
             "mass/(length^(1/2) time^2)); 0: set from contact_time",
             0, 1e308),
        real("contact_time", "0", "time",
             "head-on contact duration t_c that sets the stiffness when stiffness = 0 "
             "(hertz_mindlin: at reference_speed)",
             0, 1e308),
        real("friction", "0", "",
             "Coulomb friction coefficient mu (Eq. A8); 0: smooth, no rotation", 0, 1e308),
        real("tangential_damping", "0", "mass/time",
             "tangential dashpot c_t (Eq. A7), capped by mu |F_n|", 0, 1e308),
        optional(real("tangential_damping_ratio", "", "",
                      "c_t as a multiple of the contact's own normal dashpot c_n (replaces "
                      "tangential_damping; e.g. 1: c_t = c_n)",
                      0, 1e308)),
    };
}

inline ParamSpec tangential_stiffness_ratio_spec() {
    return real("tangential_stiffness_ratio", "0.2857142857142857", "",
                "k_t / k_n of the tangential spring (2/7: equal normal and tangential periods for "
                "uniform spheres)",
                0, 1e308, true);
}

// One contact's request, read from the law's keys for partners a and b.
struct Request {
    double e = 1;
    double k_n = 0;  // > 0: given
    double t_c = 0;  // > 0: given (k_n from it)
    double mu = 0;
    double gamma_t = 0;
    double gamma_t_ratio = -1;  // >= 0: c_t = ratio c_n
    double m_eff = 1;
    std::string what;  // "grain-grain" or "grain-wall", for messages
};

inline Request read(const Params& p, const ContactPartner& a, const ContactPartner& b) {
    Request r;
    r.e = p.real("restitution");
    r.k_n = p.real("stiffness");
    r.t_c = p.real("contact_time");
    if (r.k_n == 0 && r.t_c == 0) {
        p.fail("stiffness", "a soft contact needs `stiffness` (k_n) or `contact_time` (t_c)");
    }
    if (r.k_n > 0 && r.t_c > 0)
        p.fail("contact_time", "give `stiffness` or `contact_time`, not both");
    r.mu = p.real("friction");
    r.gamma_t = p.real("tangential_damping");
    if (p.has("tangential_damping_ratio")) r.gamma_t_ratio = p.real("tangential_damping_ratio");
    r.m_eff = b.wall ? a.mass : reduced_mass(a.mass, b.mass);
    r.what = fmt::format("{}-{}", a.name, b.name);
    return r;
}

// The linear normal spring-dashpot of a request: k_n given or from t_c, gamma_n from e (Eq. A9),
// and the head-on contact duration. Refused when the contact does not end (overdamped).
struct LinearNormal {
    double k_n = 0, gamma_n = 0, duration = 0;
};
inline LinearNormal linear_normal(const Request& r, const Params& p) {
    LinearNormal n;
    n.k_n = r.k_n > 0 ? r.k_n : linear_stiffness_from_duration(r.t_c, r.m_eff, r.e);
    n.gamma_n = linear_damping_from_restitution(n.k_n, r.m_eff, r.e);
    n.duration = linear_contact_duration(n.k_n, r.m_eff, n.gamma_n);
    if (!std::isfinite(n.duration) || !(n.duration > 0)) {
        p.fail("restitution", "the " + r.what + " contact does not end (overdamped); raise e");
    }
    return n;
}

// c_t: given, or a multiple of this contact's own c_n.
inline double tangential_damping(const Request& r, double gamma_n) {
    return r.gamma_t_ratio >= 0 ? r.gamma_t_ratio * gamma_n : r.gamma_t;
}

// The hard limit on the event-driven engine: an instantaneous collision with the same e; friction
// has none there.
inline const char* hard_limit_problem(double mu) {
    return mu > 0 ? "a contact with friction > 0 has no hard-particle limit on the event_driven "
                    "engine (roughness there is the tangential restitution beta of "
                    "constant_restitution)"
                  : nullptr;
}

// What one soft contact resolves to: its kernel's parameters (`Contact`: k_n, gamma_n, ..., mu),
// the head-on duration t_c the time step is a fraction of, and the requested restitution.
template <class Contact>
struct Resolved {
    Contact contact;
    double duration = 0;
    double restitution = 1;
};

// What every soft-contact law offers besides its resolution, force and energy: the duration and
// restitution it was asked for, rotation when it has friction, and its hard limit on the
// event-driven engine (a smooth collision with the requested restitution; none with friction).
// A law derives from it: struct MyLaw : soft_contact::LawBase<MyContact> { ... }.
template <class Contact>
struct LawBase {
    using Pair = Resolved<Contact>;
    static constexpr bool impact_dependent = false;
    static double duration(const Pair& c) { return c.duration; }
    static double restitution(const Pair& c) { return c.restitution; }
    static double nominal_restitution(const Pair& c) { return c.restitution; }
    static bool rotates(const Pair& c) { return c.contact.mu > 0; }
    // The damping (and the stiffness from a contact time) follow from the reduced mass (read());
    // sizes and inertia enter the kernels per contact, not the Pair.
    static PartnerProperties partner_properties(const Params&) { return {true, false, false}; }
    static double normal_restitution(const Pair& c, double) { return c.restitution; }
    static double tangential_restitution(const Pair&) { return -1.0; }
    static const char* hard_sphere_problem(const Pair& c) {
        return hard_limit_problem(c.contact.mu);
    }
};

}  // namespace gran::soft_contact
