#!/usr/bin/python3
"""Yielding columns against an independent computation (scipy with events, no code shared).

    tests/solvers/test_yielding_scipy.py POUNDING [OUT]

A one-storey building with two column lines of different size (x = 0: three 0.40 m columns,
x = 16 m: three 0.60 m columns) and its centre of mass 1 m off the plan centre, shaken by a
half-sine pulse along y: its y drift and its rotation couple, and both column lines yield
(bilinear, kinematic hardening 5 %, yield drift 8 mm). A second, elastic building stands 10 m
away (no contact). The program runs it with cvode-bdf at rtol 1e-10; the peer integrates
M q'' + C q' + K q = -M r a_g + sum (1 - alpha) k s_j t_j with scipy's DOP853 over each record
interval, its yield and unloading instants located by solve_ivp's events (a pair of smooth
functions d_y -+ (d - s) for an elastic spring, +-d' for a yielding one), with its own
assembly of K, its own Rayleigh fit and its own branch rules. Checked:
  1. u, v, phi of the yielding building at every history row: within 1e-8 m, 2e-9 rad
     (measured 7e-10 m, 1.1e-10 rad);
  2. per spring the number of yielding phases (equal), the first yield time (within 1e-7 s)
     and the final slip (within 1e-8 m);
  3. the energy audit closes with the hysteretic term (relative residual below 1e-6), and the
     hysteretic energy agrees with the peer's sum of (1 - alpha) k d_y |delta s| (1e-5 relative).
Then yielding with impacts, against a second method: the paper's buildings with bilinear columns
(yield drift 0.2 % of the storey height, 5 % hardening) at gap 0.05 m, where they yield up to a
ductility of 13 and strike 96 times with 13 sustained contacts, run on cvode-bdf and arkode-erk
(an implicit multistep and an explicit Runge-Kutta method) at rtol 1e-10:
  4. the same impacts, pair by pair, at times within 1e-6 s (5.2e-8 s measured), and both energy
     audits close to 1e-7 of the input.
And the needed gap of yielding buildings: `pounding gap` on examples/paper/paper-yielding.toml
(a nonlinear contact-free run, its maxima located as roots) against the event-driven runs:
  5. at the needed gap G + 1e-5 m the buildings do not meet, at G - 1e-5 m they strike;
  6. with --amplification 2, the elastic needed gap is the elastic paper scene's, and the ABS,
     SRSS and DDC rules are those of twice the elastic scene's peaks per level (formulas written
     here), largest over the levels, to 1e-12 m.
And the pounding-induced demand (--contact-free-reference) on examples/paper/paper-yielding.toml
at 0.6 g, where the yielding buildings strike:
  7. its "with" values are the run's own peak drifts and ductilities (equal), its "without" ones
     those of a separate run at a 1 m gap, where the buildings never meet (1e-6 relative), and
     pounding changes some storey's drift by more than 10 %.
"""
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

E_KPA, HEIGHT_M, MASS_T = 3.0e7, 3.5, 400.0
SLAB = (0.0, 0.0, 16.0, 10.0)
CM = np.array([9.0, 5.0])
COLUMNS = [((0.0, y), 0.40) for y in (0.0, 5.0, 10.0)] + [((16.0, y), 0.60) for y in (0.0, 5.0, 10.0)]
YIELD_DRIFT_M, ALPHA, ZETA = 0.008, 0.05, 0.05
PULSE_MPS2, PULSE_S, DT_S, DURATION_S = 6.0, 0.6, 0.005, 3.0


def scene_text(record):
    columns = ", ".join(f"[{x}, {y}, {s}, {s}]" for (x, y), s in COLUMNS)
    x0, y0, x1, y1 = SLAB
    return f"""name = "yielding-peer"
[[building]]
name = "Y"
storeys = 1
storey_height_m = {HEIGHT_M}
slab = [[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]
centre_of_mass = [{CM[0]}, {CM[1]}]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [{columns}]
[building.damping]
ratio = {ZETA}
modes = [1, 3]
[building.hysteresis]
law = "bilinear"
yield_drift_m = {YIELD_DRIFT_M}
hardening_ratio = {ALPHA}

[[building]]
name = "E"
storeys = 1
storey_height_m = {HEIGHT_M}
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
direction_deg = 90.0

[contact]
gap_m = 10.0
restitution = 0.5

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12
"""


def record():
    t = np.arange(0.0, DURATION_S + DT_S / 2, DT_S)
    return t, np.where(t < PULSE_S, PULSE_MPS2 * np.sin(np.pi * np.minimum(t, PULSE_S) / PULSE_S), 0.0)


class Peer:
    """The yielding building alone: q = (u, v, phi) of its slab about the CM."""

    def __init__(self):
        x0, y0, x1, y1 = SLAB
        a, b = x1 - x0, y1 - y0
        # "uniform": J = m (a^2 + b^2)/12 about the slab's centroid (docs/scene-format.md)
        self.m = np.array([MASS_T, MASS_T, MASS_T * (a * a + b * b) / 12.0])
        # springs: (t row over (u, v, phi), k)
        self.t, self.k = [], []
        for (x, y), s in COLUMNS:
            k = 12.0 * E_KPA * s ** 4 / 12.0 / HEIGHT_M ** 3
            arm = np.array([x, y]) - CM
            self.t += [np.array([1.0, 0.0, -arm[1]]), np.array([0.0, 1.0, arm[0]])]
            self.k += [k, k]
        self.t, self.k = np.array(self.t), np.array(self.k)
        self.K = (self.t.T * self.k) @ self.t
        w2, _ = eigh(self.K, np.diag(self.m))
        w = np.sqrt(np.sort(w2))
        a0, a1 = 2 * ZETA * w[0] * w[2] / (w[0] + w[2]), 2 * ZETA / (w[0] + w[2])
        self.C = a0 * np.diag(self.m) + a1 * self.K
        self.r = np.array([0.0, 1.0, 0.0])
        self.kp = (1.0 - ALPHA) * self.k
        n = len(self.k)
        self.branch = np.zeros(n, dtype=int)  # 0 elastic, +1 / -1 yielding up / down
        self.slip = np.zeros(n)
        self.phase_start = np.zeros(n)
        self.first_yield = np.full(n, np.nan)
        self.phases = np.zeros(n, dtype=int)
        self.hysteretic = 0.0

    def slips(self, q):
        d = self.t @ q
        return np.where(self.branch == 0, self.slip, d - self.branch * YIELD_DRIFT_M)

    def rhs(self, t, y, ag):
        q, qd = y[:3], y[3:]
        force = self.t.T @ (self.kp * self.slips(q))
        qdd = (-self.K @ q - self.C @ qd + force) / self.m - self.r * ag(t)
        return np.concatenate([qd, qdd])

    def events(self):
        fs = []
        for j in range(len(self.k)):
            for kind in ("up", "down"):
                def f(t, y, _ag, j=j, kind=kind):
                    d, dd = self.t[j] @ y[:3], self.t[j] @ y[3:]
                    if self.branch[j] == 0:
                        return YIELD_DRIFT_M - (d - self.slip[j]) if kind == "up" else YIELD_DRIFT_M + (d - self.slip[j])
                    if (self.branch[j] > 0) != (kind == "up"):
                        return 1.0
                    return self.branch[j] * dd
                f.terminal, f.direction = True, -1
                fs.append(f)
        return fs

    def switch(self, t, y, ag):
        acc = self.rhs(t, y, ag)[3:]
        for j in range(len(self.k)):
            d, dd, ddd = self.t[j] @ y[:3], self.t[j] @ y[3:], self.t[j] @ acc
            if self.branch[j] == 0:
                e = d - self.slip[j]
                if abs(e) < YIELD_DRIFT_M * (1 - 1e-9):
                    continue
                side = 1 if e > 0 else -1
                if side * dd > 0 or (side * dd == 0 and side * ddd > 0):
                    self.branch[j], self.phase_start[j] = side, self.slip[j]
                    self.phases[j] += 1
                    if np.isnan(self.first_yield[j]):
                        self.first_yield[j] = t
            elif self.branch[j] * dd <= 1e-13:
                s = d - self.branch[j] * YIELD_DRIFT_M
                self.hysteretic += self.kp[j] * YIELD_DRIFT_M * abs(s - self.phase_start[j])
                self.branch[j], self.slip[j] = 0, s

    def run(self, times, accel, out_times):
        ag = lambda t: np.interp(t, times, accel)
        y = np.zeros(6)
        rows, k_out = [], 0
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while True:
                sol = solve_ivp(self.rhs, (t0, b), y, method="DOP853", rtol=1e-11, atol=1e-13, events=self.events(),
                                args=(ag,), dense_output=True)
                while k_out < len(out_times) and out_times[k_out] <= sol.t[-1] + 1e-12:
                    rows.append(sol.sol(out_times[k_out])[:3])
                    k_out += 1
                y = sol.y[:, -1]
                if sol.status != 1:
                    break
                t0 = sol.t[-1]
                self.switch(t0, y, ag)
        for j in range(len(self.k)):
            if self.branch[j] != 0:
                s = self.t[j] @ y[:3] - self.branch[j] * YIELD_DRIFT_M
                self.hysteretic += self.kp[j] * YIELD_DRIFT_M * abs(s - self.phase_start[j])
                self.slip[j] = s
        return np.array(rows)


BILINEAR_PAPER_LAW = 'law = "bilinear"\nyield_drift_ratio = 0.002\nhardening_ratio = 0.05\n'


def paper_with_yielding(folder, law=BILINEAR_PAPER_LAW, name="paper-yielding.toml"):
    root = Path(__file__).resolve().parents[2]
    text = (root / "examples/paper/paper.toml").read_text().replace("../records/", str(root / "examples/records") + "/")
    text = text.replace("[building.damping]", "[building.hysteresis]\n" + law + "[building.damping]")
    path = folder / name
    path.write_text(text)
    return path


def check_second_method(program, out, failures, scene=None, label="yielding", residual_limit=1e-7):
    """The paper's yielding buildings at gap 0.05 m on cvode-bdf and arkode-erk at rtol 1e-10: the same
    impacts pair by pair, at times within 1e-6 s, and both audits closing to residual_limit."""
    scene = scene or paper_with_yielding(out)
    impacts, residuals = {}, {}
    for method in ("cvode-bdf", "arkode-erk"):
        folder = out / f"{scene.stem}-{method}"
        run = subprocess.run([program, "run", str(scene), "--gap", "0.05", "--method", method, "--rtol", "1e-10",
                              "--atol", "1e-12", "--history", "off", "--out", str(folder), "--no-progress"],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        with open(folder / "impacts.csv") as f:
            impacts[method] = [((r["level"], r["striking_building"], r["vertex"], r["struck_edge"]), float(r["t_s"]))
                               for r in csv.DictReader(f)]
        residuals[method] = json.loads((folder / "summary.json").read_text())["energy"]["relative_residual"]
    a, b = impacts["cvode-bdf"], impacts["arkode-erk"]
    worst = max((abs(x[1] - y[1]) for x, y in zip(a, b)), default=0.0)
    print(f"paper scene, {label}, gap 0.05 m: {len(a)} and {len(b)} impacts, largest time difference {worst:.2e} s; "
          f"energy residuals {residuals['cvode-bdf']:.1e}, {residuals['arkode-erk']:.1e}")
    if len(a) != len(b) or len(a) < 20 or any(x[0] != y[0] for x, y in zip(a, b)) or worst > 1e-6:
        failures.append(f"{label} paper scene: the two methods' impacts differ")
    if any(abs(r) > residual_limit for r in residuals.values()):
        failures.append(f"{label} paper scene: an energy audit does not close")


def check_needed_gap_brackets(program, out, scene, failures, *gap_options):
    """`pounding gap` on the scene (with gap_options), then runs 1e-5 m either side of its needed
    gap: the wider must not strike, the narrower must. Returns gap.json."""
    folder = out / f"gap-{scene.stem}"
    run = subprocess.run([program, "gap", str(scene), *gap_options, "--out", str(folder)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    gap = json.loads((folder / "gap.json").read_text())
    needed = gap["needed_gap_m"]
    counts = {}
    for offset in (1e-5, -1e-5):
        run_folder = out / f"{scene.stem}-gap{offset:+g}"
        run = subprocess.run([program, "run", str(scene), "--gap", repr(needed + offset), "--history", "off",
                              "--peaks", "none", "--out", str(run_folder), "--no-progress"], capture_output=True,
                             text=True)
        assert run.returncode == 0, run.stderr
        counts[offset] = json.loads((run_folder / "summary.json").read_text())["impact_count"]
    print(f"needed gap of {scene.name} {needed:.6f} m ({gap['yield_events']} yield events); impacts "
          f"at +1e-5 m: {counts[1e-5]}, at -1e-5 m: {counts[-1e-5]}")
    if counts[1e-5] != 0 or counts[-1e-5] == 0:
        failures.append(f"the needed gap of {scene.name} is not where the runs start to strike")
    return gap


def check_needed_gap(program, out, failures):
    root = Path(__file__).resolve().parents[2]
    gap = check_needed_gap_brackets(program, out, root / "examples/paper/paper-yielding.toml", failures,
                                    "--amplification", "2")
    run = subprocess.run([program, "gap", str(root / "examples/paper/paper.toml"), "--out", str(out / "gap-elastic")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    elastic = json.loads((out / "gap-elastic/gap.json").read_text())
    amplified = gap["amplified_elastic"]
    rules = {"abs_m": 0.0, "srss_m": 0.0, "ddc_m": 0.0}
    for level in elastic["levels"]:
        d1, d2 = (2.0 * d for d in level["peak_towards_m"])
        rules["abs_m"] = max(rules["abs_m"], d1 + d2)
        rules["srss_m"] = max(rules["srss_m"], (d1 * d1 + d2 * d2) ** 0.5)
        rules["ddc_m"] = max(rules["ddc_m"], (d1 * d1 + d2 * d2 - 2.0 * elastic["rho"] * d1 * d2) ** 0.5)
    worst = max(abs(rules[k] - amplified["rules"][k]) for k in rules)
    print(f"amplified elastic rules (x2): {amplified['rules']}; largest difference from the elastic scene's peaks "
          f"{worst:.1e} m; elastic needed gap {amplified['elastic_needed_gap_m']:.6f} m")
    if worst > 1e-12 or amplified["elastic_needed_gap_m"] != elastic["needed_gap_m"]:
        failures.append("the amplified elastic rules are not those of the elastic scene")


def check_pounding_demand(program, out, failures):
    root = Path(__file__).resolve().parents[2]
    scene = str(root / "examples/paper/paper-yielding.toml")
    summaries = {}
    for name, extra in (("demand", ["--contact-free-reference"]), ("apart", ["--gap", "1.0"])):
        folder = out / name
        run = subprocess.run([program, "run", scene, "--pga-g", "0.6", "--history", "off", "--out", str(folder),
                              "--no-progress", *extra], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        summaries[name] = json.loads((folder / "summary.json").read_text())
    demand, apart = summaries["demand"], summaries["apart"]
    assert apart["impact_count"] == 0 and demand["impact_count"] > 0
    worst_without, largest_change = 0.0, 0.0
    for b, building in enumerate(demand["pounding_demand"]["buildings"]):
        yielding = {s["storey"]: s for s in demand["yielding"]["buildings"][b]["storeys"]}
        for storey in building["storeys"]:
            f = storey["storey"] - 1
            for axis in ("x", "y"):
                own = abs(demand["peaks"][b]["floors"][f][f"drift_{axis}"]["value"])
                alone = abs(apart["peaks"][b]["floors"][f][f"drift_{axis}"]["value"])
                entry = storey[f"drift_{axis}"]
                if entry["with"] != own:
                    failures.append(f"pounding demand: B{b + 1} storey {f + 1} drift {axis} 'with' is not the run's")
                worst_without = max(worst_without, abs(entry["without"] - alone) / alone)
                largest_change = max(largest_change, abs(entry["ratio"] - 1.0))
                if storey[f"ductility_{axis}"]["with"] != yielding[f + 1][f"peak_ductility_{axis}"]:
                    failures.append(f"pounding demand: B{b + 1} storey {f + 1} ductility {axis} 'with' is not the run's")
    print(f"pounding demand: 'without' drifts within {worst_without:.1e} of a run 1 m apart; largest change "
          f"{100 * largest_change:.0f} %")
    if worst_without > 1e-6 or largest_change < 0.1:
        failures.append("pounding demand: the contact-free reference is not the run without contact")


def run_one_storey(program, out, law=None):
    """The one-storey scene under the pulse, its columns' law replaced by `law` (TOML lines) when
    given: the record (times, accel), the history times, the program's (u, v, phi) rows, building
    1's yielding.csv rows and summary.json."""
    times, accel = record()
    (out / "pulse.txt").write_text("\n".join(f"{a!r}" for a in accel) + "\n")
    text = scene_text(out / "pulse.txt")
    bilinear = f'law = "bilinear"\nyield_drift_m = {YIELD_DRIFT_M}\nhardening_ratio = {ALPHA}\n'
    assert bilinear in text
    (out / "scene.toml").write_text(text.replace(bilinear, law or bilinear))
    run = subprocess.run([program, "run", str(out / "scene.toml"), "--out", str(out / "run"), "--no-progress"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    with open(out / "run/history.csv") as f:
        hist = list(csv.DictReader(f))
    t_out = np.array([float(r["t_s"]) for r in hist])
    program_q = np.array([[float(r["B1_f1_u_m"]), float(r["B1_f1_v_m"]), float(r["B1_f1_phi_rad"])] for r in hist])
    with open(out / "run/yielding.csv") as f:
        springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
    return times, accel, t_out, program_q, springs, json.loads((out / "run/summary.json").read_text())


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    times, accel, t_out, program_q, springs, summary = run_one_storey(program, out)

    peer = Peer()
    peer_q = peer.run(times, accel, t_out)
    failures = []
    du = np.max(np.abs(program_q[:, :2] - peer_q[:, :2]))
    dphi = np.max(np.abs(program_q[:, 2] - peer_q[:, 2]))
    print(f"largest |u, v| difference {du:.3e} m, |phi| {dphi:.3e} rad over {len(t_out)} rows; "
          f"peak |v| {np.max(np.abs(peer_q[:, 1])):.4f} m, |phi| {np.max(np.abs(peer_q[:, 2])):.2e} rad")
    if du > 1e-8 or dphi > 2e-9:
        failures.append("history differs")
    assert len(springs) == len(peer.k), (len(springs), len(peer.k))
    yielded, worst_t, worst_slip = 0, 0.0, 0.0
    for j, s in enumerate(springs):
        if int(s["yield_count"]) != peer.phases[j]:
            failures.append(f"spring {j} ({s['column']} {s['direction']}): {s['yield_count']} phases, peer {peer.phases[j]}")
            continue
        if peer.phases[j] == 0:
            continue
        yielded += 1
        worst_t = max(worst_t, abs(float(s["first_yield_t_s"]) - peer.first_yield[j]))
        worst_slip = max(worst_slip, abs(float(s["final_slip_m"]) - peer.slip[j]))
        if abs(float(s["first_yield_t_s"]) - peer.first_yield[j]) > 1e-7:
            failures.append(f"spring {j}: first yield {s['first_yield_t_s']} s, peer {peer.first_yield[j]!r}")
        if abs(float(s["final_slip_m"]) - peer.slip[j]) > 1e-8:
            failures.append(f"spring {j}: final slip {s['final_slip_m']} m, peer {peer.slip[j]!r}")
    print(f"{yielded} of {len(springs)} springs yielded, {int(sum(peer.phases))} yielding phases; largest "
          f"first-yield difference {worst_t:.2e} s, final-slip difference {worst_slip:.2e} m")
    if yielded < 6:
        failures.append("the scene should make both column lines yield")
    energy = summary["energy"]
    print(f"hysteretic {energy['hysteretic_kJ']:.6f} kJ, peer {peer.hysteretic:.6f} kJ; "
          f"relative residual {energy['relative_residual']:.2e}")
    if abs(energy["hysteretic_kJ"] - peer.hysteretic) > 1e-5 * peer.hysteretic:
        failures.append("hysteretic energy differs")
    if abs(energy["relative_residual"]) > 1e-6:
        failures.append("energy audit does not close")
    check_second_method(program, out, failures)
    check_needed_gap(program, out, failures)
    check_pounding_demand(program, out, failures)
    program_run.finish(failures)


if __name__ == "__main__":
    main()
