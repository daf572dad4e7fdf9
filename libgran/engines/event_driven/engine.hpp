#pragma once
// Event-driven molecular dynamics of inelastic hard disks (D = 2) and spheres (D = 3), one
// templated code path. Design (see docs/architecture.md):
//  - structure-of-arrays particle state with per-particle clocks (lazy position updates);
//  - where pairs are found, chosen from the scene (choose_neighbour_skin, engine_shells.cpp):
//    - dilute gases: a cell list (cell_list.hpp: cells at least one largest diameter wide) with
//      cell-crossing events; after a crossing only the newly adjacent layer of cells is scanned
//      (the earlier best collision is kept);
//    - dense gases: neighbour shells (neighbour_shells.hpp), a list per particle of the particles
//      it can meet before it leaves its shell, rebuilt at a shell-exit event; the cell grid then
//      holds the shells' centres, and a crossing of a periodic boundary is a wrap event;
//  - one pending event per particle, validated lazily with per-particle collision counters, in an
//    indexed 4-ary heap (scheduler.hpp: O(log N) per event, no allocation per event);
//  - the event loop pops, validates and dispatches; the engine itself holds the physics: free
//    flight, collision, crossing and wall times, and what each event does; the loop and the two
//    events that read the contact law (collisions, wall hits) are templated on the law
//    (law_loop.hpp) and instantiated by the law's registration;
//  - round-off-proof detection: an approaching pair that already overlaps collides now, a receding
//    one is ignored, and no event is ever scheduled before the current time;
//  - the TC model against inelastic collapse (Luding & McNamara, Granular Matter 1, 113 (1998)):
//    a collision within tc of a previous collision of either partner is elastic. Counted.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/collision_record.hpp"
#include "libgran/core/particles.hpp"
#include "libgran/core/species.hpp"
#include "libgran/core/wall_motion.hpp"
#include "libgran/engines/event_driven/cell_list.hpp"
#include "libgran/engines/event_driven/collision_rules.hpp"
#include "libgran/engines/event_driven/event_times.hpp"
#include "libgran/engines/event_driven/neighbour_shells.hpp"
#include "libgran/engines/event_driven/pair_counts.hpp"
#include "libgran/engines/event_driven/scheduler.hpp"
#include "libgran/plugins/law.hpp"
#include "libgran/plugins/wall.hpp"

namespace gran {

struct EngineSettings {
    bool tc_guard = true;                               // TC model on by default
    double tc = 1e-6;                                   // [time]
    std::array<double, 3> gravity{0, 0, 0};             // uniform acceleration [length/time^2]
    CellLayout cell_layout = CellLayout::automatic;     // forced only by benchmarks (gran_bench)
    QueueLayout queue_layout = QueueLayout::automatic;  // forced only by benchmarks and tests
    // Neighbour shells' skin in largest diameters: negative, the engine chooses from the packing
    // fraction (choose_neighbour_skin); 0, cells only; > 0, shells of this skin (benchmarks and
    // tests; refused with gravity).
    double neighbour_skin = -1.0;
};

struct EngineCounters {
    std::uint64_t events = 0;
    std::uint64_t collisions = 0;
    std::uint64_t cell_crossings = 0;
    std::uint64_t wall_hits = 0;
    std::uint64_t stale_events = 0;   // invalidated predictions popped and recomputed
    std::uint64_t tc_collisions = 0;  // collisions made elastic by the TC guard
    std::uint64_t overlap_collisions =
        0;  // approaching pairs found overlapping (round-off) and collided at once
    std::uint64_t full_reschedules = 0;  // all events recomputed (e.g. after thermostat kicks)
    std::uint64_t full_rescans_after_crossing = 0;  // crossings whose kept collision went stale
    std::uint64_t sorts = 0;                        // re-sorts of the particle storage by cell
    std::uint64_t tc_wall_hits = 0;                 // wall hits made elastic by the TC guard
    std::uint64_t wall_lifts = 0;   // hits whose rebound was raised to the resting speed g tc
    std::uint64_t shell_exits = 0;  // neighbour lists rebuilt (neighbour_shells.hpp)
    std::uint64_t wraps = 0;        // crossings of a periodic boundary with neighbour shells
};

// The neighbour shells' skin (in largest diameters) the engine uses for a scene of this dimension,
// packing fraction and size, 0 for cells: measured, docs/performance.md.
double choose_neighbour_skin(int dimension, double packing_fraction, std::size_t particles);

template <int D>
class EventDrivenEngine;

// A hard-sphere law's event loop on this engine, registered by register_law<L> (law_loop.hpp)
// under the law's name; the engine calls it through this pointer once per advance.
template <int D>
struct EventDrivenLawLoops {
    std::string name;
    int (EventDrivenEngine<D>::*advance)(double t_limit, std::uint64_t collision_limit,
                                         const std::atomic<bool>* interrupt,
                                         std::uint64_t event_limit) = nullptr;
};

template <int D>
class EventDrivenEngine {
  public:
    enum class Stop { TimeLimit, CollisionLimit, Interrupted, NoEvents, EventLimit };

    // The contacts' law (a hard-sphere law, or the hard limit of a soft-contact law) selects the
    // event loop. Every wall of a bounded axis starts static, with the contacts of the wall
    // partner `box` (set_wall changes it). Throws std::invalid_argument if the law has no
    // hard-sphere form, or the contacts need angular velocities that `particles` lacks.
    EventDrivenEngine(const Box<D>& box, const SpeciesTable& table, const ContactTable& contacts,
                      Particles<D> particles, EngineSettings settings);

    // Processes events up to time t_limit; stops early once the total collision count reaches
    // collision_limit, once the total event count reaches event_limit (the run's watchdog checks
    // progress between such chunks), or when *interrupt becomes true (checked every 1024 events).
    Stop advance(double t_limit, std::uint64_t collision_limit,
                 const std::atomic<bool>* interrupt = nullptr,
                 std::uint64_t event_limit = UINT64_MAX) {
        return Stop((this->*loop_)(t_limit, collision_limit, interrupt, event_limit));
    }
    // The event loop of law L (law_loop.hpp); returns a Stop.
    template <class L>
    int advance_with(double t_limit, std::uint64_t collision_limit,
                     const std::atomic<bool>* interrupt, std::uint64_t event_limit);

    double now() const { return limit_now_ == kNoLimit ? t_origin_ + now_ : limit_now_; }
    const Particles<D>& particles() const { return p_; }
    const Box<D>& box() const { return box_; }
    // The cells the particles are filed in (for tests: each particle lies in its cell).
    const CellList<D>& cell_list() const { return cells_; }
    double species_mass(std::uint32_t s) const { return mass_[s]; }
    double species_diameter(std::uint32_t s) const { return diameter_[s]; }
    double species_inertia(std::uint32_t s) const {
        return inertia_[s] * mass_[s] * diameter_[s] * diameter_[s] / 4;
    }
    std::size_t species_count() const { return ns_; }
    const EngineCounters& counters() const { return counters_; }
    // Collisions per unordered species pair, index min(a,b) * ns + max(a,b) (ns x ns: with many
    // species made from the pairs that collided at each call, PairCounts).
    const std::vector<std::uint64_t>& pair_collisions() const { return pair_collisions_.dense(); }

    // Brings every particle to the current time (positions exact at now()).
    void synchronize();
    // Velocity access for drivers: call synchronize() first, change velocities, then
    // velocities_changed() to invalidate and recompute every pending event. `next_change`: the
    // absolute time at which the velocities will change again (a thermostat's next kick), when
    // every event is recomputed anyway: collisions later than it are not looked for (the ones
    // before it are found exactly as without it, so the run is the same bit for bit).
    Particles<D>& particles_for_update() { return p_; }
    void velocities_changed(double next_change = kInf);
    // Particles are stored in cell order and re-sorted now and then (memory locality), so the
    // storage index of a particle changes; ids()[k] is the original index (placement order) of the
    // particle stored at k. Collision records carry original ids.
    const std::vector<std::uint32_t>& ids() const { return id_; }
    // Whether the event queue is a calendar of time slices (event_queue.hpp) or one heap.
    bool event_calendar() const { return events_.calendar(); }
    // The neighbour shells' skin in largest diameters, 0 if the engine uses cells.
    double neighbour_skin() const { return shells_on_ ? shells_.skin() / largest_diameter() : 0.0; }

    void set_collision_sink(CollisionSink<D>* sink) { sink_ = sink; }

    // The dynamic state, saved or loaded between events (libgran/core/state_archive.hpp); the
    // walls' settings, the species and the contacts come from the scene.
    void checkpoint(StateArchive& ar);

    // One wall of a bounded axis (side 0: lower, 1: upper): its motion and the contacts of wall
    // partner `partner` (index into the contacts' walls), or `reflection`, a rule that replaces the
    // contact (it must outlive the engine). A moving wall's surface is at base + motion.position(t)
    // with base = motion.reach() for the lower wall and L - motion.reach() for the upper one: its
    // whole excursion lies inside the box.
    void set_wall(int axis, int side, const WallMotion& motion, std::size_t partner,
                  WallReflection<D>* reflection = nullptr);
    // Surface position of a wall at time t (index 2 * axis + side).
    double wall_position(int code, double t) const {
        return walls_[std::size_t(code)].base + walls_[std::size_t(code)].motion.position(t);
    }
    // Momentum given to each wall, sum of m |v_n' - v_n| over its hits (index 2 * axis + side).
    const std::array<double, 2 * D>& wall_impulse() const { return wall_impulse_; }
    const Vec<D>& gravity() const { return g_; }
    // Hits per wall (index 2 * axis + side).
    const std::array<std::uint64_t, 2 * D>& wall_hits() const { return wall_hit_count_; }

  private:
    void move(std::uint32_t i) {
        const double dt = now_ - p_.t[i];
        if (gravity_) {
            // Parabolic free flight (uniform gravity).
            p_.r[i] += dt * (p_.v[i] + (0.5 * dt) * g_);
            p_.v[i] += dt * g_;
        } else {
            p_.r[i] += p_.v[i] * dt;
        }
        p_.t[i] = now_;
    }
    // Prediction: i's next event (i must be at now_), from a scan of its neighbour cells for the
    // earliest collision, then its cell crossings and walls (schedule). In the event loop
    // repredict() also moves i in the queue.
    void predict(std::uint32_t i);
    void repredict(std::uint32_t i) {
        predict(i);
        events_.commit(i);
    }
    void predict_after_crossing(std::uint32_t i, int axis, int dir);
    // predict() for every particle (all at now_), each pair's collision time computed once
    // instead of once from each side; the heap is rebuilt by the caller. Collisions later than
    // `horizon` (relative time) need not be found.
    void predict_all(double horizon = kInf);
    // Earliest collision of i with the candidates of the given cells, if before best.
    void scan_cells(std::uint32_t i, const std::int32_t* cells, int ncells, double& best,
                    std::int32_t& partner);
    // Wraps: the candidates may lie across a periodic boundary (false only when they cannot,
    // CellList::interior: the minimum image is then the plain difference, bit for bit). Index:
    // the candidates' type (32-bit from the cells, 16-bit from the shells' lists).
    template <bool Gravity, bool Wraps, class Index>
    void scan_gathered(std::uint32_t i, const Index* candidates, std::size_t n, double& best,
                       std::int32_t& partner) const;
    // One-cell periodic axes: every image of each candidate (CellList::image_offsets()).
    void scan_gathered_images(std::uint32_t i, std::size_t n, double& best,
                              std::int32_t& partner) const;
    double axis_event(std::uint32_t i, int a, double best, EventKind& kind, int& code) const;
    // The earliest wall contact of i on bounded axis a before `horizon` (if earlier than t_best).
    double wall_event(std::uint32_t i, int a, double horizon, double t_best, EventKind& kind,
                      int& code) const;
    void schedule(std::uint32_t i, double collision, std::int32_t partner);
    // The earliest of a particle's candidate events while schedule() collects them.
    struct Earliest {
        double time;
        EventKind kind;
        std::int32_t code;
        void consider(double t, EventKind k, std::int32_t c) {
            if (t < time) {
                time = t;
                kind = k;
                code = c;
            }
        }
    };
    // Events: what each does to the state, then the re-prediction of the particles involved.
    template <class L>
    void collide(std::uint32_t i, std::uint32_t j);
    void record_before(CollisionRecord<D>& rec, std::uint32_t i, std::uint32_t j, const Vec<D>& n,
                       double alpha, double beta, double contact) const;
    void notify(CollisionRecord<D>& rec, std::uint32_t i, std::uint32_t j, double impulse);
    void copy_velocities(std::uint32_t i, std::uint32_t j, Vec<D>& vi, Vec<D>& vj, AngVec<D>& wi,
                         AngVec<D>& wj) const {
        vi = p_.v[i];
        vj = p_.v[j];
        if (rough_) {
            wi = p_.w[i];
            wj = p_.w[j];
        }
    }
    void cross_cell(std::uint32_t i, int code);
    // With neighbour shells (engine_shells.cpp): the pair search set up from the scene, i's scan
    // of its list, the shell exit, walls and periodic wraps among its next events, and the two
    // events of their own.
    void set_up_pair_search();
    void set_shell_bounds();
    void predict_in_shell(std::uint32_t i);
    void schedule_in_shell(std::uint32_t i, Earliest& next);
    void leave_shell(std::uint32_t i);
    void wrap(std::uint32_t i, int code);
    typename NeighbourShells<D>::Sizes sizes() const { return {p_.species.data(), radius_.data()}; }
    template <class L>
    void hit_wall(std::uint32_t i, int code);
    // After a wall hit's reflection: the resting-contact lift, the wall's impulse and hit count,
    // and the next event of i.
    void finish_wall_hit(std::uint32_t i, int code, double u, double t_abs, double before);
    double largest_diameter() const;

    Box<D> box_;
    Particles<D> p_;
    EngineSettings settings_;
    EngineCounters counters_;
    double now_ = 0;       // relative to t_origin_
    double t_origin_ = 0;  // absolute time of the internal origin (moved by rebase_time())
    static constexpr double kNoLimit = -1.0;
    double limit_now_ = kNoLimit;  // after a time-limit stop: the limit, reported exactly
    void rebase_time();

    // species tables, flattened
    std::size_t ns_ = 0;
    std::vector<double> mass_, diameter_, inertia_;
    // Half diameters: the contact distance of a pair is radius_[a] + radius_[b], bit for bit
    // 0.5 (d_a + d_b) (halving is exact), with no ns x ns table.
    std::vector<double> radius_;
    ContactTable contacts_;  // the law's parameters of every pair and wall contact
    int (EventDrivenEngine::*loop_)(double, std::uint64_t, const std::atomic<bool>*,
                                    std::uint64_t) = nullptr;
    bool rough_ = false;
    Vec<D> g_ = Vec<D>::Zero();
    bool gravity_ = false;

    // per particle
    std::vector<std::uint32_t> count_;  // collision counter (velocity changes)
    std::vector<double> last_collision_;
    Scheduler events_;
    CellList<D> cells_;
    bool shells_on_ = false;
    NeighbourShells<D> shells_;
    // Where a shell's centre must lie, per axis, for its scan to skip the minimum image
    // (set_shell_bounds; derived from the box, the radii and the skin, so not archived).
    Vec<D> shell_lo_ = Vec<D>::Zero(), shell_hi_ = Vec<D>::Zero();

    PairCounts pair_collisions_;
    CollisionSink<D>* sink_ = nullptr;

    struct WallSlot {
        WallReflection<D>* reflection = nullptr;  // null: a contact with the law
        std::size_t partner = 0;                  // wall partner in contacts_
        WallMotion motion;
        double base = 0;     // surface position at zero displacement
        int layers = 1;      // cell layers (from this wall) whose particles can reach it
        bool simple = true;  // static and no gravity along the axis: the linear fast path
    };
    std::array<WallSlot, 2 * D> walls_{};
    std::array<std::uint64_t, 2 * D> wall_hit_count_{};
    std::array<double, 2 * D> wall_impulse_{};

    void sort_by_cell();
    std::vector<std::uint32_t> id_;
    std::uint64_t events_since_sort_ = 0;
    std::uint64_t sort_every_ = 0;  // events between re-sorts (a few sweeps of N)
};

extern template class EventDrivenEngine<2>;
extern template class EventDrivenEngine<3>;

}  // namespace gran
