#include "libgran/run/simulation.hpp"

#include <stdexcept>

namespace gran {

struct Simulation::Base {
    virtual ~Base() = default;
    virtual int dimension() const = 0;
};

template <int D>
struct Simulation::Impl final : Simulation::Base, SimulationState<D> {
    int dimension() const override { return D; }
};

namespace {

template <int D>
void build(const Scene& sc, SimulationState<D>& st) {
    for (std::size_t k = 0; k < sc.drivers.size(); ++k) {
        st.drivers.push_back(DriverRegistry::instance()
                                 .find(sc.drivers[k].type)
                                 ->template make<D>(sc.drivers[k].params, plugin_info(sc, k)));
    }
    for (std::size_t k = 0; k < sc.observables.size(); ++k) {
        st.observables.push_back(
            ObservableRegistry::instance()
                .find(sc.observables[k].type)
                ->template make<D>(sc.observables[k].params, plugin_info(sc, k)));
    }
    st.runner = sc.engine->template make<D>(sc, st.drivers, st.observables);
}

// Calls f(state) with the state of the simulation's dimension.
template <class Sim, class F>
decltype(auto) visit(Sim& sim, F&& f) {
    if (sim.dimension() == 2) return f(sim.template state<2>());
    return f(sim.template state<3>());
}

// Per-particle data in placement order: out[id * width + c] = get(storage index k)[c].
template <int D, class Get>
std::vector<double> gathered(const EngineView<D>& view, std::size_t width, Get get) {
    const auto& p = view.particles();
    std::vector<double> out(p.size() * width);
    for (std::size_t k = 0; k < p.size(); ++k) {
        double* row = &out[std::size_t(view.id(k)) * width];
        get(k, row);
    }
    return out;
}

}  // namespace

Simulation::Simulation(Scene scene, const std::atomic<bool>* interrupt)
    : scene_(std::make_unique<Scene>(std::move(scene))), interrupt_(interrupt) {
    if (scene_->dimension == 2) {
        auto impl = std::make_unique<Impl<2>>();
        build<2>(*scene_, *impl);
        impl_ = std::move(impl);
    } else {
        auto impl = std::make_unique<Impl<3>>();
        build<3>(*scene_, *impl);
        impl_ = std::move(impl);
    }
}

Simulation::~Simulation() = default;

template <int D>
SimulationState<D>& Simulation::state() {
    if (impl_->dimension() != D) throw std::logic_error("Simulation::state: wrong dimension");
    return static_cast<Impl<D>&>(*impl_);
}
template <int D>
const SimulationState<D>& Simulation::state() const {
    if (impl_->dimension() != D) throw std::logic_error("Simulation::state: wrong dimension");
    return static_cast<const Impl<D>&>(*impl_);
}
template SimulationState<2>& Simulation::state<2>();
template SimulationState<3>& Simulation::state<3>();
template const SimulationState<2>& Simulation::state<2>() const;
template const SimulationState<3>& Simulation::state<3>() const;

double Simulation::time() const {
    return visit(*this, [](const auto& st) { return st.runner->now(); });
}
std::uint64_t Simulation::collisions() const {
    return visit(*this, [](const auto& st) { return st.runner->collisions(); });
}
std::uint64_t Simulation::work() const {
    return visit(*this, [](const auto& st) { return st.runner->work(); });
}
const char* Simulation::work_unit() const {
    return visit(*this, [](const auto& st) { return st.runner->work_unit(); });
}
const std::string& Simulation::failure() const {
    return visit(*this, [](const auto& st) -> const std::string& { return st.runner->failure(); });
}

Advance Simulation::advance(const Until& until) {
    return visit(*this, [&](auto& st) {
        auto& r = *st.runner;
        const std::uint64_t c = until.collisions ? r.collisions() + until.collisions : UINT64_MAX;
        const std::uint64_t w = until.work ? r.work() + until.work : UINT64_MAX;
        const bool bounded = until.time < kInf || until.collisions || until.work;
        const Advance a = bounded ? r.advance(until.time, c, w, interrupt_) : Advance::Reached;
        r.synchronize();
        return a;
    });
}

std::vector<double> Simulation::positions() const {
    return visit(*this, [](const auto& st) {
        const auto& view = st.runner->view();
        constexpr int D = std::decay_t<decltype(view.particles().r[0])>::RowsAtCompileTime;
        return gathered<D>(view, D, [&](std::size_t k, double* row) {
            for (int a = 0; a < D; ++a) row[a] = view.particles().r[k][a];
        });
    });
}

std::vector<double> Simulation::velocities() const {
    return visit(*this, [](const auto& st) {
        const auto& view = st.runner->view();
        constexpr int D = std::decay_t<decltype(view.particles().v[0])>::RowsAtCompileTime;
        return gathered<D>(view, D, [&](std::size_t k, double* row) {
            for (int a = 0; a < D; ++a) row[a] = view.particles().v[k][a];
        });
    });
}

std::vector<double> Simulation::angular_velocities() const {
    return visit(*this, [](const auto& st) {
        const auto& view = st.runner->view();
        constexpr int D = std::decay_t<decltype(view.particles().r[0])>::RowsAtCompileTime;
        if (!view.particles().rotating()) return std::vector<double>{};
        constexpr int width = D == 2 ? 1 : 3;
        return gathered<D>(view, width, [&](std::size_t k, double* row) {
            if constexpr (D == 2) {
                row[0] = view.particles().w[k];
            } else {
                for (int a = 0; a < 3; ++a) row[a] = view.particles().w[k][a];
            }
        });
    });
}

std::vector<std::uint32_t> Simulation::species() const {
    return visit(*this, [](const auto& st) {
        const auto& view = st.runner->view();
        const auto& p = view.particles();
        std::vector<std::uint32_t> out(p.size());
        for (std::size_t k = 0; k < p.size(); ++k) out[view.id(k)] = p.species[k];
        return out;
    });
}

void Simulation::sample(bool measuring, std::size_t expected_samples) {
    visit(*this, [&](auto& st) {
        const auto& view = st.runner->view();
        for (auto& o : st.observables) {
            o->sample({view.now(), measuring, expected_samples, view, scene_->species,
                       std::int64_t(st.runner->work())});
        }
    });
}

}  // namespace gran
