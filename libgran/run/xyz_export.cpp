#include "libgran/run/xyz_export.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/run/result_sink.hpp"

namespace gran {

namespace {

// Species names in index order and the periodic axes, from the resolved scene the file records.
struct SceneFacts {
    std::vector<std::string> species;
    std::vector<bool> periodic;
};

SceneFacts scene_facts(const h5::Group& root, const std::string& input) {
    if (!root.exists("parameters/scene"))
        throw OutputError(fmt::format("'{}' records no scene (/parameters/scene)", input));
    const YAML::Node scene = YAML::Load(root.read_string("parameters/scene"));
    SceneFacts facts;
    for (const auto& s : scene["species"]) facts.species.push_back(s["name"].as<std::string>());
    for (const auto& p : scene["box"]["periodic"]) facts.periodic.push_back(p.as<bool>());
    return facts;
}

std::string comment_line(const double* edges, std::size_t d, const std::vector<bool>& periodic,
                         double time, std::int64_t step) {
    std::string lattice, pbc;
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = 0; b < 3; ++b) {
            const double v = a < d && b < d ? edges[a * d + b] : (a == b ? 1.0 : 0.0);
            lattice += fmt::format("{}{:.17g}", lattice.empty() ? "" : " ", v);
        }
        const bool p = a < d && a < periodic.size() && periodic[a];
        pbc += fmt::format("{}{}", a ? " " : "", p ? "T" : "F");
    }
    return fmt::format(
        "Lattice=\"{}\" Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1 pbc=\"{}\" "
        "Time={:.17g} Step={}",
        lattice, pbc, time, step);
}

void put(std::FILE* out, const std::string& text, const std::string& path) {
    if (std::fputs(text.c_str(), out) < 0)
        throw OutputError(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
}

}  // namespace

std::size_t export_xyz(const std::string& input, const std::string& output) {
    const h5::File file = h5::File::open_read(input);
    h5::Group root = file.root();
    if (!root.exists("particles/all/position/value")) {
        throw OutputError(fmt::format(
            "'{}' holds no trajectory frames (a scene writes them with output.frames)", input));
    }
    const SceneFacts facts = scene_facts(root, input);
    h5::Group all = root.group("particles/all");
    const auto shape = all.shape("position/value");
    const std::size_t frames = shape[0], n = shape[1], d = shape[2];
    const auto r = all.read_doubles("position/value");
    const auto v = all.read_doubles("velocity/value");
    const auto times = all.read_doubles("position/time");
    const auto steps = all.read_int64s("position/step");
    const auto species = all.read_int64s("species");
    const auto diameter = all.read_doubles("diameter");
    const auto edges = all.read_doubles("box/edges/value");  // frames x d x d
    const std::string part = output + ".part";
    std::FILE* out = std::fopen(part.c_str(), "w");
    if (!out) throw OutputError(fmt::format("cannot write '{}': {}", part, std::strerror(errno)));
    try {
        for (std::size_t k = 0; k < frames; ++k) {
            put(out,
                fmt::format("{}\n{}\n", n,
                            comment_line(&edges[k * d * d], d, facts.periodic, times[k], steps[k])),
                part);
            for (std::size_t i = 0; i < n; ++i) {
                const double* ri = &r[(k * n + i) * d];
                const double* vi = &v[(k * n + i) * d];
                put(out,
                    fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n",
                                facts.species.at(std::size_t(species[i])), ri[0], ri[1],
                                d == 3 ? ri[2] : 0.0, vi[0], vi[1], d == 3 ? vi[2] : 0.0,
                                0.5 * diameter[i]),
                    part);
            }
        }
        if (std::fclose(out) != 0) {
            out = nullptr;
            throw OutputError(fmt::format("cannot write '{}': {}", part, std::strerror(errno)));
        }
    } catch (...) {
        if (out) std::fclose(out);
        std::remove(part.c_str());
        throw;
    }
    if (std::rename(part.c_str(), output.c_str()) != 0) {
        throw OutputError(
            fmt::format("cannot rename '{}' to '{}': {}", part, output, std::strerror(errno)));
    }
    return frames;
}

}  // namespace gran
