#pragma once
// A histogram accumulated in consecutive blocks of the measurement, so each bin's density has an
// error bar (standard error of the block densities). Shared by the velocity-distribution
// observables.
#include <boost/histogram.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "libgran/run/result_sink.hpp"

namespace gran {

using Histogram =
    decltype(boost::histogram::make_histogram(boost::histogram::axis::regular<>(1, 0.0, 1.0)));

struct BlockedHistogram {
    std::vector<Histogram> blocks;
    std::vector<double> entries;  // samples in range+out of range per block

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
