"""Shared figure helpers of the study scripts (studies/<paper>/figures.py)."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def label(ax, xlabel, ylabel, title=None, legend=True, **legend_kw):
    """Axis labels, optional panel title and legend."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    if legend:
        ax.legend(**({"fontsize": 8} | legend_kw))


def save(fig, outdir, name, suptitle):
    """Title, layout and PNG file `name`.png in outdir."""
    fig.suptitle(suptitle, fontsize=11)
    fig.tight_layout()
    fig.savefig(Path(outdir) / f"{name}.png", dpi=120)
    plt.close(fig)
