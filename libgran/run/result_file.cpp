#include "libgran/run/result_file.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <span>

#include "libgran/core/build_info.hpp"

namespace gran {

namespace {

// Where the run ran (issue 18): the host, the MPI rank of the `gran study` that started it
// (-1: none; the launchers' rank variables are inherited by the runs a rank starts), and the
// SLURM job and array task when a batch system started it. Attributes of /provenance.
void write_placement(ResultGroup& g) {
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
    g.attr("host", std::string(host));
    std::int64_t rank = -1;
    for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
        if (const char* x = std::getenv(v); x && *x) {
            rank = std::strtoll(x, nullptr, 10);
            break;
        }
    }
    g.attr("mpi_rank", rank);
    for (const char* v : {"SLURM_JOB_ID", "SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID"}) {
        if (const char* x = std::getenv(v); x && *x) {
            std::string name(v);
            for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
            g.attr(name, std::string(x));
        }
    }
}

}  // namespace

void write_provenance(ResultGroup root, const Scene& sc,
                      const std::vector<std::string>& command_line) {
    ResultGroup file = root.file_only();
    ResultGroup h5md = file.group("h5md");
    const std::vector<std::int64_t> version{1, 1};
    h5md.attr("version", std::span<const std::int64_t>(version));
    const char* user = std::getenv("USER");
    h5md.group("author").attr("name", user ? user : "gran user");
    ResultGroup creator = h5md.group("creator");
    creator.attr("name", "gran");
    const BuildInfo& b = build_info();
    creator.attr("version", b.code_id());

    // What built this result: `gran study` reuses it only for the same code_id.
    ResultGroup code = file.group("provenance");
    code.attr("code_id", b.code_id());
    code.attr("version", b.version);
    code.attr("commit", b.commit);
    code.attr("dirty", std::int64_t(b.dirty));
    code.attr("build_type", b.build_type);
    code.attr("compiler", b.compiler);
    write_placement(code);

    ResultGroup par = file.group("parameters");
    YAML::Emitter em;
    em << sc.resolved;
    par.text_dataset("scene", em.c_str());
    par.attr("source_file", sc.file);
    par.attr("packing_fraction", sc.packing_fraction);
    std::string cmd;
    for (const auto& a : command_line) cmd += (cmd.empty() ? "" : " ") + a;
    par.attr("command_line", cmd);
    par.attr("units", sc.units == "SI"
                          ? "SI: lengths in m, masses in kg, times in s, energies in J, "
                            "temperatures as energies (k_B = 1: J)"
                          : "reduced: lengths, masses and energies as given in the scene "
                            "(k_B = 1)");
}

void write_run_performance(ResultGroup& performance, const RunTotals& t) {
    performance.value("wall_time", t.wall_time, "s");
    performance.value("cpu_time", t.cpu_time, "s");
    performance.value("cpu_time_measuring", t.cpu_time_measuring, "s");
    ResultGroup file = performance.file_only();
    file.value("final_time", t.final_time);
    file.value("measured_collisions_per_particle", t.measured_collisions_per_particle);
    file.value("measured_time", t.measured_time);
    file.value("samples", t.samples);
    file.flag("completed", t.completed);
    file.flag("interrupted", t.interrupted);
    file.value("checkpoints", t.checkpoints);
    file.value("resumes", t.resumes);
    file.value("checkpoint_time", t.checkpoint_time, "s");
    if (!t.watchdog_stop.empty()) file.attr("watchdog_stop", t.watchdog_stop);
}

void write_summary_header(YAML::Node& summary, const Scene& sc, const std::string& output,
                          const std::string& status, const std::string& error,
                          std::size_t particles) {
    summary["scene"] = sc.file;
    const BuildInfo& b = build_info();
    summary["code"]["version"] = b.version;
    summary["code"]["commit"] = b.commit;
    summary["code"]["dirty"] = b.dirty;
    summary["code"]["build_type"] = b.build_type;
    if (!sc.title.empty()) summary["title"] = sc.title;
    summary["result"] = output;
    summary["status"] = status;
    if (!error.empty()) summary["error"] = error;
    summary["dimension"] = sc.dimension;
    summary["particles"] = particles;
    summary["packing_fraction"] = sc.packing_fraction;
}

}  // namespace gran
