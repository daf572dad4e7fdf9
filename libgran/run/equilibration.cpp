#include "libgran/run/equilibration.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <vector>

#include "libgran/core/statistics.hpp"

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
    const Estimate all = block_average(series);
    const Estimate kept = block_average(series.subspan(c.truncation));
    c.shift_z = kept.error > 0 ? (all.value - kept.value) / kept.error : 0.0;
    c.n_eff = kept.n_eff;
    c.conclusive = kept.converged && kept.n_eff >= kMinEffectiveSamplesForCheck;
    c.relaxing = c.conclusive && std::abs(c.shift_z) > kRelaxingShift;
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
                          bool steady_state_expected, ResultGroup& performance) {
    ResultGroup g = performance.group("equilibration");
    g.attr("criterion",
           fmt::format("MSER-5 truncation (White 1997) of the kinetic energy per particle at the "
                       "measurement samples; shift_z = (mean of all - mean after the truncation) "
                       "/ its error; relaxing if |shift_z| > {:g} with at least {:g} effective "
                       "samples (conclusive); drift_z = (mean of 2nd half - mean of 1st half) / "
                       "error",
                       kRelaxingShift, kMinEffectiveSamplesForCheck));
    g.file_only().value("samples", check.samples);
    g.value("truncation_samples", check.truncation);
    g.value("truncation_fraction", check.truncation_fraction);
    g.value("drift_z", check.drift_z);
    g.value("shift_z", check.shift_z);
    g.value("n_eff", check.n_eff);
    g.flag("conclusive", check.conclusive);
    g.flag("relaxing", check.relaxing);
    if (check.relaxing && steady_state_expected) {
        const double at_least =
            schedule.equilibration + double(check.truncation) * schedule.sample_interval;
        const std::string unit =
            schedule.unit == ScheduleUnit::Time ? "time units" : "collisions per particle";
        const std::string warning = fmt::format(
            "the kinetic energy was still relaxing during the first {:.0f}% of the measurement "
            "(MSER-5 truncation at sample {} of {}, which moves its mean by {:.1f} standard "
            "errors): lengthen run.equilibration to at least {:.3g} {}",
            100 * check.truncation_fraction, check.truncation, check.samples, check.shift_z,
            at_least, unit);
        spdlog::warn("{}", warning);
        g.text("warning", warning);
    }
}

}  // namespace gran
