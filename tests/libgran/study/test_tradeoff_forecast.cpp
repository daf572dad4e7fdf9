// The cost of equal error bars over a trade-off's settings (libgran/study/tradeoff_forecast.hpp):
// the forecast rule of runs with a target applied to every setting's run, the default target,
// and the settings whose bias no measurement length removes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "libgran/core/scene_error.hpp"
#include "libgran/study/study_tradeoff.hpp"
#include "libgran/study/tradeoff_forecast.hpp"

namespace {

// Two settings of one quantity q against the reference point's run.
gran::Study study_with_base() {
    gran::Study st;
    st.has_tradeoff = true;
    st.tradeoff.quantities = {"q"};
    gran::StudyRun base, ref;
    base.name = base.point = "base";
    ref.name = ref.point = "reference";
    st.runs = {base, ref};
    return st;
}

gran::Row run_row(double value, double error, double cpu, double measuring) {
    return {{"q", {value, error}},
            {"performance.cpu_time", {cpu, std::nan("")}},
            {"performance.cpu_time_measuring", {measuring, std::nan("")}}};
}

TEST(TradeoffForecast, ScalesTheMeasuringCpuByTheSquaredRatioOfErrorToTarget) {
    gran::Study st = study_with_base();
    gran::TargetError half_percent;
    half_percent.quantity = "q";
    half_percent.error = 0.005;
    half_percent.relative = true;
    st.tradeoff.target_error = {half_percent};
    // Base: 1% relative error after 8 of its 10 CPU s measuring: (1% / 0.5%)^2 = 4 times the
    // measurement, 2 + 4 x 8 = 34 CPU s.
    const std::vector<gran::Row> rows{run_row(2.0, 0.02, 10, 8), run_row(2.0, 0.01, 30, 25)};
    const std::vector<std::map<std::string, double>> n_eff{{{"q", 800.0}}, {{"q", 800.0}}};
    const auto t =
        gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true}, n_eff);
    ASSERT_EQ(t.target.size(), 1u);
    EXPECT_DOUBLE_EQ(t.target[0], 0.005);
    EXPECT_EQ(t.target_kind[0], "given");
    const auto& c = t.rows[0].cells[0];
    EXPECT_NEAR(c.cpu_to_target, 34.0, 1e-9);
    // The uncertainty of a squared error from 800 samples, sqrt(2/800) = 5%, on the 32 s part.
    EXPECT_NEAR(c.cpu_to_target_uncertainty, 32 * 0.05 / 34, 1e-9);
    EXPECT_FALSE(c.biased);
    // The reference run: (0.5% / 0.5%)^2 = 1, what it spent.
    EXPECT_NEAR(t.rows[1].cells[0].cpu_to_target, 30.0, 1e-9);
    EXPECT_NEAR(t.rows[0].cpu_to_targets, 34.0, 1e-9);
    EXPECT_NE(gran::tradeoff_forecast_table(t).find("cheapest setting to every target without "
                                                    "a bias beyond it: reference"),
              std::string::npos);
}

TEST(TradeoffForecast, WithoutAGivenTargetAimsAtTheBaseRunsErrorBar) {
    const gran::Study st = study_with_base();
    const std::vector<gran::Row> rows{run_row(2.0, 0.02, 10, 8), run_row(2.0, 0.01, 30, 25)};
    const auto t = gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true},
                                          {{{"q", 800.0}}, {{"q", 800.0}}});
    EXPECT_DOUBLE_EQ(t.target[0], 0.01);  // 0.02 / |2.0|
    EXPECT_EQ(t.target_kind[0], "base runs' error");
    EXPECT_NEAR(t.rows[0].cells[0].cpu_to_target, 10.0, 1e-9);  // it already is there
    // The reference run's error is half of it: a quarter of its measurement would do.
    EXPECT_NEAR(t.rows[1].cells[0].cpu_to_target, 5 + 25 / 4.0, 1e-9);
}

TEST(TradeoffForecast, TooFewEffectiveSamplesLengthenTheMeasurementAsARunWithATargetWould) {
    const gran::Study st = study_with_base();
    const std::vector<gran::Row> rows{run_row(2.0, 0.02, 10, 8), run_row(2.0, 0.01, 30, 25)};
    // 5 effective samples: the 20 a run with a target asks need 4 times the measurement.
    const auto t = gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true},
                                          {{{"q", 5.0}}, {{"q", 800.0}}});
    EXPECT_NEAR(t.rows[0].cells[0].cpu_to_target, 2 + 4 * 8, 1e-9);
}

TEST(TradeoffForecast, ADeviationBeyondTheTargetByTwoSigmaIsABiasNoLengthRemoves) {
    gran::Study st = study_with_base();
    gran::TargetError abs;
    abs.quantity = "q";
    abs.error = 0.01;  // absolute: 0.5% of 2.0
    st.tradeoff.target_error = {abs};
    // Base deviates by +3% +- sqrt(0.01^2 + 0.01^2)/2 = 0.71%: 3 - 1.41 > 0.5: biased.
    std::vector<gran::Row> rows{run_row(2.06, 0.01, 10, 8), run_row(2.0, 0.01, 30, 25)};
    auto t = gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true}, {});
    EXPECT_DOUBLE_EQ(t.target[0], 0.005);
    EXPECT_TRUE(t.rows[0].cells[0].biased);
    EXPECT_TRUE(t.rows[0].biased);
    EXPECT_FALSE(t.rows[1].biased);
    // +1%: 1 - 1.41 < 0.5, within its noise.
    rows[0] = run_row(2.02, 0.01, 10, 8);
    t = gran::analyse_tradeoff(st, {"q", "performance.cpu_time"}, rows, {true, true}, {});
    EXPECT_FALSE(t.rows[0].cells[0].biased);
}

}  // namespace
