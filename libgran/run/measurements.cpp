#include "libgran/run/measurements.hpp"

#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include "libgran/core/h5.hpp"
#include "libgran/run/result_file.hpp"
#include "libgran/run/result_sink.hpp"

namespace gran {

namespace {
template <int D>
void write_plugins(const Scene& sc, const SimulationState<D>& st, ResultGroup root) {
    for (std::size_t k = 0; k < st.observables.size(); ++k) {
        ResultGroup g = root.group("observables").group(sc.observables[k].name);
        g.attr("type", sc.observables[k].type);
        st.observables[k]->write(g);
    }
    for (std::size_t k = 0; k < st.drivers.size(); ++k) {
        ResultGroup g = root.group("drivers").group(sc.drivers[k].name);
        st.drivers[k]->write(g);
    }
}
}  // namespace

template <int D>
YAML::Node observables_summary_now(const Scene& sc, const SimulationState<D>& st) {
    YAML::Node summary(YAML::NodeType::Map);
    const auto level = spdlog::get_level();
    spdlog::set_level(spdlog::level::err);
    try {
        h5::File file = h5::File::in_memory("gran-look.h5");
        {
            ResultGroup root(file.root(), summary);
            for (std::size_t k = 0; k < st.observables.size(); ++k) {
                ResultGroup g = root.group("observables").group(sc.observables[k].name);
                st.observables[k]->write(g);
            }
        }
        file.close();
    } catch (...) {
        spdlog::set_level(level);
        throw;
    }
    spdlog::set_level(level);
    return summary["observables"];
}

template YAML::Node observables_summary_now<2>(const Scene&, const SimulationState<2>&);
template YAML::Node observables_summary_now<3>(const Scene&, const SimulationState<3>&);

std::string write_measurements(const Simulation& sim, const std::string& path) {
    YAML::Node summary(YAML::NodeType::Map);
    {
        h5::File file = h5::File::create(path);
        {
            ResultGroup root(file.root(), summary);
            write_provenance(root, sim.scene(), {"python: gran.Simulation"});
            if (sim.dimension() == 2) {
                write_plugins<2>(sim.scene(), sim.state<2>(), root);
            } else {
                write_plugins<3>(sim.scene(), sim.state<3>(), root);
            }
        }  // every group closed before the file
        file.close();
    }
    YAML::Emitter em;
    em << summary;
    return em.c_str();
}

}  // namespace gran
