#!/usr/bin/python3
"""Contacts at zero gap and in grazing, on every event-driven path (issue 22, defects 1-3).

    tests/solvers/test_zero_gap_and_grazing.py POUNDING [OUT]

1. Two identical buildings at zero gap (examples/beyond-paper/twins-zero-gap.toml). They move
   as one until the slabs' equal turns φ press the corners 28 (1 - cos φ) into each other, so the
   first impact is where that depth first reaches the overlap allowance (1e-9 m) on some floor:
   computed here with scipy (DOP853, rtol 1e-12) for one building, from bench/peers/scipy_paper.py
   (which shares no code with pounding), to 1e-6 s. Every method must complete, take no impact
   at round-off speed (below 1e-12 m/s), and find the same impacts faster than 1e-4 m/s as the
   reference (cvode-bdf at rtol 1e-12).
2. The paper scene at zero gap: every method completes (no pair sinks past the touch band) with
   the same impacts faster than 1e-4 m/s as the reference.
3. The paper scene 1 µm below its critical gap: the one grazing impact is found, and the largest
   overlap reported is one the computed motion has (below the 1e-8 m touch band), not the
   -1e-6 m the slabs would have reached without the impact.
4. Struck to rest beside a held corner (issue 46): the paper scene at zero gap with k = 0, and the
   long pulse at zero gap with k = 0.2 (validation/extreme/cases/pulse-gap-0.toml). No impact with
   k = 0 may leave its contact closing (ġ⁺ below -1e-12 m/s): bringing the held corner of the same
   slabs to rest must not pull the struck one in again, which was struck again 1 nm deeper each
   time, 5 nm in all. The largest overlap is at most the allowance (a masked pair that never
   reopened is caught at its floor root, 1 nm down; 2 % for the floor's own start below zero).
"""
import csv
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "peers"))
from scipy_paper import building, record  # noqa: E402  (the independent model)

METHODS = ["exact", "cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk"]
REFERENCE = ["--method", "cvode-bdf", "--rtol", "1e-12", "--atol", "1e-14"]
SIGNIFICANT_MPS = 1e-4      # impacts compared across methods
ROUND_OFF_MPS = 1e-12       # no impact may be this slow
TIME_TOL_S = 1e-5           # matched significant impacts, any method at its default tolerance
FIRST_IMPACT_TOL_S = 1e-6   # twins' first impact against the scipy closed form
ALLOWANCE_M = 1e-9          # overlap_allowance_m: a masked pair's root sits this far below zero
TOUCH_BAND_M = 1e-8         # contact_tolerance_m

failures = []


def check(condition, message):
    print(("ok    " if condition else "FAIL  ") + message)
    if not condition:
        failures.append(message)


def run(pounding, scene, out, *args):
    subprocess.run([pounding, "run", str(scene), "--out", str(out), "--history", "off", *args],
                   check=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "impacts.csv") as f:
        impacts = [(float(r["t_s"]), int(r["level"]), float(r["approach_velocity_mps"])) for r in csv.DictReader(f)]
    return summary, impacts


def significant(impacts):
    return [(t, level) for t, level, v in impacts if v > SIGNIFICANT_MPS]


def compare_to_reference(name, method, impacts, reference):
    mine, theirs = significant(impacts), significant(reference)
    same_count = len(mine) == len(theirs)
    worst = max((abs(a[0] - b[0]) for a, b in zip(mine, theirs) if a[1] == b[1]), default=0.0)
    same_levels = all(a[1] == b[1] for a, b in zip(mine, theirs))
    check(same_count and same_levels and worst <= TIME_TOL_S,
          f"{name} {method}: {len(mine)} impacts faster than {SIGNIFICANT_MPS} m/s (reference {len(theirs)}), "
          f"same levels {same_levels}, largest time difference {worst:.2e} s (tolerance {TIME_TOL_S} s)")


def twins_first_impact_s():
    """One building's free motion; the first t at which 28 (1 - cos φ) reaches the allowance."""
    b = building(10, [(0, 8), (28, 8), (28, 33), (0, 33)], (12.6, 19.25), 845, 810, [0, 7, 14, 21, 28],
                 [8, 13, 18, 23, 28, 33], 0.50, 0.572683)
    n = 30
    m_inv_k, m_inv_c = np.linalg.solve(b["m"], b["k"]), np.linalg.solve(b["m"], b["c"])
    influence = np.zeros(n)
    influence[0::3] = 1.0  # u along x
    t_rec, a_rec = record()
    centres_m = 12.6 + 15.4  # distance between the two slabs' centres of mass

    def events(floor):
        def depth(_, y):
            return centres_m * 2.0 * math.sin(y[3 * floor + 2] / 2.0) ** 2 - ALLOWANCE_M
        depth.terminal, depth.direction = True, 1
        return depth

    y = np.zeros(2 * n)
    for k in range(len(t_rec) - 1):  # one piece of the piecewise-linear record at a time
        t0, t1, a0, a1 = t_rec[k], t_rec[k + 1], a_rec[k], a_rec[k + 1]

        def rhs(t, state):
            a_g = a0 + (a1 - a0) * (t - t0) / (t1 - t0)
            q, q_rate = state[:n], state[n:]
            return np.concatenate([q_rate, -m_inv_k @ q - m_inv_c @ q_rate - influence * a_g])

        sol = solve_ivp(rhs, (t0, t1), y, method="DOP853", rtol=1e-12, atol=1e-16,
                        events=[events(f) for f in range(10)])
        hits = [e[0] for e in sol.t_events if len(e)]
        if hits:
            return min(hits)
        y = sol.y[:, -1]
    return math.inf


def main():
    pounding = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    twins = ROOT / "examples" / "beyond-paper" / "twins-zero-gap.toml"
    paper = ROOT / "examples" / "paper" / "paper.toml"

    t_first = twins_first_impact_s()
    _, twins_reference = run(pounding, twins, out / "twins-reference", *REFERENCE)
    _, paper_reference = run(pounding, paper, out / "paper0-reference", "--gap", "0", *REFERENCE)
    for method in METHODS:
        summary, impacts = run(pounding, twins, out / f"twins-{method}", "--method", method)
        check(summary["status"] == "completed", f"twins {method}: status {summary['status']} {summary['status_detail']}")
        slowest = min((v for _, _, v in impacts), default=math.inf)
        check(slowest > ROUND_OFF_MPS, f"twins {method}: slowest impact {slowest:.2e} m/s (> {ROUND_OFF_MPS})")
        first = impacts[0][0] if impacts else math.inf
        check(abs(first - t_first) <= FIRST_IMPACT_TOL_S,
              f"twins {method}: first impact {first:.9f} s, closed form with scipy {t_first:.9f} s")
        compare_to_reference("twins", method, impacts, twins_reference)

        summary, impacts = run(pounding, paper, out / f"paper0-{method}", "--gap", "0", "--method", method)
        check(summary["status"] == "completed", f"paper gap 0 {method}: status {summary['status']} "
              f"{summary['status_detail']}")
        compare_to_reference("paper gap 0", method, impacts, paper_reference)

        grazing = ROOT / "validation" / "extreme" / "cases" / "grazing-minus-1e-6.toml"
        summary, impacts = run(pounding, grazing, out / f"grazing-{method}", "--method", method)
        overlap = summary["statistics"]["max_interpenetration_m"]
        check(summary["status"] == "completed" and len(impacts) == 1 and overlap <= TOUCH_BAND_M,
              f"grazing -1e-6 {method}: {summary['status']}, {len(impacts)} impact(s), largest overlap {overlap:.2e} m")

        for scene, args, name in ((paper, ["--gap", "0", "--restitution", "0"], "paper gap 0 k 0"),
                                  (ROOT / "validation" / "extreme" / "cases" / "pulse-gap-0.toml",
                                   ["--restitution", "0.2"], "pulse gap 0 k 0.2")):
            folder = out / f"{name.replace(' ', '-')}-{method}"
            summary, _ = run(pounding, scene, folder, "--method", method, *args)
            overlap = summary["statistics"]["max_interpenetration_m"]
            with open(folder / "impacts.csv") as f:
                closing = min((float(r["separation_velocity_mps"]) for r in csv.DictReader(f)), default=0.0)
            plastic = "--restitution" in args and args[args.index("--restitution") + 1] == "0"
            check(summary["status"] == "completed" and overlap <= 1.02 * ALLOWANCE_M
                  and (not plastic or closing >= -ROUND_OFF_MPS),
                  f"{name} {method}: {summary['status']}, largest overlap {overlap:.3e} m (at most "
                  f"{1.02 * ALLOWANCE_M:.2e}), most closing separation {closing:.2e} m/s")
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
