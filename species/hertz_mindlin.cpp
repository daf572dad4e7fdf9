// Hertz-Mindlin contact with Tsuji damping (Tsuji, Tanaka & Ishida, Powder Technol. 71, 239 (1992),
// Ref. 31 of Bhateja et al. 2016): F_n = k_n delta^(3/2) - gamma_n delta^(1/4) g_n with
// gamma_n = alpha(e) sqrt(m_eff k_n), which gives a restitution independent of the impact speed,
// and a Mindlin tangential spring k_t delta^(1/2) with history, capped by Coulomb friction. Kernel:
// hertz_mindlin_force (species/contact_laws.hpp). Its contact duration depends on the impact speed
// (t_c ~ v^(-1/5)), so a reference speed defines t_c: the `contact_time` it is set from, and the
// duration the engine's time step is a fraction of.
#include "libgran/engines/register_law.hpp"
#include "species/soft_contact.hpp"

namespace gran {
namespace {

// Its Pair's duration is the head-on contact time at the reference speed.
struct HertzMindlin : soft_contact::LawBase<HertzMindlinContact> {
    static constexpr bool history = true;

    // Tsuji: gamma_n = alpha(e) sqrt(m_eff k_n); at impact speed v the head-on duration is
    // t_c = tau_c(alpha) (m_eff / k_n)^(2/5) v^(-1/5) (species/contact_laws.hpp), inverted for k_n
    // when t_c is given: k_n = m_eff (tau_c / t_c)^(5/2) v^(-1/2).
    static Pair resolve(const Params& p, const ContactPartner& a, const ContactPartner& b,
                        const LawContext& ctx) {
        const soft_contact::Request r = soft_contact::read(p, a, b);
        if (r.e < 0.01) p.fail("restitution", "hertz_mindlin needs e in [0.01, 1]");
        const double given = p.real("reference_speed");
        if (r.t_c > 0 && given == 0) {
            p.fail("reference_speed",
                   "hertz_mindlin with contact_time needs the impact speed at which t_c holds "
                   "(reference_speed)");
        }
        const double v = given > 0 ? given : std::sqrt(ctx.initial_temperature / ctx.lightest_mass);
        const double alpha = hertz_tsuji_alpha(r.e);
        const double tau = hertz_tsuji_collision(alpha).duration;
        Pair c;
        auto& k = c.contact;
        k.k_n = r.k_n > 0 ? r.k_n : r.m_eff * std::pow(tau / r.t_c, 2.5) / std::sqrt(v);
        k.gamma_n = alpha * std::sqrt(r.m_eff * k.k_n);
        k.k_t = p.real("tangential_stiffness_ratio") * k.k_n;
        k.gamma_t = soft_contact::tangential_damping(r, k.gamma_n);
        k.mu = r.mu;
        c.duration = tau * std::pow(r.m_eff / k.k_n, 0.4) * std::pow(v, -0.2);
        c.restitution = r.e;
        if (!std::isfinite(c.duration) || !(c.duration > 0)) {
            p.fail("restitution", "the " + r.what + " contact does not end (overdamped); raise e");
        }
        return c;
    }
    template <int D>
    static ContactForce<D> force(const Pair& c, double delta, const Vec<D>& n, const Vec<D>& g,
                                 double l_i, double l_j, Vec<D>& spring) {
        return hertz_mindlin_force<D>(c.contact, delta, n, g, l_i, l_j, spring);
    }
    // (2/5) k_n delta^(5/2) + k_t delta^(1/2) |xi|^2 / 2.
    static double elastic_energy(const Pair& c, double delta, double spring2) {
        const double root = std::sqrt(delta);
        return 0.4 * c.contact.k_n * delta * delta * root + 0.5 * c.contact.k_t * root * spring2;
    }
};

const char* const kDescription =
    R"md(
F_n = k_n delta^(3/2) - gamma_n delta^(1/4) g_n with Tsuji's damping gamma_n = alpha(e)
sqrt(m_eff k_n) (alpha(e) from the dimensionless contact, so e does not depend on the impact
speed), and a Mindlin tangential spring k_t delta^(1/2) with history and the Coulomb cap. Its
contact time scales as v^(-1/5): `contact_time` and the duration the time step is a fraction of
hold at `reference_speed` (default sqrt(T0 / m) of the lightest species). Frictionless, it runs on
the event-driven engine as its hard limit.)md";

const bool registered = register_law<HertzMindlin>(
    "hertz_mindlin",
    "soft contact: Hertz normal force with Tsuji damping (e independent of the impact speed), "
    "Mindlin tangential spring with history and Coulomb cap",
    [] {
        Schema s = soft_contact::common_schema();
        s.push_back(soft_contact::tangential_stiffness_ratio_spec());
        s.push_back(real("reference_speed", "0", "velocity",
                         "impact speed at which contact_time (and the duration the time step is "
                         "a fraction of) holds; 0: sqrt(T0 / m) of the lightest species",
                         0, 1e308));
        return s;
    }(),
    kDescription);

}  // namespace
}  // namespace gran
