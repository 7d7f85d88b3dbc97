#!/usr/bin/python3
"""`pounding check`'s slab axial stiffness (slab_thickness_m) against E t w / L worked out here.

    tests/cli/test_slab_axial_stiffness.py POUNDING SCENE OUT

SCENE is the paper's scene; the test gives its buildings slab thicknesses of 0.20 and 0.25 m and
the kelvin law, and reads check's line: each slab's E t w / L along the printed direction n (w, L:
the outline's extents across and along n, from the scene's vertices), the two in series, and the
kelvin stiffness as a multiple of it, each to its printed 4 (3) digits. Then one building alone
(its own value, no series), and a thickness of 3 m refused naming the file and slab_thickness_m.
"""
import re
import subprocess
import sys
import tomllib
from pathlib import Path

THICKNESS_M = (0.20, 0.25)


def with_thickness(text, thicknesses):
    """The scene with `slab_thickness_m = t` after each building's E_kPa (None: left out)."""
    parts = text.split("E_kPa")
    out = parts[0]
    for part, t in zip(parts[1:], thicknesses):
        line_end = part.index("\n")
        out += "E_kPa" + part[:line_end + 1] + (f"slab_thickness_m = {t}\n" if t is not None else "") + \
            part[line_end + 1:]
    return out


def expected_kN_per_m(building, thickness_m, n):
    along = [x * n[0] + y * n[1] for x, y in building["slab"]]
    across = [-x * n[1] + y * n[0] for x, y in building["slab"]]
    return building["E_kPa"] * thickness_m * (max(across) - min(across)) / (max(along) - min(along))


def check_line(program, scene_path):
    run = subprocess.run([program, "check", str(scene_path), "--contact-law", "kelvin"], capture_output=True,
                         text=True)
    line = next((l.strip() for l in run.stdout.splitlines() if "slab axial stiffness" in l), "")
    return run, line


def close(printed, expected, digits):
    return abs(float(printed) / expected - 1.0) <= 0.6 * 10.0 ** (1 - digits)


def main():
    program, scene, out = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    out.mkdir(parents=True, exist_ok=True)
    text = scene.read_text().replace('file = "', f'file = "{scene.parent.resolve()}/')
    data = tomllib.loads(text)
    failures = []

    both = out / "both.toml"
    both.write_text(with_thickness(text, THICKNESS_M))
    run, line = check_line(program, both)
    print(f"check: {line}")
    match = re.search(r"along \(([-0-9.e]+), ([-0-9.e]+)\): \S+ ([0-9.e+]+) kN/m, \S+ ([0-9.e+]+) kN/m, in series "
                      r"([0-9.e+]+) kN/m; the kelvin stiffness ([0-9.e+]+) kN/m is ([0-9.e+]+) times", line)
    if run.returncode != 0 or not match:
        failures.append(f"both: exit {run.returncode}, line '{line}' {run.stderr[-300:]}")
    else:
        n = (float(match.group(1)), float(match.group(2)))
        k = [expected_kN_per_m(b, t, n) for b, t in zip(data["building"], THICKNESS_M)]
        series = k[0] * k[1] / (k[0] + k[1])
        kelvin = float(match.group(6))
        print(f"  expected {k[0]:.4g}, {k[1]:.4g}, in series {series:.4g} kN/m, ratio {kelvin / series:.3g}")
        for printed, value, digits in ((match.group(3), k[0], 4), (match.group(4), k[1], 4),
                                       (match.group(5), series, 4), (match.group(7), kelvin / series, 3)):
            if not close(printed, value, digits):
                failures.append(f"both: printed {printed}, expected {value:.6g}")

    one = out / "one.toml"
    one.write_text(with_thickness(text, (None, THICKNESS_M[1])))
    run, line = check_line(program, one)
    print(f"check: {line}")
    match = re.search(r"along \(([-0-9.e]+), ([-0-9.e]+)\): \S+ ([0-9.e+]+) kN/m$", line)
    if run.returncode != 0 or not match:
        failures.append(f"one: exit {run.returncode}, line '{line}'")
    else:
        n = (float(match.group(1)), float(match.group(2)))
        if not close(match.group(3), expected_kN_per_m(data["building"][1], THICKNESS_M[1], n), 4):
            failures.append(f"one: printed {match.group(3)}")

    bad = out / "bad.toml"
    bad.write_text(with_thickness(text, (3.0, None)))
    run = subprocess.run([program, "check", str(bad)], capture_output=True, text=True)
    message = run.stderr + run.stdout
    print(f"bad: exit {run.returncode}: {message.strip().splitlines()[-1] if message.strip() else ''}")
    if run.returncode == 0 or "bad.toml" not in message or "slab_thickness_m" not in message:
        failures.append(f"bad: exit {run.returncode}: {message[-300:]}")

    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
