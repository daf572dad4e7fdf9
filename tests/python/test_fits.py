#!/usr/bin/python3
"""gran.fits: power laws (ordinary and weighted, McNamara & Falcon's validity rule) and nonlinear
least squares, checked on exact laws and on textbook closed forms.

Run: PYTHONPATH=python /usr/bin/python3 tests/python/test_fits.py (make test does).
"""
import math
import unittest

import numpy as np

from gran.fits import levenberg_marquardt, power_law

X = np.array([1.0, 2.0, 4.0, 8.0, 16.0])
LOG_SPREAD = float(np.sum((np.log(X) - np.log(X).mean()) ** 2))  # sum (log x - mean)^2


class PowerLawTest(unittest.TestCase):
    def test_exact_power_law_gives_exponent_and_prefactor_without_error(self):
        fit = power_law(X, 3.0 * X**1.7)
        self.assertAlmostEqual(fit.exponent, 1.7, places=12)
        self.assertAlmostEqual(math.exp(fit.log_prefactor), 3.0, places=10)
        self.assertAlmostEqual(fit.exponent_error, 0.0, places=10)
        self.assertLess(fit.max_deviation, 1e-12)
        self.assertTrue(fit.valid())
        np.testing.assert_allclose(fit([3.0]), 3.0 * 3.0**1.7)

    def test_weighted_exact_law_error_comes_from_the_relative_errors(self):
        # sigma(log y) = 10% for every point: error of the slope = 0.1 / sqrt(sum (log x - mean)^2)
        y = 0.5 * X**-2.0
        fit = power_law(X, y, 0.1 * y)
        self.assertAlmostEqual(fit.exponent, -2.0, places=12)
        self.assertAlmostEqual(fit.exponent_error, 0.1 / math.sqrt(LOG_SPREAD), places=12)

    def test_scatter_beyond_the_errors_inflates_the_weighted_error_to_the_ordinary_one(self):
        y = X**1.5 * np.exp([0.05, -0.05, 0.05, -0.05, 0.05])
        ordinary, weighted = power_law(X, y), power_law(X, y, 1e-4 * y)
        self.assertAlmostEqual(weighted.exponent, ordinary.exponent, places=12)
        self.assertAlmostEqual(weighted.exponent_error, ordinary.exponent_error, places=12)
        # the textbook standard error of an ordinary least-squares slope
        lx, ly = np.log(X), np.log(y)
        resid = ly - np.polyval(np.polyfit(lx, ly, 1), lx)
        self.assertAlmostEqual(ordinary.exponent_error,
                               math.sqrt(np.sum(resid**2) / 3 / LOG_SPREAD), places=12)

    def test_a_point_off_by_more_than_the_tolerance_in_log_voids_the_exponent(self):
        y = X**2.0
        y[2] *= math.exp(0.6)  # the line moves towards it, the point stays > 0.25 away
        fit = power_law(X, y)
        self.assertGreater(fit.max_deviation, 0.25)
        self.assertFalse(fit.valid())
        self.assertTrue(fit.valid(tolerance=1.0))

    def test_two_points_give_no_error_and_one_point_no_fit(self):
        two = power_law([1.0, 2.0], [1.0, 4.0])
        self.assertAlmostEqual(two.exponent, 2.0, places=12)
        self.assertTrue(math.isnan(two.exponent_error))
        one = power_law([1.0], [1.0])
        self.assertTrue(math.isnan(one.exponent))
        self.assertEqual(one.points, 1)


class LevenbergMarquardtTest(unittest.TestCase):
    @staticmethod
    def saturating(w, p):
        a, b, c = p
        return a * (1 + c * np.exp(-b * w))

    def test_recovers_the_parameters_of_an_exact_curve_from_a_nearby_start(self):
        w = np.linspace(0.5, 20, 30)
        y = self.saturating(w, (0.3, 0.25, 1.5))
        fit = levenberg_marquardt(self.saturating, w, y, start=(0.25, 0.3, 1.2))
        np.testing.assert_allclose(fit["p"], (0.3, 0.25, 1.5), rtol=1e-6)
        self.assertAlmostEqual(fit["r2"], 1.0, places=10)
        self.assertEqual(fit["n"], 30)

    def test_errors_of_a_straight_line_are_those_of_linear_regression(self):
        x = np.arange(8.0)
        y = 1.0 + 0.5 * x + np.array([0.1, -0.2, 0.05, 0.1, -0.1, 0.15, -0.05, -0.05])
        fit = levenberg_marquardt(lambda x, p: p[0] + p[1] * x, x, y, start=(0.0, 0.0))
        (slope, intercept), cov = np.polyfit(x, y, 1, cov=True)  # scaled by the residuals
        np.testing.assert_allclose(fit["p"], (intercept, slope), rtol=1e-7)
        np.testing.assert_allclose(fit["err"], np.sqrt(np.diag(cov))[::-1], rtol=1e-4)
        resid = y - (intercept + slope * x)
        self.assertAlmostEqual(fit["chi2_reduced"], float(np.sum(resid**2)) / 6, places=8)


if __name__ == "__main__":
    unittest.main()
