#!/usr/bin/python3
"""Column strength from the section ([building.flexural_strength]) and a column's own strength and
shear capacity (`columns` entries as tables) against strain compatibility solved here.

    tests/model/test_flexural_strength_section.py POUNDING [OUT]

In N, mm, MPa, for a column b x h swaying along x (along y: h for b), D = b the depth along the sway,
W = h the width, two bar layers of A_s = rho_l D W / 2 at d' = cover_ratio D from the faces, N the
axial compression (given, or the storey's gravity share g x (the floor masses it carries) / (its
number of columns)), at the concrete's ultimate strain 0.003 (ACI 318: stress block 0.85 f'c over
a = beta_1 c, beta_1 = 0.85 up to f'c = 28 MPa, less 0.05 per 7 MPa, at least 0.65; steel
E_s = 200 GPa, stresses within +-f_y), the neutral axis c solved here (scipy's brentq) from

    0.85 f'c a W + A_s (f_s(d') + f_s(D - d')) = N,   f_s(y) = clip(E_s 0.003 (c - y) / c, -f_y, f_y)
    M_n = 0.85 f'c a W (D - a) / 2 + A_s (f_s(d') - f_s(D - d')) (D / 2 - d')
    F_y = 2 M_n / H                                  (double curvature over the storey height H)
    N_b = the section's N at c_b = 0.003 (D - d') / (0.003 + f_y / E_s)   (the balanced load)

A two-storey building (4.0 m and 3.2 m) of 0.4 x 0.4 m and 0.6 x 0.3 m columns with rho_l a storey,
one column given as a table with its own yield_force_kN and shear_capacity_kN, and a column grid
with its own yield force: every column spring's yield_force_kN in yielding.csv within 1e-9
relative of F_y (or of the force given), the table column's shear capacity its own and the others'
the building's, and `pounding check`'s storey yield shears the sums (5 printed digits). Three
cases: the gravity share with the default cover (the compression layer short of yield: F_y below
the both-layers-yield closed form A_s f_y (D - 2 d') + N (D - a) / 2 by more than 1 %, which the
test requires, so that it tells the two apart), a given axial load with f'c above 28 MPa (beta_1
below 0.85), f_y = 500 MPa and another cover, and a load at which both layers yield (there the
closed form and the solution here must agree, 1e-9). Then the refusals: an axial load above the
balanced load (named with its N_b, which the test computes), the section with a storey strength
key, a longitudinal_ratio list of the wrong length, the section on elastic columns, an unknown key
of a column table: each a non-zero exit naming the scene file and the field.
"""
import csv
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from scipy.optimize import brentq

HEIGHTS_M, MASSES_T, G = (4.0, 3.2), (300.0, 200.0), 9.81
SECTION_COLUMNS = [((0.0, y), 0.4, 0.4) for y in (0.0, 5.0, 10.0)] + [((16.0, y), 0.6, 0.3) for y in (0.0, 10.0)]
OWN = {"x": 16.0, "y": 5.0, "b_m": 0.5, "h_m": 0.5, "yield_force_kN": [260.0, 180.0], "shear_capacity_kN": 310.0}
GRID = {"x": [8.0], "y": [0.0, 10.0], "b_m": 0.35, "h_m": 0.35, "yield_force_kN": 140.0}
N_COLUMNS = len(SECTION_COLUMNS) + 1 + 2
CASES = {
    "gravity": {"longitudinal_ratio": [0.02, 0.012], "steel_yield_strength_MPa": 420.0, "concrete_strength_MPa": 25.0},
    "given": {"longitudinal_ratio": [0.015, 0.01], "steel_yield_strength_MPa": 500.0, "concrete_strength_MPa": 40.0,
              "axial_load_kN": 900.0, "cover_ratio": 0.12},
    "yielded": {"longitudinal_ratio": [0.02, 0.012], "steel_yield_strength_MPa": 420.0, "concrete_strength_MPa": 25.0,
                "axial_load_kN": 1200.0},
}
CAPACITY_KN = 250.0  # column_shear_capacity_kN for the columns without their own


def axial_kN(storey, keys):
    return keys.get("axial_load_kN", sum(MASSES_T[storey - 1:]) * (G / N_COLUMNS))


E_S, EPS_CU = 200000.0, 0.003


def section_strength(storey, b_m, h_m, direction, keys):
    """(F_y in kN, N_b in kN, the both-layers-yield closed form's F_y in kN) by the docstring's rules."""
    fc, fy, cover = keys["concrete_strength_MPa"], keys["steel_yield_strength_MPa"], keys.get("cover_ratio", 0.1)
    depth, width = (1000.0 * b_m, 1000.0 * h_m) if direction == "x" else (1000.0 * h_m, 1000.0 * b_m)
    layer = keys["longitudinal_ratio"][storey - 1] * depth * width / 2.0
    d1, d2 = cover * depth, depth - cover * depth
    beta_1 = min(0.85, max(0.65, 0.85 - 0.05 * (fc - 28.0) / 7.0))

    def stress(c, y):
        return min(fy, max(-fy, E_S * EPS_CU * (c - y) / c))

    def axial(c):
        return 0.85 * fc * min(beta_1 * c, depth) * width + layer * (stress(c, d1) + stress(c, d2))

    def moment(c):
        a = min(beta_1 * c, depth)
        return 0.85 * fc * a * width * (depth - a) / 2.0 + layer * (stress(c, d1) - stress(c, d2)) * (depth / 2 - d1)

    n = 1000.0 * axial_kN(storey, keys)
    c = brentq(lambda c: axial(c) - n, 1e-9 * depth, 10.0 * depth, xtol=1e-14 * depth, rtol=1e-15)
    balanced = axial(EPS_CU * d2 / (EPS_CU + fy / E_S))
    a = n / (0.85 * fc * width)
    closed = layer * fy * (depth - 2.0 * d1) + n * (depth - a) / 2.0
    height = HEIGHTS_M[storey - 1]
    return 2.0 * moment(c) / 1e6 / height, balanced / 1000.0, 2.0 * closed / 1e6 / height


def toml_value(value):
    return "[" + ", ".join(repr(v) for v in value) + "]" if isinstance(value, list) else repr(value)


def scene(record, keys, hysteresis="law = \"bilinear\"", extra_column=""):
    columns = [f"[{x}, {y}, {b}, {h}]" for (x, y), b, h in SECTION_COLUMNS]
    columns.append("{" + ", ".join(f"{k} = {toml_value(v)}" for k, v in OWN.items()) + extra_column + "}")
    section = "\n".join(f"{k} = {toml_value(v)}" for k, v in keys.items())
    grid = "\n".join(f"{k} = {toml_value(v)}" for k, v in GRID.items())
    return f"""name = "flexural-strength-section"
[[building]]
name = "S"
storeys = 2
storey_height_m = [{HEIGHTS_M[0]}, {HEIGHTS_M[1]}]
slab = [[0.0, 0.0], [16.0, 0.0], [16.0, 10.0], [0.0, 10.0]]
centre_of_mass = [8.0, 5.0]
mass_t = [{MASSES_T[0]}, {MASSES_T[1]}]
polar_moment_tm2 = "uniform"
E_kPa = 3.0e7
frame_factor = 1.0
columns = [{", ".join(columns)}]
column_shear_capacity_kN = {CAPACITY_KN}
[[building.column_grid]]
{grid}
[building.hysteresis]
{hysteresis}
[building.flexural_strength]
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


def expected_spring(spring, keys):
    """(yield force, shear capacity) in kN that the spring should have."""
    storey, direction, name = int(spring["storey"]), spring["direction"], spring["column"]
    if name.startswith("column_grid"):
        return GRID["yield_force_kN"], CAPACITY_KN
    index = int(re.search(r"\d+", name).group()) - 1
    if index == len(SECTION_COLUMNS):
        return OWN["yield_force_kN"][storey - 1], OWN["shear_capacity_kN"]
    (_, b_m, h_m) = SECTION_COLUMNS[index]
    return section_strength(storey, b_m, h_m, direction, keys)[0], CAPACITY_KN


def closed_form_gap(keys):
    """The largest relative difference between F_y and the both-layers-yield closed form over the
    section columns."""
    gaps = []
    for storey in (1, 2):
        for _, b_m, h_m in SECTION_COLUMNS:
            for direction in "xy":
                force, _, closed = section_strength(storey, b_m, h_m, direction, keys)
                gaps.append(abs(closed / force - 1.0))
    return max(gaps)


def write_scene(out, name, keys, **kwargs):
    folder = out / name
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "pulse.txt").write_text("\n".join(["0.0", "1.0", "0.0", "0.0"]) + "\n")
    (folder / "scene.toml").write_text(scene(folder / "pulse.txt", keys, **kwargs))
    return folder


def check_case(program, out, name, failures):
    keys = CASES[name]
    folder = write_scene(out, name, keys)
    run = subprocess.run([program, "run", str(folder / "scene.toml"), "--out", str(folder / "run"), "--no-progress"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        failures.append(f"{name}: exit {run.returncode}: {(run.stderr + run.stdout)[-400:]}")
        return
    with open(folder / "run/yielding.csv") as f:
        springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
    worst_force = worst_capacity = 0.0
    storey_sums = {}
    for s in springs:
        force, capacity = expected_spring(s, keys)
        worst_force = max(worst_force, abs(float(s["yield_force_kN"]) / force - 1.0))
        worst_capacity = max(worst_capacity, abs(float(s["shear_capacity_kN"]) / capacity - 1.0))
        key = (int(s["storey"]), s["direction"])
        storey_sums[key] = storey_sums.get(key, 0.0) + force
    print(f"{name}: {len(springs)} springs; yield forces off by {worst_force:.1e}, capacities by "
          f"{worst_capacity:.1e} relative; storey yield shears "
          + ", ".join(f"{k[0]}{k[1]} {v:.1f} kN" for k, v in sorted(storey_sums.items())))
    if len(springs) != 2 * 2 * N_COLUMNS or worst_force > 1e-9 or worst_capacity > 1e-12:
        failures.append(f"{name}: {len(springs)} springs, yield forces off by {worst_force:.2e}, capacities by "
                        f"{worst_capacity:.2e} relative (1e-9, 1e-12)")
    gap = closed_form_gap(keys)
    print(f"  the both-layers-yield closed form differs from strain compatibility by up to {gap:.1e}")
    if (name == "yielded") != (gap < 1e-9) or (name == "gravity" and gap < 1e-2):
        failures.append(f"{name}: the closed form differs by {gap:.2e}: expected below 1e-9 only where both layers "
                        f"yield, and above 1e-2 for the gravity case")
    check = subprocess.run([program, "check", str(folder / "scene.toml")], capture_output=True, text=True).stdout
    line = next((l.strip() for l in check.splitlines() if "storey yield shear" in l), "")
    printed = re.findall(r"(\d+(?:\.\d+)?) \| (\d+(?:\.\d+)?)", line)
    print(f"  check: {line}")
    if len(printed) != 2 or "2 M_n / H" not in line:
        failures.append(f"{name}: check's line '{line}' does not give both storeys' yield shears from the sections")
    for storey, numbers in enumerate(printed[:2], start=1):
        for direction, value in zip("xy", numbers):
            if abs(float(value) / storey_sums[(storey, direction)] - 1.0) > 5e-5:
                failures.append(f"{name}: check prints storey {storey} {direction} {value} kN, expected "
                                f"{storey_sums[(storey, direction)]:.5g}")


def refused(program, out, name, keys, expected, failures, **kwargs):
    folder = write_scene(out, name, keys, **kwargs)
    run = subprocess.run([program, "check", str(folder / "scene.toml")], capture_output=True, text=True)
    message = run.stderr + run.stdout
    ok = run.returncode != 0 and "scene.toml" in message and all(e in message for e in expected)
    print(f"{name}: exit {run.returncode}: {message.strip().splitlines()[-1] if message.strip() else ''}")
    if not ok:
        failures.append(f"{name}: expected a refusal naming scene.toml and {expected}, got exit {run.returncode}: "
                        f"{message[-400:]}")


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    failures = []
    for name in CASES:
        check_case(program, out, name, failures)
    # An axial load above the balanced load of every section column: the first refused is columns[1]
    # (0.4 x 0.4 m) in storey 1 along x, with its N_b.
    heavy = {**CASES["gravity"], "axial_load_kN": 2200.0}
    _, balanced_kN, _ = section_strength(1, 0.4, 0.4, "x", heavy)
    refused(program, out, "above-balanced", heavy,
            ["flexural_strength.axial_load_kN", "balanced load", f"{balanced_kN:.5g} kN"], failures)
    refused(program, out, "with-storey-strength", CASES["gravity"],
            ["hysteresis.yield_drift_ratio", "flexural_strength"], failures,
            hysteresis="law = \"bilinear\"\nyield_drift_ratio = 0.005")
    refused(program, out, "ratio-list", {**CASES["gravity"], "longitudinal_ratio": [0.02, 0.02, 0.02]},
            ["flexural_strength.longitudinal_ratio", "3 values"], failures)
    refused(program, out, "elastic", CASES["gravity"], ["flexural_strength", "yielding columns"], failures,
            hysteresis="law = \"elastic\"")
    refused(program, out, "column-key", CASES["gravity"], ["columns[6]", "yield_drift"], failures,
            extra_column=", yield_drift = 0.01")
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
