#!/usr/bin/python3
"""Strength per storey against an independent computation (scipy with events, no code shared).

    tests/solvers/test_storey_strength_scipy.py POUNDING [OUT]

A two-storey building of unequal storeys (4.0 m and 3.2 m) with two column lines of different
size (x = 0: three 0.40 m square columns, x = 16 m: three 0.55 x 0.45 m ones, so that a storey is
stiffer along x than along y) and its centre of mass 1 m
off the plan centre, shaken by a half-sine pulse at 30 degrees to x: both floors sway in x and y
and twist, and the columns yield (bilinear, 5 % hardening) at a strength given per storey in two
ways:
  A. `yield_shear_kN = [V1, V2]`: the storey yield shear, at which all of a storey's columns yield
     together in a translation, so each column's yield drift along a direction is V_j over the sum
     of its storey's column stiffnesses along it, which differ (docs/model.md, "Yielding columns");
  B. `yield_drift_ratio = [r1, r2]`: d_y = r_j H_j.
A second, elastic building stands 10 m away (no contact). The program runs each with cvode-bdf at
rtol 1e-10; the peer integrates M q'' + C q' + K q = -M r a_g + sum (1 - alpha) k s_j t_j over the
six DOF (u, v, phi of each floor) with scipy's DOP853 over each record interval, its yield and
unloading instants located by solve_ivp's events, with its own assembly of K, its own Rayleigh fit,
its own yield drifts per spring and its own branch rules. Checked, for A and for B:
  1. u, v, phi of both floors at every history row: within 1e-8 m and 2e-9 rad;
  2. per spring (yielding.csv) the yield drift (1e-12 relative) and the yield force k d_y (1e-9
     relative) are the peer's, the number of yielding phases is equal, the first yield time within
     1e-7 s and the final slip within 1e-8 m;
  3. `pounding check` prints each storey's yield shear along x and y, sum of k d_y: for A the V_j
     given, for B the peer's sum, to its 5 printed digits (5e-5 relative);
  4. the residual drift (summary.json's residual_drift, written for yielding scenes): each storey's
     drift ratio at the end of the run at the CM along x and y and the largest |ratio| over the CM
     and the four slab corners (exact rigid-body rotation) within 1e-8, the oscillation ratio
     |rate| / omega_1 within 1e-7, the end time, the `settled` verdict by its documented rule, and
     the damage state of the largest residual (FEMA P-58's DS1-DS4 from 0.2, 0.5, 1 and 2 %);
and the storeys' strengths matter: in A (the upper storey weaker by force) storey 2 yields first, in
B (storey 1 weaker) storey 1 does. A third case, C, is A under the pulse cut at 0.5 s (its last
sample 4.8 m/s2, not zero) with `free_vibration_s = 5.5`: the program appends the quiet tail to
6.0 s, the peer integrates its own record of zeros after 0.5 s (a_g linear from the last sample to
0 over the first interval), and the building must have come to rest (settled) with the storeys'
permanent drifts left, 1 to 4 checked as for A. A fourth case, D, gives each column line its own
strength instead of the storeys (a `[[building.column_grid]]` per line with `yield_force_kN`:
700 and 300 kN a column for the x = 0 line's storeys 1 and 2, 450 and 200 kN for the x = 16 m
line's), so that each column yields at its own d_y = F_y / k along each direction: 1 to 4 checked
as for A (check's storey yield shear is then the sum of the columns' forces, 3450 and 1500 kN), and
the x = 16 m line, stiffer but weaker by force, yields first.
"""
import csv
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

E_KPA, MASS_T, HEIGHTS_M = 3.0e7, 400.0, (4.0, 3.2)
SLAB = (0.0, 0.0, 16.0, 10.0)
CM = np.array([9.0, 5.0])
COLUMNS = [((0.0, y), 0.40, 0.40) for y in (0.0, 5.0, 10.0)] + [((16.0, y), 0.55, 0.45) for y in (0.0, 5.0, 10.0)]
ALPHA, ZETA = 0.05, 0.05
PULSE_MPS2, PULSE_S, DT_S, DURATION_S, DIRECTION_DEG = 5.0, 0.6, 0.005, 3.0, 30.0
# D: each column line its own yield force per column (kN), storey 1 and 2: the x = 16 m line's
# stiffer columns are the weaker by force, so they yield first (a column grid's yield_force_kN)
LINE_FORCES_KN = {0.0: (700.0, 300.0), 16.0: (450.0, 200.0)}
STRENGTHS = {"A": ("yield_shear_kN", (4000.0, 1500.0)), "B": ("yield_drift_ratio", (0.004, 0.003)),
             "D": ("column_line", LINE_FORCES_KN)}
LINES_FIRST_YIELD = {}  # case D: each column line's first yield (s), from the peer
CUT_S, FREE_VIBRATION_S = 0.5, 5.5  # case C: the pulse cut at CUT_S, then the program's quiet tail
CASES = {"A": ("A", None), "B": ("B", None), "C": ("A", FREE_VIBRATION_S), "D": ("D", None)}  # strength, tail


def scene_text(key, values, free_vibration_s=None):
    tail = "" if free_vibration_s is None else f"free_vibration_s = {free_vibration_s}\n"

    def text(record):
        columns = "columns = [" + ", ".join(f"[{x}, {y}, {b}, {h}]" for (x, y), b, h in COLUMNS) + "]"
        if key != "column_line":
            strength = f"{key} = [{values[0]!r}, {values[1]!r}]"
        else:  # a grid per column line, each with its yield force; none for the storeys
            lines = sorted({x for (x, _), _, _ in COLUMNS})
            columns = "\n".join(
                f"[[building.column_grid]]\nx = [{x}]\ny = [{', '.join(str(c[0][1]) for c in COLUMNS if c[0][0] == x)}]\n"
                f"b_m = {next(c[1] for c in COLUMNS if c[0][0] == x)}\nh_m = {next(c[2] for c in COLUMNS if c[0][0] == x)}\n"
                f"yield_force_kN = [{values[x][0]!r}, {values[x][1]!r}]" for x in lines)
            strength = ""
        x0, y0, x1, y1 = SLAB
        return f"""name = "storey-strength-peer"
[[building]]
name = "Y"
storeys = 2
storey_height_m = [{HEIGHTS_M[0]}, {HEIGHTS_M[1]}]
slab = [[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]
centre_of_mass = [{CM[0]}, {CM[1]}]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
{columns}
[building.damping]
ratio = {ZETA}
modes = [1, 3]
[building.hysteresis]
law = "bilinear"
{strength}
hardening_ratio = {ALPHA}

[[building]]
name = "E"
storeys = 1
storey_height_m = 4.0
slab = [[26.0, 0.0], [36.0, 0.0], [36.0, 10.0], [26.0, 10.0]]
centre_of_mass = [31.0, 5.0]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [[26.0, 0.0, 0.5, 0.5], [36.0, 0.0, 0.5, 0.5], [26.0, 10.0, 0.5, 0.5], [36.0, 10.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S}
direction_deg = {DIRECTION_DEG}
{tail}
[contact]
gap_m = 10.0
restitution = 0.5

[output.floor_history]
Y = [2]

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12
"""
    return text


def record(cut_s=None, end_s=DURATION_S):
    """The pulse sampled every DT_S to end_s, zero from cut_s on (the record the program is given
    stops at cut_s)."""
    t = np.arange(0.0, end_s + DT_S / 2, DT_S)
    a = np.where(t < PULSE_S, PULSE_MPS2 * np.sin(np.pi * np.minimum(t, PULSE_S) / PULSE_S), 0.0)
    if cut_s is not None:
        a[t > cut_s + DT_S / 2] = 0.0
    return t, a


class Peer:
    """The yielding building alone: q = (u1, v1, phi1, u2, v2, phi2), each floor about its CM."""

    def __init__(self, key, values):
        x0, y0, x1, y1 = SLAB
        a, b = x1 - x0, y1 - y0
        # "uniform": J = m (a^2 + b^2)/12 about the slab's centroid (docs/scene-format.md)
        self.m = np.tile([MASS_T, MASS_T, MASS_T * (a * a + b * b) / 12.0], 2)
        # springs, storey by storey, column by column, x then y: (t row over q, k, storey)
        rows, self.k, self.storey, self.direction = [], [], [], []
        for storey, height in enumerate(HEIGHTS_M):
            for (x, y), b_m, h_m in COLUMNS:
                # fixed at both ends: k = 12 E I / H^3, I = h b^3/12 for a sway along x (b is the size along x)
                ks = (12.0 * E_KPA * h_m * b_m ** 3 / 12.0 / height ** 3, 12.0 * E_KPA * b_m * h_m ** 3 / 12.0 / height ** 3)
                arm = np.array([x, y]) - CM
                for direction, row in enumerate(([1.0, 0.0, -arm[1]], [0.0, 1.0, arm[0]])):
                    k = ks[direction]
                    t = np.zeros(6)
                    t[3 * storey:3 * storey + 3] = row
                    if storey == 1:
                        t[0:3] = -np.array(row)
                    rows.append(t)
                    self.k.append(k)
                    self.storey.append(storey)
                    self.direction.append(direction)
        self.t, self.k = np.array(rows), np.array(self.k)
        self.storey, self.direction = np.array(self.storey), np.array(self.direction)
        # each storey's stiffness along each direction: the sum over its columns
        self.storey_k = np.array([[self.k[(self.storey == j) & (self.direction == d)].sum() for d in (0, 1)]
                                  for j in (0, 1)])
        if key == "column_line":  # each column its line's force over its own stiffness, per direction
            forces = [values[x][storey] for storey in range(2) for (x, _), _, _ in COLUMNS for _direction in (0, 1)]
            self.d_y = np.array(forces) / self.k
        elif key == "yield_shear_kN":
            self.d_y = np.array([values[j] / self.storey_k[j, d] for j, d in zip(self.storey, self.direction)])
        else:
            self.d_y = np.array([values[j] * HEIGHTS_M[j] for j in self.storey])
        self.K = (self.t.T * self.k) @ self.t
        w2, _ = eigh(self.K, np.diag(self.m))
        w = np.sqrt(np.sort(w2))
        self.omega_1 = w[0]
        a0, a1 = 2 * ZETA * w[0] * w[2] / (w[0] + w[2]), 2 * ZETA / (w[0] + w[2])
        self.C = a0 * np.diag(self.m) + a1 * self.K
        beta = np.radians(DIRECTION_DEG)
        self.r = np.tile([np.cos(beta), np.sin(beta), 0.0], 2)
        self.kp = (1.0 - ALPHA) * self.k
        n = len(self.k)
        self.branch = np.zeros(n, dtype=int)  # 0 elastic, +1 / -1 yielding up / down
        self.slip = np.zeros(n)
        self.first_yield = np.full(n, np.nan)
        self.phases = np.zeros(n, dtype=int)

    def slips(self, q):
        d = self.t @ q
        return np.where(self.branch == 0, self.slip, d - self.branch * self.d_y)

    def rhs(self, t, y, ag):
        q, qd = y[:6], y[6:]
        force = self.t.T @ (self.kp * self.slips(q))
        qdd = (-self.K @ q - self.C @ qd + force) / self.m - self.r * ag(t)
        return np.concatenate([qd, qdd])

    def events(self):
        fs = []
        for j in range(len(self.k)):
            for up in (True, False):
                def f(t, y, _ag, j=j, up=up):
                    d, dd = self.t[j] @ y[:6], self.t[j] @ y[6:]
                    if self.branch[j] == 0:
                        return self.d_y[j] - (d - self.slip[j]) if up else self.d_y[j] + (d - self.slip[j])
                    if (self.branch[j] > 0) != up:
                        return 1.0
                    return self.branch[j] * dd
                f.terminal, f.direction = True, -1
                fs.append(f)
        return fs

    def switch(self, t, y, ag):
        acc = self.rhs(t, y, ag)[6:]
        for j in range(len(self.k)):
            d, dd, ddd = self.t[j] @ y[:6], self.t[j] @ y[6:], self.t[j] @ acc
            if self.branch[j] == 0:
                e = d - self.slip[j]
                if abs(e) < self.d_y[j] * (1 - 1e-9):
                    continue
                side = 1 if e > 0 else -1
                if side * dd > 0 or (side * dd == 0 and side * ddd > 0):
                    self.branch[j] = side
                    self.phases[j] += 1
                    if np.isnan(self.first_yield[j]):
                        self.first_yield[j] = t
            elif self.branch[j] * dd <= 1e-13:
                self.branch[j], self.slip[j] = 0, d - self.branch[j] * self.d_y[j]

    def run(self, times, accel, out_times):
        ag = lambda t: np.interp(t, times, accel)
        y = np.zeros(12)
        rows, k_out = [], 0
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while True:
                sol = solve_ivp(self.rhs, (t0, b), y, method="DOP853", rtol=1e-11, atol=1e-13, events=self.events(),
                                args=(ag,), dense_output=True)
                while k_out < len(out_times) and out_times[k_out] <= sol.t[-1] + 1e-12:
                    rows.append(sol.sol(out_times[k_out])[:6])
                    k_out += 1
                y = sol.y[:, -1]
                if sol.status != 1:
                    break
                t0 = sol.t[-1]
                self.switch(t0, y, ag)
        for j in range(len(self.k)):
            if self.branch[j] != 0:
                self.slip[j] = self.t[j] @ y[:6] - self.branch[j] * self.d_y[j]
        self.final = y
        return np.array(rows)

    def end_drifts(self):
        """Per storey, the drift ratios at the end and their rates at the CM then at each slab corner
        (outline order), x and y: arrays (storeys, points, 2)."""
        x0, y0, x1, y1 = SLAB
        arms = [np.zeros(2)] + [np.array(c) - CM for c in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
        q, qd = self.final[:6], self.final[6:]

        def motion(floor):  # displacement and velocity of every point of a floor (exact rotation)
            if floor < 0:
                return np.zeros((len(arms), 2)), np.zeros((len(arms), 2))
            u, v, phi = q[3 * floor:3 * floor + 3]
            du, dv, dphi = qd[3 * floor:3 * floor + 3]
            c, s = np.cos(phi), np.sin(phi)
            disp = [(u + (c - 1) * a[0] - s * a[1], v + s * a[0] + (c - 1) * a[1]) for a in arms]
            vel = [(du - dphi * (s * a[0] + c * a[1]), dv + dphi * (c * a[0] - s * a[1])) for a in arms]
            return np.array(disp), np.array(vel)

        ratio, rate = [], []
        for storey, height in enumerate(HEIGHTS_M):
            (d_up, v_up), (d_low, v_low) = motion(storey), motion(storey - 1)
            ratio.append((d_up - d_low) / height)
            rate.append((v_up - v_low) / height)
        return np.array(ratio), np.array(rate)


HISTORY = [f"B1_f{f}_{c}" for f in (1, 2) for c in ("u_m", "v_m", "phi_rad")]


def printed_storey_shears(program, scene):
    """The storey yield shears `pounding check` prints for building 1: [[x, y] per storey] (kN)."""
    check = subprocess.run([program, "check", str(scene)], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    line = next(l for l in check.stdout.splitlines() if "yield shear" in l and " x | y" in l)
    numbers = [float(v) for v in re.findall(r"(\d+(?:\.\d+)?(?:e[+-]?\d+)?) \| (\d+(?:\.\d+)?(?:e[+-]?\d+)?)",
                                             line) for v in v]
    return np.array(numbers).reshape(-1, 2), line.strip()


def check_residual_drift(run, peer, label, failures):
    """summary.json's residual drift of building 1 against the peer's end state."""
    ratio, rate = peer.end_drifts()
    oscillation = np.abs(rate).max(axis=(1, 2)) / peer.omega_1
    section = run.summary.get("residual_drift")
    if section is None:
        failures.append(f"{label}: summary.json has no residual_drift")
        return
    building = section["buildings"][0]
    worst = {"ratio": 0.0, "oscillation": 0.0}
    for j, storey in enumerate(building["storeys"]):
        worst["ratio"] = max(worst["ratio"], abs(storey["drift_ratio_x"] - ratio[j, 0, 0]),
                             abs(storey["drift_ratio_y"] - ratio[j, 0, 1]),
                             abs(storey["largest_drift_ratio"] - np.abs(ratio[j]).max()))
        worst["oscillation"] = max(worst["oscillation"], abs(storey["oscillation_ratio"] - oscillation[j]))
    largest = np.abs(ratio).max()
    settled = oscillation.max() <= max(0.1 * largest, 1e-4)
    print(f"  residual drift at {section['t_s']} s: largest {100 * largest:.4f} % (peer), "
          f"oscillation {100 * oscillation.max():.5f} %, settled {building['settled']} (peer {settled}), "
          f"damage state {building['damage_state']}; "
          f"differences {worst['ratio']:.1e} in ratio, {worst['oscillation']:.1e} in oscillation")
    for name, limit in (("ratio", 1e-8), ("oscillation", 1e-7)):
        if worst[name] > limit:
            failures.append(f"{label}: residual drift {name} differs by {worst[name]:.2e} (limit {limit:g})")
    if abs(section["t_s"] - peer.end_s) > 1e-9:
        failures.append(f"{label}: residual drift read at {section['t_s']} s, the record ends at {peer.end_s} s")
    if building["settled"] != settled:
        failures.append(f"{label}: settled is {building['settled']}, the peer's numbers say {settled}")
    reached = [name for name, ratio in (("DS1", 0.002), ("DS2", 0.005), ("DS3", 0.01), ("DS4", 0.02)) if largest >= ratio]
    if building["damage_state"] != (reached[-1] if reached else None):
        failures.append(f"{label}: damage state {building['damage_state']}, the peer's largest residual "
                        f"{100 * largest:.4f} % is {reached[-1] if reached else 'below DS1'}")


def check_case(program, out, label, failures):
    strength, tail_s = CASES[label]
    key, values = STRENGTHS[strength]
    # the program gets the record to its cut; the peer integrates it with the quiet tail written out
    times, accel = record() if tail_s is None else record(CUT_S, CUT_S + tail_s)
    given = accel if tail_s is None else accel[times <= CUT_S + DT_S / 2]
    folder = out / label
    run, message = program_run.run_scene(program, folder, scene_text(key, values, tail_s), given, columns=HISTORY)
    if run is None:
        failures.append(f"{label}: {message}")
        return None
    peer = Peer(key, values)
    peer.end_s = times[-1]
    peer_q = peer.run(times, accel, run.t)
    du = np.max(np.abs(run.q[:, [0, 1, 3, 4]] - peer_q[:, [0, 1, 3, 4]]))
    dphi = np.max(np.abs(run.q[:, [2, 5]] - peer_q[:, [2, 5]]))
    print(f"{label} ({key} = {list(values)}): largest |u, v| difference {du:.2e} m, |phi| {dphi:.2e} rad over "
          f"{len(run.t)} rows; peak |u| {np.max(np.abs(peer_q[:, [0, 3]])):.4f} m")
    if du > 1e-8 or dphi > 2e-9:
        failures.append(f"{label}: history differs")
    with open(folder / "run/yielding.csv") as f:
        springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
    if len(springs) != len(peer.k):
        failures.append(f"{label}: {len(springs)} springs, the peer has {len(peer.k)}")
        return None
    worst = {"d_y": 0.0, "force": 0.0, "t": 0.0, "slip": 0.0}
    for j, s in enumerate(springs):
        worst["d_y"] = max(worst["d_y"], abs(float(s["yield_drift_m"]) / peer.d_y[j] - 1))
        worst["force"] = max(worst["force"], abs(float(s["yield_force_kN"]) / (peer.k[j] * peer.d_y[j]) - 1))
        if int(s["yield_count"]) != peer.phases[j]:
            failures.append(f"{label} spring {j} ({s['column']} storey {s['storey']} {s['direction']}): "
                            f"{s['yield_count']} yielding phases, the peer {peer.phases[j]}")
            continue
        if peer.phases[j] > 0:
            worst["t"] = max(worst["t"], abs(float(s["first_yield_t_s"]) - peer.first_yield[j]))
            worst["slip"] = max(worst["slip"], abs(float(s["final_slip_m"]) - peer.slip[j]))
    print(f"  {int((peer.phases > 0).sum())} of {len(springs)} springs yielded; yield drift {worst['d_y']:.1e} and "
          f"force {worst['force']:.1e} relative, first yield {worst['t']:.1e} s, final slip {worst['slip']:.1e} m")
    for name, limit in (("d_y", 1e-12), ("force", 1e-9), ("t", 1e-7), ("slip", 1e-8)):
        if worst[name] > limit:
            failures.append(f"{label}: {name} differs by {worst[name]:.2e} (limit {limit:g})")
    printed, line = printed_storey_shears(program, folder / "scene.toml")
    expected = np.array([[np.sum((peer.k * peer.d_y)[(peer.storey == j) & (peer.direction == d)]) for d in (0, 1)]
                         for j in (0, 1)])
    print(f"  check: {line}")
    if printed.shape != expected.shape or np.max(np.abs(printed / expected - 1)) > 5e-5:
        failures.append(f"{label}: check prints storey yield shears {printed.tolist()}, the peer {expected.tolist()}")
    check_residual_drift(run, peer, label, failures)
    if tail_s is not None and not run.summary["residual_drift"]["buildings"][0]["settled"]:
        failures.append(f"{label}: still moving after a {tail_s} s quiet tail")
    never = np.where(np.isnan(peer.first_yield), np.inf, peer.first_yield)
    if key == "column_line":
        line_of = np.array([x for _storey in range(2) for (x, _), _, _ in COLUMNS for _direction in (0, 1)])
        LINES_FIRST_YIELD.update({x: float(np.min(never[line_of == x])) for x in LINE_FORCES_KN})
    return [float(np.min(never[peer.storey == j])) for j in (0, 1)]  # inf: the storey never yields


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    orders = {label: check_case(program, out, label, failures) for label in CASES}
    lines_first = LINES_FIRST_YIELD
    if all(orders.values()):
        print(f"first yield by storey 1, 2 (s; inf: never): A {orders['A']}, B {orders['B']}")
        if not (orders["A"][1] < orders["A"][0] and orders["B"][0] < orders["B"][1]):
            failures.append("storey 2 should yield first in A, storey 1 in B")
    if lines_first:
        print(f"D: first yield of the x = 0 m and x = 16 m lines' columns (s): {lines_first}")
        if not lines_first[16.0] < lines_first[0.0]:
            failures.append("D: the x = 16 m line (weaker by force) should yield first")
    program_run.finish(failures)


if __name__ == "__main__":
    main()
