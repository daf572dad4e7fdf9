#include "libgran/run/result_sink.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
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
    return ResultGroup(file_.group(name), node, summarise_, unreliable_);
}

void ResultGroup::estimate(const std::string& name, const Estimate& e, const std::string& unit) {
    file_.write_scalar(name, e.value);
    file_.attr_on(name, "error", e.error);
    file_.attr_on(name, "unit", unit);
    file_.attr_on(name, "n_eff", e.n_eff);
    file_.attr_on(name, "tau_int", e.tau_int);
    file_.attr_on(name, "samples", static_cast<std::int64_t>(e.samples));
    file_.attr_on(name, "converged", static_cast<std::int64_t>(e.converged ? 1 : 0));
    if (unreliable_ && !(std::isfinite(e.value) && std::isfinite(e.error))) {
        const std::string& base = file_.path();
        unreliable_->push_back((base.ends_with('/') ? base : base + "/") + name);
    }
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

std::string partial_path_for(const std::string& output) {
    std::filesystem::path p(output);
    p.replace_extension(".partial.h5");
    return p.string();
}

namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse_output(const std::string& output, const std::string& why) {
    throw OutputError(fmt::format("output '{}': {}", output, why));
}

// Writes and removes a probe file in `folder`: the only test that also catches a read-only file
// system and works for root, whom access(2) always allows.
void probe_writable(const fs::path& folder, const std::string& output) {
    const fs::path probe = folder / fmt::format(".gran-probe-{}", ::getpid());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0)
        refuse_output(output, fmt::format("cannot write in the folder '{}': {}", folder.string(),
                                          std::strerror(errno)));
    ::close(fd);
    ::unlink(probe.c_str());
}

bool completed_result(const std::string& file) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return false;
    try {
        const h5::File f = h5::File::open_read(file);
        return f.root().read_int64s("performance/completed").at(0) == 1;
    } catch (const std::exception&) {
        return false;
    }
}

// fsync(2) of a written file, so that a rename after it never exposes a file whose data the
// operating system still holds in memory (power loss).
void sync_file(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
        const int err = errno;
        if (fd >= 0) ::close(fd);
        throw OutputError(fmt::format("cannot write '{}': {}", path, std::strerror(err)));
    }
    ::close(fd);
}

void rename_or_throw(const std::string& from, const std::string& to) {
    std::error_code ec;
    fs::rename(from, to, ec);
    if (ec)
        throw OutputError(fmt::format("cannot rename '{}' to '{}': {}", from, to, ec.message()));
}

// The summary text into `path` (checked: a full disk is an error, not an empty summary).
void write_text(const std::string& path, const std::string& text) {
    {
        std::ofstream out(path, std::ios::trunc);
        out << text;
        out.close();
        if (!out)
            throw OutputError(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
    }
    sync_file(path);
}

// The folder first: h5::File::create does not make it.
h5::File create_part(const std::string& output, const std::string& part) {
    const auto parent = fs::path(output).parent_path();
    if (!parent.empty()) fs::create_directories(parent);
    return h5::File::create(part);
}

}  // namespace

void check_output_path(const std::string& output, const std::vector<std::string>& inputs) {
    if (output.empty()) refuse_output(output, "empty file name");
    const fs::path out(output);
    const std::string ext = out.extension().string();
    if (ext != ".h5" && ext != ".hdf5")
        refuse_output(output, "expected a result file name ending in .h5, e.g. results/run.h5");
    std::error_code ec;
    if (fs::is_directory(out, ec))
        refuse_output(output,
                      "is a directory; expected a file name such as " + (out / "run.h5").string());
    for (const std::string& in : inputs) {
        if (fs::exists(out, ec) && fs::equivalent(out, in, ec))
            refuse_output(output, "is the input file '" + in + "'; choose another result file");
    }
    for (const std::string& other : {summary_path_for(output), output + ".part"}) {
        if (fs::is_directory(other, ec))
            refuse_output(output, "'" + other + "', which the run writes, is a directory");
    }
    fs::path folder = out.parent_path();
    if (folder.empty()) folder = ".";
    fs::create_directories(folder, ec);
    if (ec)
        refuse_output(output, fmt::format("cannot create the folder '{}': {}", folder.string(),
                                          ec.message()));
    probe_writable(folder, output);
}

namespace {
// The step and time of an H5MD time series: written, or linked to those of `clock`.
void series_clock(h5::Group& g, const std::string& name, std::span<const std::int64_t> step,
                  std::span<const double> time, const std::string& clock) {
    if (!clock.empty()) {
        const std::string base =
            clock.starts_with('/') ? "" : (g.path() == "/" ? "/" : g.path() + "/");
        g.hard_link(name + "/step", base + clock + "/step");
        g.hard_link(name + "/time", base + clock + "/time");
        return;
    }
    g.write(name + "/step", step);
    g.write(name + "/time", time);
    g.attr_on(name + "/time", "unit", std::string("time"));
}
}  // namespace

void ResultGroup::time_series(const std::string& name, std::span<const std::int64_t> step,
                              std::span<const double> time, std::span<const double> value,
                              const std::string& unit, const std::string& clock) {
    series_clock(file_, name, step, time, clock);
    file_.write(name + "/value", value);
    if (!unit.empty()) file_.attr_on(name + "/value", "unit", unit);
}

void ResultGroup::time_series(const std::string& name, std::span<const std::int64_t> step,
                              std::span<const double> time, std::span<const std::int64_t> value,
                              const std::string& unit, const std::string& clock) {
    series_clock(file_, name, step, time, clock);
    file_.write(name + "/value", value);
    if (!unit.empty()) file_.attr_on(name + "/value", "unit", unit);
}

void write_synced_text(const std::string& path, const std::string& text) {
    write_text(path, text);
}

ResultSink::ResultSink(std::string output)
    : output_(std::move(output)),
      part_(output_ + ".part"),
      summary_file_(summary_path_for(output_)),
      file_(create_part(output_, part_)),
      // A map from the start: a default (null) node would not be shared with the copies that
      // ResultGroups hold, and what they write would be lost.
      summary_(YAML::NodeType::Map) {}

ResultGroup ResultSink::root() {
    return ResultGroup(file_.root(), summary_, true, &unreliable_);
}

void ResultSink::finish(bool completed) {
    if (const std::size_t open = file_.open_objects(); open > 0) {
        throw std::logic_error("result sink: " + std::to_string(open) + " objects of " + part_ +
                               " are still open at the end of the run");
    }
    // A completed run whose estimates include a non-finite value or error bar is not a result to
    // quote without looking: its status says so and names them.
    if (!unreliable_.empty() && summary_["status"] &&
        summary_["status"].as<std::string>() == "completed") {
        summary_["status"] = "unreliable";
        for (const auto& q : unreliable_) summary_["unreliable"].push_back(q);
    }
    // A run that did not complete never replaces a completed result: it goes beside it.
    written_ = destination(completed);
    if (written_ != output_) {
        summary_file_ = summary_path_for(written_);
        summary_["result"] = written_;
    }
    // Every step checked, the renames last: a failure (full disk, I/O error) leaves the .part
    // files and whatever was at the final names before.
    file_.close();
    sync_file(part_);
    YAML::Emitter em;
    em << summary_;
    const std::string summary_part = summary_file_ + ".part";
    write_text(summary_part,
               std::string("# gran run summary (values with one-standard-error bars)\n") +
                   em.c_str() + "\n");
    for (const auto& [part, final_path] : companions_) {
        sync_file(part);
        rename_or_throw(part, final_path);
    }
    rename_or_throw(part_, written_);
    rename_or_throw(summary_part, summary_file_);
}

std::string ResultSink::destination(bool completed) const {
    return !completed && completed_result(output_) ? partial_path_for(output_) : output_;
}

void ResultSink::add_companion(std::string part, std::string final_path) {
    companions_.emplace_back(std::move(part), std::move(final_path));
}

}  // namespace gran
