#include "libgran/run/summary_numbers.hpp"

namespace gran {

namespace {

double number_or_nan(const YAML::Node& n) {
    if (!n || !n.IsScalar()) return std::numeric_limits<double>::quiet_NaN();
    try {
        return n.as<double>();
    } catch (const YAML::Exception&) {
        return std::numeric_limits<double>::quiet_NaN();
    }
}

void collect(const YAML::Node& n, const std::string& prefix,
             std::map<std::string, SummaryNumber>& out) {
    if (n.IsMap()) {
        if (n["value"] && n["value"].IsScalar()) {
            // The number first: a text or a flag is no number and leaves no entry behind.
            try {
                const SummaryNumber x{n["value"].as<double>(), number_or_nan(n["error"]),
                                      number_or_nan(n["n_eff"])};
                out[prefix] = x;
            } catch (const YAML::Exception&) {
            }
            return;
        }
        for (auto it = n.begin(); it != n.end(); ++it) {
            const std::string k = it->first.as<std::string>();
            collect(it->second, prefix.empty() ? k : prefix + "." + k, out);
        }
    } else if (n.IsScalar()) {
        try {
            const SummaryNumber x{n.as<double>()};
            out[prefix] = x;
        } catch (const YAML::Exception&) {
        }
    }
}

}  // namespace

std::map<std::string, SummaryNumber> summary_numbers(const YAML::Node& node,
                                                     const std::string& prefix) {
    std::map<std::string, SummaryNumber> out;
    collect(node, prefix, out);
    return out;
}

}  // namespace gran
