#include "libgran/equilibration.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <vector>

#include "libgran/statistics.hpp"

namespace gran {

std::size_t mser_truncation(std::span<const double> series, std::size_t batch) {
    const std::size_t m = batch == 0 ? 0 : series.size() / batch;
    if (m < kMserMinBatches) return 0;
    // Batch means, shifted by their mean so that the suffix sums below do not cancel.
    std::vector<double> b(m);
    double shift = 0;
    for (std::size_t j = 0; j < m; ++j) {
        double s = 0;
        for (std::size_t i = 0; i < batch; ++i) s += series[j * batch + i];
        b[j] = s / double(batch);
        shift += b[j] / double(m);
    }
    for (double& v : b) v -= shift;
    // Suffix sums from the end: after the loop at index d they hold the sums over j >= d.
    double s1 = 0, s2 = 0;
    std::vector<double> mser(m);
    for (std::size_t d = m; d-- > 0;) {
        s1 += b[d];
        s2 += b[d] * b[d];
        const double k = double(m - d);
        mser[d] = (s2 - s1 * s1 / k) / (k * k);
    }
    std::size_t best = 0;
    for (std::size_t d = 1; d <= m / 2; ++d) {
        if (mser[d] < mser[best]) best = d;
    }
    return best * batch;
}

EquilibrationCheck check_equilibration(std::span<const double> series) {
    EquilibrationCheck c;
    c.samples = series.size();
    if (c.samples == 0) return c;
    c.truncation = mser_truncation(series);
    c.truncation_fraction = double(c.truncation) / double(c.samples);
    c.relaxing = c.truncation_fraction > kRelaxingFraction;
    const std::size_t half = c.samples / 2;
    // The error of the difference from the second half alone, sqrt(2) times its blocking error:
    // in a stationary series both halves have the same error, and a transient in the first half
    // would inflate that half's blocking error (it looks like a long correlation) and hide itself.
    const Estimate first = block_average(series.first(half));
    const Estimate second = block_average(series.subspan(half));
    const double error = std::sqrt(2.0) * second.error;
    c.drift_z =
        error > 0 ? (second.value - first.value) / error : std::numeric_limits<double>::quiet_NaN();
    return c;
}

void report_equilibration(const EquilibrationCheck& check, const Schedule& schedule,
                          bool steady_state_expected, h5::Group& performance,
                          YAML::Node& performance_summary) {
    h5::Group g = performance.group("equilibration");
    g.attr("criterion",
           "MSER-5 truncation (White 1997) of the kinetic energy per particle at the measurement "
           "samples; relaxing if above " +
               fmt::format("{:g}", kRelaxingFraction) +
               " of the samples. drift_z: (mean of 2nd half - mean of 1st half) / error");
    g.write_scalar("samples", static_cast<std::int64_t>(check.samples));
    g.write_scalar("truncation_samples", static_cast<std::int64_t>(check.truncation));
    g.write_scalar("truncation_fraction", check.truncation_fraction);
    g.write_scalar("drift_z", check.drift_z);
    g.write_scalar("relaxing", static_cast<std::int64_t>(check.relaxing ? 1 : 0));
    YAML::Node y;
    y["truncation_samples"] = check.truncation;
    y["truncation_fraction"] = check.truncation_fraction;
    y["drift_z"] = check.drift_z;
    y["relaxing"] = check.relaxing;
    if (check.relaxing && steady_state_expected) {
        const double at_least =
            schedule.equilibration + double(check.truncation) * schedule.sample_interval;
        const std::string unit =
            schedule.unit == ScheduleUnit::Time ? "time units" : "collisions per particle";
        const std::string warning = fmt::format(
            "the kinetic energy was still relaxing during the first {:.0f}% of the measurement "
            "(MSER-5 truncation at sample {} of {}): lengthen run.equilibration to at least {:.3g} "
            "{}",
            100 * check.truncation_fraction, check.truncation, check.samples, at_least, unit);
        spdlog::warn("{}", warning);
        g.attr("warning", warning);
        y["warning"] = warning;
    }
    performance_summary["equilibration"] = y;
}

}  // namespace gran
