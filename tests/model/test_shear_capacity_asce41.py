#!/usr/bin/python3
"""Column shear capacity from the section ([building.shear_capacity], ASCE 41-17 Eq. 10-3) against
the equation written out here.

    tests/model/test_shear_capacity_asce41.py POUNDING [OUT]

In SI units (N, mm, MPa), for a column b x h swaying along x (the section's depth along the sway b;
along y, h):

    V = k_nl [alpha A_v f_yt d / s + lambda (0.5 sqrt(f'c) / (M/Vd)) sqrt(1 + N / (0.5 sqrt(f'c) A_g)) 0.8 A_g]

with d = (d/h ratio) x depth, A_g = b h, M/Vd = (H/2)/d bounded to [2, 4], alpha = 1 for s/d <= 0.75,
0 for s/d >= 1 and linear between, lambda = 1, N the axial compression: given, or the storey's
gravity share g x (the floor masses it carries) / (its number of columns). A two-storey building
(4.0 m and 1.8 m) with three 0.4 x 0.4 m and three 0.6 x 0.3 m columns covers M/Vd clamped at 4
(storey 1), clamped at 2 (storey 2, the 0.6 m depth along x), between the bounds, and alpha between
0 and 1 (the 0.3 m depth along y: s/d = 0.83). Checked, with the gravity share and with a given
axial load, effective depth ratio and ductility factor: every column spring's shear_capacity_kN
in yielding.csv within 1e-12 relative of the equation, and `pounding check`'s per-storey ranges
x | y to their 5 printed digits.
"""
import csv
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

HEIGHTS_M, MASSES_T, G = (4.0, 1.8), (300.0, 200.0), 9.81
COLUMNS = [((0.0, y), 0.4, 0.4) for y in (0.0, 5.0, 10.0)] + [((16.0, y), 0.6, 0.3) for y in (0.0, 5.0, 10.0)]
SECTION = {"concrete_strength_MPa": 25.0, "transverse_yield_strength_MPa": 420.0, "transverse_area_mm2": 157.0,
           "transverse_spacing_mm": 200.0}
CASES = {"gravity": {}, "given": {"axial_load_kN": 650.0, "effective_depth_ratio": 0.9, "ductility_factor": 0.85}}


def capacity_kN(storey, b_m, h_m, direction, keys):
    """ASCE 41-17 Eq. 10-3 in SI units, as the docstring writes it."""
    fc, fyt = keys["concrete_strength_MPa"], keys["transverse_yield_strength_MPa"]
    area_v, s = keys["transverse_area_mm2"], keys["transverse_spacing_mm"]
    ratio, k_nl = keys.get("effective_depth_ratio", 0.8), keys.get("ductility_factor", 1.0)
    depth = 1000.0 * (b_m if direction == "x" else h_m)
    d = ratio * depth
    gross = 1e6 * b_m * h_m
    m_vd = min(4.0, max(2.0, 1000.0 * HEIGHTS_M[storey - 1] / 2.0 / d))
    alpha = min(1.0, max(0.0, (1.0 - s / d) / 0.25))
    n_kN = keys.get("axial_load_kN", G * sum(MASSES_T[storey - 1:]) / len(COLUMNS))
    steel = alpha * area_v * fyt * d / s
    concrete = 0.5 * math.sqrt(fc) / m_vd * math.sqrt(1.0 + 1000.0 * n_kN / (0.5 * math.sqrt(fc) * gross)) * 0.8 * gross
    return k_nl * (steel + concrete) / 1000.0


def scene(record, keys):
    columns = ", ".join(f"[{x}, {y}, {b}, {h}]" for (x, y), b, h in COLUMNS)
    section = "\n".join(f"{k} = {v!r}" for k, v in keys.items())
    return f"""name = "shear-capacity-asce41"
[[building]]
name = "C"
storeys = 2
storey_height_m = [{HEIGHTS_M[0]}, {HEIGHTS_M[1]}]
slab = [[0.0, 0.0], [16.0, 0.0], [16.0, 10.0], [0.0, 10.0]]
centre_of_mass = [8.0, 5.0]
mass_t = [{MASSES_T[0]}, {MASSES_T[1]}]
polar_moment_tm2 = "uniform"
E_kPa = 3.0e7
frame_factor = 1.0
columns = [{columns}]
[building.hysteresis]
law = "bilinear"
yield_drift_ratio = 0.005
[building.shear_capacity]
{section}

[[building]]
name = "far"
storeys = 1
storey_height_m = 4.0
slab = [[26.0, 0.0], [36.0, 0.0], [36.0, 10.0], [26.0, 10.0]]
centre_of_mass = [31.0, 5.0]
mass_t = 300.0
polar_moment_tm2 = "uniform"
E_kPa = 3.0e7
frame_factor = 1.0
columns = [[26.0, 0.0, 0.5, 0.5], [36.0, 0.0, 0.5, 0.5], [26.0, 10.0, 0.5, 0.5], [36.0, 10.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = 0.01

[contact]
gap_m = 10.0
restitution = 0.5
"""


def check_case(program, out, name, failures):
    keys = {**SECTION, **CASES[name]}
    folder = out / name
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "pulse.txt").write_text("\n".join(["0.0", "1.0", "0.0", "0.0"]) + "\n")
    (folder / "scene.toml").write_text(scene(folder / "pulse.txt", keys))
    run = subprocess.run([program, "run", str(folder / "scene.toml"), "--out", str(folder / "run"), "--no-progress"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        failures.append(f"{name}: exit {run.returncode}: {(run.stderr + run.stdout)[-400:]}")
        return
    with open(folder / "run/yielding.csv") as f:
        springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
    worst, expected_ranges = 0.0, {}
    for s in springs:
        index = int(re.search(r"\d+", s["column"]).group()) - 1
        (_, b_m, h_m), storey = COLUMNS[index], int(s["storey"])
        expected = capacity_kN(storey, b_m, h_m, s["direction"], keys)
        worst = max(worst, abs(float(s["shear_capacity_kN"]) / expected - 1.0))
        expected_ranges.setdefault((storey, s["direction"]), []).append(expected)
    print(f"{name}: {len(springs)} springs, capacities "
          f"{min(min(v) for v in expected_ranges.values()):.1f} to {max(max(v) for v in expected_ranges.values()):.1f} kN; "
          f"largest difference {worst:.1e} relative")
    if len(springs) != 2 * 2 * len(COLUMNS) or worst > 1e-12:
        failures.append(f"{name}: {len(springs)} springs, capacities off by {worst:.2e} relative (1e-12)")
    check = subprocess.run([program, "check", str(folder / "scene.toml")], capture_output=True, text=True).stdout
    line = next((l.strip() for l in check.splitlines() if "column shear capacity" in l), "")
    printed = re.findall(r"(\d+(?:\.\d+)?)-(\d+(?:\.\d+)?) \| (\d+(?:\.\d+)?)-(\d+(?:\.\d+)?)", line)
    print(f"  check: {line}")
    for storey, numbers in enumerate(printed, start=1):
        for direction, (low, high) in zip("xy", (numbers[:2], numbers[2:])):
            values = expected_ranges[(storey, direction)]
            if abs(float(low) / min(values) - 1) > 5e-5 or abs(float(high) / max(values) - 1) > 5e-5:
                failures.append(f"{name}: check prints storey {storey} {direction} {low}-{high}, expected "
                                f"{min(values):.5g}-{max(values):.5g}")
    if len(printed) != 2:
        failures.append(f"{name}: check's line '{line}' does not give both storeys' ranges")


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    failures = []
    for name in CASES:
        check_case(program, out, name, failures)
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
