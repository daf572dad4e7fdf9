#include "libgran/run/measurements.hpp"

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
