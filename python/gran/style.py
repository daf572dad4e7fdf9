"""The figure style of gran's plots: PNG files without a display, labelled axes, error bars.

Importing this module selects matplotlib's Agg backend (files only: the scripts run without a
display, e.g. from `make` or `gran tradeoff`); `plt` is matplotlib.pyplot.
"""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

DPI = 120
GAUSSIAN_LABEL = r"Gaussian $e^{-c^2/2}/\sqrt{2\pi}$"


def label(ax, xlabel, ylabel, title=None, legend=True, **legend_kw):
    """Axis labels, optional panel title and legend (small font unless `fontsize` is given)."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    if legend:
        ax.legend(**({"fontsize": 8} | legend_kw))


def save(fig, outdir, name, suptitle):
    """Title the figure, lay it out and write `name`.png into outdir; closes the figure."""
    fig.suptitle(suptitle, fontsize=11)
    fig.tight_layout()
    fig.savefig(Path(outdir) / f"{name}.png", dpi=DPI)
    plt.close(fig)


def errorbars(ax, curve, fmt, label=None, **kw):
    """Plot a curve (x, value, error) with error bars; `fmt` as in matplotlib ('o', '-', 's--')."""
    x, y, e = curve
    style = dict(ms=3.5, lw=1.2, elinewidth=0.7, capsize=0) | kw
    ax.errorbar(x, y, yerr=e, fmt=fmt, label=label, **style)


def positive(curve):
    """The points of a curve (x, value, error) with a positive value, error bars clipped above
    zero: what a logarithmic axis can show."""
    x, y, e = curve
    sel = y > 0
    return x[sel], y[sel], np.minimum(e[sel], 0.999 * y[sel])


def gaussian(ax, lo=-5, hi=5, fmt="k-", label=GAUSSIAN_LABEL, **kw):
    """The unit-variance Gaussian P(c) = exp(-c^2/2)/sqrt(2 pi) over lo < c < hi: the reference of
    rescaled velocity distributions."""
    c = np.linspace(lo, hi, 400)
    ax.plot(c, np.exp(-c**2 / 2) / np.sqrt(2 * np.pi), fmt, lw=kw.pop("lw", 1), label=label, **kw)
