// gran._native: the compiled half of the Python package (python/gran). Thin bindings over the
// objects the command line uses (libgran/run/simulation.hpp, run.hpp, study.hpp), so a run from
// Python is the same code, and the same numbers, as `gran run`. The Python half
// (python/gran/scene.py, simulation.py) adds the documented API: keyword arguments, NumPy shapes,
// exceptions with file, line and key.
//
// Work runs with the GIL released. Ctrl-C: Python runs its SIGINT handler only when control
// returns to the interpreter, so while a run or an advance is in C++ a C handler sets the flag the
// engines poll (SigintToFlag) and the previous handler is restored afterwards.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <signal.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libgran/core/build_info.hpp"
#include "libgran/core/h5.hpp"
#include "libgran/core/scene_error.hpp"
#include "libgran/run/checkpoint.hpp"
#include "libgran/run/measurements.hpp"
#include "libgran/run/result_sink.hpp"
#include "libgran/run/run.hpp"
#include "libgran/run/simulation.hpp"
#include "libgran/scene/scene.hpp"
#include "libgran/study/study.hpp"

namespace py = pybind11;

namespace {

std::atomic<bool> g_interrupt{false};

void on_sigint(int) {
    g_interrupt.store(true);
}

bool in_main_thread() {
    py::module_ threading = py::module_::import("threading");
    return threading.attr("main_thread")().attr("ident").cast<long>() ==
           threading.attr("get_ident")().cast<long>();
}

// While alive (and in the main thread, the only one Python delivers signals to): SIGINT sets
// g_interrupt instead of raising KeyboardInterrupt later.
class SigintToFlag {
  public:
    SigintToFlag() {
        g_interrupt.store(false);
        if (!in_main_thread()) return;
        struct sigaction sa = {};
        sa.sa_handler = on_sigint;
        sigemptyset(&sa.sa_mask);
        installed_ = sigaction(SIGINT, &sa, &previous_) == 0;
    }
    ~SigintToFlag() {
        if (installed_) sigaction(SIGINT, &previous_, nullptr);
    }
    SigintToFlag(const SigintToFlag&) = delete;
    SigintToFlag& operator=(const SigintToFlag&) = delete;
    bool interrupted() const { return g_interrupt.load(); }

  private:
    struct sigaction previous_ = {};
    bool installed_ = false;
};

std::string emit(const YAML::Node& node) {
    YAML::Emitter em;
    em << node;
    return em.c_str();
}

// A validated scene (gran::load_scene_text): shared with the simulations built from it.
struct PyScene {
    std::shared_ptr<const gran::Scene> scene;
};

PyScene load(const std::string& text, const std::string& path,
             const std::vector<std::string>& overrides) {
    return {std::make_shared<const gran::Scene>(gran::load_scene_text(text, path, overrides))};
}

py::dict scene_facts(const PyScene& s) {
    const gran::Scene& sc = *s.scene;
    py::dict d;
    d["dimension"] = sc.dimension;
    d["particles"] = sc.species.total_count();
    d["species"] = sc.species.size();
    d["packing_fraction"] = sc.packing_fraction;
    d["box_length"] = sc.box_length;
    d["periodic"] = std::vector<bool>(sc.periodic.begin(), sc.periodic.end());
    d["engine"] = sc.engine_settings.type;
    d["cost"] = sc.cost.text;
    d["seed"] = sc.seed;
    return d;
}

// `gran run`: the same run_scene, with a Python callback after every `every` measurement
// samples. An exception in the callback stops the run (its data is written) and is re-raised.
py::dict run(const PyScene& s, const std::string& output, bool progress, py::object callback,
             std::size_t every) {
    gran::RunOptions opt;
    opt.output = output;
    opt.progress = progress;
    opt.terminal = false;
    opt.command_line = {"python: gran.run"};
    opt.interrupt = &g_interrupt;
    std::optional<py::error_already_set> callback_error;
    if (!callback.is_none() && every > 0) {
        opt.on_sample = [&](std::size_t samples, double time) {
            if (samples % every != 0 || callback_error) return;
            py::gil_scoped_acquire gil;
            try {
                callback(samples, time);
            } catch (py::error_already_set& e) {
                callback_error.emplace(std::move(e));
                g_interrupt.store(true);  // stop: the error is raised once the data is written
            }
        };
    }
    gran::RunReport rep;
    bool sigint = false;
    {
        // Without progress, only warnings (as `gran run -q`).
        const spdlog::level::level_enum level = spdlog::get_level();
        if (!progress) spdlog::set_level(spdlog::level::warn);
        SigintToFlag guard;
        py::gil_scoped_release release;
        try {
            rep = gran::run_scene(*s.scene, opt);
        } catch (...) {
            spdlog::set_level(level);
            throw;
        }
        spdlog::set_level(level);
        sigint = guard.interrupted() && !callback_error;
    }
    py::dict d;
    d["completed"] = rep.completed;
    d["error"] = rep.error;
    d["output"] = rep.output;
    d["summary_file"] = rep.summary_file;
    d["summary"] = emit(rep.summary);
    d["interrupted"] = sigint;
    if (callback_error) {
        // The run stopped on the callback's exception with its data written: the exception
        // carries the report, so gran.run can attach the Result to it.
        callback_error->value().attr("gran_report") = d;
        throw std::move(*callback_error);
    }
    return d;
}

// gran.Simulation: stepwise access to one simulation.
class PySimulation {
  public:
    explicit PySimulation(const PyScene& s)
        : scene_(s.scene), sim_(std::make_unique<gran::Simulation>(*s.scene, &g_interrupt)) {}

    // "reached", "interrupted" (Ctrl-C), "stalled" or "watchdog" (see failure()).
    std::string advance(double time, std::uint64_t collisions, std::uint64_t work) {
        gran::Advance a;
        {
            SigintToFlag guard;
            py::gil_scoped_release release;
            a = sim_->advance({.time = time, .collisions = collisions, .work = work});
        }
        switch (a) {
            case gran::Advance::Reached:
                return "reached";
            case gran::Advance::Interrupted:
                return "interrupted";
            case gran::Advance::Stalled:
                return "stalled";
            case gran::Advance::Watchdog:
                return "watchdog";
        }
        return "reached";
    }

    // N x width (N x 0 when `v` is empty: grains that do not rotate).
    py::array_t<double> rows(std::vector<double> v, std::size_t width) const {
        const std::size_t n = sim_->size();
        if (v.empty()) width = 0;
        py::array_t<double> a({n, width});
        std::copy(v.begin(), v.end(), a.mutable_data());
        return a;
    }
    py::array_t<double> positions() const { return rows(sim_->positions(), dim()); }
    py::array_t<double> velocities() const { return rows(sim_->velocities(), dim()); }
    py::array_t<double> angular_velocities() const {
        return rows(sim_->angular_velocities(), dim() == 2 ? 1 : 3);
    }
    py::array_t<std::uint32_t> species() const {
        const std::vector<std::uint32_t> v = sim_->species();
        py::array_t<std::uint32_t> a(v.size());
        std::copy(v.begin(), v.end(), a.mutable_data());
        return a;
    }
    // Samples every observable now; `expected` is how many samples the measurement will take
    // (blocks of histograms and profiles are sized by it); 0: the scene's schedule.
    void sample(bool measuring, std::size_t expected) {
        if (expected == 0) {
            const auto& s = scene_->schedule;
            expected =
                static_cast<std::size_t>(std::floor(s.measurement / s.sample_interval + 1e-9));
        }
        sim_->sample(measuring, expected);
    }
    std::string write_measurements(const std::string& path) const {
        return gran::write_measurements(*sim_, path);
    }
    std::size_t dim() const { return std::size_t(sim_->dimension()); }
    const gran::Simulation& sim() const { return *sim_; }

  private:
    std::shared_ptr<const gran::Scene> scene_;
    std::unique_ptr<gran::Simulation> sim_;
};

// `gran study`: the runs are `gran run` processes of this build's binary.
py::dict study(const std::string& path, const std::string& output_dir, int jobs, bool progress,
               bool reuse_any_version) {
    const gran::Study st = gran::load_study(path);
    gran::StudyOptions opt;
    opt.output_dir = output_dir;
    opt.jobs = jobs;
    opt.gran_binary = std::string(GRAN_BINARY_DIR) + "/gran";
    opt.reuse_any_version = reuse_any_version;
    opt.progress = progress;
    opt.interrupt = &g_interrupt;
    gran::StudyReport rep;
    {
        SigintToFlag guard;
        py::gil_scoped_release release;
        rep = gran::run_study(st, opt);
    }
    py::dict d;
    d["ran"] = rep.ran;
    d["reused"] = rep.reused;
    d["failed"] = rep.failed;
    d["interrupted"] = rep.interrupted;
    d["merged"] = rep.merged;
    d["table"] = rep.table;
    d["tradeoff"] = rep.tradeoff;
    return d;
}

py::dict version() {
    const gran::BuildInfo& b = gran::build_info();
    py::dict d;
    d["version"] = b.version;
    d["commit"] = b.commit;
    d["dirty"] = b.dirty;
    d["build_type"] = b.build_type;
    d["compiler"] = b.compiler;
    d["code_id"] = b.code_id();
    d["binary_dir"] = GRAN_BINARY_DIR;
    return d;
}

}  // namespace

PYBIND11_MODULE(_native, m) {
    m.doc() = "gran's compiled core (use the package gran, which wraps it)";
    // Log lines on stderr, never mixed into what a script prints on stdout.
    spdlog::set_default_logger(spdlog::stderr_color_mt("gran"));
    spdlog::set_pattern("[%H:%M:%S] [%^%l%$] %v");
    py::register_exception<gran::SceneError>(m, "SceneError", PyExc_ValueError);
    py::register_exception<gran::OutputError>(m, "OutputError", PyExc_OSError);
    py::register_exception<gran::CheckpointError>(m, "CheckpointError", PyExc_RuntimeError);
    py::register_exception<gran::h5::Error>(m, "HDF5Error", PyExc_OSError);

    m.def("version", &version, "version, commit, dirty, build_type, compiler, code_id");

    py::class_<PyScene>(m, "Scene", "a validated scene (gran.Scene wraps it)")
        .def("facts", &scene_facts)
        .def("resolved", [](const PyScene& s) { return emit(s.scene->resolved); })
        .def("check", [](const PyScene& s) { gran::check_scene(*s.scene); });
    m.def("load_scene", &load, py::arg("text"), py::arg("path"), py::arg("overrides"));

    m.def("run", &run, py::arg("scene"), py::arg("output"), py::arg("progress"),
          py::arg("callback"), py::arg("every"));
    m.def("study", &study, py::arg("path"), py::arg("output_dir"), py::arg("jobs"),
          py::arg("progress"), py::arg("reuse_any_version"));

    py::class_<PySimulation>(m, "Simulation", "one simulation (gran.Simulation wraps it)")
        .def(py::init<const PyScene&>())
        .def("advance", &PySimulation::advance, py::arg("time"), py::arg("collisions"),
             py::arg("work"))
        .def("positions", &PySimulation::positions)
        .def("velocities", &PySimulation::velocities)
        .def("angular_velocities", &PySimulation::angular_velocities)
        .def("species", &PySimulation::species)
        .def("sample", &PySimulation::sample, py::arg("measuring"), py::arg("expected"))
        .def("write_measurements", &PySimulation::write_measurements, py::arg("path"))
        .def_property_readonly("time", [](const PySimulation& s) { return s.sim().time(); })
        .def_property_readonly("collisions",
                               [](const PySimulation& s) { return s.sim().collisions(); })
        .def_property_readonly("work", [](const PySimulation& s) { return s.sim().work(); })
        .def_property_readonly("work_unit",
                               [](const PySimulation& s) { return s.sim().work_unit(); })
        .def_property_readonly("failure", [](const PySimulation& s) { return s.sim().failure(); })
        .def_property_readonly("dimension", &PySimulation::dim);
}
