#pragma once
// Power-law fits over the runs of a study: log y = theta log x + c by ordinary least squares
// (McNamara & Falcon 2005, Sec. IV). The paper reports an exponent only when every point lies
// within 0.25 of the fit in natural log, |log y_obs - log y_fit| < 0.25; `valid` applies that rule.
#include <functional>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libgran/core/h5.hpp"
#include "libgran/study/study.hpp"

namespace gran {

struct PowerLawFit {
    double theta = 0;        // exponent
    double theta_error = 0;  // standard error of the slope (NaN with two points)
    double log_prefactor = 0;
    double max_deviation = 0;  // max |log y - log y_fit|
    std::size_t points = 0;
    bool valid = false;  // at least two points and max_deviation < tolerance
};

// Plain kernel: points with x <= 0 or y <= 0 (or NaN) are skipped.
PowerLawFit fit_power_law(std::span<const double> x, std::span<const double> y, double tolerance);

struct FitResult {
    std::string name;  // the fit's name, plus "_<group_by key><value>" per group
    StudyFit spec;
    std::string group;  // the group_by value ("" without group_by)
    std::vector<double> x, y, y_error;
    PowerLawFit fit;
    std::string problem;  // why there is no fit at all (e.g. an unknown quantity), else empty
};

using Row = std::map<std::string, std::pair<double, double>>;
std::vector<FitResult> fit_all(const Study& st, const std::vector<std::string>& quantities,
                               const std::vector<Row>& rows, const std::vector<bool>& have,
                               const std::function<double(const StudyFit&, std::size_t)>& x_of);

void write_fits(h5::Group& root, const std::vector<FitResult>& fits);
void write_fits_csv(const std::string& path, const std::vector<FitResult>& fits);
std::string describe(const FitResult& r);

}  // namespace gran
