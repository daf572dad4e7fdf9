#pragma once
// The event queue of the event-driven engine: one entry per particle, the time of its single
// pending event; top() is the earliest, update() moves an entry. Two layouts, chosen at reset():
//
//  - A heap: every entry in an indexed 4-ary min-heap. The heap holds (time, id) pairs so that
//    sifting reads contiguous memory, and the smallest of four children is chosen without
//    branches (measured: 24% fewer cycles than a binary heap for dilute disks, where most events
//    are cell crossings). The four children of a node (4 x 16 bytes) fill exactly one cache line:
//    the storage is line-aligned and node k sits at storage index k + 3, so the children
//    4k+1..4k+4 start on a line boundary.
//
//  - A calendar (large N): time is cut into slices of a few events each. Only the entries of the
//    current slice are in the heap, which stays small and in cache; each later slice of the cycle
//    is a doubly linked list of its entries, and entries beyond the cycle sit in one more list.
//    When the heap empties, the next slice's list is moved into it; at the end of a cycle every
//    entry is redistributed and the slice width chosen again. At N = 10^6 a sift through the
//    heap's lower levels is a chain of dependent misses (one line per level, about 5 of them);
//    a calendar update is one unlink and one push, a few independent misses (the scheme of
//    Paul, J. Comput. Phys. 221, 615 (2007), here with one entry per particle).
//
// Both give the earliest entry first. Equal times pop in an order set by the layout, so the layout
// is part of the state (checkpoint()).
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "libgran/core/cache_line.hpp"
#include "libgran/core/state_archive.hpp"

namespace gran {

// The engine's choice (a calendar from EventQueue::kCalendarFromEntries entries on), or one
// layout forced (benchmarks and tests).
enum class QueueLayout { automatic, heap, calendar };

class EventQueue {
  public:
    // With the next slice asked for ahead, the calendar was 1.00-1.05x the heap at 2000-5000
    // particles and 1.05-1.25x at 10^4 (docs/performance.md, "The calendar from 4096 particles
    // on"). Below the threshold the heap keeps the order of equal times that the regression
    // scenes (at most a few hundred particles) were made with.
    static constexpr std::size_t kCalendarFromEntries = 4096;
    static bool calendar_for(QueueLayout layout, std::size_t n) {
        return layout == QueueLayout::automatic ? n >= kCalendarFromEntries
                                                : layout == QueueLayout::calendar;
    }
    // Calendar slices hold about this many entries each (the heap of the current slice); the
    // cycle spans this many median event delays. The slice size was measured at 10^6 particles
    // (docs/performance.md, "The calendar queue from 10^5 particles on"); the cycle length was not
    // varied.
    static inline double slice_entries = 4.0;
    static inline double cycle_medians = 8.0;

    // n entries, all at "never"; `calendar` chooses the layout (above).
    void reset(std::size_t n, bool calendar = false) {
        n_ = n;
        calendar_ = calendar;
        ahead_ = -1;
        pos_.resize(n);
        // Freed, not cleared: a calendar turned into a heap (Scheduler::rebuild_as_heap, at a
        // thermostat's first kick) keeps no links it will not use (16 B per particle).
        nodes_ = {};
        head_ = {};
        if (!calendar_) {
            active_ = false;
            storage_.assign(n + kArity, Entry{kNever, 0, 0});  // top() reads node 0 if n = 0
            hn_ = n;
            for (std::size_t k = 0; k < n; ++k) {
                h()[k] = {kNever, static_cast<std::uint32_t>(k), 0};
                pos_[k] = static_cast<std::uint32_t>(k);
            }
            return;
        }
        // Every entry in the list beyond the cycle and an empty heap (its top reads "never"):
        // the heap's full storage is never allocated. Until the first rebuild() the slices have
        // width infinity, so an update puts a finite time in the heap.
        std::size_t slices = 16;
        while (double(slices) * slice_entries < 0.5 * cycle_medians * double(n)) slices *= 2;
        nb_ = std::int64_t(slices);
        storage_ = decltype(storage_)(kPad + 64, Entry{kNever, 0, 0});
        hn_ = 0;
        active_ = true;
        cur_ = 0;
        t0_ = 0;
        inv_width_ = 0;
        nodes_.assign(n, Node{});
        head_.assign(slices + 1, -1);
        for (std::size_t k = n; k-- > 0;) link(std::uint32_t(k), kNever, nb_);
    }
    // Sets all keys at once, then orders them in O(N).
    template <class TimeOf>
    void rebuild(TimeOf time_of) {
        if (!calendar_) {
            for (std::size_t k = 0; k < n_; ++k) h()[k].time = time_of(h()[k].id);
            heapify();
            return;
        }
        for (std::size_t id = 0; id < n_; ++id) nodes_[id].time = time_of(std::uint32_t(id));
        distribute();
    }
    std::uint32_t top() const { return h()[0].id; }
    double top_time() const { return h()[0].time; }
    double time_of(std::uint32_t id) const {
        return pos_[id] == kListed ? nodes_[id].time : h()[pos_[id]].time;
    }
    void update(std::uint32_t id, double time) {
        if (!active_) {
            update_in_heap(pos_[id], time);
            return;
        }
        const std::int64_t s = slice(time);
        const std::uint32_t k = pos_[id];
        if (k != kListed) {
            if (s <= cur_) {
                update_in_heap(k, time);
                return;
            }
            erase_from_heap(k);
        } else {
            unlink(id);
        }
        if (s <= cur_) {
            insert_in_heap(id, time);
        } else {
            link(id, time, s);
        }
        if (hn_ == 0) next_slice();
        look_ahead();
    }
    std::size_t size() const { return n_; }
    // Entries in the heap now (all of them without a calendar).
    std::size_t heap_size() const { return hn_; }
    bool calendar() const { return calendar_; }

    // The layout as it is: equal times pop in layout order, so the layout is part of the state.
    void checkpoint(StateArchive& ar) {
        ar.io(storage_);
        ar.io(pos_);
        ar.io(hn_);
        ar.io(calendar_);
        ar.io(active_);
        ar.io(nodes_);
        ar.io(head_);
        ar.io(nb_);
        ar.io(cur_);
        ar.io(t0_);
        ar.io(inv_width_);
        if (ar.loading()) {
            n_ = pos_.size();
            ahead_ = -1;  // a hint, not state
        }
    }

  private:
    static constexpr double kNever = 1e300;
    static constexpr std::uint32_t kListed = 0xffffffffu;  // pos_ of an entry in a slice list
    struct Entry {
        double time;
        std::uint32_t id;
        std::uint32_t unused = 0;  // named, so a checkpoint's bytes are all defined
    };
    // An entry in a slice list: its time and links; prev < 0 marks the first of list -prev - 1.
    struct Node {
        double time = kNever;
        std::int32_t next = -1;
        std::int32_t prev = -1;
    };

    Entry* h() { return storage_.data() + kPad; }
    const Entry* h() const { return storage_.data() + kPad; }
    void place(std::size_t k, const Entry& e) {
        h()[k] = e;
        pos_[e.id] = static_cast<std::uint32_t>(k);
    }
    static constexpr std::size_t kArity = 4;

    // --- the heap
    void heapify() {
        for (std::size_t k = hn_ / kArity + 1; k-- > 0;) sift_down(k);
    }
    void update_in_heap(std::size_t k, double time) {
        const double old = h()[k].time;
        h()[k].time = time;
        if (time < old) {
            sift_up(k);
        } else {
            sift_down(k);
        }
    }
    void insert_in_heap(std::uint32_t id, double time) {
        // A calendar's heap holds one slice: its storage grows on demand (the spare slot kept).
        if (kPad + hn_ + 1 >= storage_.size()) storage_.resize(2 * storage_.size());
        place(hn_, Entry{time, id, 0});
        sift_up(hn_++);
    }
    void erase_from_heap(std::size_t k) {
        --hn_;
        if (k == hn_) return;
        const Entry last = h()[hn_];
        const double old = h()[k].time;
        place(k, last);
        if (last.time < old) {
            sift_up(k);
        } else {
            sift_down(k);
        }
    }
    void sift_up(std::size_t k) {
        const Entry e = h()[k];
        while (k > 0) {
            const std::size_t parent = (k - 1) / kArity;
            if (!(e.time < h()[parent].time)) break;
            place(k, h()[parent]);
            k = parent;
        }
        place(k, e);
    }
    void sift_down(std::size_t k) {
        const std::size_t n = hn_;
        const Entry e = h()[k];
        while (true) {
            const std::size_t first = kArity * k + 1;
            if (first >= n) break;
            std::size_t child = first;
            double tc = h()[first].time;
            const std::size_t last = std::min(first + kArity, n);
            for (std::size_t c = first + 1; c < last; ++c) {
                const double t = h()[c].time;
                child = t < tc ? c : child;
                tc = t < tc ? t : tc;
            }
            if (!(tc < e.time)) break;
            place(k, h()[child]);
            k = child;
        }
        place(k, e);
    }

    // --- the calendar
    // The slice of a time: 0 is the slice of the earliest entry at the last redistribution;
    // "never" and anything beyond the cycle map past the last slice.
    std::int64_t slice(double time) const {
        const double x = (time - t0_) * inv_width_;
        return x < 4e18 ? std::int64_t(x) : std::int64_t(4e18);
    }
    void link(std::uint32_t id, double time, std::int64_t s) {
        const std::int64_t list = std::min(s, nb_);  // nb_: the list beyond the cycle
        Node& e = nodes_[id];
        e.time = time;
        e.next = head_[std::size_t(list)];
        e.prev = -std::int32_t(list) - 1;
        if (e.next >= 0) nodes_[std::size_t(e.next)].prev = std::int32_t(id);
        head_[std::size_t(list)] = std::int32_t(id);
        pos_[id] = kListed;
    }
    void unlink(std::uint32_t id) {
        const Node& e = nodes_[id];
        if (e.prev >= 0) {
            nodes_[std::size_t(e.prev)].next = e.next;
        } else {
            head_[std::size_t(-e.prev - 1)] = e.next;
        }
        if (e.next >= 0) nodes_[std::size_t(e.next)].prev = e.prev;
    }
    // The heap is empty: the next slice with entries becomes the heap; past the cycle's last
    // slice, everything is redistributed.
    void next_slice() {
        while (hn_ == 0) {
            if (++cur_ >= nb_) {
                distribute();  // the heap is empty: every entry is in a list, its time in its node
                return;
            }
            std::int32_t k = head_[std::size_t(cur_)];
            head_[std::size_t(cur_)] = -1;
            while (k >= 0) {
                const std::int32_t next = nodes_[std::size_t(k)].next;
                insert_in_heap(std::uint32_t(k), nodes_[std::size_t(k)].time);
                k = next;
            }
        }
        ahead_ = cur_ + 1 < nb_ ? head_[std::size_t(cur_ + 1)] : -1;
        if (ahead_ >= 0) __builtin_prefetch(&nodes_[std::size_t(ahead_)]);
    }
    // The walk of the next slice's list is a chain of misses, one node after the other. While
    // the current slice is in the heap, each update asks for one more node of that list (its
    // predecessor arrived meanwhile), so the walk in next_slice() finds them in cache. Only a
    // hint: an entry moved away meanwhile sends the cursor down another list, which ends too.
    void look_ahead() {
        if (ahead_ < 0) return;
        ahead_ = nodes_[std::size_t(ahead_)].next;
        if (ahead_ >= 0) __builtin_prefetch(&nodes_[std::size_t(ahead_)]);
    }
    // Every entry (times in nodes_) placed anew: slice 0 starts at the earliest time, and the
    // width gives slice_entries entries per slice at the density of the first half of the
    // entries (the median delay, from a fixed sample of at most 4096 entries). Without a positive
    // median (no finite times, or half of them tied with the earliest) the epoch is a plain heap.
    void distribute();

    static constexpr std::size_t kPad = kArity - 1;
    std::vector<Entry, CacheLineAllocator<Entry>>
        storage_;                     // kPad unused entries, the heap, one spare
    std::size_t n_ = 0;               // entries
    std::size_t hn_ = 0;              // entries in the heap
    std::vector<std::uint32_t> pos_;  // heap position of each entry, or kListed
    bool calendar_ = false;           // the layout chosen at reset()
    bool active_ = false;             // slices in use since the last distribute()
    std::vector<Node> nodes_;         // per entry (calendar)
    std::vector<std::int32_t> head_;  // first entry of each slice list, then the list beyond
    std::int64_t nb_ = 0;             // slices per cycle
    std::int64_t cur_ = 0;            // the slice in the heap
    std::int32_t ahead_ = -1;         // look_ahead()'s cursor in the next slice's list
    double t0_ = 0, inv_width_ = 0;   // start of slice 0, 1 / slice width
};

inline void EventQueue::distribute() {
    double tmin = kNever;
    for (std::size_t id = 0; id < n_; ++id) tmin = std::min(tmin, nodes_[id].time);
    std::vector<double> sample;
    const std::size_t step = std::max<std::size_t>(1, n_ / 4096);
    std::size_t looked = 0;
    for (std::size_t id = 0; id < n_; id += step, ++looked)
        if (nodes_[id].time < 0.5 * kNever) sample.push_back(nodes_[id].time - tmin);
    double median = 0;
    if (!sample.empty()) {
        auto mid = sample.begin() + std::ptrdiff_t(sample.size() / 2);
        std::nth_element(sample.begin(), mid, sample.end());
        median = *mid;
    }
    active_ = tmin < 0.5 * kNever && median > 0;
    hn_ = 0;
    if (!active_) {
        storage_.assign(n_ + kArity, Entry{kNever, 0, 0});
        for (std::size_t id = 0; id < n_; ++id)
            place(hn_++, Entry{nodes_[id].time, std::uint32_t(id), 0});
        heapify();
        return;
    }
    // Entries per unit time near the front: about half of the finite ones within the median
    // delay (the finite fraction from the same sample).
    const double finite = double(n_) * double(sample.size()) / double(looked);
    const double width = slice_entries * 2.0 * median / finite;
    t0_ = tmin;
    inv_width_ = 1.0 / width;
    storage_ = decltype(storage_)(kPad + 64, Entry{kNever, 0, 0});  // the full heap freed
    cur_ = 0;
    ahead_ = -1;
    head_.assign(std::size_t(nb_) + 1, -1);
    for (std::size_t id = 0; id < n_; ++id) {
        const double t = nodes_[id].time;
        const std::int64_t s = slice(t);
        if (s <= 0) {
            if (kPad + hn_ + 1 >= storage_.size()) storage_.resize(2 * storage_.size());
            place(hn_++, Entry{t, std::uint32_t(id), 0});
        } else {
            link(std::uint32_t(id), t, s);
        }
    }
    heapify();
}

}  // namespace gran
