"""Least-squares fits of measured curves (NumPy only: Debian's python3 has no SciPy).

- `power_law`: y = C x^theta as a straight line in log-log, ordinary (the error of theta from the
  residuals, as `gran study` fits, libgran/study/study_fit.cpp) or weighted by the errors of y
  (the error of theta from those errors, inflated by sqrt(reduced chi^2) when the scatter exceeds
  them). `max_deviation` and `valid` apply McNamara & Falcon's rule (2005, Sec. IV): no exponent
  when a point deviates from the line by |log y - log y_fit| >= 0.25.
- `levenberg_marquardt`: weighted nonlinear least squares y = model(x, p) with the parameter
  covariance (J^T W J)^-1 scaled by the reduced chi^2 (as SciPy's curve_fit with
  absolute_sigma=False), and R^2 = 1 - SS_res / SS_tot (unweighted) of the fitted curve.
"""
import math
from dataclasses import dataclass

import numpy as np

POWER_LAW_TOLERANCE = 0.25  # McNamara & Falcon 2005: largest |log y - log y_fit| of a power law


@dataclass(frozen=True)
class PowerLaw:
    """y = exp(log_prefactor) x^exponent fitted over `points` points; errors are one standard
    error (NaN when the points cannot give one: two points unweighted, fewer than two at all)."""

    exponent: float
    exponent_error: float
    log_prefactor: float
    max_deviation: float
    points: int

    def valid(self, tolerance=POWER_LAW_TOLERANCE):
        """Whether every point lies within `tolerance` of the line in natural log."""
        return self.max_deviation < tolerance

    def __call__(self, x):
        """The fitted power law at x."""
        return np.exp(self.log_prefactor) * np.asarray(x, dtype=float) ** self.exponent


def power_law(x, y, y_error=None):
    """Fit log y = exponent log x + log_prefactor by least squares (x, y > 0).

    Without `y_error`: ordinary least squares, the exponent's error from the scatter of the points
    (none with two). With `y_error`: weights y / y_error (the error of log y), the exponent's
    error from the errors, scaled up by sqrt(reduced chi^2) when the points scatter more than
    their errors say (never down: a few points cannot show that the errors are too large).
    """
    lx, ly = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    n = len(lx)
    if n < 2:
        return PowerLaw(math.nan, math.nan, math.nan, math.nan, n)
    if y_error is None:
        slope, intercept = np.polyfit(lx, ly, 1)
        error = math.nan
        if n >= 3:
            resid = ly - (slope * lx + intercept)
            error = math.sqrt(float(np.sum(resid**2)) / (n - 2)
                              / float(np.sum((lx - lx.mean()) ** 2)))
    else:
        w = np.asarray(y, float) / np.asarray(y_error, float)
        (slope, intercept), cov = np.polyfit(lx, ly, 1, w=w, cov="unscaled")
        chi2 = np.sum((w * (ly - (intercept + slope * lx))) ** 2) / max(n - 2, 1)
        error = float(np.sqrt(cov[0, 0] * max(chi2, 1.0)))
    deviation = float(np.max(np.abs(ly - (slope * lx + intercept))))
    return PowerLaw(float(slope), error, float(intercept), deviation, n)


def _jacobian(model, x, p):
    """Forward-difference Jacobian of model(x, p) with respect to p."""
    f0 = model(x, p)
    jac = np.empty((len(x), len(p)))
    for k in range(len(p)):
        h = 1e-7 * max(abs(p[k]), 1e-3)
        q = p.copy()
        q[k] += h
        jac[:, k] = (model(x, q) - f0) / h
    return jac


def _minimise(model, x, y, weight, p, iterations):
    """Levenberg-Marquardt iterations from p: (best p, its chi^2)."""
    lam = 1e-3
    chi2 = float(np.sum(weight * (y - model(x, p)) ** 2))
    for _ in range(iterations):
        jac = _jacobian(model, x, p)
        jtw = jac.T * weight
        a_mat, g = jtw @ jac, jtw @ (y - model(x, p))
        step = np.linalg.solve(a_mat + lam * np.diag(np.diag(a_mat)), g)
        trial = p + step
        chi2_trial = float(np.sum(weight * (y - model(x, trial)) ** 2))
        if np.isfinite(chi2_trial) and chi2_trial < chi2:
            converged = chi2 - chi2_trial < 1e-12 * max(chi2, 1e-300)
            p, chi2, lam = trial, chi2_trial, lam / 3
            if converged:
                break
        else:
            lam *= 4
            if lam > 1e12:
                break
    return p, chi2


def levenberg_marquardt(model, x, y, start, sigma=None, iterations=500):
    """Fit y = model(x, p) from the parameters `start`, weighted by 1/sigma^2 (equal weights
    without sigma).

    Returns a dict: p (best parameters), err (standard errors from the covariance scaled by the
    reduced chi^2; NaN when singular or with no degree of freedom), chi2_reduced, r2, n."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    weight = np.ones_like(y) if sigma is None else 1 / np.asarray(sigma, float) ** 2
    p, chi2 = _minimise(model, x, y, weight, np.asarray(start, float), iterations)
    dof = len(y) - len(p)
    jac = _jacobian(model, x, p)
    try:
        cov = np.linalg.inv((jac.T * weight) @ jac) * (chi2 / dof if dof > 0 else math.nan)
        err = np.sqrt(np.abs(np.diag(cov)))
    except np.linalg.LinAlgError:
        err = np.full(len(p), math.nan)
    resid = y - model(x, p)
    r2 = 1 - float(np.sum(resid**2) / np.sum((y - y.mean()) ** 2))
    return {"p": p, "err": err, "chi2_reduced": chi2 / dof if dof > 0 else math.nan,
            "r2": r2, "n": len(y)}
