#pragma once
// A minimal, single-purpose event-driven code for exactly one case: equal elastic smooth hard
// disks (D = 2) or spheres (D = 3) of diameter 1 and mass 1 in a periodic cubic box. It is the
// yardstick of `gran_bench_features`: gran's bare gas, run through the full scene/run path, must
// come within 10% of it (issue 6). It shares no code with gran's engine.
//
// Written for speed with no generality, using the standard techniques of fast EDMD codes:
//  - per-particle clocks (positions updated lazily), one pending event per particle (the earlier
//    of its first collision and its next cell crossing), validated on pop by the partner's
//    collision counter (Lubachevsky 1991; Isobe 1999);
//  - cell list (cells at least one diameter wide, doubly linked lists), 3^D neighbour cells with
//    the periodic image shift folded into the cell offset;
//  - after a cell crossing only the newly adjacent layer of 3^(D-1) cells is scanned and the
//    earlier best collision is kept if its partner has not collided since;
//  - pairs are rejected before the square root when their collision cannot beat the best so far;
//  - an indexed 4-ary min-heap of (time, particle) entries;
//  - particle storage re-sorted by cell every 16 N events (neighbours stay close in memory).
#include <cstdint>
#include <vector>

namespace gran::bench {

// Positions r and velocities v are n * D values each (positions in [0, box)); diameter 1, mass 1.
template <int D>
class MinimalEventDriven {
  public:
    MinimalEventDriven(double box, std::vector<double> r, std::vector<double> v);
    // Processes events until the total collision count reaches `collision_target`.
    void run_until(std::uint64_t collision_target);
    std::uint64_t events() const { return events_; }
    std::uint64_t collisions() const { return collisions_; }
    std::uint64_t overlaps() const { return overlaps_; }
    double now() const { return now_; }
    // Positions and velocities at now().
    void state(std::vector<double>& r, std::vector<double>& v);

  private:
    struct P {
        double r[D];
        double v[D];
        double t;
    };
    void predict(std::uint32_t i, int layer_axis, int layer_dir);
    void collide(std::uint32_t i, std::uint32_t j);
    void cross(std::uint32_t i);
    void insert(std::uint32_t i, std::int32_t c);
    void remove(std::uint32_t i);
    void heap_update(std::uint32_t i, double t);
    void sift_down(std::size_t k);
    void sort_by_cell();

    double L_;
    int nc_;    // cells per axis
    double w_;  // cell width
    std::vector<P> p_;
    std::vector<std::int32_t> cell_;  // cell of each particle
    std::vector<std::int32_t> cc_;    // cell coordinates, D per particle
    std::vector<std::int32_t> head_, next_, prev_;
    std::vector<std::uint32_t> count_;  // collisions of each particle
    // Pending event: time, kind (0 collision, 1 crossing), partner and its counter, crossing axis.
    std::vector<double> ev_t_;
    std::vector<std::int32_t> ev_partner_;
    std::vector<std::uint32_t> ev_count_;
    std::vector<std::int8_t> ev_axis_;  // -1: collision; else the crossing's axis
    // Best collision found by the last full scan (kept across crossings).
    std::vector<double> best_t_;
    std::vector<std::int32_t> best_j_;
    std::vector<std::uint32_t> best_count_;
    struct Entry {
        double t;
        std::uint32_t id;
    };
    std::vector<Entry> heap_;
    std::vector<std::uint32_t> pos_;
    double now_ = 0;
    std::uint64_t events_ = 0, collisions_ = 0, overlaps_ = 0;
    std::uint64_t next_sort_ = 0;  // events at which the storage is next re-sorted by cell
};

extern template class MinimalEventDriven<2>;
extern template class MinimalEventDriven<3>;

}  // namespace gran::bench
