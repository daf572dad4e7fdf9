#include "libgran/engines/dem/contact_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gran {

const char* dem_law_name(DemLaw law) {
    switch (law) {
        case DemLaw::linear_dashpot:
            return "linear_dashpot";
        case DemLaw::cundall_strack:
            return "cundall_strack";
        case DemLaw::hertz_mindlin:
        default:
            return "hertz_mindlin";
    }
}

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& why) {
    throw std::invalid_argument("DemContactTable: " + what + ": " + why);
}

// Linear normal force (linear_dashpot, cundall_strack): k_n given, or from t_c through
// k_n = m_eff (pi^2 + ln^2 e) / t_c^2; gamma_n from Eq. (A9); t_c = pi / sqrt(k/m - (gamma/2m)^2).
void resolve_linear(const DemContactSpec& s, DemContactParams& p) {
    p.k_n = s.k_n > 0 ? s.k_n : linear_stiffness_from_duration(s.t_c, p.m_eff, s.e);
    p.gamma_n = linear_damping_from_restitution(p.k_n, p.m_eff, s.e);
    p.duration = linear_contact_duration(p.k_n, p.m_eff, p.gamma_n);
}

// Hertz with Tsuji damping: gamma_n = alpha(e) sqrt(m_eff k_n) and, at impact speed v,
// t_c = tau_c(alpha) (m_eff / k_n)^{2/5} v^{-1/5} (species/contact_laws.hpp), inverted for k_n:
// k_n = m_eff (tau_c / t_c)^{5/2} v^{-1/2}.
void resolve_hertz(const DemContactSpec& s, DemContactParams& p, const std::string& what) {
    if (!(s.reference_speed > 0)) {
        fail(what,
             "hertz_mindlin needs reference_speed > 0 (its contact duration depends on the impact "
             "speed, t_c ~ v^{-1/5})");
    }
    if (!(s.e >= 0.01)) fail(what, "hertz_mindlin needs e in [0.01, 1]");
    const double alpha = hertz_tsuji_alpha(s.e);
    const double tau = hertz_tsuji_collision(alpha).duration;
    const double v = s.reference_speed;
    p.k_n = s.k_n > 0 ? s.k_n : p.m_eff * std::pow(tau / s.t_c, 2.5) / std::sqrt(v);
    p.gamma_n = alpha * std::sqrt(p.m_eff * p.k_n);
    p.duration = tau * std::pow(p.m_eff / p.k_n, 0.4) * std::pow(v, -0.2);
}

}  // namespace

DemContactParams resolve_dem_contact(DemLaw law, const DemContactSpec& s, double m_eff,
                                     double sigma, const std::string& what) {
    if (!(s.e > 0 && s.e <= 1)) fail(what, "restitution e must lie in (0, 1]");
    if (!(s.k_n > 0) && !(s.t_c > 0)) fail(what, "give k_n > 0 or a contact duration t_c > 0");
    if (!(s.mu >= 0) || !(s.gamma_t >= 0)) fail(what, "mu and gamma_t must be >= 0");
    if (law != DemLaw::linear_dashpot && !(s.k_t_ratio >= 0)) fail(what, "k_t_ratio must be >= 0");
    if (!(m_eff > 0) || !(sigma > 0)) fail(what, "masses and diameters must be > 0");
    DemContactParams p;
    p.m_eff = m_eff;
    p.sigma = sigma;
    p.mu = s.mu;
    p.gamma_t = s.gamma_t;
    p.restitution = s.e;
    if (law == DemLaw::hertz_mindlin) {
        resolve_hertz(s, p, what);
    } else {
        resolve_linear(s, p);
    }
    p.k_t = law == DemLaw::linear_dashpot ? 0.0 : s.k_t_ratio * p.k_n;  // (A7): k_t = 0
    if (s.gamma_t_ratio >= 0) p.gamma_t = s.gamma_t_ratio * p.gamma_n;
    if (!std::isfinite(p.duration) || !(p.duration > 0)) {
        fail(what, "the contact does not end (overdamped); raise e");
    }
    return p;
}

DemContactTable::DemContactTable(const SpeciesTable& species, DemLaw law,
                                 const DemContactSpec& pair)
    : law_(law) {
    for (const auto& s : species.species) {
        mass_.push_back(s.mass);
        diameter_.push_back(s.diameter);
    }
    const std::size_t ns = mass_.size();
    pairs_.resize(ns * ns);
    walls_.resize(ns);
    wall_specs_.resize(ns);
    for (std::size_t a = 0; a < ns; ++a) {
        for (std::size_t b = a; b < ns; ++b) set_pair(a, b, pair);
    }
    for (std::size_t s = 0; s < ns; ++s) {
        DemContactSpec w = pair;
        w.k_n = pairs_[s * ns + s].k_n;  // the grain's own spring
        set_wall(s, w);
    }
}

DemContactTable::DemContactTable(const SpeciesTable& species, DemLaw law,
                                 const DemContactSpec& pair, const DemContactSpec& wall)
    : DemContactTable(species, law, pair) {
    for (std::size_t s = 0; s < mass_.size(); ++s) set_wall(s, wall);
}

void DemContactTable::set_pair(std::size_t a, std::size_t b, const DemContactSpec& spec) {
    const std::size_t ns = mass_.size();
    if (a >= ns || b >= ns) throw std::out_of_range("DemContactTable::set_pair: no such species");
    const std::string what = "pair (" + std::to_string(a) + ", " + std::to_string(b) + ")";
    const DemContactParams p = resolve_dem_contact(law_, spec, reduced_mass(mass_[a], mass_[b]),
                                                   0.5 * (diameter_[a] + diameter_[b]), what);
    pairs_[a * ns + b] = p;
    pairs_[b * ns + a] = p;
}

void DemContactTable::set_wall(std::size_t s, const DemContactSpec& spec) {
    if (s >= mass_.size()) throw std::out_of_range("DemContactTable::set_wall: no such species");
    const std::string what = "species " + std::to_string(s) + " against a wall";
    walls_[s] = resolve_dem_contact(law_, spec, mass_[s], 0.5 * diameter_[s], what);
    wall_specs_[s] = spec;
}

DemContactParams DemContactTable::wall_with_restitution(std::size_t s, double e) const {
    if (s >= mass_.size()) throw std::out_of_range("DemContactTable: no such species");
    DemContactSpec spec = wall_specs_[s];
    spec.e = e;
    const std::string what = "species " + std::to_string(s) + " against a wall";
    return resolve_dem_contact(law_, spec, mass_[s], 0.5 * diameter_[s], what);
}

double DemContactTable::shortest_duration(bool with_walls) const {
    double t = kInf;
    for (const auto& p : pairs_) t = std::min(t, p.duration);
    if (with_walls) {
        for (const auto& p : walls_) t = std::min(t, p.duration);
    }
    return t;
}

bool DemContactTable::needs_rotation() const {
    const auto rough = [](const DemContactParams& p) { return p.mu > 0; };
    return std::any_of(pairs_.begin(), pairs_.end(), rough) ||
           std::any_of(walls_.begin(), walls_.end(), rough);
}

}  // namespace gran
