#include "libgran/run/trajectory.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <optional>

#include "libgran/core/h5.hpp"
#include "libgran/run/result_file.hpp"

namespace gran {

namespace {

std::string stem_of(const std::string& result) {
    const std::filesystem::path p(result);
    return (p.parent_path() / p.stem()).string();
}

// Units (H5MD units module): SI scenes carry H5MD unit strings ("m", "m s-1", ...); in reduced
// units, which no reader can convert, the H5MD `unit` attribute is left out (it is optional, and
// MDAnalysis refuses unit strings it does not know) and `reduced_unit` names the dimension.
struct Units {
    bool si = false;
    void mark(h5::Group g, const std::string& dataset, const std::string& quantity) const {
        if (quantity.empty()) return;
        if (!si) {
            g.attr_on(dataset, "reduced_unit", quantity);
            return;
        }
        static const std::map<std::string, std::string> symbol = {{"length", "m"},
                                                                  {"time", "s"},
                                                                  {"velocity", "m s-1"},
                                                                  {"mass", "kg"},
                                                                  {"1/time", "s-1"}};
        g.attr_on(dataset, "unit", symbol.at(quantity));
    }
};

// One time-dependent H5MD element {step, time, value}: value rows of `row_shape`.
struct Element {
    h5::Appendable step, time, value;
};

template <class T>
Element element(h5::Group parent, const std::string& name, std::vector<std::size_t> row_shape,
                const std::string& quantity, const Units& units) {
    h5::Group g = parent.group(name);
    Element e{g.appendable<std::int64_t>("step"), g.appendable<double>("time"),
              g.appendable<T>("value", std::move(row_shape))};
    units.mark(g, "time", "time");
    units.mark(g, "value", quantity);
    return e;
}

void append(Element& e, const Frame& f, std::span<const double> v) {
    e.step.append(std::span<const std::int64_t>(&f.step, 1));
    e.time.append(std::span<const double>(&f.time, 1));
    e.value.append(v);
}
void append(Element& e, const Frame& f, std::span<const std::int64_t> v) {
    e.step.append(std::span<const std::int64_t>(&f.step, 1));
    e.time.append(std::span<const double>(&f.time, 1));
    e.value.append(v);
}

// Per-particle constants: species index, mass and diameter.
void write_particle_constants(h5::Group all, const Scene& sc,
                              const std::vector<std::int64_t>& species, const Units& units) {
    std::vector<double> mass, diameter;
    for (std::int64_t s : species) {
        mass.push_back(sc.species.species[std::size_t(s)].mass);
        diameter.push_back(sc.species.species[std::size_t(s)].diameter);
    }
    all.write("species", std::span<const std::int64_t>(species));
    all.write("mass", std::span<const double>(mass));
    units.mark(all, "mass", "mass");
    all.write("diameter", std::span<const double>(diameter));
    units.mark(all, "diameter", "length");
    std::vector<std::string> names;
    for (const auto& s : sc.species.species) names.push_back(s.name);
    all.attr("species_names", names);
}

// The H5MD file at `path`; returns the frames' times (for the XDMF sidecar).
std::vector<double> write_h5md(FrameWriter& frames, const std::string& path, const Scene& sc,
                               const std::vector<std::string>& command_line,
                               const std::string& step_unit) {
    const FrameLayout& L = frames.layout();
    const FrameBox& box = frames.box();
    std::vector<double> times;
    h5::File file = h5::File::create(path);
    {
        ResultGroup root(file.root(), YAML::Node(YAML::NodeType::Map), false);
        write_provenance(root, sc, command_line);
        h5::Group all = file.root().group("particles/all");
        all.attr("step_unit", step_unit);
        h5::Group b = all.group("box");
        b.attr("dimension", box.dimension);
        b.attr("boundary", box.boundary);
        const std::size_t n = L.particles, d = L.dimension;
        const Units units{sc.units == "SI"};
        // The edges as a D x D matrix of edge vectors (H5MD's triclinic form, diagonal here): the
        // form MDAnalysis reads into its box dimensions.
        Element edges = element<double>(b, "edges", {d, d}, "length", units);
        std::vector<double> edge_vectors(d * d, 0.0);
        for (std::size_t a = 0; a < d; ++a) edge_vectors[a * d + a] = box.edges[a];
        Element position = element<double>(all, "position", {n, d}, "length", units);
        Element velocity = element<double>(all, "velocity", {n, d}, "velocity", units);
        std::optional<Element> image, angular;
        if (L.images) image = element<std::int64_t>(all, "image", {n, d}, "", units);
        if (L.angular_width) {
            angular =
                element<double>(all, "angular_velocity", {n, L.angular_width}, "1/time", units);
        }
        std::vector<std::int64_t> images64;
        bool first = true;
        frames.for_each([&](const Frame& f) {
            if (first) write_particle_constants(all, sc, f.species, units);
            first = false;
            times.push_back(f.time);
            append(edges, f, std::span<const double>(edge_vectors));
            append(position, f, std::span<const double>(f.positions));
            append(velocity, f, std::span<const double>(f.velocities));
            if (image) {
                images64.assign(f.images.begin(), f.images.end());
                append(*image, f, std::span<const std::int64_t>(images64));
            }
            if (angular) append(*angular, f, std::span<const double>(f.angular));
        });
    }  // every element closed before the file
    file.close();
    return times;
}

// A hyperslab of frame k of `dataset` (frames x n x width) as an n x width DataItem.
std::string slab(const std::string& h5, const std::string& dataset, std::size_t k,
                 std::size_t frames, std::size_t n, std::size_t width, const char* type) {
    return fmt::format(
        "        <DataItem ItemType=\"HyperSlab\" Dimensions=\"{n} {w}\" Type=\"HyperSlab\">\n"
        "          <DataItem Dimensions=\"3 3\" Format=\"XML\">{k} 0 0 1 1 1 1 {n} {w}</DataItem>\n"
        "          <DataItem Dimensions=\"{f} {n} {w}\" {type} Precision=\"8\" "
        "Format=\"HDF\">{h5}:{ds}</DataItem>\n"
        "        </DataItem>\n",
        fmt::arg("n", n), fmt::arg("w", width), fmt::arg("k", k), fmt::arg("f", frames),
        fmt::arg("type", type), fmt::arg("h5", h5), fmt::arg("ds", dataset));
}

std::string attribute(const std::string& name, const std::string& kind, const std::string& data) {
    return fmt::format(
        "      <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n{}      "
        "</Attribute>\n",
        name, kind, data);
}

std::string constant(const std::string& h5, const std::string& dataset, std::size_t n,
                     const char* type) {
    return fmt::format(
        "        <DataItem Dimensions=\"{}\" {} Precision=\"8\" Format=\"HDF\">{}:{}</DataItem>\n",
        n, type, h5, dataset);
}

}  // namespace

std::string trajectory_path_for(const std::string& result) {
    return stem_of(result) + ".trajectory.h5";
}
std::string xdmf_path_for(const std::string& result) {
    return stem_of(result) + ".trajectory.xdmf";
}

std::string xdmf_text(const FrameLayout& L, const std::vector<double>& times,
                      const std::string& h5) {
    const char* dbl = "NumberType=\"Float\"";
    const char* integer = "NumberType=\"Int\"";
    const std::size_t n = L.particles, d = L.dimension, F = times.size();
    std::string out =
        "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        "<!-- gran trajectory: the frames of the H5MD file beside it, as point clouds -->\n"
        "<Xdmf Version=\"2.0\">\n  <Domain>\n"
        "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t k = 0; k < F; ++k) {
        out += fmt::format("    <Grid Name=\"frame {}\" GridType=\"Uniform\">\n", k);
        out += fmt::format("      <Time Value=\"{:.17g}\"/>\n", times[k]);
        out += fmt::format(
            "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
            "NodesPerElement=\"1\"/>\n",
            n);
        out += fmt::format("      <Geometry GeometryType=\"{}\">\n", d == 2 ? "XY" : "XYZ");
        out += slab(h5, "/particles/all/position/value", k, F, n, d, dbl);
        out += "      </Geometry>\n";
        out += attribute("velocity", "Vector",
                         slab(h5, "/particles/all/velocity/value", k, F, n, d, dbl));
        out += attribute("species", "Scalar", constant(h5, "/particles/all/species", n, integer));
        out += attribute("diameter", "Scalar", constant(h5, "/particles/all/diameter", n, dbl));
        out += attribute("mass", "Scalar", constant(h5, "/particles/all/mass", n, dbl));
        if (L.images) {
            out += attribute("image", "Vector",
                             slab(h5, "/particles/all/image/value", k, F, n, d, integer));
        }
        if (L.angular_width) {
            out += attribute(
                "angular_velocity", L.angular_width == 1 ? "Scalar" : "Vector",
                slab(h5, "/particles/all/angular_velocity/value", k, F, n, L.angular_width, dbl));
        }
        out += "    </Grid>\n";
    }
    out += "    </Grid>\n  </Domain>\n</Xdmf>\n";
    return out;
}

void write_trajectory(FrameWriter& frames, ResultSink& sink, const std::string& destination,
                      const Scene& sc, const std::vector<std::string>& command_line,
                      const std::string& step_unit) {
    if (frames.frames() == 0) return;
    const std::string h5 = trajectory_path_for(destination);
    const std::string xdmf = xdmf_path_for(destination);
    const std::string h5_name = std::filesystem::path(h5).filename().string();
    const std::vector<double> times = write_h5md(frames, h5 + ".part", sc, command_line, step_unit);
    write_synced_text(xdmf + ".part", xdmf_text(frames.layout(), times, h5_name));
    sink.root().file_only().external_link("particles", h5_name, "/particles");
    sink.add_companion(h5 + ".part", h5);
    sink.add_companion(xdmf + ".part", xdmf);
}

}  // namespace gran
