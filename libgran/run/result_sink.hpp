#pragma once
// The one way results leave a run: each quantity is described once (name, value, error, unit) and
// lands both in the HDF5 result file and in the human-readable summary, which therefore cannot
// disagree. Arrays, histograms, series and attributes go to the HDF5 file only.
//
// Rules, the same for every plugin and for the run loop:
//   - a name is a path in HDF5 ("middle/T" nests groups) and one key in the summary ("middle/T");
//     group("a") nests in both;
//   - estimate(): dataset with attributes error, unit ('' when dimensionless), n_eff, tau_int,
//     samples, converged; summary {value, error, unit (when not ''), n_eff (rounded, when known),
//     converged: false (only when the error is a lower bound)};
//   - value(): scalar dataset (double or int64) with a `unit` attribute when it has a unit;
//     summary `name: value` when dimensionless, `name: {value, unit}` otherwise;
//   - flag(): int64 0/1 in HDF5 (what h5py users compare), true/false in the summary;
//   - text(): string attribute of the group in HDF5, string in the summary;
//   - file_only() gives the same group writing nothing to the summary (settings echoed back,
//     counters too detailed for the summary).
#include <yaml-cpp/yaml.h>

#include <concepts>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/core/statistics.hpp"

namespace gran {

// Integers written as counts (int64 in HDF5); a bool is a flag().
template <class T>
concept Count = std::integral<T> && !std::same_as<T, bool>;

class ResultGroup {
  public:
    // `unreliable` (optional) collects the paths of estimates whose value or error is not finite.
    ResultGroup(h5::Group file, YAML::Node summary, bool summarise = true,
                std::vector<std::string>* unreliable = nullptr)
        : file_(std::move(file)),
          summary_(std::move(summary)),
          summarise_(summarise),
          unreliable_(unreliable) {}

    // Sub-group `name` in HDF5 and in the summary.
    ResultGroup group(const std::string& name);
    // Sub-group `name` in HDF5 whose summary node is at `summary_keys` below this one (e.g. the
    // temperatures' species groups, summarised under `species`).
    ResultGroup group(const std::string& name, const std::vector<std::string>& summary_keys);
    // The group's absolute path in the file (for time-series clocks shared across groups).
    const std::string& path() const { return file_.path(); }
    // This group, writing to the HDF5 file only.
    ResultGroup file_only() const { return ResultGroup(file_, summary_, false, unreliable_); }

    // ---- Quantities: HDF5 and summary -------------------------------------------------------
    void estimate(const std::string& name, const Estimate& e, const std::string& unit);
    void value(const std::string& name, double v, const std::string& unit = "");
    template <Count T>
    void value(const std::string& name, T v, const std::string& unit = "") {
        file_.write_scalar(name, static_cast<std::int64_t>(v));
        finish_value(name, unit);
        if (summarise_) summarise(name, YAML::Node(v), unit);
    }
    void flag(const std::string& name, bool v);
    void text(const std::string& name, const std::string& v);

    // ---- HDF5 only ---------------------------------------------------------------------------
    // Arrays: empty dims => 1D; otherwise the shape (h5::Group::write).
    void array(const std::string& name, std::span<const double> v, const std::string& unit = "",
               std::vector<std::size_t> dims = {});
    void array(const std::string& name, std::span<const std::int64_t> v,
               const std::string& unit = "", std::vector<std::size_t> dims = {});
    // A profile and its errors: `name` (with its unit) and `name_error`.
    void profile(const std::string& name, std::span<const double> values,
                 std::span<const double> errors, const std::string& unit = "");
    // A histogram as <prefix>edges (with the unit of x), <prefix>density and <prefix>error.
    void histogram(const std::string& prefix, std::span<const double> edges,
                   std::span<const double> density, std::span<const double> error,
                   const std::string& edges_unit = "");
    // An H5MD time series `name` = {step, time, value} (HDF5 only), value in `unit`. With `clock`,
    // the path (absolute, or relative to this group) of an earlier series of the same samples, its
    // step and time are shared by hard links instead of written again.
    void time_series(const std::string& name, std::span<const std::int64_t> step,
                     std::span<const double> time, std::span<const double> value,
                     const std::string& unit = "", const std::string& clock = "");
    void time_series(const std::string& name, std::span<const std::int64_t> step,
                     std::span<const double> time, std::span<const std::int64_t> value,
                     const std::string& unit = "", const std::string& clock = "");
    // A dataset appended to row by row while the run goes on (h5::Group::appendable).
    template <class T>
    h5::Appendable series(const std::string& name, std::vector<std::size_t> row_shape = {},
                          const std::string& unit = "") {
        h5::Appendable a = file_.appendable<T>(name, std::move(row_shape));
        if (!unit.empty()) file_.attr_on(name, "unit", unit);
        return a;
    }
    // A link to an object of another file (h5::Group::external_link).
    void external_link(const std::string& name, const std::string& file,
                       const std::string& object) {
        file_.external_link(name, file, object);
    }
    void text_dataset(const std::string& name, const std::string& v) {
        file_.write_string(name, v);
    }
    // Attributes of this group, and of one of its datasets or sub-groups (h5::Group::attr).
    template <class V>
    void attr(const std::string& name, const V& v) {
        file_.attr(name, v);
    }
    template <class V>
    void attr_on(const std::string& object, const std::string& name, const V& v) {
        file_.attr_on(object, name, v);
    }

  private:
    void finish_value(const std::string& name, const std::string& unit);
    void summarise(const std::string& name, const YAML::Node& v, const std::string& unit);

    h5::Group file_;
    YAML::Node summary_;  // a node of the summary (yaml-cpp adds it to its parent when written)
    bool summarise_;
    std::vector<std::string>* unreliable_;
};

// An output that cannot or must not be written (full disk, a directory, the scene file itself):
// the message names the path and the cause; `gran run` exits 1.
class OutputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Refuses (OutputError), before anything runs, a result path the run could not or must not
// write: not ending in .h5/.hdf5, a directory, one of `inputs` (the scene file), or in a folder
// that cannot be created or written. Creates the folder.
void check_output_path(const std::string& output, const std::vector<std::string>& inputs);

// The result of one run: OUT.h5.part is created with the sink and written to while the run goes
// on; finish() closes it, renames it to OUT.h5 and writes OUT.summary.yaml. A run that fails
// before finish() leaves an earlier OUT.h5 and its summary as they were. A run that did not
// complete (interrupted, stopped) while OUT.h5 holds a completed result goes beside it, to
// OUT.partial.h5 and OUT.partial.summary.yaml.
class ResultSink {
  public:
    // Creates OUT's folder and OUT.h5.part (h5::Error naming the path when it cannot).
    explicit ResultSink(std::string output);
    ResultSink(const ResultSink&) = delete;
    ResultSink& operator=(const ResultSink&) = delete;

    ResultGroup root();
    // Entries of the summary that are not quantities (scene, status, ...).
    YAML::Node& summary() { return summary_; }
    const std::string& output() const { return output_; }
    const std::string& part() const { return part_; }
    // Estimates written so far whose value or error is not finite (paths in the result file). A
    // run with any has status `unreliable` instead of `completed` (finish()).
    const std::vector<std::string>& unreliable() const { return unreliable_; }
    // Where finish(completed) puts the result: OUT.h5, or OUT.partial.h5 for a run that did not
    // complete when OUT.h5 holds a completed result.
    std::string destination(bool completed) const;
    // A file that goes with the result (the trajectory and its XDMF sidecar), already written
    // complete to `part`: finish() syncs and renames it to `final_path` before the result itself,
    // so a result never names a companion that is not there.
    void add_companion(std::string part, std::string final_path);
    // Where the result and its summary went (after finish()).
    const std::string& written() const { return written_; }
    const std::string& summary_file() const { return summary_file_; }
    // Every group and series obtained from root() must be gone: the file is complete only once
    // all are closed (std::logic_error otherwise). Each write, close and rename is checked
    // (h5::Error or OutputError naming the path and the cause).
    void finish(bool completed = true);

  private:
    std::string output_, part_, summary_file_, written_;
    h5::File file_;
    YAML::Node summary_;
    std::vector<std::string> unreliable_;
    std::vector<std::pair<std::string, std::string>> companions_;  // part, final path
};

// A text file written and synced to disk (OutputError naming the path and the cause).
void write_synced_text(const std::string& path, const std::string& text);

// OUT.summary.yaml beside OUT.h5.
std::string summary_path_for(const std::string& output);
// OUT.partial.h5: where a run that did not complete goes when OUT.h5 is a completed result.
std::string partial_path_for(const std::string& output);

}  // namespace gran
