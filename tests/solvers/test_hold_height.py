#!/usr/bin/python3
"""contact.hold_height_m reaches the solver and does what model.md §7 says (issue 23's example of
adding a setting: one row of the [contact] table plus the line that passes it on).

    tests/solvers/test_hold_height.py POUNDING [OUT]

The paper scene (k = 0.5) run as given and with hold_height_m = 1e-3 m:
1. both runs are the same up to the first impact the raised threshold holds: same times (to
   1e-12 s) and approach speeds (to 1e-9 relative);
2. that impact starts a sustained contact although its rebound k·v⁻ is far above
   hold_velocity_mps (so the velocity rule alone would not hold it), and the default run bounces
   off it instead;
3. the raised threshold leaves fewer impacts (the bounce sequence is cut short);
4. a value outside (0, 1e-3] m is refused naming contact.hold_height_m (exit 2).
"""
import csv
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PAPER = ROOT / "examples/paper/paper.toml"


def scene_with(folder, extra):
    text = PAPER.read_text().replace("../records/", str(ROOT / "examples/records") + "/")
    text = text.replace("restitution = 0.5", "restitution = 0.5\n" + extra)
    path = Path(folder) / "scene.toml"
    path.write_text(text)
    return path


def impacts(program, scene, out):
    run = subprocess.run([program, "run", str(scene), "--history", "off", "--out", str(out)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    with open(Path(out) / "impacts.csv") as f:
        return list(csv.DictReader(f))


def main(program, out):
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        default = impacts(program, scene_with(work, ""), out / "default")
        held = impacts(program, scene_with(work, "hold_height_m = 1e-3"), out / "held")
        first = next(i for i, row in enumerate(held) if row["starts_sustained_contact"] == "1")
        for a, b in zip(default[:first + 1], held[:first + 1]):
            assert abs(float(a["t_s"]) - float(b["t_s"])) < 1e-12, (a["t_s"], b["t_s"])
            assert abs(float(a["approach_velocity_mps"]) / float(b["approach_velocity_mps"]) - 1) < 1e-9
        rebound = 0.5 * float(held[first]["approach_velocity_mps"])
        assert rebound > 100 * 1e-3, f"impact {first} rebounds at {rebound} m/s: the velocity rule would hold it"
        assert default[first]["starts_sustained_contact"] == "0", "the default threshold holds it too"
        assert len(held) < len(default), (len(held), len(default))
        print(f"held from impact {first} at {held[first]['t_s']} s (rebound {rebound:.3f} m/s); "
              f"{len(held)} impacts against {len(default)}")
        for bad in ("0.0", "2e-3", "-1e-8"):
            run = subprocess.run([program, "check", str(scene_with(work, f"hold_height_m = {bad}"))],
                                 capture_output=True, text=True)
            assert run.returncode == 2 and "contact.hold_height_m" in run.stderr and "(0, 0.001] m" in run.stderr, run.stderr
    print("hold_height_m: 4 checks passed")


if __name__ == "__main__":
    main(sys.argv[1], Path(sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp()))
