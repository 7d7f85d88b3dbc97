#!/usr/bin/python3
"""`pounding plan` against closed forms.

    tests/cli/test_plan.py POUNDING [OUT]

A one-storey building with two lines of square columns (x = 0: three of 0.40 m, x = 16 m: three
of 0.60 m) and an elastic neighbour: the centre of stiffness lies at x = 16 b2^4 / (b1^4 + b2^4)
(a square column's stiffness goes as b^4, the same in x and y) and y = 5 m (symmetric), within
1e-9 m; plan.json holds the slabs, columns, centres of mass, floor elevations, the one level and
its candidates as the scene gives them; plan.png is drawn; a missing scene exits 2.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENE = """name = "two-lines"
[[building]]
name = "Y"
storeys = 1
storey_height_m = 3.5
slab = [[0.0, 0.0], [16.0, 0.0], [16.0, 10.0], [0.0, 10.0]]
centre_of_mass = [9.0, 5.0]
mass_t = 400.0
polar_moment_tm2 = "uniform"
E_kPa = 3e7
frame_factor = 1.0
columns = [[0, 0, 0.4, 0.4], [0, 5, 0.4, 0.4], [0, 10, 0.4, 0.4], [16, 0, 0.6, 0.6], [16, 5, 0.6, 0.6],
           [16, 10, 0.6, 0.6]]
[building.damping]
ratio = 0.05
modes = [1, 3]

[[building]]
name = "E"
storeys = 1
storey_height_m = 3.5
slab = [[16.3, 0.0], [26.3, 0.0], [26.3, 10.0], [16.3, 10.0]]
centre_of_mass = [21.3, 5.0]
mass_t = 400.0
polar_moment_tm2 = "uniform"
E_kPa = 3e7
frame_factor = 1.0
columns = [[16.3, 0.0, 0.5, 0.5], [26.3, 0.0, 0.5, 0.5], [16.3, 10.0, 0.5, 0.5], [26.3, 10.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "peer-at2"
units = "g"

[contact]
gap_m = 0.3
restitution = 0.5
"""


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp(prefix="plan-"))
    out.mkdir(parents=True, exist_ok=True)
    scene = out / "two-lines.toml"
    scene.write_text(SCENE.replace("{record}", str(ROOT / "examples/records/elcentro1940_ns_0.02s.AT2")))
    failures = []
    done = subprocess.run([program, "plan", str(scene), "--out", str(out / "plan")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    plan = json.loads((out / "plan/plan.json").read_text())
    y = plan["buildings"][0]
    expected_x = 16.0 * 0.6 ** 4 / (0.4 ** 4 + 0.6 ** 4)
    cs = y["centres_of_stiffness"][0]
    print(f"centre of stiffness ({cs[0]:.9f}, {cs[1]:.9f}) m; closed form ({expected_x:.9f}, 5) m")
    if abs(cs[0] - expected_x) > 1e-9 or abs(cs[1] - 5.0) > 1e-9:
        failures.append("the centre of stiffness is not the closed form's")
    if (y["centre_of_mass"] != [9.0, 5.0] or len(y["columns"]) != 6 or y["floor_elevations_m"] != [3.5]
            or y["slab"][2] != [16.0, 10.0]):
        failures.append(f"plan.json does not hold the scene's building: {y}")
    if len(plan["levels"]) != 1 or plan["gap_m"] != 0.3 or not plan["candidates"]:
        failures.append("plan.json's levels, gap or candidates are not the scene's")
    if "centre of stiffness of storey 1" not in done.stdout:
        failures.append("the printout does not give the centre of stiffness")
    image = out / "plan/plan.png"
    if "No plot" not in done.stdout and not (image.is_file() and image.stat().st_size > 10_000):
        failures.append("plan.png was not drawn")
    missing = subprocess.run([program, "plan", str(out / "nowhere.toml")], capture_output=True, text=True)
    if missing.returncode != 2 or "no such scene file" not in missing.stderr:
        failures.append(f"a missing scene: exit {missing.returncode}, {missing.stderr.strip()}")
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
