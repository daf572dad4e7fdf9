#pragma once
// The numbers of a run summary by their dotted names, the names a study table's columns and a
// run's `target_error` use ("observables.temperatures.ratios.light_over_heavy.gamma",
// "observables.profiles.middle/mixture/T", "performance.cpu_time").
#include <yaml-cpp/yaml.h>

#include <limits>
#include <map>
#include <string>

namespace gran {

struct SummaryNumber {
    double value = std::numeric_limits<double>::quiet_NaN();
    double error = std::numeric_limits<double>::quiet_NaN();  // NaN: none (a plain value)
    double n_eff = std::numeric_limits<double>::quiet_NaN();  // effective samples of the error
};

// Every number below `node`: estimates {value, error, n_eff, ...}, values with a unit
// {value, unit} and plain scalars, keyed by `prefix` and their path joined with '.'.
std::map<std::string, SummaryNumber> summary_numbers(const YAML::Node& node,
                                                     const std::string& prefix);

}  // namespace gran
