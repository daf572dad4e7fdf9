// Collision counts and rates: the collision frequency per particle omega = 2 dN_coll / (N dt) (each
// collision involves two particles) and, per species pair (a, b), the frequency with which one
// particle of species a collides with particles of species b:
// nu_ab = dN_ab (x2 if a == b) / (N_a dt). Rates are ratios of time averages with jackknife errors.
// On the dem engine a collision is a particle-particle contact that formed, counted in total only.
#include <fmt/format.h>

#include <vector>

#include "libgran/plugins/observable.hpp"

namespace gran {
namespace {

template <int D>
class CollisionStatistics final : public Observable<D> {
  public:
    CollisionStatistics(const Params&, const SceneInfo& info) : table_(*info.species) {
        const std::size_t ns = table_.size();
        pair_increments_.resize(ns * ns);
    }

    void sample(const SampleContext<D>& ctx) override {
        const auto& pc = ctx.engine.pair_collisions();
        const std::uint64_t total = ctx.engine.collisions();
        if (started_ && ctx.measuring) {
            dt_.push(ctx.time - last_time_);
            dtotal_.push(double(total - last_total_));
            for (std::size_t k = 0; k < pc.size(); ++k)
                pair_increments_[k].push(double(pc[k] - last_pairs_[k]));
        }
        if (ctx.measuring) started_ = true;
        last_time_ = ctx.time;
        last_total_ = total;
        last_pairs_ = pc;
        n_ = ctx.engine.particles().size();
        totals_pairs_ = pc;
        total_ = total;
        walls_ = ctx.engine.total_wall_hits();
    }

    void write(ResultGroup& out) const override {
        const std::size_t ns = table_.size();
        out.value("collisions", total_);
        out.file_only().value("wall_hits", walls_);
        if (dt_.size() < 2) return;
        const double scale = 2.0 / double(n_);
        const Estimate omega = ratio_of_means(dtotal_.values(), dt_.values()).affine(scale);
        out.estimate("frequency_per_particle", omega, "1/time");
        if (totals_pairs_.size() != ns * ns)
            return;  // the dem engine counts contacts in total only
        for (std::size_t a = 0; a < ns; ++a) {
            for (std::size_t b = a; b < ns; ++b) {
                const auto& inc = pair_increments_[a * ns + b];
                const std::string pair = table_.species[a].name + "-" + table_.species[b].name;
                ResultGroup gp = out.group("pairs").group(pair);
                gp.file_only().value("collisions", totals_pairs_[a * ns + b]);
                const Estimate r = ratio_of_means(inc.values(), dt_.values());
                // Frequency seen by one particle of a (colliding with b), and by one of b.
                const double fa = (a == b ? 2.0 : 1.0) / double(table_.species[a].count);
                gp.estimate("frequency_" + table_.species[a].name, r.affine(fa), "1/time");
                if (a != b) {
                    const double fb = 1.0 / double(table_.species[b].count);
                    gp.estimate("frequency_" + table_.species[b].name, r.affine(fb), "1/time");
                }
            }
        }
    }

    void checkpoint(StateArchive& ar) override {
        ar.section("collision_statistics");
        ar.io(started_);
        ar.io(last_time_);
        ar.io(last_total_);
        ar.io(total_);
        ar.io(walls_);
        ar.io(last_pairs_);
        ar.io(totals_pairs_);
        ar.io(n_);
        ar.io(dt_);
        ar.io(dtotal_);
        ar.io(pair_increments_);
    }

  private:
    const SpeciesTable& table_;
    bool started_ = false;
    double last_time_ = 0;
    std::uint64_t last_total_ = 0, total_ = 0, walls_ = 0;
    std::vector<std::uint64_t> last_pairs_, totals_pairs_;
    std::size_t n_ = 1;
    Series dt_, dtotal_;
    std::vector<Series> pair_increments_;
};

const char* const kDescription =
    R"md(
Collision frequency per particle, per species pair (as seen by one particle of each species), counts
and wall hits. On the dem engine a collision is a contact that formed, counted in total only (no
per-pair frequencies). Its memory and time per sample grow with the square of the number of species
S (a series per species pair: S = 10^4 is 5 10^7 pairs); the engine itself counts only the pairs
that collided beyond 1024 species.)md";

const bool registered = register_plugin<Observable, CollisionStatistics>(
    "collision_statistics", "collision counts and frequencies per particle and per species pair",
    {}, kDescription);

}  // namespace
}  // namespace gran
