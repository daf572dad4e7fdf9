#include "libgran/run/result_sink.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace gran {

// ---- ResultGroup ------------------------------------------------------------------------------

ResultGroup ResultGroup::group(const std::string& name) {
    return group(name, {name});
}

ResultGroup ResultGroup::group(const std::string& name,
                               const std::vector<std::string>& summary_keys) {
    YAML::Node node = summary_;
    for (const auto& k : summary_keys) node.reset(node[k]);
    return ResultGroup(file_.group(name), node, summarise_);
}

void ResultGroup::estimate(const std::string& name, const Estimate& e, const std::string& unit) {
    file_.write_scalar(name, e.value);
    file_.attr_on(name, "error", e.error);
    file_.attr_on(name, "unit", unit);
    file_.attr_on(name, "n_eff", e.n_eff);
    file_.attr_on(name, "tau_int", e.tau_int);
    file_.attr_on(name, "samples", static_cast<std::int64_t>(e.samples));
    file_.attr_on(name, "converged", static_cast<std::int64_t>(e.converged ? 1 : 0));
    if (!summarise_) return;
    YAML::Node s;
    s["value"] = e.value;
    s["error"] = e.error;
    if (!unit.empty()) s["unit"] = unit;
    if (std::isfinite(e.n_eff)) s["n_eff"] = std::round(e.n_eff);
    if (!e.converged) s["converged"] = false;
    summary_[name] = s;
}

void ResultGroup::value(const std::string& name, double v, const std::string& unit) {
    file_.write_scalar(name, v);
    finish_value(name, unit);
    if (summarise_) summarise(name, YAML::Node(v), unit);
}

void ResultGroup::flag(const std::string& name, bool v) {
    file_.write_scalar(name, static_cast<std::int64_t>(v ? 1 : 0));
    if (summarise_) summary_[name] = v;
}

void ResultGroup::text(const std::string& name, const std::string& v) {
    file_.attr(name, v);
    if (summarise_) summary_[name] = v;
}

void ResultGroup::finish_value(const std::string& name, const std::string& unit) {
    if (!unit.empty()) file_.attr_on(name, "unit", unit);
}

void ResultGroup::summarise(const std::string& name, const YAML::Node& v, const std::string& unit) {
    if (unit.empty()) {
        summary_[name] = v;
        return;
    }
    YAML::Node s;
    s["value"] = v;
    s["unit"] = unit;
    summary_[name] = s;
}

void ResultGroup::array(const std::string& name, std::span<const double> v, const std::string& unit,
                        std::vector<std::size_t> dims) {
    file_.write(name, v, std::move(dims));
    finish_value(name, unit);
}

void ResultGroup::array(const std::string& name, std::span<const std::int64_t> v,
                        const std::string& unit, std::vector<std::size_t> dims) {
    file_.write(name, v, std::move(dims));
    finish_value(name, unit);
}

void ResultGroup::profile(const std::string& name, std::span<const double> values,
                          std::span<const double> errors, const std::string& unit) {
    file_.write(name, values);
    file_.write(name + "_error", errors);
    finish_value(name, unit);
}

void ResultGroup::histogram(const std::string& prefix, std::span<const double> edges,
                            std::span<const double> density, std::span<const double> error,
                            const std::string& edges_unit) {
    file_.write(prefix + "edges", edges);
    file_.write(prefix + "density", density);
    file_.write(prefix + "error", error);
    finish_value(prefix + "edges", edges_unit);
}

// ---- ResultSink -------------------------------------------------------------------------------

std::string summary_path_for(const std::string& output) {
    std::filesystem::path p(output);
    p.replace_extension(".summary.yaml");
    return p.string();
}

namespace {
// The folder first: h5::File::create does not make it.
h5::File create_part(const std::string& output, const std::string& part) {
    const auto parent = std::filesystem::path(output).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    return h5::File::create(part);
}
}  // namespace

ResultSink::ResultSink(std::string output)
    : output_(std::move(output)),
      part_(output_ + ".part"),
      summary_file_(summary_path_for(output_)),
      file_(create_part(output_, part_)),
      // A map from the start: a default (null) node would not be shared with the copies that
      // ResultGroups hold, and what they write would be lost.
      summary_(YAML::NodeType::Map) {}

ResultGroup ResultSink::root() {
    return ResultGroup(file_.root(), summary_);
}

void ResultSink::finish() {
    if (const std::size_t open = file_.open_objects(); open > 0) {
        throw std::logic_error("result sink: " + std::to_string(open) + " objects of " + part_ +
                               " are still open at the end of the run");
    }
    file_.close();
    std::filesystem::rename(part_, output_);
    std::ofstream out(summary_file_);
    YAML::Emitter em;
    em << summary_;
    out << "# gran run summary (values with one-standard-error bars)\n" << em.c_str() << "\n";
}

}  // namespace gran
