#!/usr/bin/python3
"""Yielding columns on random scenes: the paper's buildings (examples/paper/paper-yielding.toml)
with a random yield drift, hardening, P-Δ, gap, restitution, contact law, record scale and
method, each run once; with --law bouc-wen the columns are Bouc-Wen with random n in
{1, 2, 5, 20}, beta in [0.1, 0.9] and gamma in (-beta, beta] (A = 1). Checks that no run crashes, hangs or writes NaN, that every run ends with
a named status, and that every completed run's energy audit (with the hysteretic term) closes
to 1e-4 of the input at the default tolerances. Prints a table and a summary line.

    validation/yielding/random_scenes.py [--pounding build/apps/pounding] [--count 60] [--seed 1]
                                         [--law bilinear|bouc-wen] [--out out/yielding-random]
"""
import argparse
import json
import math
import random
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TEMPLATE = ROOT / "examples/paper/paper-yielding.toml"
METHODS = ("cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk")
STATUSES = {"completed", "collapse", "event_limit", "step_limit", "time_limit", "unresolved_overlap"}


def scene_text(rng, law="bilinear"):
    ratio = math.exp(rng.uniform(math.log(5e-4), math.log(2e-2)))
    hardening = rng.choice((0.0, 0.01, 0.05, 0.2, 0.9))
    p_delta = rng.random() < 0.5
    text = TEMPLATE.read_text().replace("../records/", str(ROOT / "examples/records") + "/")
    text = text.replace("yield_drift_ratio = 0.005               # yield drift / storey height",
                        f"yield_drift_ratio = {ratio!r}")
    text = text.replace("hardening_ratio = 0.05                  # post-yield / initial stiffness",
                        f"hardening_ratio = {hardening!r}")
    if p_delta:
        text = text.replace("E_kPa = 3.15e7", "E_kPa = 3.15e7\np_delta = true")
    case = {"yield_drift_ratio": round(ratio, 5), "hardening_ratio": hardening, "p_delta": p_delta}
    if law == "bouc-wen":
        beta = round(rng.uniform(0.1, 0.9), 3)
        gamma = max(round(rng.uniform(-beta, beta), 3), round(-beta + 0.001, 3))  # gamma = -beta is refused
        shape = {"n": rng.choice((1.0, 2.0, 5.0, 20.0)), "beta": beta, "gamma": gamma}
        text = text.replace('law = "bilinear"', 'law = "bouc-wen"\n' + "".join(f"{k} = {v!r}\n" for k, v in shape.items()))
        case.update(shape)
    return text, case


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    parser.add_argument("--count", type=int, default=60)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--law", choices=("bilinear", "bouc-wen"), default="bilinear")
    parser.add_argument("--out", default=str(ROOT / "out/yielding-random"))
    args = parser.parse_args()
    rng = random.Random(args.seed)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    failures, rows = [], []
    for k in range(args.count):
        text, case = scene_text(rng, args.law)
        case.update(gap_m=round(rng.uniform(0.0, 0.3), 4), restitution=rng.choice((0.0, 0.5, 1.0)),
                    law=rng.choice(("impulse", "impulse", "kelvin")), pga_g=round(rng.uniform(0.1, 1.0), 3),
                    method=rng.choice(METHODS))
        folder = out / f"case{k:03d}"
        folder.mkdir(exist_ok=True)
        (folder / "scene.toml").write_text(text)
        command = [args.pounding, "run", str(folder / "scene.toml"), "--gap", repr(case["gap_m"]), "--restitution",
                   repr(case["restitution"]), "--contact-law", case["law"], "--pga-g", repr(case["pga_g"]),
                   "--method", case["method"], "--history", "off", "--max-wall-time", "120", "--no-progress",
                   "--out", str(folder / "run")]
        if case["law"] == "kelvin" and case["restitution"] == 0.0:
            command[command.index("--restitution") + 1] = "0.1"
            case["restitution"] = 0.1
        start = time.monotonic()
        try:
            done = subprocess.run(command, capture_output=True, text=True, timeout=180)
        except subprocess.TimeoutExpired:
            failures.append(f"case {k} {case}: hang")
            continue
        elapsed = time.monotonic() - start
        summary_file = folder / "run/summary.json"
        if done.returncode not in (0, 3) or not summary_file.exists():
            failures.append(f"case {k} {case}: exit {done.returncode} {done.stderr.strip()[-200:]}")
            continue
        text = summary_file.read_text()
        if "NaN" in text or "Infinity" in text:
            failures.append(f"case {k} {case}: NaN in summary.json")
        summary = json.loads(text)
        status, residual = summary["status"], summary["energy"]["relative_residual"]
        if status not in STATUSES:
            failures.append(f"case {k} {case}: status {status}")
        if status == "completed" and abs(residual) > 1e-4:
            failures.append(f"case {k} {case}: energy residual {residual:.2e}")
        ductility = max((max(s["peak_ductility_x"], s["peak_ductility_y"]) for b in summary["yielding"]["buildings"]
                         for s in b["storeys"]), default=0.0)
        rows.append((k, case, status, summary["impact_count"], ductility, residual, elapsed))
        shape = f"n {case['n']:g} b {case['beta']} g {case['gamma']} " if "n" in case else ""
        print(f"{k:3d} {case['method']:<11} {shape}ratio {case['yield_drift_ratio']:<8} alpha {case['hardening_ratio']:<4} "
              f"P-D {int(case['p_delta'])} gap {case['gap_m']:<6} k {case['restitution']:<3} {case['law']:<7} "
              f"{case['pga_g']:<5} g: {status:<12} {summary['impact_count']:5d} impacts, ductility {ductility:9.3f}, "
              f"residual {residual:+.1e}, {elapsed:.1f} s", flush=True)
    statuses = {}
    for row in rows:
        statuses[row[2]] = statuses.get(row[2], 0) + 1
    print(f"{len(rows)} runs, statuses {statuses}, largest |residual| of completed runs "
          f"{max((abs(r[5]) for r in rows if r[2] == 'completed'), default=0.0):.1e}, longest "
          f"{max((r[6] for r in rows), default=0.0):.1f} s; {len(failures)} failures")
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
