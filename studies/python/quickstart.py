#!/usr/bin/python3
"""Quickstart of gran's Python package: a heated binary mixture built in Python, swept over the
mass ratio, against the Maxwellian kinetic theory.

Run from the repository (after `make build`):

    PYTHONPATH=python /usr/bin/python3 studies/python/quickstart.py [--out results/quickstart]

What it does:
  1. builds a scene from a dict (gran.Scene.from_dict): 1000 inelastic hard disks (2D), an
     equimolar mixture of a heavy and a light species of equal size, constant restitution
     alpha = 0.9, heated by a white-noise thermostat (stochastic_thermostat, equal velocity-kick
     variance), with the `temperatures` observable;
  2. sweeps the mass ratio m_heavy / m_light with scene.set("species.0.mass", ...) and runs each
     point with gran.run (one result file per point in --out);
  3. prints a table and plots gamma = T_light / T_heavy (the ratio the `temperatures` observable
     reports against its reference species, here `heavy`) with its error bars against the
     Maxwellian theory of the heated mixture, into <out>/quickstart.png.

Units are reduced (k_B = 1): masses in units of m_light, lengths in units of the diameter.
About 20 s on one core (1000 collisions per particle per point). docs/python.md is the guide
to the package.
"""

import argparse
import math
import sys
import time
from pathlib import Path

import gran
from gran.style import DPI, plt

ALPHA = 0.9  # normal restitution of every pair
PHI = 0.02  # packing fraction: dilute, where the theory (Enskog factors cancel) is accurate
MASS_RATIOS = (1, 2, 3, 5, 10)  # m_heavy / m_light

# The scene as a dict shaped like a scene file (docs/scene-reference.md lists every key).
SCENE = {
    "title": "quickstart: heated binary mixture of disks, alpha = 0.9",
    "dimension": 2,
    "seed": 1,
    # With 200 disks gamma comes out about 1% above the theory (a finite-size effect, several
    # standard errors at this run length); with 1000 it agrees within its error bars.
    "particles": 1000,
    "species": [
        {"name": "heavy", "mass": 3, "diameter": 1, "number_fraction": 0.5},
        {"name": "light", "mass": 1, "diameter": 1, "number_fraction": 0.5},
    ],
    "interactions": {"law": "constant_restitution", "alpha": ALPHA},
    "box": {"packing_fraction": PHI, "periodic": [True, True]},
    "initial": {"placement": "random", "temperature": 1},
    # strength ~ (1 - alpha^2) omega_E / d keeps T of order 1 (omega_E ~ 0.09 at phi = 0.02, T = 1);
    # the ratio gamma does not depend on it. Kicks every 1/8 mean free time (the default interval).
    "drivers": [{"type": "stochastic_thermostat", "noise": "equal_velocity_variance",
                 "strength": 0.01}],
    # gamma = T_s / T_ref with T_ref the temperature of `reference_species` (default: the first).
    "observables": [{"type": "temperatures", "reference_species": "heavy"}],
    "run": {"unit": "collisions_per_particle", "equilibration": 100, "measurement": 1000,
            "sample_interval": 1},
}


# --- Maxwellian theory of the white-noise heated binary mixture -----------------------------------
# The same equations as gran's C++ (libgran/core/kinetic_theory.cpp: energy_rate and
# heated_mixture_temperature_ratio, the theory tests/drivers/test_stochastic_thermostat.cpp
# compares with; docs/physics.md "Theory the tests compare with"); there is no Python home for
# them. They reproduce the C++ values of docs/physics.md (0.7459 at m1/m2 = 3, alpha = 0.85;
# 0.4351 at 10, 0.85; 0.4816 at 3, 0.5; 0.1848 at 10, 0.5).
# Both species Maxwellian at T_i (Gaussian approximation), species i heated by velocity kicks of
# variance xi^2 dt per component, the same xi for every species (equal velocity variance: the
# heated case of A. Barrat & E. Trizac, Granular Matter 4, 57 (2002)). Steady state: the energy
# balance of each species, sum_j R_ij + d m_i xi^2 / 2 = 0, so (sum_j R_1j)/m_1 = (sum_j R_2j)/m_2,
# where R_ij is the collisional energy change rate of one particle of species i due to species j
# (the Gaussian-approximation cooling rate of V. Garzo & J. W. Dufty, Phys. Rev. E 60, 5706
# (1999): sum_j R_ij = -(d/2) T_i zeta_i):
#   R_ij = n_j chi_ij sigma_ij^(d-1) (pi^((d-1)/2) 2^(3/2) s2^(3/2) / Gamma(d/2)) (m_i/2)
#          mu_ji (1 + alpha_ij) [-2 (T_i - T_j) / (M s2) - mu_ji (1 - alpha_ij)],
#   M = m_i + m_j, mu_ji = m_j / M, s2 = T_i/m_i + T_j/m_j.
# Only gamma = T_2/T_1 is fixed (every R_ij scales as T^(3/2) at fixed gamma). With equal sizes the
# Enskog factors chi_ij are equal and cancel, and gamma is the same in 2D and 3D.


def energy_rate(d, n_j, sigma_ij, chi_ij, alpha_ij, T_i, m_i, T_j, m_j):
    """R_ij: mean rate of change of the kinetic energy of one particle of species i from its
    collisions with species j (number density n_j), both Maxwellian."""
    M = m_i + m_j
    mu_ji = m_j / M
    s2 = T_i / m_i + T_j / m_j
    prefactor = (n_j * chi_ij * sigma_ij ** (d - 1) * math.pi ** ((d - 1) / 2) / math.gamma(d / 2)
                 * 2 ** 1.5 * s2 ** 1.5)
    bracket = -2 * (T_i - T_j) / (M * s2) - mu_ji * (1 - alpha_ij)
    return prefactor * 0.5 * m_i * mu_ji * (1 + alpha_ij) * bracket


def heated_mixture_gamma(m1, m2, alpha, d=2, x1=0.5, sigma1=1.0, sigma2=1.0):
    """gamma = T_2 / T_1 of a binary mixture heated with equal velocity-kick variance (species 1 of
    mass m1 and number fraction x1, species 2 of mass m2; the same alpha for every pair; dilute,
    chi = 1). Solved by bisection in ln(gamma) on [1e-4, 1e4], where the residual changes sign
    once."""
    n1, n2 = x1, 1 - x1  # only ratios of densities matter
    s12 = 0.5 * (sigma1 + sigma2)

    def residual(gamma):
        T1, T2 = 1.0, gamma
        r1 = (energy_rate(d, n1, sigma1, 1, alpha, T1, m1, T1, m1)
              + energy_rate(d, n2, s12, 1, alpha, T1, m1, T2, m2))
        r2 = (energy_rate(d, n1, s12, 1, alpha, T2, m2, T1, m1)
              + energy_rate(d, n2, sigma2, 1, alpha, T2, m2, T2, m2))
        return (r1 / m1 - r2 / m2) / (1 + gamma) ** 1.5

    lo, hi = math.log(1e-4), math.log(1e4)
    f_lo = residual(math.exp(lo))
    if f_lo * residual(math.exp(hi)) > 0:
        raise ValueError("no temperature ratio in [1e-4, 1e4]")
    for _ in range(100):  # 2^-100 of the bracket: far below double precision
        mid = 0.5 * (lo + hi)
        f_mid = residual(math.exp(mid))
        if f_mid == 0:
            return math.exp(mid)
        if (f_mid > 0) == (f_lo > 0):
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    return math.exp(0.5 * (lo + hi))


# --- the sweep ------------------------------------------------------------------------------------


def sweep(out):
    """Run every mass ratio; returns rows (mass ratio, Estimate of gamma, theory, Result)."""
    scene = gran.Scene.from_dict(SCENE, name="quickstart")
    facts = scene.check()
    print(f"{facts['particles']} disks, packing fraction {facts['packing_fraction']:g}, box "
          f"{facts['box_length'][0]:.1f} x {facts['box_length'][1]:.1f}, {facts['engine']} engine")
    m_light = scene.resolved["species"][1]["mass"]
    rows = []
    for ratio in MASS_RATIOS:
        scene.set("species.0.mass", ratio * m_light)  # validated at once (SceneError otherwise)
        result = gran.run(scene, output=out / f"mass-ratio-{ratio:g}.h5")
        if not result.completed:
            print(f"warning: m_heavy/m_light = {ratio:g}: run {result.status}", file=sys.stderr)
        # The headline of the run: T_light / T_heavy. The same number, by its full path:
        # result.summary["observables.temperatures.ratios.light_over_heavy.gamma"].
        gamma = result.summary["gamma"]
        rows.append((ratio, gamma, heated_mixture_gamma(ratio * m_light, m_light, ALPHA), result))
    return rows


def print_table(rows):
    print(f"{'m_heavy/m_light':>15}  {'gamma measured':>16}  {'theory':>7}  {'meas/theory':>11}"
          f"  {'(meas-theory)/error':>19}")
    for ratio, gamma, theory, _ in rows:
        deviation = (gamma.value - theory) / gamma.error if gamma.error > 0 else math.nan
        print(f"{ratio:>15g}  {str(gamma):>16}  {theory:>7.4f}  {gamma.value / theory:>11.4f}"
              f"  {deviation:>19.1f}")


def plot(rows, path):
    ratios = [r[0] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    fine = [10 ** (k / 100) for k in range(0, int(100 * math.log10(max(ratios) * 1.2)) + 1)]
    ax.plot(fine, [heated_mixture_gamma(m, 1.0, ALPHA) for m in fine], "k-", lw=1.2,
            label="Maxwellian theory (equal velocity-kick variance)")
    ax.errorbar(ratios, [r[1].value for r in rows], yerr=[r[1].error for r in rows], fmt="o",
                ms=5, capsize=3, label=f"gran, N = {SCENE['particles']} disks, "
                                       f"phi = {PHI:g}, alpha = {ALPHA:g}")
    ax.set_xscale("log")
    ax.set_xticks(ratios)
    ax.set_xticklabels([f"{r:g}" for r in ratios])
    ax.set_xlabel(r"mass ratio $m_\mathrm{heavy} / m_\mathrm{light}$")
    ax.set_ylabel(r"$\gamma = T_\mathrm{light} / T_\mathrm{heavy}$ (reference species: heavy)")
    ax.set_title("White-noise heated binary mixture (2D)", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Heated binary mixture swept over the mass ratio, against the theory.")
    parser.add_argument("--out", default="results/quickstart",
                        help="folder for the result files and the figure (default: %(default)s)")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    rows = sweep(out)
    print_table(rows)
    png = out / "quickstart.png"
    plot(rows, png)
    print(f"figure: {png}  ({time.perf_counter() - start:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
