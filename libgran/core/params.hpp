#pragma once
// Parameter declarations: every plugin and scene section declares its keys once (name, type,
// default, unit, allowed range, one-line doc). The same table drives validation, defaults, the
// resolved scene written to results, and `gran list`.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libgran/core/scene_error.hpp"

namespace gran {

enum class ParamType {
    Real,
    Integer,
    Boolean,
    String,
    Choice,
    RealList,
    BoolList,
    StringList,
    Map,
    List
};

struct ParamSpec {
    std::string name;
    ParamType type = ParamType::Real;
    std::string default_value;  // YAML text; empty and !optional => required
    std::string unit;           // "" for dimensionless; shown by `gran list`
    std::string doc;
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;  // true: value must be > min (else >=)
    bool max_open = false;
    std::vector<std::string> choices;  // for Choice
    bool optional = false;             // may be absent without a default
    std::size_t length =
        0;  // required list length (0 = any; for lists of dimension length the caller checks)
};

using Schema = std::vector<ParamSpec>;

// Builders that keep declarations one line each.
ParamSpec real(std::string name, std::string def, std::string unit, std::string doc,
               double min = -1e308, double max = 1e308, bool min_open = false,
               bool max_open = false);
ParamSpec integer(std::string name, std::string def, std::string doc, double min = -1e18,
                  double max = 1e18);
ParamSpec boolean(std::string name, std::string def, std::string doc);
ParamSpec choice(std::string name, std::string def, std::vector<std::string> choices,
                 std::string doc);
ParamSpec text(std::string name, std::string def, std::string doc);
ParamSpec optional(ParamSpec spec);

// A validated section: every declared key has a value (given or default) unless declared optional.
class Params {
  public:
    Params() = default;
    Params(YAML::Node values, YAML::Node source, Where where)
        : values_(std::move(values)), source_(std::move(source)), where_(std::move(where)) {}

    bool has(const std::string& key) const {
        return values_[key].IsDefined() && !values_[key].IsNull();
    }
    double real(const std::string& key) const;
    std::int64_t integer(const std::string& key) const;
    bool boolean(const std::string& key) const;
    std::string str(const std::string& key) const;
    std::vector<double> reals(const std::string& key) const;
    std::vector<bool> booleans(const std::string& key) const;
    std::vector<std::string> strings(const std::string& key) const;
    YAML::Node node(const std::string& key) const { return values_[key]; }

    // The resolved values (defaults filled in), as written to /parameters.
    const YAML::Node& resolved() const { return values_; }
    // For consistency errors found after validation: point at the key (or the section).
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;
    const Where& where() const { return where_; }

  private:
    YAML::Node values_;
    YAML::Node source_;
    Where where_;
};

// map[key] when map is a map holding key; otherwise an undefined node. (yaml-cpp's const
// operator[] returns an invalid node for absent keys, on which most calls throw.)
YAML::Node child(const YAML::Node& map, const std::string& key);

// Validates `node` (a map, or null for an empty section) against `schema`. Unknown keys, wrong
// types, out-of-range values and missing required keys are SceneErrors naming file:line:column and
// key. Keys in `passthrough` are accepted without checks (e.g. the "type" key that selected the
// plugin).
Params read_params(const YAML::Node& node, const Schema& schema, const Where& where,
                   const std::vector<std::string>& passthrough = {});

// Human description of a spec's type and range, e.g. "real > 0 [1/time]".
std::string describe(const ParamSpec& spec);

}  // namespace gran
