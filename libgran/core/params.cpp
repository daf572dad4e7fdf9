#include "libgran/core/params.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gran {

ParamSpec real(std::string name, std::string def, std::string unit, std::string doc, double min,
               double max, bool min_open, bool max_open) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = ParamType::Real;
    s.default_value = std::move(def);
    s.unit = std::move(unit);
    s.doc = std::move(doc);
    s.min = min;
    s.max = max;
    s.min_open = min_open;
    s.max_open = max_open;
    return s;
}

ParamSpec integer(std::string name, std::string def, std::string doc, double min, double max) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = ParamType::Integer;
    s.default_value = std::move(def);
    s.doc = std::move(doc);
    s.min = min;
    s.max = max;
    return s;
}

ParamSpec boolean(std::string name, std::string def, std::string doc) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = ParamType::Boolean;
    s.default_value = std::move(def);
    s.doc = std::move(doc);
    return s;
}

ParamSpec choice(std::string name, std::string def, std::vector<std::string> choices,
                 std::string doc) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = ParamType::Choice;
    s.default_value = std::move(def);
    s.choices = std::move(choices);
    s.doc = std::move(doc);
    return s;
}

ParamSpec text(std::string name, std::string def, std::string doc) {
    ParamSpec s;
    s.name = std::move(name);
    s.type = ParamType::String;
    s.default_value = std::move(def);
    s.doc = std::move(doc);
    return s;
}

ParamSpec optional(ParamSpec spec) {
    spec.optional = true;
    return spec;
}

namespace {

std::string fmt_bound(double x) {
    if (std::abs(x) >= 1e300) return x > 0 ? "inf" : "-inf";
    return fmt::format("{:g}", x);
}

std::string range_text(const ParamSpec& s) {
    const bool has_min = s.min > -1e300;
    const bool has_max = s.max < 1e300;
    if (has_min && has_max) {
        return fmt::format(" in {}{}, {}{}", s.min_open ? "(" : "[", fmt_bound(s.min),
                           fmt_bound(s.max), s.max_open ? ")" : "]");
    }
    if (has_min) return fmt::format(" {} {}", s.min_open ? ">" : ">=", fmt_bound(s.min));
    if (has_max) return fmt::format(" {} {}", s.max_open ? "<" : "<=", fmt_bound(s.max));
    return "";
}

bool in_range(const ParamSpec& s, double x) {
    if (std::isnan(x)) return false;
    if (s.min_open ? !(x > s.min) : !(x >= s.min)) return false;
    if (s.max_open ? !(x < s.max) : !(x <= s.max)) return false;
    return true;
}

std::string shown(const YAML::Node& n) {
    if (n.IsScalar()) return "'" + n.Scalar() + "'";
    if (n.IsSequence()) return "a list";
    if (n.IsMap()) return "a map";
    return "nothing";
}

std::optional<double> as_real(const YAML::Node& n) {
    if (!n.IsScalar()) return std::nullopt;
    const std::string& t = n.Scalar();
    if (t.empty()) return std::nullopt;
    try {
        std::size_t used = 0;
        const double x = std::stod(t, &used);
        if (used != t.size()) return std::nullopt;
        return x;
    } catch (...) {
        if (t == ".inf" || t == "inf") return std::numeric_limits<double>::infinity();
        return std::nullopt;
    }
}

std::optional<bool> as_bool(const YAML::Node& n) {
    if (!n.IsScalar()) return std::nullopt;
    const std::string& t = n.Scalar();
    if (t == "true" || t == "True" || t == "yes" || t == "on") return true;
    if (t == "false" || t == "False" || t == "no" || t == "off") return false;
    return std::nullopt;
}

// Checks one value; returns the canonical node to store.
YAML::Node check_value(const ParamSpec& s, const YAML::Node& n, const Where& w) {
    const std::string expected = describe(s);
    auto bad = [&](const std::string& why) {
        fail(w, n, fmt::format("expected {}, got {}{}", expected, shown(n), why));
    };
    switch (s.type) {
        case ParamType::Real:
        case ParamType::Integer: {
            auto x = as_real(n);
            if (!x) bad("");
            if (s.type == ParamType::Integer && std::floor(*x) != *x) bad(" (not a whole number)");
            if (!in_range(s, *x)) bad(" (out of range)");
            return YAML::Node(n.Scalar());
        }
        case ParamType::Boolean: {
            auto b = as_bool(n);
            if (!b) bad("");
            return YAML::Node(*b);
        }
        case ParamType::String:
            if (!n.IsScalar()) bad("");
            return YAML::Node(n.Scalar());
        case ParamType::Choice: {
            if (!n.IsScalar() ||
                std::find(s.choices.begin(), s.choices.end(), n.Scalar()) == s.choices.end()) {
                bad("");
            }
            return YAML::Node(n.Scalar());
        }
        case ParamType::RealList:
        case ParamType::BoolList:
        case ParamType::StringList: {
            YAML::Node list(YAML::NodeType::Sequence);
            if (!n.IsSequence()) bad("");
            if (s.length != 0 && n.size() != s.length) {
                bad(fmt::format(" ({} entries instead of {})", n.size(), s.length));
            }
            for (std::size_t k = 0; k < n.size(); ++k) {
                const YAML::Node e = n[k];
                const Where we = w.item(k);
                if (s.type == ParamType::RealList) {
                    auto x = as_real(e);
                    if (!x || !in_range(s, *x)) {
                        fail(we, e, fmt::format("expected {}, got {}", expected, shown(e)));
                    }
                    list.push_back(e.Scalar());
                } else if (s.type == ParamType::BoolList) {
                    auto b = as_bool(e);
                    if (!b) fail(we, e, fmt::format("expected {}, got {}", expected, shown(e)));
                    list.push_back(*b);
                } else {
                    if (!e.IsScalar())
                        fail(we, e, fmt::format("expected {}, got {}", expected, shown(e)));
                    list.push_back(e.Scalar());
                }
            }
            return list;
        }
        case ParamType::Map:
            if (!n.IsMap() && !n.IsNull()) bad("");
            return n;
        case ParamType::List:
            if (!n.IsSequence() && !n.IsNull()) bad("");
            return n;
    }
    return n;
}

}  // namespace

YAML::Node child(const YAML::Node& map, const std::string& key) {
    if (!map.IsDefined() || !map.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    YAML::Node c = map[key];
    return c.IsDefined() ? c : YAML::Node(YAML::NodeType::Undefined);
}

std::string describe(const ParamSpec& s) {
    std::string t;
    switch (s.type) {
        case ParamType::Real:
            t = "a real number" + range_text(s);
            break;
        case ParamType::Integer:
            t = "a whole number" + range_text(s);
            break;
        case ParamType::Boolean:
            t = "true or false";
            break;
        case ParamType::String:
            t = "a string";
            break;
        case ParamType::Choice: {
            t = "one of";
            for (std::size_t k = 0; k < s.choices.size(); ++k) t += (k ? ", " : " ") + s.choices[k];
            break;
        }
        case ParamType::RealList:
            t = (s.length ? fmt::format("a list of {} real numbers", s.length)
                          : "a list of real numbers") +
                range_text(s);
            break;
        case ParamType::BoolList:
            t = "a list of true/false";
            break;
        case ParamType::StringList:
            t = s.length ? fmt::format("a list of {} strings", s.length) : "a list of strings";
            break;
        case ParamType::Map:
            t = "a map";
            break;
        case ParamType::List:
            t = "a list";
            break;
    }
    if (!s.unit.empty()) t += " [" + s.unit + "]";
    return t;
}

Params read_params(const YAML::Node& node, const Schema& schema, const Where& where,
                   const std::vector<std::string>& passthrough) {
    if (node.IsDefined() && !node.IsNull() && !node.IsMap()) {
        fail(where, node, fmt::format("expected a map of keys, got {}", shown(node)));
    }
    YAML::Node out(YAML::NodeType::Map);
    if (node.IsMap()) {
        std::vector<std::string> seen;
        for (auto it = node.begin(); it != node.end(); ++it) {
            if (!it->first.IsScalar()) {  // a YAML complex key (`? - a`): found by fuzzing
                fail(where, it->first,
                     fmt::format("expected a key name, got {}", shown(it->first)));
            }
            const std::string key = it->first.as<std::string>();
            if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
                fail(where.child(key), it->first, fmt::format("key '{}' is given twice", key));
            }
            seen.push_back(key);
            const bool known = std::any_of(schema.begin(), schema.end(),
                                           [&](const ParamSpec& s) { return s.name == key; });
            const bool pass =
                std::find(passthrough.begin(), passthrough.end(), key) != passthrough.end();
            if (!known && !pass) {
                std::string allowed;
                for (const auto& s : schema) allowed += (allowed.empty() ? "" : ", ") + s.name;
                fail(where.child(key), it->first,
                     fmt::format("unknown key '{}'; allowed keys here: {}", key, allowed));
            }
            if (pass) out[key] = it->second;
        }
    }
    for (const auto& s : schema) {
        const YAML::Node given = child(node, s.name);
        if (given.IsDefined() && !given.IsNull()) {
            out[s.name] = check_value(s, given, where.child(s.name));
        } else if (!s.default_value.empty()) {
            out[s.name] = check_value(s, YAML::Load(s.default_value), where.child(s.name));
        } else if (!s.optional) {
            fail(where, node,
                 fmt::format("missing required key '{}' ({}: {})", s.name, describe(s), s.doc));
        }
    }
    return Params(out, node, where);
}

double Params::real(const std::string& key) const {
    const YAML::Node n = values_[key];
    if (n.Scalar() == ".inf" || n.Scalar() == "inf") return std::numeric_limits<double>::infinity();
    return std::stod(n.Scalar());
}

std::int64_t Params::integer(const std::string& key) const {
    return static_cast<std::int64_t>(std::llround(std::stod(values_[key].Scalar())));
}

bool Params::boolean(const std::string& key) const {
    return values_[key].as<bool>();
}

std::string Params::str(const std::string& key) const {
    return values_[key].as<std::string>();
}

std::vector<double> Params::reals(const std::string& key) const {
    std::vector<double> v;
    for (const auto& e : values_[key]) v.push_back(std::stod(e.Scalar()));
    return v;
}

std::vector<bool> Params::booleans(const std::string& key) const {
    std::vector<bool> v;
    for (const auto& e : values_[key]) v.push_back(e.as<bool>());
    return v;
}

std::vector<std::string> Params::strings(const std::string& key) const {
    std::vector<std::string> v;
    for (const auto& e : values_[key]) v.push_back(e.as<std::string>());
    return v;
}

void Params::fail(const std::string& key, const std::string& message) const {
    const YAML::Node c = child(source_, key);
    const YAML::Node n = c.IsDefined() ? c : source_;
    gran::fail(key.empty() ? where_ : where_.child(key), n, message);
}

}  // namespace gran
