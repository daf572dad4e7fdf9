#pragma once
// A histogram accumulated in consecutive blocks of the measurement, so each bin's density has an
// error bar (standard error of the block densities). Shared by the velocity-distribution
// observables.
#include <boost/core/nvp.hpp>
#include <boost/histogram.hpp>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "libgran/core/state_archive.hpp"
#include "libgran/run/result_sink.hpp"

namespace gran {

using Histogram =
    decltype(boost::histogram::make_histogram(boost::histogram::axis::regular<>(1, 0.0, 1.0)));

// Checkpoints (libgran/core/state_archive.hpp) of a one-axis histogram's counts: every bin,
// underflow and overflow included, as doubles (exact: unweighted counts are integers). The axis is
// not archived: loading needs the histogram already built with the saved axis.
template <class H>
void checkpoint_counts(StateArchive& ar, H& h) {
    const int n = static_cast<int>(h.axis().size());
    std::vector<double> counts;
    if (!ar.loading()) {
        for (int i = -1; i <= n; ++i) counts.push_back(h.at(i));
    }
    ar.io(counts);
    if (!ar.loading()) return;
    if (counts.size() != std::size_t(n) + 2)
        throw StateMismatch("checkpoint state: a histogram with another number of bins");
    for (int i = -1; i <= n; ++i) {
        const double c = counts[std::size_t(i + 1)];
        // Integral counts go back as integers: assigning a double would turn the storage into
        // doubles (same outputs, but not the same histogram).
        if (c >= 0 && c < 0x1p53 && c == std::floor(c))
            h.at(i) = static_cast<std::uint64_t>(c);
        else
            h.at(i) = c;
    }
}

// Routes the `ar & make_nvp(...)` calls of a Boost.Histogram axis's serialize() to a
// StateArchive: an axis is archived as stored (start and width), not recomputed from its edges,
// which could differ in the last bit.
struct AxisArchive {
    StateArchive& ar;

    template <class T>
    AxisArchive& operator&(const boost::serialization::nvp<T>& x) {
        if constexpr (requires { x.value().serialize(*this, 0u); })
            x.value().serialize(*this, 0u);
        else
            ar.io(x.value());
        return *this;
    }
};

struct BlockedHistogram {
    std::vector<Histogram> blocks;
    std::vector<double> entries;  // samples in range+out of range per block

    // Blocks with their axes (some observables size the axis at the first sample) and counts.
    // One block per entry: entries is archived first and gives the number of blocks.
    void checkpoint(StateArchive& ar) {
        ar.io(entries);
        if (ar.loading()) blocks.resize(entries.size());
        for (auto& h : blocks) {
            auto axis = h.axis();
            AxisArchive a{ar};
            axis.serialize(a, 0u);
            if (ar.loading()) h = boost::histogram::make_histogram(axis);
            checkpoint_counts(ar, h);
        }
    }

    // Neighbouring pairs of blocks merged (an open-ended measurement, observables/block_clock.hpp):
    // block b holds blocks 2b and 2b + 1, the upper half is emptied.
    void merge_pairs() {
        const std::size_t n = blocks.size(), half = (n + 1) / 2;
        for (std::size_t b = 0; b < half; ++b) {
            Histogram h = blocks[2 * b];
            double e = entries[2 * b];
            if (2 * b + 1 < n) {
                h += blocks[2 * b + 1];
                e += entries[2 * b + 1];
            }
            blocks[b] = h;
            entries[b] = e;
        }
        for (std::size_t b = half; b < n; ++b) {
            blocks[b].reset();
            entries[b] = 0;
        }
    }

    // Writes <prefix>edges (in `edges_unit`), <prefix>density, <prefix>error; edges and density
    // may be rescaled (a change of variable x -> x / scale) for rescaled distributions.
    void write(ResultGroup& g, const std::string& prefix, double scale = 1.0,
               const std::string& edges_unit = "") const {
        const auto& axis = blocks.front().axis();
        const auto nb = static_cast<std::size_t>(axis.size());
        std::vector<double> edges(nb + 1), density(nb, 0), error(nb, 0);
        for (std::size_t k = 0; k <= nb; ++k) edges[k] = axis.bin(int(k)).lower();
        const double width = edges[1] - edges[0];
        std::vector<std::vector<double>> per_block;
        double total = 0;
        for (const double e : entries) total += e;
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            if (entries[b] == 0) continue;
            std::vector<double> d(nb);
            for (std::size_t k = 0; k < nb; ++k) d[k] = blocks[b].at(int(k)) / (entries[b] * width);
            per_block.push_back(d);
        }
        for (std::size_t b = 0; b < blocks.size(); ++b) {
            for (std::size_t k = 0; k < nb; ++k)
                density[k] += blocks[b].at(int(k)) / (total * width);
        }
        const double nblk = double(per_block.size());
        if (nblk >= 2) {
            for (std::size_t k = 0; k < nb; ++k) {
                double mean = 0, var = 0;
                for (const auto& d : per_block) mean += d[k] / nblk;
                for (const auto& d : per_block) var += (d[k] - mean) * (d[k] - mean) / (nblk - 1);
                error[k] = std::sqrt(var / nblk);
            }
        }
        for (auto& e : edges) e /= scale;
        for (auto& d : density) d *= scale;
        for (auto& e : error) e *= scale;
        g.histogram(prefix, edges, density, error, edges_unit);
    }
};

}  // namespace gran
