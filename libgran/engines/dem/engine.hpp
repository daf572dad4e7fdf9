#pragma once
// Time-stepped soft-sphere discrete element method (DEM) for disks (D = 2) and spheres (D = 3),
// the method of Bhateja, Sharma & Singh, Phys. Fluids 28, 043301 (2016), Appendix (issue #5).
//
// Equations of motion (A1), (A2): m_i dv_i/dt = sum_j f_ij + m_i g, I_i dw_i/dt = sum_j tau_ij,
// I_i = q m_i sigma_i^2 / 4, with the contact forces of the scene's soft-contact law (one law type
// for every contact, libgran/plugins/law.hpp; its force loop, templated on the law, is in
// libgran/engines/dem/law_loop.hpp and instantiated by the law's registration). Lever arms are the
// radii (Eq. A3: l = R).
//
// Integrator: velocity Verlet for translation and rotation, one step of length dt:
//   1. half kick    v <- v + (dt/2) a(t),  w <- w + (dt/2) alpha(t)          (v(t + dt/2))
//      predictor    v* = v + (dt/2) a(t),  w* likewise                         (~ v(t + dt))
//   2. drift        r <- r + dt v                                             (r(t + dt))
//      wrap periodic axes; rebuild the neighbour list if a particle moved more than skin / 2
//   3. forces       F(t + dt): positions r(t + dt); dampers (normal and tangential) evaluated at
//                   the predicted velocities v*, w* (first-order unbiased restitution and
//                   duration, contact_laws.hpp notes); tangential springs advanced by g dt with g
//                   at the half-step velocities that moved the positions (only the in-contact part
//                   delta / |g_n| of the step when the contact forms)
//   4. half kick    v <- v + (dt/2) a(t + dt), w likewise.
// Symplectic (hence bounded energy error) for conservative forces; gravity is integrated exactly.
//
// Walls: on bounded axes, a lower and an upper plane, each static or moving along its normal
// with a WallMotion (fixed, sinusoid, parabolic_piston, sawtooth_ramp). Convention of the
// event-driven engine: the lower surface is at reach + position(t), the upper at L - reach +
// position(t), so each excursion stays inside [0, L]. A wall is a contact partner of infinite mass
// (m_eff = m_i) with its own contact parameters (a wall partner of the scene's interactions); the
// relative velocity uses the wall velocity along the normal (tangential wall velocity 0) and no
// wall rotation (lever arm 0).
#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/box.hpp"
#include "libgran/core/particles.hpp"
#include "libgran/core/species.hpp"
#include "libgran/core/stage_clock.hpp"
#include "libgran/core/wall_motion.hpp"
#include "libgran/engines/dem/contact_force.hpp"
#include "libgran/engines/dem/neighbour_list.hpp"
#include "libgran/plugins/law.hpp"

namespace gran {

struct DemSettings {
    double dt = 0;                           // time step; 0: dt_fraction x shortest t_c
    double dt_fraction = 1.0 / 50;           // of the shortest contact duration, when dt = 0
    std::array<double, 3> gravity{0, 0, 0};  // uniform acceleration g (the body force b of A1)
    double skin = 0.1;                       // Verlet skin in units of the largest diameter
    int threads = 1;  // threads of a step; the results are the same bits for any number
    // Fewer threads for fewer particles: each thread gets at least this many (a step of a small
    // system is shorter than the threads' hand-overs, and a thread that waits for a busy core
    // stalls every step).
    std::size_t min_particles_per_thread = 4096;
    // Spatial sort: at the first list build, then at the first build sort_interval steps or more
    // after the last sort, the particles are renumbered in the order of the list's cells, so
    // that grains near each other in space are near each other in memory (a fluidised bed mixes
    // them, and a step whose arrays outgrow the cache then waits on memory). Only with at least
    // min_particles_to_sort particles; sort_interval 0: never. The order of the force sums then
    // changes, so the bits of a run depend on these two settings (never on the thread count).
    // (docs/performance.md, "The spatial sort": at N = 10^4 it gains 2-5%, at 10^5 24-70%.)
    std::uint64_t sort_interval = 1000;
    std::size_t min_particles_to_sort = 8192;
};

struct DemCounters {
    std::uint64_t steps = 0;
    std::uint64_t contacts = 0;              // particle-particle contacts formed
    std::uint64_t wall_contacts = 0;         // particle-wall contacts formed
    std::uint64_t active_contacts = 0;       // particle-particle contacts at the last step
    std::uint64_t active_contact_steps = 0;  // their sum over the steps (a mean contact number)
    std::uint64_t rebuilds = 0;              // neighbour-list builds
    std::uint64_t sorts = 0;                 // spatial sorts (DemSettings::sort_interval)
    double max_overlap = 0;  // largest delta / sigma_ij seen (a wall: delta / sigma_i)
};

// Wall-clock seconds of the stages of the steps since DemEngine::time_stages(true). A threaded
// stage includes its threads' waits for each other.
struct DemStageTimes {
    double kicks_and_drift = 0;  // the half kicks, the drift and the displacement tally
    double neighbour_list = 0;   // the rebuild test, the list builds and the spatial sorts
    double pair_contacts = 0;    // grain-grain contact forces (with their threaded sums)
    double wall_contacts = 0;    // grain-wall contact forces (with finding the wall candidates)
    double total() const {
        return kicks_and_drift + neighbour_list + pair_contacts + wall_contacts;
    }
};

// How evenly a threaded step's work is cut (DemEngine::time_stages), summed over the list builds
// of the timed steps: the halo grains of the pair shares (threaded_sums.cpp) and the list
// search's imbalance, the largest thread's work over the mean (DemNeighbourList::search_work).
struct DemThreadShares {
    std::uint64_t splits = 0;     // pair-row splits (one per build on more than one thread)
    double halo_grains = 0;       // sum over the splits of the halo grains
    double grains = 0;            // sum over the splits of the grains
    std::uint64_t searches = 0;   // list builds searched on more than one thread
    double search_imbalance = 0;  // sum over those builds of max / mean work per thread
    // The search's wall-clock seconds (DemNeighbourList::search_seconds), on any number of
    // threads: summed over the timed builds, the slowest thread's and all threads' together.
    std::uint64_t timed_searches = 0;
    double search_slowest = 0, search_all = 0;
};

struct DemEnergies {
    double translational = 0;  // sum m v^2 / 2
    double rotational = 0;     // sum I w^2 / 2
    double elastic = 0;        // normal and tangential springs of the current contacts and walls
    double gravitational = 0;  // -sum m g.r (meaningless along a periodic axis)
    double total() const { return translational + rotational + elastic + gravitational; }
};

template <int D>
class DemEngine;

// A soft-contact law's loops on this engine, registered by register_law<L> (law_loop.hpp) under
// the law's name: the engine calls them through these pointers, once per step.
template <int D>
struct DemLawLoops {
    std::string name;
    void (DemEngine<D>::*accumulate_forces)(double dt_advance) = nullptr;
    double (DemEngine<D>::*elastic_energy)() const = nullptr;
    std::vector<double> (DemEngine<D>::*contact_virial)() const = nullptr;
};

// The shortest contact duration t_c of the soft-contact law over the grain-grain contacts, and the
// grain-wall ones when `walls`: what the time step must resolve. Throws std::invalid_argument when
// the law has no soft-contact form.
double shortest_contact_duration(const ContactTable& contacts, bool walls);

// The time step of a scene: `dt` if > 0, else dt_fraction x the shortest contact duration (over
// the grain-grain contacts, and the grain-wall ones when `walls`). Throws std::invalid_argument
// when it exceeds t_c / 5 or is not finite.
double dem_time_step(const ContactTable& contacts, bool walls, double dt, double dt_fraction);

template <int D>
class DemEngine {
  public:
    enum class Stop { TimeLimit, Interrupted };

    // Every bounded axis starts with static walls at 0 and L with the contacts of the wall
    // partner `box` (set_wall, remove_wall change them). Allocates angular velocities if some
    // contact has friction and `particles` has none. Throws std::invalid_argument if the law has
    // no soft-contact form, if dt > t_c / 5 (dem_time_step), if a cutoff sigma + skin reaches half
    // a periodic length, or for inconsistent inputs.
    DemEngine(const Box<D>& box, const SpeciesTable& species, const ContactTable& contacts,
              Particles<D> particles, DemSettings settings);

    // Whole steps until now() >= t_limit: the last step is not shortened, so now() ends in
    // [t_limit, t_limit + dt). Checks *interrupt every 1024 steps.
    Stop advance(double t_limit, const std::atomic<bool>* interrupt = nullptr);
    // One step; steps(k): k steps, the same bits as k calls of step(), with each step's closing
    // half kick done in the same pass as the next step's opening half kick and drift (one sweep
    // over the particles fewer per step: the integrator is most of a dilute bed's memory traffic).
    void step();
    void steps(std::uint64_t k);

    double now() const { return t_start_ + double(steps_) * dt_; }
    double dt() const { return dt_; }
    int threads() const { return threads_; }  // the threads a step uses (DemSettings::threads)
    const Particles<D>& particles() const { return p_; }
    // The index in the constructor's particles of the particle stored at k (the spatial sort
    // renumbers them; DemSettings::sort_interval).
    const std::vector<std::uint32_t>& ids() const { return id_; }
    const Box<D>& box() const { return box_; }
    const Vec<D>& gravity() const { return g_; }
    const DemCounters& counters() const { return counters_; }
    // Times the stages of the following steps (a clock read per stage and step), from zero;
    // false stops timing and keeps the times. No bit of the run changes.
    void time_stages(bool on) {
        stage_clock_.enable(on);
        if (on) {
            stage_times_ = DemStageTimes{};
            thread_shares_ = DemThreadShares{};
        }
    }
    const DemStageTimes& stage_times() const { return stage_times_; }
    const DemThreadShares& thread_shares() const { return thread_shares_; }
    const ContactTable& contacts() const { return contacts_; }
    std::size_t species_count() const { return mass_.size(); }
    double species_mass(std::uint32_t s) const { return mass_[s]; }
    double species_diameter(std::uint32_t s) const { return 2 * radius_[s]; }
    double species_inertia(std::uint32_t s) const { return inertia_[s]; }
    // Contact forces (and torques) of the last evaluation, at now(); gravity not included.
    const std::vector<Vec<D>>& forces() const { return f_; }
    const std::vector<AngVec<D>>& torques() const { return tau_; }
    DemEnergies energies() const;
    // The pair virial of the grain-grain contacts at now(), per species s and axis a at
    // [s * D + a]: sum over the contacts of (r_i - r_j)_a F_a (F the force on i, the contact
    // force of the last evaluation), half to the species of each partner. Walls excluded.
    std::vector<double> contact_virial() const { return (this->*loops_.contact_virial)(); }
    const DemNeighbourList<D>& neighbour_list() const { return list_; }
    // The dynamic state, saved or loaded between steps (libgran/core/state_archive.hpp): particles,
    // the forces of the last evaluation (the next half kick uses them), the predicted velocities,
    // the displacements since the last list build, contact and wall-spring history, counters.
    void checkpoint(StateArchive& ar);
    // Wall partner (index into contacts().walls) of a wall (index 2 * axis + side).
    std::size_t wall_partner(int code) const { return walls_[std::size_t(code)].partner; }

    // Walls (side 0: lower, 1: upper) of a bounded axis, with the contacts of wall partner
    // `partner` (index into contacts().walls). Sawtooth motion is refused (it has no position).
    // Throws std::invalid_argument if one of its contacts is shorter than 5 dt. Forces are
    // re-evaluated at the current time.
    void set_wall(int axis, int side, const WallMotion& motion, std::size_t partner);
    // The wall's surface also moves in its own plane, along `axis` (another axis than its
    // normal), with the velocity of `motion` (a box vibrated as a whole: its floor and lid slide
    // under the grains). Only the tangential force of a contact sees it.
    void set_wall_slide(int wall_axis, int side, int axis, const WallMotion& motion);
    void remove_wall(int axis, int side);
    bool wall_is_set(int axis, int side) const { return walls_[code(axis, side)].present; }
    // Surface position of a wall at time t (index 2 * axis + side).
    double wall_position(int code, double t) const {
        const Wall& w = walls_[std::size_t(code)];
        return w.base + w.motion.position(t);
    }
    // Normal momentum given by each wall to the particles, sum over steps of F_n dt (= sum of
    // m |v_n' - v_n| of the event-driven engine for binary collisions).
    const std::array<double, 2 * D>& wall_impulse() const { return wall_impulse_; }
    // Contacts formed per wall (index 2 * axis + side).
    const std::array<std::uint64_t, 2 * D>& wall_hits() const { return wall_hits_; }

    // The force loop and contact energy of law L (law_loop.hpp), reached through DemLawLoops.
    template <class L>
    void accumulate_forces_with(double dt_advance);
    template <class L>
    double elastic_energy_with() const;
    template <class L>
    std::vector<double> contact_virial_with() const;

  private:
    struct Wall {
        bool present = false;
        WallMotion motion;
        double base = 0;
        std::size_t partner = 0;  // wall partner in contacts_
        int slide_axis = -1;      // in-plane motion along this axis (-1: none)
        WallMotion slide;
    };
    static std::size_t code(int axis, int side) { return std::size_t(2 * axis + side); }

    void set_species(const SpeciesTable& species);
    void configure_neighbours();
    std::vector<double> neighbour_cutoffs() const;  // sigma_ij + skin, ns x ns
    void allocate_state();
    void place_walls();
    void rebuild();
    // Whether this run sorts its grains at all (DemSettings::sort_interval,
    // min_particles_to_sort), and whether a sort is due at this build.
    bool sorts() const {
        return settings_.sort_interval > 0 && p_.size() >= settings_.min_particles_to_sort;
    }
    bool sort_due() const;
    void sort_particles();  // renumbers every per-particle array in the list's cell order
    void find_wall_candidates();
    // Forces at the present state with the dampers at the current velocities (construction,
    // wall changes); springs and wall impulses do not advance.
    void reevaluate_forces();
    void compute_forces(double dt_advance);  // zeroes, then accumulates
    void accumulate_forces(double dt_advance) { (this->*loops_.accumulate_forces)(dt_advance); }
    template <class L, bool Rot>
    void pair_forces(double dt_advance);
    template <class L, bool Rot>
    void wall_forces(double dt_advance);
    template <class L, bool Rot>
    void wall_range(double dt_advance, std::size_t c, std::size_t k0, std::size_t k1,
                    double& impulse, std::uint64_t& formed, double& worst,
                    std::vector<double>* touched);
    // Contacts counted by one thread's share of the entries.
    struct PairTally {
        std::uint64_t formed = 0, active = 0;
        double worst = 0;  // largest delta / sigma_ij
        void add(const PairTally& o) {
            formed += o.formed;
            active += o.active;
            worst = o.worst > worst ? o.worst : worst;
        }
    };
    template <class L, bool Rot, bool Halo>
    void pair_range(double dt_advance, std::size_t k0, std::size_t k1, PairTally& tally);
    // Threaded pair forces (threaded_sums.cpp): the list's rows split between the threads and
    // the halo grains found, once per list; each halo grain's sum of its per-entry slots in the
    // serial order, by thread `part` of `parts`.
    void split_pair_rows();
    void sum_halo_pair_forces(std::size_t part, std::size_t parts);
    void tally_search_shares();
    // Step stages over particles [i0, i1): the first half kick and the drift (returns the
    // largest squared displacement since the last build), preceded, with ClosingKick, by the
    // previous step's second half kick; and that second half kick alone.
    template <bool ClosingKick>
    double kick_drift(std::size_t i0, std::size_t i1);
    void kick(std::size_t i0, std::size_t i1);
    // A step's opening pass (kick_drift), the list check and the forces: all of a step but its
    // closing half kick.
    template <bool ClosingKick>
    void open_step();

    Box<D> box_;
    ContactTable contacts_;
    DemLawLoops<D> loops_;
    bool history_ = false;       // the law keeps a tangential spring per contact
    std::vector<double> sigma_;  // contact distance R_i + R_j per species pair (ns x ns)
    Particles<D> p_;
    DemSettings settings_;
    DemCounters counters_;
    StageClock stage_clock_;
    DemStageTimes stage_times_;
    DemThreadShares thread_shares_;  // tallied while the stages are timed
    Vec<D> g_ = Vec<D>::Zero();
    double dt_ = 0;
    double t_start_ = 0;
    std::uint64_t steps_ = 0;  // since t_start_ (now() = t_start_ + steps_ dt, no accumulation)
    double skin_ = 0;
    double dmax_ = 0;  // largest diameter

    // species, flattened
    std::vector<double> mass_, radius_, inertia_, inv_mass_, inv_inertia_;

    // per particle
    std::vector<std::uint32_t> id_;         // index in the constructor's particles
    std::vector<std::uint32_t> new_index_;  // sort_particles(): old index -> new
    std::uint64_t steps_at_sort_ = 0;       // steps_ at the last sort
    std::vector<Vec<D>> f_, v_pred_, disp_;
    std::vector<AngVec<D>> tau_, w_pred_;
    std::vector<std::uint8_t> wall_touching_;  // n x 2D
    std::vector<Vec<D>> wall_spring_;          // n x 2D, history laws only
    // Per wall, the particles that can touch it before the next list build, in increasing index
    // (find_wall_candidates): the wall pass visits only these. Stale after a build, a wall
    // change or a restore, and found again by the next wall pass.
    std::array<std::vector<std::uint32_t>, 2 * D> wall_candidates_;
    bool wall_candidates_stale_ = true;

    DemNeighbourList<D> list_;
    // Threaded steps (threads_ > 1): thread t adds the contacts of rows pair_rows_[t] ..
    // pair_rows_[t + 1] - 1 of the list. Halo grains (halo_ 1, listed in halo_list_) are partners
    // of an earlier thread's rows: their contacts go to the per-entry slots, summed after the
    // rows; the entries of halo grain halo_list_[h] as partner are halo_entries_[halo_start_[h]]
    // .. halo_entries_[halo_start_[h + 1] - 1], in increasing k. Derived from the list, found
    // again after each build or restore.
    static constexpr int kMaxThreads = 256;
    int threads_ = 1;
    std::vector<std::size_t> pair_rows_;
    // Whether pair_rows_ cut all the grains into one range per thread: the stages that follow
    // the pair loop's rows (drift, walls) take them then, and equal chunks before the first
    // split or after a change of the thread count.
    bool rows_split() const {
        return threads_ > 1 && pair_rows_.size() == std::size_t(threads_) + 1 &&
               pair_rows_.back() == p_.size();
    }
    std::vector<std::uint8_t> halo_;
    std::vector<std::uint32_t> halo_list_;
    std::vector<std::size_t>
        halo_shares_;  // thread t sums halo_list_[halo_shares_[t]] .. (its rows)
    std::vector<std::uint32_t> halo_start_, halo_entries_;
    std::vector<std::uint32_t> halo_slot_, halo_fill_;  // split_pair_rows' scratch
    bool pair_split_stale_ = true;
    std::vector<Vec<D>> pair_force_;
    std::vector<AngVec<D>> pair_torque_i_, pair_torque_j_;
    std::vector<PairTally> tallies_;
    std::vector<std::vector<double>> wall_touched_;  // per thread: its wall contacts' normal forces
    std::vector<std::size_t> wall_shares_;  // a wall's candidates cut at pair_rows_ (wall_forces)
    std::array<Wall, 2 * D> walls_{};
    std::array<double, 2 * D> wall_impulse_{};
    std::array<std::uint64_t, 2 * D> wall_hits_{};
};

extern template class DemEngine<2>;
extern template class DemEngine<3>;

}  // namespace gran
