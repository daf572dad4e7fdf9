"""Least-squares helpers of the Bhateja et al. 2016 analysis (numpy only: Debian's python3 has no
scipy).

- `fit_model`: weighted nonlinear least squares (Levenberg-Marquardt) with the parameter
  covariance (J^T W J)^-1 scaled by the reduced chi^2 (as scipy's curve_fit with
  absolute_sigma=False), and R^2 = 1 - SS_res / SS_tot (unweighted) of the fitted curve.
- `ALGEBRAIC`, `EXPONENTIAL`: the two forms of Table III, a (1 + c W^-b) and a (1 + c e^-bW).
  For a fixed b both are linear in (a, a c), so the starting point is the best b on a grid with
  (a, a c) from linear least squares: no hand-picked starting values.
- `loglog_slope`: ordinary least squares of log y against log x, slope and its standard error
  from the residuals (none with two points): the power-law exponents of Tables I-II and Fig. 10.
"""
import math

import numpy as np


def algebraic(w, p):
    """Table III, algebraic: a (1 + c W^-b), p = (a, b, c)."""
    a, b, c = p
    return a * (1 + c * np.power(w, -b))


def exponential(w, p):
    """Table III, exponential: a (1 + c e^-bW), p = (a, b, c)."""
    a, b, c = p
    return a * (1 + c * np.exp(-b * w))


ALGEBRAIC = (algebraic, lambda w, b: np.power(w, -b), np.linspace(0.02, 4, 400))
EXPONENTIAL = (exponential, lambda w, b: np.exp(-b * w), np.geomspace(1e-3, 3, 400))
MODELS = {"algebraic": ALGEBRAIC, "exponential": EXPONENTIAL}


def _start(w, y, weight, basis, grid):
    """Best (a, b, c) with b on a grid and (a, a c) from weighted linear least squares."""
    best = None
    sw = np.sqrt(weight)
    for b in grid:
        design = np.column_stack([np.ones_like(w), basis(w, b)])
        coef, *_ = np.linalg.lstsq(design * sw[:, None], y * sw, rcond=None)
        chi2 = float(np.sum(weight * (y - design @ coef) ** 2))
        if coef[0] != 0 and (best is None or chi2 < best[0]):
            best = (chi2, np.array([coef[0], b, coef[1] / coef[0]]))
    return best[1]


def _jacobian(model, w, p):
    """Forward-difference Jacobian of model(w, p) with respect to p."""
    f0 = model(w, p)
    jac = np.empty((len(w), len(p)))
    for k in range(len(p)):
        h = 1e-7 * max(abs(p[k]), 1e-3)
        q = p.copy()
        q[k] += h
        jac[:, k] = (model(w, q) - f0) / h
    return jac


def fit_model(name, w, y, sigma=None, iterations=500):
    """Fit Table III form `name` to (w, y) weighted by 1/sigma^2.

    Returns dict: p (a, b, c), err (standard errors), chi2_reduced, r2, n."""
    model, basis, grid = MODELS[name]
    w, y = np.asarray(w, float), np.asarray(y, float)
    weight = np.ones_like(y) if sigma is None else 1 / np.asarray(sigma, float) ** 2
    p = _start(w, y, weight, basis, grid)
    lam = 1e-3
    chi2 = float(np.sum(weight * (y - model(w, p)) ** 2))
    for _ in range(iterations):
        jac = _jacobian(model, w, p)
        jtw = jac.T * weight
        a_mat, g = jtw @ jac, jtw @ (y - model(w, p))
        step = np.linalg.solve(a_mat + lam * np.diag(np.diag(a_mat)), g)
        trial = p + step
        chi2_trial = float(np.sum(weight * (y - model(w, trial)) ** 2))
        if np.isfinite(chi2_trial) and chi2_trial < chi2:
            converged = chi2 - chi2_trial < 1e-12 * max(chi2, 1e-300)
            p, chi2, lam = trial, chi2_trial, lam / 3
            if converged:
                break
        else:
            lam *= 4
            if lam > 1e12:
                break
    dof = len(y) - len(p)
    jac = _jacobian(model, w, p)
    try:
        cov = np.linalg.inv((jac.T * weight) @ jac) * (chi2 / dof if dof > 0 else math.nan)
        err = np.sqrt(np.abs(np.diag(cov)))
    except np.linalg.LinAlgError:
        err = np.full(len(p), math.nan)
    resid = y - model(w, p)
    r2 = 1 - float(np.sum(resid**2) / np.sum((y - y.mean()) ** 2))
    return {"p": p, "err": err, "chi2_reduced": chi2 / dof if dof > 0 else math.nan,
            "r2": r2, "n": len(y)}


def loglog_slope(x, y):
    """Slope of log y against log x (ordinary least squares) and its standard error."""
    lx, ly = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    n = len(lx)
    if n < 2:
        return math.nan, math.nan
    slope, intercept = np.polyfit(lx, ly, 1)
    if n < 3:
        return float(slope), math.nan
    resid = ly - (slope * lx + intercept)
    se = math.sqrt(float(np.sum(resid**2)) / (n - 2) / float(np.sum((lx - lx.mean()) ** 2)))
    return float(slope), se
