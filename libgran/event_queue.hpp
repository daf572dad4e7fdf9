#pragma once
// Indexed binary min-heap with one entry per particle: the time of the particle's single pending
// event. update() moves an entry in O(log N); the heap holds (time, id) pairs so that sifting reads
// contiguous memory.
#include <cstdint>
#include <utility>
#include <vector>

namespace gran {

class EventQueue {
public:
    void reset(std::size_t n) {
        heap_.resize(n);
        pos_.resize(n);
        for (std::size_t k = 0; k < n; ++k) {
            heap_[k] = {kNever, static_cast<std::uint32_t>(k)};
            pos_[k] = static_cast<std::uint32_t>(k);
        }
    }
    // Sets all keys at once then heapifies in O(N).
    template <class TimeOf>
    void rebuild(TimeOf time_of) {
        for (auto& e : heap_) e.time = time_of(e.id);
        for (std::size_t k = heap_.size() / 2; k-- > 0;) sift_down(k);
    }
    std::uint32_t top() const { return heap_[0].id; }
    double top_time() const { return heap_[0].time; }
    double time_of(std::uint32_t id) const { return heap_[pos_[id]].time; }
    void update(std::uint32_t id, double time) {
        const std::size_t k = pos_[id];
        const double old = heap_[k].time;
        heap_[k].time = time;
        if (time < old) {
            sift_up(k);
        } else {
            sift_down(k);
        }
    }
    std::size_t size() const { return heap_.size(); }

private:
    static constexpr double kNever = 1e300;
    struct Entry {
        double time;
        std::uint32_t id;
    };
    void place(std::size_t k, const Entry& e) {
        heap_[k] = e;
        pos_[e.id] = static_cast<std::uint32_t>(k);
    }
    void sift_up(std::size_t k) {
        const Entry e = heap_[k];
        while (k > 0) {
            const std::size_t parent = (k - 1) / 2;
            if (!(e.time < heap_[parent].time)) break;
            place(k, heap_[parent]);
            k = parent;
        }
        place(k, e);
    }
    void sift_down(std::size_t k) {
        const std::size_t n = heap_.size();
        const Entry e = heap_[k];
        while (true) {
            std::size_t child = 2 * k + 1;
            if (child >= n) break;
            if (child + 1 < n && heap_[child + 1].time < heap_[child].time) ++child;
            if (!(heap_[child].time < e.time)) break;
            place(k, heap_[child]);
            k = child;
        }
        place(k, e);
    }
    std::vector<Entry> heap_;
    std::vector<std::uint32_t> pos_;
};

}  // namespace gran
