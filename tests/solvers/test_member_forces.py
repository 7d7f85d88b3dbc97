#!/usr/bin/python3
"""Storey and column forces ([output] member_forces, docs/model.md §2c) against forces computed here.

    tests/solvers/test_member_forces.py POUNDING [OUT]

The test computes every force itself from what history.csv says the floors did (u, v, phi of each
floor, written with every digit) and from the columns' sizes: a column's stiffness 12 E I / H^3
along x with I = h b^3 / 12 (b along x) and along y with b h^3 / 12, its drift along x
du - (y_c - y_CM) dphi and along y dv + (x_c - x_CM) dphi, its shear k times that, its end moment
V H / 2, the storey's shears their sums and its torque sum (dx V_y - dy V_x) about the CM. It
shares no code with the program. Cases:
  A. an elastic two-storey building of unequal storeys and column lines of different sizes, its
     CM off the plan centre, under a half-sine pulse at 30 degrees: every storey and column force
     of every history row within 1e-9 of the largest of its kind (relative), and each peak in
     summary.json no smaller than the largest |value| of the history rows (1e-9) and at most 1e-3
     above it (rows every 1 ms; a turning point between rows rises above them by about
     (pi dt / T)^2 / 2 = 1e-4 here);
  B. the same building with elastic-perfectly-plastic columns (alpha = 0) of a storey yield shear
     V_1 under a strong pulse along x (no twist: the CM on the columns' line of symmetry y = 5 m; storey 2 far stronger): the storey's peak
     shear is V_1 (1e-9 relative), each column's peak its share k_c V_1 / sum k (1e-9), its end
     moment that times H / 2, and no history row passes V_1;
  C. a building of storey matrices (storey_stiffness, with a torsional coupling K_uphi): the
     storey forces are K dq of the given matrix (1e-9); with elastic-perfectly-plastic storey
     springs the storey's peak |V_x| is its yield shear (1e-9 relative);
     `pounding report` shows a member-forces table, a row per storey;
  D. the opt-in: without the key history.csv and summary.json hold no member force; with
     contact_free_reference and a contact, pounding_demand gives each storey's shears with and
     without contact and their ratio.
"""
import csv
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

E_KPA, MASS_T, HEIGHTS_M = 3.0e7, 400.0, (4.0, 3.2)
COLUMNS = [((0.0, y), 0.40, 0.40) for y in (0.0, 5.0, 10.0)] + [((16.0, y), 0.55, 0.45) for y in (0.0, 5.0, 10.0)]
DT_S, DURATION_S = 0.005, 2.0
YIELD_SHEAR_KN = 1800.0
STOREY_MATRICES = ([[2.0e5, 0.0, 3.0e5], [0.0, 1.6e5, -2.0e5], [3.0e5, -2.0e5, 9.0e6]],
                   [[1.5e5, 0.0, 1.0e5], [0.0, 1.2e5, 0.0], [1.0e5, 0.0, 7.0e6]])


def column_stiffness(b, h, height):
    """k along x and along y (kN/m) of a fixed-fixed column, b along x."""
    bending = 12.0 * E_KPA / height ** 3
    return bending * h * b ** 3 / 12.0, bending * b * h ** 3 / 12.0


def pulse(amplitude, duration_s):
    t = np.arange(0.0, DURATION_S + DT_S / 2, DT_S)
    return np.where(t < duration_s, amplitude * np.sin(np.pi * np.minimum(t, duration_s) / duration_s), 0.0)


def scene_text(cm, direction_deg, hysteresis="", matrices=None, gap_m=10.0, output=""):
    def text(record):
        if matrices is None:
            stiffness = f"E_kPa = {E_KPA}\nframe_factor = 1.0\ncolumns = [" + ", ".join(f"[{x}, {y}, {b}, {h}]" for (x, y), b, h in COLUMNS) + "]"
        else:
            stiffness = "storey_stiffness = [" + ", ".join(str(m) for m in matrices) + "]"
        return f"""name = "member-forces"
[[building]]
name = "Y"
storeys = 2
storey_height_m = [{HEIGHTS_M[0]}, {HEIGHTS_M[1]}]
slab = [[0.0, 0.0], [16.0, 0.0], [16.0, 10.0], [0.0, 10.0]]
centre_of_mass = [{cm[0]}, {cm[1]}]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
{stiffness}
[building.damping]
ratio = 0.05
modes = [1, 3]
{hysteresis}
[[building]]
name = "E"
storeys = 1
storey_height_m = 4.0
slab = [[{16.0 + gap_m}, 0.0], [{26.0 + gap_m}, 0.0], [{26.0 + gap_m}, 10.0], [{16.0 + gap_m}, 10.0]]
centre_of_mass = [{21.0 + gap_m}, 5.0]
mass_t = 100.0
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [[{16.0 + gap_m}, 0.0, 0.5, 0.5], [{26.0 + gap_m}, 0.0, 0.5, 0.5], [{16.0 + gap_m}, 10.0, 0.5, 0.5], [{26.0 + gap_m}, 10.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S}
direction_deg = {direction_deg}

[contact]
gap_m = {gap_m}
restitution = 0.5

[output]
history_interval_s = 0.001
{output}
[output.floor_history]
Y = [2]

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12
"""
    return text


def read_history(folder):
    with open(folder / "run/history.csv") as f:
        rows = list(csv.DictReader(f))
    return {name: np.array([float(r[name]) for r in rows]) for name in rows[0]}


def expected_forces(history, cm, matrices=None):
    """{column name: values} the test computes from the floors' motion."""
    expected = {}
    below = np.zeros((3, len(history["t_s"])))
    for storey in (1, 2):
        q = np.array([history[f"B1_f{storey}_{c}"] for c in ("u_m", "v_m", "phi_rad")])
        dq = q - below
        below = q
        prefix = f"B1_s{storey}_"
        height = HEIGHTS_M[storey - 1]
        if matrices is not None:
            force = np.array(matrices[storey - 1]) @ dq
            for name, values in zip(("Vx_kN", "Vy_kN", "T_kNm"), force):
                expected[prefix + name] = values
            continue
        vx_sum, vy_sum, torque = 0.0, 0.0, 0.0
        for n, ((x, y), b, h) in enumerate(COLUMNS, start=1):
            kx, ky = column_stiffness(b, h, height)
            dx, dy = x - cm[0], y - cm[1]
            vx, vy = kx * (dq[0] - dy * dq[2]), ky * (dq[1] + dx * dq[2])
            expected[f"{prefix}col{n}_Vx_kN"], expected[f"{prefix}col{n}_Vy_kN"] = vx, vy
            expected[f"{prefix}col{n}_Mx_kNm"], expected[f"{prefix}col{n}_My_kNm"] = vx * height / 2, vy * height / 2
            vx_sum, vy_sum, torque = vx_sum + vx, vy_sum + vy, torque + dx * vy - dy * vx
        expected[prefix + "Vx_kN"], expected[prefix + "Vy_kN"], expected[prefix + "T_kNm"] = vx_sum, vy_sum, torque
    return expected


def summary_peaks(summary):
    """{history column name: (value, t_s)} of summary.json's member_forces for building Y."""
    peaks = {}
    building = summary["member_forces"]["buildings"][0]
    for storey in building["storeys"]:
        prefix = f"B1_s{storey['storey']}_"
        for key, peak in storey.items():
            if isinstance(peak, dict):
                peaks[prefix + key] = (peak["value"], peak["t_s"])
        for n, column in enumerate(storey.get("columns", []), start=1):
            for key, peak in column.items():
                if isinstance(peak, dict):
                    peaks[f"{prefix}col{n}_{key}"] = (peak["value"], peak["t_s"])
    return peaks


def run(program, folder, text, accel, failures, options=("--member-forces",)):
    result, error = program_run.run_scene(program, folder, text, accel, options=options, columns=("t_s",))
    if error:
        failures.append(f"{folder.name}: {error}")
        return None
    return result


def compare_histories(case, history, expected, failures):
    for name, values in expected.items():
        if name not in history:
            failures.append(f"{case}: history.csv has no column {name}")
            continue
        scale = max(np.max(np.abs(values)), 1e-12)
        worst = np.max(np.abs(history[name] - values)) / scale
        if not worst <= 1e-9:
            failures.append(f"{case}: {name} differs by {worst:.2e} of its largest (limit 1e-9)")


def case_a(program, out, failures):
    cm = (9.0, 5.0)
    result = run(program, out / "A", scene_text(cm, 30.0), pulse(5.0, 0.6), failures)
    if result is None:
        return
    history = read_history(out / "A")
    expected = expected_forces(history, cm)
    compare_histories("A", history, expected, failures)
    peaks = summary_peaks(result.summary)
    if set(peaks) != set(expected):
        failures.append(f"A: summary.json's member_forces name {sorted(set(peaks) ^ set(expected))[:4]} differently")
    worst = 0.0
    for name, (value, t_s) in peaks.items():
        largest = np.max(np.abs(history.get(name, np.zeros(1))))
        rise = (abs(value) - largest) / max(largest, 1e-12)
        worst = max(worst, rise)
        if not -1e-9 <= rise <= 1e-3:
            failures.append(f"A: peak {name} {value:.6g} against the history's largest {largest:.6g} ({rise:.2e})")
        if not 0.0 <= t_s <= DURATION_S:
            failures.append(f"A: peak {name} at {t_s} s, outside the run")
    print(f"A: {len(expected)} forces over {len(history['t_s'])} rows; peaks at most {worst:.2e} above the rows")
    report = subprocess.run([str(program), "report", str(out / "A/run")], capture_output=True, text=True)
    if "has no Python" in report.stderr:  # a build without the Python module (the sanitizer pass)
        print(f"A: skip report.html: {report.stderr.strip()}")
        return
    page = (out / "A/run/report.html").read_text() if report.returncode == 0 else ""
    table = page.split('id="member-forces"')[1].split("</table>")[0] if 'id="member-forces"' in page else ""
    rows = table.count("<tr>") - 1  # the header's
    if rows != 3:  # Y's two storeys and E's one
        failures.append(f"A: report.html's member-forces table has {rows} storey rows, not 3 ({report.stderr[-200:]})")


def case_b(program, out, failures):
    cm = (8.0, 5.0)
    hysteresis = f"[building.hysteresis]\nlaw = \"bilinear\"\nyield_shear_kN = [{YIELD_SHEAR_KN}, 2.0e4]\nhardening_ratio = 0.0\n"
    result = run(program, out / "B", scene_text(cm, 0.0, hysteresis), pulse(4.0, 0.5), failures)
    if result is None:
        return
    history = read_history(out / "B")
    peaks = summary_peaks(result.summary)
    storey = peaks.get("B1_s1_Vx_kN", (0.0, 0.0))[0]
    if not abs(abs(storey) - YIELD_SHEAR_KN) <= 1e-9 * YIELD_SHEAR_KN:
        failures.append(f"B: storey 1's peak |Vx| {abs(storey)!r} kN, not its yield shear {YIELD_SHEAR_KN}")
    if not np.max(np.abs(history["B1_s1_Vx_kN"])) <= YIELD_SHEAR_KN * (1 + 1e-9):
        failures.append(f"B: a history row's |Vx| {np.max(np.abs(history['B1_s1_Vx_kN']))} passes the yield shear")
    kx = [column_stiffness(b, h, HEIGHTS_M[0])[0] for _, b, h in COLUMNS]
    for n, k in enumerate(kx, start=1):
        share = k * YIELD_SHEAR_KN / sum(kx)
        value = abs(peaks.get(f"B1_s1_col{n}_Vx_kN", (0.0, 0.0))[0])
        moment = abs(peaks.get(f"B1_s1_col{n}_Mx_kNm", (0.0, 0.0))[0])
        if not abs(value - share) <= 1e-9 * share:
            failures.append(f"B: column {n}'s peak |Vx| {value!r} kN, not its share {share!r}")
        if not abs(moment - share * HEIGHTS_M[0] / 2) <= 1e-9 * share * HEIGHTS_M[0]:
            failures.append(f"B: column {n}'s peak |Mx| {moment!r} kNm, not {share * HEIGHTS_M[0] / 2!r}")
    print(f"B: storey 1 plateau {abs(storey):.6f} kN (yield shear {YIELD_SHEAR_KN})")


def case_c(program, out, failures):
    cm = (8.0, 5.0)
    result = run(program, out / "C", scene_text(cm, 30.0, matrices=STOREY_MATRICES), pulse(5.0, 0.6), failures)
    if result is None:
        return
    history = read_history(out / "C")
    expected = expected_forces(history, cm, STOREY_MATRICES)
    compare_histories("C", history, expected, failures)
    if any("col" in name for name in history if name.startswith("B1_s")):
        failures.append("C: a building of storey matrices has column forces")
    # Yielding storey springs (alpha = 0): the x spring carries the storey's whole x shear (the
    # split of a matrix with K_uv = 0 is exact), so its plateau is the storey's yield shear.
    hysteresis = f"[building.hysteresis]\nlaw = \"bilinear\"\nyield_shear_kN = [{YIELD_SHEAR_KN / 4}, 5.0e3]\nhardening_ratio = 0.0\n"
    result = run(program, out / "C2", scene_text(cm, 0.0, hysteresis, matrices=STOREY_MATRICES), pulse(2.0, 0.5),
                 failures)
    if result is None:
        return
    storey = abs(summary_peaks(result.summary).get("B1_s1_Vx_kN", (0.0, 0.0))[0])
    if not abs(storey - YIELD_SHEAR_KN / 4) <= 1e-9 * YIELD_SHEAR_KN:
        failures.append(f"C: yielding storey springs' peak |Vx| {storey!r} kN, not the yield shear {YIELD_SHEAR_KN / 4}")
    print(f"C: storey matrices, {len(expected)} forces; yielding storey spring plateau {storey:.6f} kN")


def case_d(program, out, failures):
    cm = (8.0, 5.0)
    result = run(program, out / "D0", scene_text(cm, 0.0), pulse(5.0, 0.6), failures, options=())
    if result is not None:
        history = read_history(out / "D0")
        if any(name.startswith("B1_s") for name in history) or "member_forces" in result.summary:
            failures.append("D: member forces written without being asked for")
    result = run(program, out / "D1", scene_text(cm, 0.0, gap_m=0.01, output="contact_free_reference = true"),
                 pulse(5.0, 0.6), failures)
    if result is None:
        return
    if result.summary["impact_count"] == 0:
        failures.append("D: the buildings 0.01 m apart did not meet")
    storeys = result.summary["pounding_demand"]["buildings"][0]["storeys"]
    peaks = summary_peaks(result.summary)
    for storey in storeys:
        shear = storey.get("storey_shear_x_kN")
        if shear is None:
            failures.append(f"D: pounding_demand storey {storey['storey']} has no storey_shear_x_kN")
            continue
        mine = abs(peaks[f"B1_s{storey['storey']}_Vx_kN"][0])
        if not abs(shear["with"] - mine) <= 1e-12 * mine:
            failures.append(f"D: storey {storey['storey']}'s shear with contact {shear['with']} is not member_forces' {mine}")
        if not abs(shear["ratio"] - shear["with"] / shear["without"]) <= 1e-12:
            failures.append(f"D: storey {storey['storey']}'s ratio {shear['ratio']} is not with / without")
    print("D: opt-in and pounding_demand's storey shears")


def main():
    started = time.time()
    program = Path(sys.argv[1])
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    failures = []
    for case in (case_a, case_b, case_c, case_d):
        case(program, out, failures)
    program_run.finish(failures, started)


if __name__ == "__main__":
    main()
