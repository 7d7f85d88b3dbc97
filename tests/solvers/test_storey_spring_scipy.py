#!/usr/bin/python3
"""Storey springs against an independent computation (scipy with events, no code shared).

    tests/solvers/test_storey_spring_scipy.py POUNDING [OUT]

A two-storey building (4.0 m and 3.2 m) given by its storey matrices about the CM
(`storey_stiffness`, rows and columns u, v, phi in kN/m, kN, kN m/rad), different per storey and
eccentric (K_uphi and K_vphi nonzero, K_uv = 0: the centre of rigidity 1.2 m and 0.8 m off the CM in
storey 1, -0.7 m and -1.0 m in storey 2), 400 t a floor with the slab's "uniform" J, shaken by a
half-sine pulse at 30 degrees to x: both floors sway in x and y and twist, and each storey yields
as two storey springs (bilinear, 5 % hardening; docs/model.md §2a, "Storey springs"): an x spring
k_x = K_uu on the drift t_x . (q_j - q_{j-1}), t_x = (1, 0, -e_y), e_y = -K_uphi/K_uu, and a y
spring k_y = K_vv on t_y = (0, 1, e_x), e_x = K_vphi/K_vv, the torsional remainder
K_phiphi - K_uphi^2/K_uu - K_vphi^2/K_vv staying elastic. The strength is given in two ways:
  A. `yield_shear_kN = [V1, V2]`: d_y = V_j / K_uu along x and V_j / K_vv along y;
  B. `yield_drift_m = [d1, d2]`: d_y as given.
A second, elastic building stands 10 m away (no contact). The program runs each with cvode-bdf at
rtol 1e-10; the peer integrates M q'' + C q' + K q = -M r a_g + sum (1 - alpha) k s t over the six
DOF (u, v, phi of each floor) with scipy's DOP853 (rtol 1e-12) over each record interval (a_g linear
between samples), its yield and unloading instants located by solve_ivp's events, with its own
block-tridiagonal assembly of K from the matrices (checked against the springs' split of it), its
own Rayleigh fit at modes 1 and 3, its own spring rows and yield drifts from the formulas above
and its own branch rules. Checked, for A and for B:
  1. u, v, phi of both floors at every history row: within 1e-8 m and 2e-9 rad (measured 7e-10 m
     and 2e-11 rad in A, 4e-10 m and 2e-11 rad in B; peak |u| 0.14 and 0.19 m);
  2. per spring (yielding.csv's rows `storey_stiffness[j]`, x and y) the stiffness and the yield
     drift (1e-12 relative) and the yield force k d_y (1e-9 relative; all three measured exact)
     are the peer's, the number of yielding phases is equal (every spring yields, 1 to 3 times),
     the first yield time within 1e-7 s and the final slip within 1e-8 m (measured 2e-9 s and
     5e-10 m);
  3. `pounding check` prints each storey's yield shear along x and y, k d_y of its two springs:
     for A the V_j given, for B the peer's, to its 5 printed digits (5e-5 relative).
And the springs matter: the peer with its springs kept elastic, and the peer whose springs act at
the CM (e_x = e_y = 0 in their rows, K unchanged), each differ from the yielding peer by more than
1000 times the history tolerance. And a storey matrix that couples u and v (K_uv != 0) under a
yielding law is refused by `pounding check` (non-zero exit, naming `storey_stiffness` and K_uv), as is
a yielding law without a strength key (exit 2, naming hysteresis.yield_drift_ratio as missing),
while the same matrix elastic is accepted.
"""
import csv
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

MASS_T, HEIGHTS_M = 400.0, (4.0, 3.2)
SLAB = (0.0, 0.0, 16.0, 10.0)
CM = (9.0, 5.0)
# storey matrices about the CM, (u, v, phi): K_uu, K_vv, offsets e_y, e_x of the centre of rigidity
# (K_uphi = -e_y K_uu, K_vphi = e_x K_vv) and K_phiphi
STOREYS = [dict(kuu=3.0e5, kvv=2.4e5, e_y=1.2, e_x=0.8, kpp=1.5e7),
           dict(kuu=2.2e5, kvv=1.8e5, e_y=-0.7, e_x=-1.0, kpp=1.1e7)]
ALPHA, ZETA = 0.05, 0.05
PULSE_MPS2, PULSE_S, DT_S, DURATION_S, DIRECTION_DEG = 5.0, 0.6, 0.005, 3.0, 30.0
STRENGTHS = {"A": ("yield_shear_kN", (1800.0, 1000.0)), "B": ("yield_drift_m", (0.004, 0.0035))}
HISTORY_M, HISTORY_RAD = 1e-8, 2e-9
K_UV_KN_PER_M = 4.0e4  # the refused coupling, storey 1


def matrix(storey, k_uv=0.0):
    s = STOREYS[storey]
    k_uphi, k_vphi = -s["e_y"] * s["kuu"], s["e_x"] * s["kvv"]
    return [[s["kuu"], k_uv, k_uphi], [k_uv, s["kvv"], k_vphi], [k_uphi, k_vphi, s["kpp"]]]


def scene_text(key, values, k_uv=0.0, law="bilinear"):
    def text(record):
        matrices = "[" + ", ".join("[" + ", ".join("[" + ", ".join(repr(v) for v in row) + "]"
                                                    for row in matrix(j, k_uv if j == 0 else 0.0)) + "]"
                                   for j in range(2)) + "]"
        hysteresis = "" if law == "elastic" else (
            f"[building.hysteresis]\nlaw = \"{law}\"\n{key} = [{values[0]!r}, {values[1]!r}]\n"
            f"hardening_ratio = {ALPHA}\n")
        x0, y0, x1, y1 = SLAB
        return f"""name = "storey-spring-peer"
[[building]]
name = "Y"
storeys = 2
storey_height_m = [{HEIGHTS_M[0]}, {HEIGHTS_M[1]}]
slab = [[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]
centre_of_mass = [{CM[0]}, {CM[1]}]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
storey_stiffness = {matrices}
[building.damping]
ratio = {ZETA}
modes = [1, 3]
{hysteresis}
[[building]]
name = "E"
storeys = 1
storey_height_m = 4.0
slab = [[26.0, 0.0], [36.0, 0.0], [36.0, 10.0], [26.0, 10.0]]
centre_of_mass = [31.0, 5.0]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = 3.0e7
frame_factor = 1.0
columns = [[26.0, 0.0, 0.5, 0.5], [36.0, 0.0, 0.5, 0.5], [26.0, 10.0, 0.5, 0.5], [36.0, 10.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S}
direction_deg = {DIRECTION_DEG}

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


def record():
    t = np.arange(0.0, DURATION_S + DT_S / 2, DT_S)
    return t, np.where(t < PULSE_S, PULSE_MPS2 * np.sin(np.pi * np.minimum(t, PULSE_S) / PULSE_S), 0.0)


class Peer:
    """The storey-spring building alone: q = (u1, v1, phi1, u2, v2, phi2), each floor about its CM.
    `elastic`: the springs never yield; `centred`: the springs' rows without their offsets (the
    plastic forces then act at the CM; K as assembled)."""

    def __init__(self, key, values, elastic=False, centred=False):
        x0, y0, x1, y1 = SLAB
        a, b = x1 - x0, y1 - y0
        self.m = np.tile([MASS_T, MASS_T, MASS_T * (a * a + b * b) / 12.0], 2)  # "uniform" J of a rectangle
        # K: storey j's matrix on floor j, floor j - 1 and between them (the ground's rows dropped)
        self.K = np.zeros((6, 6))
        for j in range(2):
            Kj = np.array(matrix(j))
            blocks = [(j, j, 1.0)] + ([(j - 1, j - 1, 1.0), (j, j - 1, -1.0), (j - 1, j, -1.0)] if j > 0 else [])
            for r, c, sign in blocks:
                self.K[3 * r:3 * r + 3, 3 * c:3 * c + 3] += sign * Kj
        # the springs, storey by storey, x then y: row over q, stiffness, yield drift
        rows, self.k, self.d_y, self.storey, self.direction = [], [], [], [], []
        split = np.zeros((6, 6))
        for j in range(2):
            (kuu, _, kup), (_, kvv, kvp), (_, _, kpp) = matrix(j)
            e_y, e_x = -kup / kuu, kvp / kvv
            remainder = kpp - kup ** 2 / kuu - kvp ** 2 / kvv
            assert remainder > 0, remainder
            for direction, (k, local) in enumerate(((kuu, [1.0, 0.0, -e_y]), (kvv, [0.0, 1.0, e_x]))):
                t = np.zeros(6)
                t[3 * j:3 * j + 3] = local
                if j > 0:
                    t[3 * j - 3:3 * j] = -np.array(local)
                split += k * np.outer(t, t)
                if centred:
                    t = np.zeros(6)
                    t[3 * j + direction] = 1.0
                    if j > 0:
                        t[3 * j - 3 + direction] = -1.0
                rows.append(t)
                self.k.append(k)
                self.d_y.append(values[j] / k if key == "yield_shear_kN" else values[j])
                self.storey.append(j)
                self.direction.append(direction)
            rot = np.zeros(6)
            rot[3 * j + 2] = 1.0
            if j > 0:
                rot[3 * j - 1] = -1.0
            split += remainder * np.outer(rot, rot)
        # the documented split reproduces the assembled K
        assert np.max(np.abs(split - self.K)) <= 1e-12 * np.max(np.abs(self.K)), np.max(np.abs(split - self.K))
        self.t, self.k, self.d_y = np.array(rows), np.array(self.k), np.array(self.d_y)
        if elastic:
            self.d_y = np.full(len(self.k), np.inf)
        self.storey, self.direction = np.array(self.storey), np.array(self.direction)
        w2 = eigh(self.K, np.diag(self.m), eigvals_only=True)
        w = np.sqrt(np.sort(w2))
        self.periods = 2 * np.pi / w
        a0, a1 = 2 * ZETA * w[0] * w[2] / (w[0] + w[2]), 2 * ZETA / (w[0] + w[2])
        self.C = a0 * np.diag(self.m) + a1 * self.K
        beta = np.radians(DIRECTION_DEG)
        self.r = np.tile([np.cos(beta), np.sin(beta), 0.0], 2)
        self.kp = (1.0 - ALPHA) * self.k
        n = len(self.k)
        self.branch = np.zeros(n, dtype=int)  # 0 elastic, +1 / -1 yielding in + / - drift
        self.slip = np.zeros(n)
        self.first_yield = np.full(n, np.nan)
        self.phases = np.zeros(n, dtype=int)

    def current_slip(self, q):
        d = self.t @ q
        return np.where(self.branch == 0, self.slip, d - self.branch * np.where(self.branch == 0, 0.0, self.d_y))

    def rhs(self, t, y, ag):
        q, qd = y[:6], y[6:]
        plastic = self.t.T @ (self.kp * self.current_slip(q))
        return np.concatenate([qd, (plastic - self.K @ q - self.C @ qd) / self.m - self.r * ag(t)])

    def events(self):
        functions = []
        for j in range(len(self.k)):
            for side in (1, -1):
                def f(t, y, _ag, j=j, side=side):
                    if self.branch[j] == 0:  # the elastic part reaching +-d_y
                        return self.d_y[j] - side * (self.t[j] @ y[:6] - self.slip[j])
                    if self.branch[j] != side:
                        return 1.0
                    return side * (self.t[j] @ y[6:])  # the drift rate turning: unloading
                f.terminal, f.direction = True, -1
                functions.append(f)
        return functions

    def switch(self, t, y, ag):
        acc = self.rhs(t, y, ag)[6:]
        for j in range(len(self.k)):
            d, rate, rate2 = self.t[j] @ y[:6], self.t[j] @ y[6:], self.t[j] @ acc
            if self.branch[j] == 0:
                e = d - self.slip[j]
                if abs(e) < self.d_y[j] * (1 - 1e-9):
                    continue
                side = 1 if e > 0 else -1
                if side * rate > 0 or (side * rate == 0 and side * rate2 > 0):
                    self.branch[j] = side
                    self.phases[j] += 1
                    if np.isnan(self.first_yield[j]):
                        self.first_yield[j] = t
            elif self.branch[j] * rate <= 1e-13:
                self.slip[j] = d - self.branch[j] * self.d_y[j]
                self.branch[j] = 0

    def run(self, times, accel, out_times):
        ag = lambda t: np.interp(t, times, accel)
        y = np.zeros(12)
        rows, k_out = [], 0
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while True:
                sol = solve_ivp(self.rhs, (t0, b), y, method="DOP853", rtol=1e-12, atol=1e-14, events=self.events(),
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
        return np.array(rows)


HISTORY = [f"B1_f{f}_{c}" for f in (1, 2) for c in ("u_m", "v_m", "phi_rad")]


def history_difference(a, b):
    return np.max(np.abs(a[:, [0, 1, 3, 4]] - b[:, [0, 1, 3, 4]])), np.max(np.abs(a[:, [2, 5]] - b[:, [2, 5]]))


def printed_storey_shears(program, scene):
    """The storey yield shears `pounding check` prints for building 1: [[x, y] per storey] (kN)."""
    check = subprocess.run([program, "check", str(scene)], capture_output=True, text=True)
    if check.returncode != 0:
        return None, check.stderr.strip()[-400:]
    line = next((l for l in check.stdout.splitlines() if "yield shear" in l and " x | y" in l), None)
    if line is None:
        return None, "no storey yield shear line"
    number = r"(\d+(?:\.\d+)?(?:e[+-]?\d+)?)"
    pairs = re.findall(number + r" \| " + number, line)
    values = np.array([[float(x), float(y)] for x, y in pairs])
    if "every storey" in line and len(values) == 1:
        values = np.repeat(values, 2, axis=0)
    return values, line.strip()


def check_case(program, out, label, failures):
    key, values = STRENGTHS[label]
    times, accel = record()
    folder = out / label
    run, message = program_run.run_scene(program, folder, scene_text(key, values), accel, columns=HISTORY)
    if run is None:
        failures.append(f"{label}: {message}")
        return
    peer = Peer(key, values)
    peer_q = peer.run(times, accel, run.t)
    du, dphi = history_difference(run.q, peer_q)
    print(f"{label} ({key} = {list(values)}): periods {np.round(peer.periods, 4).tolist()} s; largest |u, v| "
          f"difference {du:.2e} m, |phi| {dphi:.2e} rad over {len(run.t)} rows; peak |u| "
          f"{np.max(np.abs(peer_q[:, [0, 3]])):.4f} m, |v| {np.max(np.abs(peer_q[:, [1, 4]])):.4f} m, "
          f"|phi| {np.max(np.abs(peer_q[:, [2, 5]])):.2e} rad")
    if len(run.t) != len(peer_q):
        failures.append(f"{label}: the peer gave {len(peer_q)} rows, the program {len(run.t)}")
        return
    if du > HISTORY_M or dphi > HISTORY_RAD:
        failures.append(f"{label}: history differs ({du:.2e} m, {dphi:.2e} rad)")
    with open(folder / "run/yielding.csv") as f:
        springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
    names = sorted((r["column"], int(r["storey"]), r["direction"]) for r in springs)
    expected_names = sorted((f"storey_stiffness[{j + 1}]", j + 1, d) for j in range(2) for d in "xy")
    if names != expected_names:
        failures.append(f"{label}: yielding.csv's springs are {names}, expected {expected_names}")
        return
    worst = {"k": 0.0, "d_y": 0.0, "force": 0.0, "t": 0.0, "slip": 0.0}
    for i in range(len(peer.k)):
        storey, direction = peer.storey[i] + 1, "xy"[peer.direction[i]]
        s = next(r for r in springs if int(r["storey"]) == storey and r["direction"] == direction)
        worst["k"] = max(worst["k"], abs(float(s["stiffness_kN_per_m"]) / peer.k[i] - 1))
        worst["d_y"] = max(worst["d_y"], abs(float(s["yield_drift_m"]) / peer.d_y[i] - 1))
        worst["force"] = max(worst["force"], abs(float(s["yield_force_kN"]) / (peer.k[i] * peer.d_y[i]) - 1))
        if int(s["yield_count"]) != peer.phases[i]:
            failures.append(f"{label} storey {storey} {direction}: {s['yield_count']} yielding phases, "
                            f"the peer {peer.phases[i]}")
            continue
        if peer.phases[i] > 0:
            worst["t"] = max(worst["t"], abs(float(s["first_yield_t_s"]) - peer.first_yield[i]))
            worst["slip"] = max(worst["slip"], abs(float(s["final_slip_m"]) - peer.slip[i]))
    print(f"  springs' yielding phases (storey 1 x, y, storey 2 x, y) {peer.phases.tolist()}, first yield "
          f"{np.round(peer.first_yield, 4).tolist()} s; stiffness {worst['k']:.1e}, yield drift {worst['d_y']:.1e} "
          f"and force {worst['force']:.1e} relative, first yield {worst['t']:.1e} s, final slip {worst['slip']:.1e} m")
    if np.any(peer.phases == 0):
        failures.append(f"{label}: a spring never yields in the peer ({peer.phases.tolist()}): the scene checks less")
    for name, limit in (("k", 1e-12), ("d_y", 1e-12), ("force", 1e-9), ("t", 1e-7), ("slip", 1e-8)):
        if worst[name] > limit:
            failures.append(f"{label}: {name} differs by {worst[name]:.2e} (limit {limit:g})")
    printed, line = printed_storey_shears(program, folder / "scene.toml")
    expected = np.array([[np.sum((peer.k * peer.d_y)[(peer.storey == j) & (peer.direction == d)]) for d in (0, 1)]
                         for j in (0, 1)])
    print(f"  check: {line}")
    if printed is None or printed.shape != expected.shape or np.max(np.abs(printed / expected - 1)) > 5e-5:
        failures.append(f"{label}: check prints storey yield shears {None if printed is None else printed.tolist()}"
                        f", the peer {expected.tolist()}")
    if label == "A":  # the springs matter, and where they act
        for name, variant in (("elastic springs", dict(elastic=True)), ("springs at the CM", dict(centred=True))):
            other = Peer(key, values, **variant).run(times, accel, run.t)
            du_v, dphi_v = history_difference(other, peer_q)
            print(f"  the peer with {name} differs from the yielding peer by {du_v:.2e} m, {dphi_v:.2e} rad")
            if du_v < 1e3 * HISTORY_M or dphi_v < 1e3 * HISTORY_RAD:
                failures.append(f"{label}: the peer with {name} is within 1000 tolerances of the yielding one")


def check_refusal(program, out, failures):
    """K_uv != 0 under a yielding law is refused; the same matrix elastic is not."""
    key, values = STRENGTHS["A"]
    _, accel = record()
    for law in ("bilinear", "elastic"):
        folder = out / f"coupled-{law}"
        folder.mkdir(parents=True, exist_ok=True)
        program_run.write_record(folder / "pulse.txt", accel)
        (folder / "scene.toml").write_text(scene_text(key, values, K_UV_KN_PER_M, law)(folder / "pulse.txt"))
        check = subprocess.run([program, "check", str(folder / "scene.toml")], capture_output=True, text=True)
        message = (check.stderr + check.stdout).strip()
        print(f"K_uv = {K_UV_KN_PER_M:g} kN/m, {law}: exit {check.returncode}"
              + (f": {message.splitlines()[-1][:300]}" if check.returncode != 0 and message else ""))
        if law == "bilinear":
            if check.returncode == 0:
                failures.append("a yielding storey matrix with K_uv != 0 is accepted")
            elif "storey_stiffness" not in message or "K_uv" not in message:
                failures.append(f"the refusal of K_uv != 0 does not name storey_stiffness and K_uv: {message[-300:]}")
        elif check.returncode != 0:
            failures.append(f"the elastic storey matrix with K_uv != 0 is refused: {message[-300:]}")
    # A yielding law without a strength: refused by name (exit 2), not a crash on the missing list.
    folder = out / "no-strength"
    folder.mkdir(parents=True, exist_ok=True)
    program_run.write_record(folder / "pulse.txt", accel)
    text = scene_text(key, values)(folder / "pulse.txt")
    (folder / "scene.toml").write_text(text.replace(f"{key} = [{values[0]!r}, {values[1]!r}]\n", "", 1))
    check = subprocess.run([program, "check", str(folder / "scene.toml")], capture_output=True, text=True)
    message = (check.stderr + check.stdout).strip()
    print(f"no strength key: exit {check.returncode}: {message.splitlines()[-1][:200] if message else ''}")
    if check.returncode != 2 or "hysteresis.yield_drift_ratio" not in message or "missing" not in message:
        failures.append(f"a yielding storey matrix without a strength: exit {check.returncode}: {message[-300:]}")


def main():
    started = time.time()
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    for label in STRENGTHS:
        check_case(program, out, label, failures)
    check_refusal(program, out, failures)
    program_run.finish(failures, started)


if __name__ == "__main__":
    main()
