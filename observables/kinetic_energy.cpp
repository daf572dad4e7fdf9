// Total kinetic energy (translational + rotational) per particle, as a time series over both the
// equilibration and the measurement phases (free cooling is analysed from t = 0), with the
// cumulative collisions per particle at each sample (2 N_coll / N).
#include <vector>

#include "libgran/plugins/observable.hpp"

namespace gran {
namespace {

template <int D>
class KineticEnergy final : public Observable<D> {
  public:
    KineticEnergy(const Params&, const SceneInfo& info) : table_(*info.species) {}

    void sample(const SampleContext<D>& ctx) override {
        const double per = ctx.engine.kinetic_energy_per_particle(table_);
        const std::size_t n = ctx.engine.particles().size();
        time_.push_back(ctx.time);
        steps_.push_back(ctx.step);
        energy_.push_back(per);
        phase_.push_back(ctx.measuring ? 1 : 0);
        cpp_.push_back(2.0 * double(ctx.engine.collisions()) / double(n));
        if (ctx.measuring) measured_.push(per);
    }

    void write(ResultGroup& out) const override {
        // H5MD time series {step, time, value} sharing one step and time.
        out.time_series("energy_per_particle", steps_, time_, energy_, "energy");
        out.time_series("collisions_per_particle", steps_, time_, cpp_, "", "energy_per_particle");
        out.time_series("measuring", steps_, time_, phase_, "", "energy_per_particle");
        if (measured_.size() > 0)
            out.estimate("mean_energy_per_particle", measured_.estimate(), "energy");
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("kinetic_energy");
        ar.io(time_);
        ar.io(steps_);
        ar.io(energy_);
        ar.io(cpp_);
        ar.io(phase_);
        ar.io(measured_);
    }

  private:
    const SpeciesTable& table_;
    std::vector<double> time_, energy_, cpp_;
    std::vector<std::int64_t> phase_, steps_;
    Series measured_;
};

const char* const kDescription =
    R"md(
Kinetic energy per particle (translational + rotational) at every sample of both phases, with the
cumulative collisions per particle and whether the sample was measuring (1) or equilibrating (0):
H5MD time series {step, time, value} `energy_per_particle`, `collisions_per_particle`, `measuring`. The one observable that also measures the equilibration.)md";

const bool registered = register_plugin<Observable, KineticEnergy>(
    "kinetic_energy", "total kinetic energy per particle over time (equilibration and measurement)",
    {}, kDescription);

}  // namespace
}  // namespace gran
