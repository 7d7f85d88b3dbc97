#!/usr/bin/python3
"""tools/plot_run.py's signed gap against independent facts of the paper scene: the centres of
mass it recovers from history.csv equal the scene's, every pair's gap at rest is the scene's
clear gap, and at every impact row one pair of the impact's level is closed (CTest: test_plot_run).

    tests/tools/test_plot_run.py build/apps/pounding
"""
import importlib.util
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("plot_run", ROOT / "tools/plot_run.py")
plot_run = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plot_run)


def check(condition, message):
    if not condition:
        sys.exit(f"FAILED: {message}")


def main():
    pounding = sys.argv[1]
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch) / "run"
        subprocess.run([pounding, "run", str(ROOT / "examples/paper/paper.toml"), "--out", str(folder)],
                       check=True, stdout=subprocess.DEVNULL)
        summary, columns = plot_run.read_run(folder)

    # examples/paper/paper.toml: centre_of_mass = [-10.8, 11.0] and [12.8, 19.25] (gap 0.20 m).
    for building, centre in ((1, (-10.8, 11.0)), (2, (12.8, 19.25))):
        found = plot_run.centre_of_mass(plot_run.slab_history(summary, columns, building, 7))
        check(np.allclose(found, centre, atol=1e-6), f"B{building} centre of mass {found}, scene {centre}")

    t, impacts = columns["t_s"], 0
    for level in summary["history_levels"]:
        floors = dict(zip((1, 2), summary["levels"][level - 1]["floors"]))
        gaps = plot_run.pair_gaps(summary, columns, level, floors)
        check(len(gaps) == 2, f"level {level}: {len(gaps)} pairs, the paper scene has 2 on each level")
        for pair in gaps:
            check(abs(pair["g"][0] - summary["gap_m"]) < 1e-12, f"level {level}: gap at rest {pair['g'][0]}")
        for impact in (i for i in summary["impacts"] if i["level"] == level):
            row = int(np.argmin(np.abs(t - impact["t_s"])))
            check(t[row] == impact["t_s"], f"no history row at the impact at {impact['t_s']} s")
            closest = min(abs(pair["g"][row]) for pair in gaps)
            check(closest < 1e-9, f"impact at {impact['t_s']} s: smallest |g| {closest:.1e} m")  # solver tolerance
            impacts += 1
    check(impacts == summary["impact_count"], f"{impacts} impacts checked of {summary['impact_count']}")
    print(f"ok: centres of mass recovered; gaps at rest {summary['gap_m']} m; {impacts} impacts closed")


if __name__ == "__main__":
    main()
