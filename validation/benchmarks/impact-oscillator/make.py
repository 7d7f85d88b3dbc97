#!/usr/bin/python3
"""The impact oscillator x'' + 2 zeta x' + x = cos(omega t + phi) against a rigid stop at x = sigma
with restitution r: its periodic orbits with one impact per forcing period (Budd & Dux 1994 for
zeta = 0; here with light damping, so that a run from rest settles on the orbit), as a validation
manifest for `pounding verify` (impact-oscillator.verify.toml, CTest verify_impact_oscillator).

The orbit. Between impacts x = x_h + x_p, x_p = X cos(omega t + phi - theta) with
X = 1 / sqrt((1 - omega^2)^2 + (2 zeta omega)^2), theta = atan2(2 zeta omega, 1 - omega^2). With the
impact at t = 0 (x = sigma, leaving at -r V) and the next at T = 2 pi / omega (arriving at V), x_p is
T-periodic, so the homogeneous part must map (a, -r V - P1) to (a, V - P1) over T, a = sigma - P0,
(P0, P1) = x_p(0), x_p'(0): two equations in (phi, V). The first gives V for each phi, the second is
one scalar equation in phi, solved by bracketing. For zeta = 0 this reduces to Budd & Dux's
relation V = -2 omega sin(phi) / ((1 - omega^2)(1 - r)) with
omega (1 + r)/(1 - r) sin(phi) + tan(T/2) cos(phi) = sigma (1 - omega^2) tan(T/2), whose orbits are
checked numerically here too. Each orbit is checked numerically first (scipy, events): started on it, the next impacts come every T
with speed V to 1e-9, and x stays below sigma between them.

The mapping to a scene: a one-storey building (mass 100 t, storey stiffness 100 (2 pi)^2 kN/m in x
and y: T_n = 1 s, 5 % damping at its first mode, exactly that of its x mode) and a rigid wall
stand-in (1e9 t, 1e16 kN/m) whose vertex strikes the building's face through both centres of mass
(no rotation), restitution r, under a_g(t) = -A cos(Omega t), A = 2 m/s^2, Omega = omega 2 pi / T_n.
Then u = L x with L = A / omega_n^2, the gap is sigma L, times scale by 1/omega_n and speeds by
L omega_n. The record is sampled 100 times a forcing period with amplitude A / sinc^2(Omega h / 2), so that
its piecewise-linear interpolant's fundamental is exactly A cos(Omega t); its other harmonics lie
near multiples of the sampling frequency, where the oscillator's response is below 1e-8 of L. The
mapping's errors: the wall moves by A / omega_wall^2 = 2e-7 m (4e-6 of L), and its finite mass
changes the rebound by (1 + r) m / M = 2e-7. The manifest checks the impacts after 50 s (the start
from rest has decayed as exp(-zeta omega_n t) < 2e-7): each at its orbit time within 1e-5 s and
with the orbit's approach speed within 1e-4 relative, on the exact path and on CVODE BDF (rtol 1e-10).
Measured (2026-11-26): times within 2.4e-7 s, speeds within 2.1e-5 relative.

    validation/benchmarks/impact-oscillator/make.py     (writes the scenes, records and manifest here)
"""
import itertools
import math
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

HERE = Path(__file__).resolve().parent
ZETA, T_N, ACCEL, MASS_T, DURATION_S, AFTER_S, SAMPLES_PER_PERIOD = 0.05, 1.0, 2.0, 100.0, 60.0, 50.0, 100
CASES = [(2.5, 0.0, 0.8), (2.0, 0.1, 0.7), (1.5, 0.2, 0.8)]  # omega, sigma, r: orbits a start from rest reaches


def flow(zeta, t):
    """[h, h'](t) = flow @ [h, h'](0) for h'' + 2 zeta h' + h = 0."""
    wd = math.sqrt(1 - zeta**2)
    e, c, s = math.exp(-zeta * t), math.cos(wd * t), math.sin(wd * t)
    return e * np.array([[c + zeta / wd * s, s / wd], [-s / wd, c - zeta / wd * s]])


def orbits(omega, sigma, r, zeta):
    """[(phi, V)] of the period-one orbits with V > 0, and T."""
    period = 2 * math.pi / omega
    amplitude, lag = 1 / math.hypot(1 - omega**2, 2 * zeta * omega), math.atan2(2 * zeta * omega, 1 - omega**2)
    phi_map = flow(zeta, period)

    def parts(phi):
        p0, p1 = amplitude * math.cos(phi - lag), -amplitude * omega * math.sin(phi - lag)
        a = sigma - p0
        return a, p1, ((phi_map[0, 0] - 1) * a / phi_map[0, 1] - p1) / r

    def residual(phi):
        a, p1, v = parts(phi)
        return phi_map[1, 0] * a + phi_map[1, 1] * (-r * v - p1) - (v - p1)

    grid = np.linspace(0, 2 * math.pi, 4001)
    values = [residual(p) for p in grid]
    found = []
    for k in range(len(grid) - 1):
        if values[k] * values[k + 1] < 0:
            phi = brentq(residual, grid[k], grid[k + 1], xtol=1e-15)
            if parts(phi)[2] > 0:
                found.append((phi, parts(phi)[2]))
    return period, found


def budd_dux(omega, sigma, r):
    """The undamped relation (zeta = 0) in closed form: [(phi, V)] with V > 0."""
    gamma = math.tan(math.pi / omega)
    a, b, c = omega * (1 + r) / (1 - r), gamma, sigma * (1 - omega**2) * gamma
    base, spread = math.atan2(a, b), math.acos(c / math.hypot(a, b))
    result = []
    for phi in (base + spread, base - spread):
        v = -2 * omega * math.sin(phi) / ((1 - omega**2) * (1 - r))
        if v > 0:
            result.append((phi % (2 * math.pi), v))
    return result


def check_on_orbit(omega, sigma, r, zeta, phi, v, period):
    """Started just after an impact of the orbit, three periods: impacts every T at speed V."""
    def rhs(t, y):
        return [y[1], -2 * zeta * y[1] - y[0] + math.cos(omega * t + phi)]

    def hit(t, y):
        return y[0] - sigma
    hit.terminal, hit.direction = True, 1
    t, y, highest = 0.0, [sigma, -r * v], -math.inf
    for k in range(1, 4):
        sol = solve_ivp(rhs, (t, t + 1.5 * period), y, events=hit, rtol=1e-12, atol=1e-14, max_step=period / 50,
                        dense_output=True)
        assert sol.status == 1, "no impact within 1.5 periods"
        te, ye = sol.t_events[0][0], sol.y_events[0][0]
        inside = np.linspace(t, te, 2001)[10:-10]
        highest = max(highest, float(np.max(sol.sol(inside)[0])))
        assert abs(te - k * period) < 1e-9 and abs(ye[1] - v) < 1e-9, (te, k * period, ye[1], v)
        t, y = te, [sigma, -r * ye[1]]
    assert highest < sigma, f"the orbit crosses the stop between impacts ({highest} >= {sigma})"


def write_case(omega, sigma, r, phi, v):
    omega_n = 2 * math.pi / T_N
    length = ACCEL / omega_n**2
    forcing = omega * omega_n
    h = 2 * math.pi / forcing / SAMPLES_PER_PERIOD
    sinc = math.sin(forcing * h / 2) / (forcing * h / 2)
    t = np.arange(0, DURATION_S + h / 2, h)
    name = f"omega{omega:g}-sigma{sigma:g}-r{r:g}"
    (HERE / f"{name}.txt").write_text(
        "".join(f"{a:.12g}\n" for a in -ACCEL / sinc**2 * np.cos(forcing * t)))
    gap = sigma * length
    k = MASS_T * omega_n**2
    (HERE / f"{name}.toml").write_text(f'''# Generated by make.py: the impact oscillator omega = {omega:g}, sigma = {sigma:g}, r = {r:g}, zeta = {ZETA:g}.
name = "{name}"

[[building]]
name = "oscillator"
storeys = 1
storey_height_m = 3.0
slab = [[-10.0, 0.0], [0.0, 0.0], [0.0, 10.0], [-10.0, 10.0]]
centre_of_mass = [-5.0, 5.0]
mass_t = {MASS_T!r}
polar_moment_tm2 = "uniform"
storey_stiffness = [[{k!r}, 0.0, 0.0], [0.0, {k!r}, 0.0], [0.0, 0.0, {20 * k!r}]]
[building.damping]
ratio = {ZETA!r}
modes = [1, 3]

[[building]]
name = "wall"
storeys = 1
storey_height_m = 3.0
slab = [[{gap!r}, 5.0], [{gap + 5!r}, 0.0], [{gap + 10!r}, 5.0], [{gap + 5!r}, 10.0]]
centre_of_mass = [{gap + 5!r}, 5.0]
mass_t = 1e9
polar_moment_tm2 = "uniform"
storey_stiffness = [[1e16, 0.0, 0.0], [0.0, 1e16, 0.0], [0.0, 0.0, 1e16]]
[building.damping]
ratio = {ZETA!r}
modes = [1, 3]

[excitation]
file = "{name}.txt"
format = "single"
dt_s = {h!r}
units = "m/s2"

[contact]
gap_m = {gap!r}
restitution = {r!r}
''')
    first = math.ceil((AFTER_S * forcing - phi) / (2 * math.pi))
    times = [(phi + 2 * math.pi * k) / forcing for k in range(first, 10**6)
             if (phi + 2 * math.pi * k) / forcing <= DURATION_S - 0.5 * h]
    return name, times, v * length * omega_n


def main():
    cases = []
    for omega, sigma, r in CASES:
        period, found = orbits(omega, sigma, r, ZETA)
        assert len(found) == 1, found
        phi, v = found[0]
        check_on_orbit(omega, sigma, r, ZETA, phi, v, period)
        closed = budd_dux(omega, sigma, r)  # the published undamped relation, checked on its own orbit
        for undamped_phi, undamped_v in closed:
            check_on_orbit(omega, sigma, r, 0.0, undamped_phi, undamped_v, period)
        cases.append((omega, sigma, r, phi, v, *write_case(omega, sigma, r, phi, v)))
        print(f"omega {omega:g}, sigma {sigma:g}, r {r:g}: phi = {phi:.12f}, V = {v:.12f} (zeta {ZETA:g}); "
              f"undamped Budd & Dux {closed}")
    lines = ["# Generated by make.py (read its header): the impact oscillator's period-one orbits as",
             "# `pounding verify` cases. Each case's expected impact times and approach speed after 50 s are",
             "# the orbit's, from the closed form checked numerically in make.py.",
             'name = "impact-oscillator"', ""]
    # The wall stand-in's 1e16 kN/m storey holds its strain energy to CVODE's atol only: the audit of
    # the event-driven run closes to a few 1e-4 of the input, the exact path's to round-off.
    methods = [("exact", "", 1e-6), ("cvode-bdf", "settings = { rtol = 1e-10, atol = 1e-12 }", 2e-3)]
    for (omega, sigma, r, phi, v, name, times, speed), (method, settings, energy) in itertools.product(cases, methods):
        lines += ["[[case]]", f'name = "{name}-{method}"', f'scene = "{name}.toml"', f'method = "{method}"',
                  *([settings] if settings else []), "[case.checks]", 'status = "completed"',
                  f"impact_times = {{ abs_s = 1e-5, after_s = {AFTER_S!r} }}",
                  f"approach_velocity = {{ rel = 1e-4, after_s = {AFTER_S!r} }}",
                  f"energy_residual = {{ max_relative = {energy!r} }}",
                  "[case.expected]", f"# phi = {phi!r} rad, V = {v!r} (dimensionless), T = {2 * math.pi / omega!r}",
                  f"impact_times_s = [{', '.join(repr(t) for t in times)}]",
                  f"approach_velocity_mps = {speed!r}", ""]
    (HERE / "impact-oscillator.verify.toml").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
