#!/usr/bin/python3
"""A column that fails in shear and loses its stiffness (column_shear_failure = "lose-stiffness"),
against the closed form of an SDOF that goes free at the failure.

    tests/solvers/test_shear_failure_loses_stiffness.py POUNDING [OUT]

The building of test_shear_failure_closed_form.py (one storey, four equal columns at the corners of
a square slab, the CM at the plan centre, undamped), shaken along x by a constant a_g = A from
t = 0, with a shear capacity V_c below the columns' yield force: all four reach it together while
elastic, at t* = arccos(1 - 4 V_c/(m A))/w, and lose their stiffness along x there, so that the
slab then moves as a free mass,

    u = -(m A / 4k)(1 - cos w t)              for t <= t*,
    u = u* + v* (t - t*) - A (t - t*)^2 / 2   after,

until its drift passes 10 % of the storey and the run ends as a collapse. Checked: every history
row's u within 1e-8 m of the closed form (a run that kept the stiffness would swing back within
0.2 s, by centimetres); the run's status `collapse`, its detail naming the storey, at a time past
the closed form's instant of |u| = 0.1 H and within 0.05 s of it; the four x springs' failure at
t* (1e-7 s) and their force 0 after (peak force V_c: the largest at step ends and events); the y
springs never failing; and the energy audit closing (its relative residual below 1e-6: the energy
the columns held when they failed, k u*^2/2 each, is counted as dissipated). The same scene with
column_shear_failure = "report" keeps its stiffness (u swings back, no collapse).
"""
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

E_KPA, MASS_T, HEIGHT_M, SIDE_M, COLUMN_M = 3.0e7, 500.0, 4.0, 10.0, 0.5
A_MPS2, DT_S, DURATION_S = 2.0, 0.01, 1.5
YIELD_KN, CAPACITY_KN = 450.0, 300.0
K_COLUMN = 12.0 * E_KPA * COLUMN_M ** 4 / 12.0 / HEIGHT_M ** 3  # kN/m, per column and direction


def scene(record, failure):
    s = SIDE_M
    return f"""name = "shear-failure-free"
[[building]]
name = "S"
storeys = 1
storey_height_m = {HEIGHT_M}
slab = [[0.0, 0.0], [{s}, 0.0], [{s}, {s}], [0.0, {s}]]
centre_of_mass = [{s / 2}, {s / 2}]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [[0.0, 0.0, {COLUMN_M}, {COLUMN_M}], [{s}, 0.0, {COLUMN_M}, {COLUMN_M}],
           [{s}, {s}, {COLUMN_M}, {COLUMN_M}], [0.0, {s}, {COLUMN_M}, {COLUMN_M}]]
column_shear_capacity_kN = {CAPACITY_KN}
column_shear_failure = "{failure}"
[building.damping]
ratio = 0.0
[building.hysteresis]
law = "bilinear"
yield_drift_m = {YIELD_KN / K_COLUMN!r}
hardening_ratio = 0.05

[[building]]
name = "far"
storeys = 1
storey_height_m = 4.0
slab = [[20.0, 0.0], [30.0, 0.0], [30.0, 10.0], [20.0, 10.0]]
centre_of_mass = [25.0, 5.0]
mass_t = 500.0
polar_moment_tm2 = "uniform"
E_kPa = 3.0e7
frame_factor = 1.0
columns = [[20.0, 0.0, 0.5, 0.5], [30.0, 0.0, 0.5, 0.5], [20.0, 10.0, 0.5, 0.5], [30.0, 10.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S}

[contact]
gap_m = 10.0
restitution = 0.5

[output]
history_interval_s = 0.005

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12
"""


def closed_form(t):
    w = np.sqrt(4.0 * K_COLUMN / MASS_T)
    static = MASS_T * A_MPS2 / (4.0 * K_COLUMN)
    t_fail = np.arccos(1.0 - CAPACITY_KN / (K_COLUMN * static)) / w
    u_fail, v_fail = -static * (1.0 - np.cos(w * t_fail)), -static * w * np.sin(w * t_fail)
    tau = np.maximum(t - t_fail, 0.0)
    u = np.where(t <= t_fail, -static * (1.0 - np.cos(w * t)), u_fail + v_fail * tau - 0.5 * A_MPS2 * tau ** 2)
    # |u| = 0.1 H after the failure: A tau^2/2 - v* tau - u* = 0.1 H (u*, v* < 0)
    tau_c = (v_fail + np.sqrt(v_fail ** 2 + 2.0 * A_MPS2 * (0.1 * HEIGHT_M + u_fail))) / A_MPS2
    return u, t_fail, t_fail - tau_c if tau_c < 0 else t_fail + tau_c


def run(program, folder, failure):
    folder.mkdir(parents=True, exist_ok=True)
    samples = int(round(DURATION_S / DT_S)) + 1
    (folder / "step.txt").write_text("\n".join([repr(A_MPS2)] * samples) + "\n")
    (folder / "scene.toml").write_text(scene(folder / "step.txt", failure))
    done = subprocess.run([program, "run", str(folder / "scene.toml"), "--out", str(folder / "run"), "--no-progress"],
                          capture_output=True, text=True)
    summary_file = folder / "run/summary.json"
    if not summary_file.is_file():
        return None, None, f"exit {done.returncode}: {(done.stderr + done.stdout)[-400:]}"
    with open(folder / "run/history.csv") as f:
        rows = list(csv.DictReader(f))
    history = np.array([[float(r["t_s"]), float(r["B1_f1_u_m"])] for r in rows])
    return json.loads(summary_file.read_text()), history, None


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    failures = []
    summary, history, message = run(program, out / "lose-stiffness", "lose-stiffness")
    if summary is None:
        failures.append(f"lose-stiffness: {message}")
    else:
        expected, t_fail, t_collapse = closed_form(history[:, 0])
        worst = np.max(np.abs(history[:, 1] - expected))
        print(f"lose-stiffness: failure at {t_fail:.9f} s, |u| = 0.1 H at {t_collapse:.6f} s (closed form); "
              f"history within {worst:.1e} m over {len(history)} rows to {history[-1, 0]:.4f} s; "
              f"status {summary['status']} ({summary.get('status_detail', '')[:90]})")
        if worst > 1e-8:
            failures.append(f"lose-stiffness: u differs from the closed form by {worst:.2e} m (1e-8)")
        end_s = summary["end_s"] if "end_s" in summary else history[-1, 0]
        if summary["status"] != "collapse" or "storey 1" not in summary.get("status_detail", "") or \
                not (t_collapse <= end_s <= t_collapse + 0.05):
            failures.append(f"lose-stiffness: status {summary['status']} at {end_s} s, expected collapse just after "
                            f"{t_collapse:.6f} s")
        with open(out / "lose-stiffness/run/yielding.csv") as f:
            springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
        for s in springs:
            failed = s["shear_failure_t_s"] != ""
            if s["direction"] == "x" and (not failed or abs(float(s["shear_failure_t_s"]) - t_fail) > 1e-7 or
                                          abs(float(s["peak_force_kN"]) / CAPACITY_KN - 1.0) > 1e-7):
                failures.append(f"lose-stiffness: {s['column']} x: failure {s['shear_failure_t_s']}, peak force "
                                f"{s['peak_force_kN']} (expected {t_fail:.9f} s, {CAPACITY_KN} kN)")
            if s["direction"] == "y" and failed:
                failures.append(f"lose-stiffness: {s['column']} y failed with no force")
        energy = summary["energy"]
        print(f"  energy: input {energy['input_kJ']:.4f} kJ, hysteretic {energy['hysteretic_kJ']:.4f} kJ "
              f"(closed form {4 * 0.5 * CAPACITY_KN ** 2 / K_COLUMN:.4f} kJ released by the failures), "
              f"relative residual {energy['relative_residual']:.1e}")
        if abs(energy["relative_residual"]) > 1e-6:
            failures.append(f"lose-stiffness: the energy audit leaves {energy['relative_residual']:.2e} of the input")
    summary, history, message = run(program, out / "report", "report")
    if summary is None or summary["status"] != "completed" or np.min(history[:, 1]) < -0.05:
        failures.append(f"report: a column that keeps its stiffness should swing back ({message or summary['status']})")
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
