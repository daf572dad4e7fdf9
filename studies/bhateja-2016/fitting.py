"""The Table III fits of the Bhateja et al. 2016 analysis.

- `ALGEBRAIC`, `EXPONENTIAL`: the two forms of Table III, a (1 + c W^-b) and a (1 + c e^-bW).
  For a fixed b both are linear in (a, a c), so the starting point is the best b on a grid with
  (a, a c) from linear least squares: no hand-picked starting values.
- `fit_model`: one form fitted from that start by weighted nonlinear least squares
  (gran.fits.levenberg_marquardt: covariance errors scaled by the reduced chi^2, R^2).

The power-law exponents of Tables I-II and Figs. 6, 10 are gran.fits.power_law (ordinary least
squares in log-log, errors from the residuals).
"""
import numpy as np

from gran.fits import levenberg_marquardt


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


def fit_model(name, w, y, sigma=None, iterations=500):
    """Fit Table III form `name` to (w, y) weighted by 1/sigma^2 (gran.fits.levenberg_marquardt
    from the best grid start).

    Returns dict: p (a, b, c), err (standard errors), chi2_reduced, r2, n."""
    model, basis, grid = MODELS[name]
    w, y = np.asarray(w, float), np.asarray(y, float)
    weight = np.ones_like(y) if sigma is None else 1 / np.asarray(sigma, float) ** 2
    return levenberg_marquardt(model, w, y, _start(w, y, weight, basis, grid), sigma, iterations)
