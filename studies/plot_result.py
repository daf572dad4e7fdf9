#!/usr/bin/python3
"""Plot a gran result file (HDF5) as one PNG figure.

Usage:
    /usr/bin/python3 studies/plot_result.py RESULT.h5 [-o OUT.png]

OUT defaults to RESULT with the suffix .png. The path of the written PNG is printed.

The figure has up to four panels; a panel whose data the result does not hold is skipped:
  1. temperature series of every species (and of the mixture) during the measurement, with the
     time averages and their one-standard-error bars in the legend (observable `temperatures`);
  2. rescaled velocity distributions P(c_x) of every species on a log axis, with error bars and
     the Gaussian exp(-c^2/2)/sqrt(2 pi) as a dashed reference (observable `velocity_pdf`);
  3. kinetic energy per particle versus time on log-log axes, with a t^-2 guide (Haff's law)
     when the gas cools (observable `kinetic_energy`);
  4. a text panel: temperature ratios gamma, Sonine coefficients a2, collision frequency and
     performance (events/s, wall time).
The figure title is the `title:` of the scene stored in /parameters/scene.

Any number of species, 2D or 3D results, and any subset of observables are handled. The script
exits with status 1 and a message on stderr when the file is missing or is not a gran result.
The file is read through gran's reader (gran.results.Run, PYTHONPATH=<repository>/python), never
with h5py directly. Needs numpy and matplotlib, and h5py for the reader (Debian: python3-h5py
python3-numpy python3-matplotlib).
"""

import argparse
import math
import sys
import warnings
from pathlib import Path

import numpy as np
from matplotlib.ticker import FormatStrFormatter

from gran.results import AXES, NotAResult, Run, as_text, with_error
from gran.style import DPI, GAUSSIAN_LABEL, plt

GAMMAS = ["gamma"] + [f"gamma_{a}" for a in AXES] + ["gamma_rot"]  # the ratios T_s / T_ref


# --- reading: Run methods by path, None for what the result does not hold -------------------------


def optional(read, path, *args):
    """read(path, *args) with a Run method (run.array, run.estimate, run.histogram, ...), or None
    when the result does not hold `path` (the Run methods raise KeyError)."""
    try:
        return read(path, *args)
    except KeyError:
        return None


def scalar(run, path):
    """(value, error) of a scalar dataset, or None when absent; error is nan when not recorded."""
    if path is None or is_group(run, path):
        return None
    estimate = optional(run.estimate, path)
    return None if estimate is None else tuple(estimate)


def observable_path(run, type_name):
    """The path of the first observable of type `type_name` ('observables/<name>'), or None."""
    group = run.observable(type_name)
    return None if group is None else "observables/" + group.name.rsplit("/", 1)[-1]


def is_group(run, path):
    """Whether the result holds a group (not a dataset) at `path`. The reader has no listing, so
    this and `subgroups` look at the groups under run.root (groups have keys, datasets do not)."""
    return path is not None and path in run.root and hasattr(run.root[path], "keys")


def subgroups(run, path, required=None):
    """Names of the groups directly below `path` (those holding `required`, when given), in file
    order: the species of an observable, the species pairs of a `ratios` group. [] when the
    result holds no group at `path`."""
    if not is_group(run, path):
        return []
    return [name for name, sub in run.root[path].items()
            if hasattr(sub, "keys") and (required is None or required in sub)]


def attribute(run, path, name, default):
    """An attribute of the group at `path` (e.g. the profiles' `axis`), `default` when absent."""
    return run.root[path].attrs.get(name, default)


def figure_title(run, source_name):
    """The scene title, then the file name, dimension and particle count."""
    try:
        scene = run.scene
    except ValueError:  # a malformed scene only costs the title
        scene = {}
    details = [source_name]
    if "dimension" in scene:
        details.append(f"{scene['dimension']}D")
    if "particles" in scene:
        details.append(f"N = {scene['particles']}")
    title = str(scene.get("title", ""))
    return f"{title}\n({', '.join(details)})" if title else ", ".join(details)


# --- formatting ----------------------------------------------------------------------------------


def spans_decades(values, factor=20.0):
    """Whether the positive entries of `values` span more than `factor` (worth a log axis)."""
    positive = values[values > 0]
    return positive.size > 1 and positive.max() > factor * positive.min()


def plain_log_labels(axis):
    """Label the minor ticks of a log axis spanning less than a decade with plain numbers."""
    axis.set_major_formatter(FormatStrFormatter("%g"))
    axis.set_minor_formatter(FormatStrFormatter("%g"))


# --- panels: each returns False when it has nothing to draw ---------------------------------------


def plot_temperatures(ax, run):
    obs = observable_path(run, "temperatures")
    clock = None if obs is None else optional(run.series, f"{obs}/series/T_mixture")
    time = None if clock is None else clock.x
    if time is None or time.size == 0:
        return False

    def series_of(path):
        curve = optional(run.series, path)
        return None if curve is None else curve.value

    curves = [(name, series_of(f"{obs}/{name}/series/T"), scalar(run, f"{obs}/{name}/T"))
              for name in subgroups(run, obs, "series")]
    if len(curves) > 1:
        curves.append(("mixture", series_of(f"{obs}/series/T_mixture"),
                       scalar(run, f"{obs}/T_mixture")))
    drawn = False
    for name, series, mean in curves:
        if series is None or series.size != time.size:
            continue
        label = name if mean is None else f"{name}: T = {with_error(*mean)}"
        style = dict(color="k", ls="--", lw=1.0) if name == "mixture" else dict(lw=0.8)
        ax.plot(time, series, label=label, **style)
        drawn = True
    if not drawn:
        return False
    values = np.concatenate([s for _, s, _ in curves if s is not None and s.size == time.size])
    if spans_decades(values):  # a cooling gas: decades in T, and usually in time too
        ax.set_yscale("log")
        if time.min() > 0 and spans_decades(time):
            ax.set_xscale("log")
    else:  # a steady state: leave room above the noisy series for the legend
        low, high = ax.get_ylim()
        ax.set_ylim(low, high + 0.1 * len(curves) * (high - low))
    ax.set_xlabel("time")
    ax.set_ylabel("temperature T")
    ax.set_title("Temperatures during the measurement")
    ax.legend(fontsize="small")
    return True


def plot_velocity_pdfs(ax, run):
    obs = observable_path(run, "velocity_pdf")
    if obs is None:
        return False
    lowest = math.inf
    for name in subgroups(run, obs, "x"):
        axis = f"{obs}/{name}/x"
        histogram = optional(run.histogram, axis, "scaled_")  # the rescaled P(c_x)
        if histogram is None:
            continue
        c, density, error = histogram.curve()
        shown = density > 0  # empty bins cannot be drawn on a log axis
        kurt = scalar(run, f"{axis}/kurtosis")
        label = name if kurt is None else f"{name} (kurtosis {with_error(*kurt)})"
        ax.errorbar(c[shown], density[shown], yerr=None if error is None else error[shown],
                    fmt="o", ms=2.5, capsize=1.5, lw=0.8, label=label)
        lowest = min(lowest, density[shown].min(initial=math.inf))
    if not math.isfinite(lowest):
        return False
    c = np.linspace(*ax.get_xlim(), 400)
    ax.plot(c, np.exp(-0.5 * c**2) / math.sqrt(2 * math.pi), "k--", lw=1.0, label=GAUSSIAN_LABEL)
    ax.set_yscale("log")
    ax.set_ylim(bottom=0.3 * lowest)  # error bars reaching zero end at the frame
    ax.set_xlabel(r"$c_x = v_x / \sqrt{T_s/m_s}$")
    ax.set_ylabel(r"$P(c_x)$")
    ax.set_title("Rescaled velocity distributions")
    ax.legend(fontsize="small")
    return True


def plot_kinetic_energy(ax, run):
    obs = observable_path(run, "kinetic_energy")
    if obs is None:
        return False
    curve = optional(run.series, f"{obs}/energy_per_particle")
    if curve is None or curve.x.size == 0:
        return False
    time, energy = curve.x, curve.value
    shown = (time > 0) & (energy > 0)
    t, e = time[shown], energy[shown]
    if t.size == 0:
        return False
    ax.loglog(t, e, lw=1.0, label="kinetic energy per particle")
    phase = optional(run.series, f"{obs}/measuring")
    measuring = None if phase is None else phase.value
    if measuring is not None and measuring.size == time.size and measuring.any():
        start = time[np.argmax(measuring > 0)]
        if start > t[0]:
            ax.axvline(start, color="gray", ls=":", lw=1.0, label="measurement starts")
    if e[-1] < 0.1 * e.max():  # the gas cools: Haff's law, E ~ t^-2 at long times
        ax.loglog(t, e[-1] * (t / t[-1]) ** -2.0, "k--", lw=1.0,
                  label=r"Haff's law $\propto t^{-2}$")
        ax.set_ylim(0.5 * e.min(), 2 * e.max())
    elif not spans_decades(e, 10.0):
        plain_log_labels(ax.yaxis)
    ax.set_xlabel("time")
    ax.set_ylabel("E / N")
    ax.set_title("Kinetic energy")
    ax.legend(fontsize="small")
    return True


def ratio_lines(run, ratios, where=""):
    """The temperature ratios gamma (total, per component, rotational) of each species pair in the
    `ratios` group at path `ratios` (absent: none)."""
    lines = []
    for ratio in subgroups(run, ratios):
        lines.append(f"{ratio.replace('_over_', ' / ')}{where}:")
        for key in GAMMAS:
            gamma = scalar(run, f"{ratios}/{ratio}/{key}")
            if gamma is not None:
                lines.append(f"    {key} = {with_error(*gamma)}")
    return lines


def summary_lines(run):
    """The lines of the text panel (empty when nothing is known)."""
    lines = []
    temps = observable_path(run, "temperatures")
    if temps is not None:
        for name in subgroups(run, temps, "T"):
            parts = [f"T = {with_error(*scalar(run, f'{temps}/{name}/T'))}"]
            for key, label in (("T_rot", "T_rot"), ("sonine_a2", "a2")):
                value = scalar(run, f"{temps}/{name}/{key}")
                if value is not None:
                    parts.append(f"{label} = {with_error(*value)}")
            lines.append(f"{name}: " + ",  ".join(parts))
        lines += ratio_lines(run, f"{temps}/ratios")
    prof = observable_path(run, "profiles")
    if prof is not None:
        lines += ratio_lines(run, f"{prof}/middle/ratios", " in the middle of the cell")
    coll = observable_path(run, "collision_statistics")
    frequency = None if coll is None else scalar(run, f"{coll}/frequency_per_particle")
    if frequency is not None:
        freq = with_error(*frequency)
        lines.append(f"collision frequency per particle: {freq} / time")
    perf = run.performance
    if "events_per_second" in perf:
        lines.append(f"events per second: {perf['events_per_second']:.3g}")
    if "wall_time" in perf:
        lines.append(f"wall time: {perf['wall_time']:.3g} s")
    return lines


def plot_summary(ax, run):
    lines = summary_lines(run)
    if not lines:
        return False
    ax.axis("off")
    ax.text(0.02, 0.98, "\n".join(lines), va="top", ha="left", family="monospace",
            fontsize="small", transform=ax.transAxes)
    ax.set_title("Summary")
    return True


def plot_profiles(ax, run):
    """Packing fraction (solid) and temperature (dashed, right axis) across the cell, per species."""
    obs = observable_path(run, "profiles")
    y = None if obs is None else optional(run.array, f"{obs}/position")
    if y is None:
        return False
    twin = ax.twinx()
    for k, name in enumerate(subgroups(run, obs, "packing_fraction")):
        colour = f"C{k}"
        ax.plot(y, run.profile(f"{obs}/{name}/packing_fraction").value, color=colour,
                label=f"{name}: packing fraction")
        twin.plot(y, run.profile(f"{obs}/{name}/T").value, color=colour, ls="--",
                  label=f"{name}: T")
    axis = as_text(attribute(run, obs, "axis", "y"))
    ax.set_xlabel(axis)
    ax.set_ylabel("packing fraction (solid)")
    twin.set_ylabel("temperature T (dashed)")
    ax.set_title("Profiles across the cell")
    lines = ax.get_legend_handles_labels()
    lines2 = twin.get_legend_handles_labels()
    ax.legend(lines[0] + lines2[0], lines[1] + lines2[1], fontsize="small")
    return True


def plot_profile_ratios(ax, run):
    """Temperature ratios gamma(y), per component, with the central window shaded."""
    obs = observable_path(run, "profiles")
    y = None if obs is None else optional(run.array, f"{obs}/position")
    ratios = f"{obs}/ratios"
    if y is None or not is_group(run, ratios):
        return False
    for ratio in subgroups(run, ratios):
        for key in GAMMAS:
            profile = optional(run.profile, f"{obs}/ratios/{ratio}/{key}")  # with its _error
            if profile is None:
                continue
            ax.errorbar(y, profile.value, yerr=profile.error, marker=".", lw=1, capsize=2,
                        label=f"{key} ({ratio.replace('_over_', '/')})")
    window = float(attribute(run, obs, "middle_window", 0.2))
    length = float(y[0] + y[-1])
    ax.axvspan(0.5 * (1 - window) * length, 0.5 * (1 + window) * length, color="0.9", label="middle window")
    ax.set_xlabel(as_text(attribute(run, obs, "axis", "y")))
    ax.set_ylabel("temperature ratio")
    ax.set_title("Temperature ratios across the cell")
    ax.legend(fontsize="small")
    return True


PANELS = (plot_temperatures, plot_velocity_pdfs, plot_profiles, plot_profile_ratios, plot_kinetic_energy,
          plot_summary)


# --- figure --------------------------------------------------------------------------------------


def make_figure(run, source_name):
    """Draw every panel that has data; returns the figure (None when no panel has data)."""
    fig, axes = plt.subplots(3, 2, figsize=(12, 13))
    used = []
    for ax, panel in zip(axes.flat, PANELS):
        if panel(ax, run):
            used.append(ax)
        else:
            ax.remove()
    if not used:
        plt.close(fig)
        return None
    ncols = 1 if len(used) == 1 else 2
    nrows = math.ceil(len(used) / ncols)
    grid = fig.add_gridspec(nrows, ncols)
    for ax, cell in zip(used, grid):  # close the gaps left by skipped panels
        ax.set_subplotspec(cell)
    fig.set_size_inches(6 * ncols, 4.5 * nrows)
    fig.suptitle(figure_title(run, source_name), fontsize="medium")
    with warnings.catch_warnings():  # uneven grids after skipped panels
        warnings.simplefilter("ignore")
        fig.tight_layout()
    return fig


def plot_result(result, out=None):
    """Plot `result` into `out` (default: result with .png); returns the PNG path."""
    out = Path(out) if out else Path(result).with_suffix(".png")
    with Run.open(result) as run:
        fig = make_figure(run, Path(result).name)
    if fig is None:
        raise NotAResult(f"{result}: the result holds no observable that can be plotted")
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot a gran result file (HDF5) as a PNG figure.")
    parser.add_argument("result", help="gran result file (.h5)")
    parser.add_argument("-o", "--output", help="PNG to write (default: RESULT with .png)")
    args = parser.parse_args(argv)
    try:
        print(plot_result(args.result, args.output))
    except NotAResult as e:
        print(f"plot_result: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
