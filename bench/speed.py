#!/usr/bin/python3
"""Solver time and accuracy of every method on the paper scene against the scipy peer, and how
the cost grows with building size: the measurements issue 12's targets are stated in.

    bench/speed.py [--pounding build/apps/pounding] [--repeat 5] [--out bench/results] [--sizes 10,20,40,60]
                   [--size-gap 0.5]

Writes speed.md (tables to paste into the README) and speed.json into --out, with the commit
and the CPU they were measured on. Every run is timed twice: with minimal outputs (`--history off
--peaks none`: impacts and the energy audit only, the solver's own cost, which the issue's targets
mean) and with full outputs (the defaults: history.csv and every peak group, what a user's run
costs). Times are medians of --repeat runs:
- solver time: the run's own `statistics.wall_time_s` (the solution path and its recorder, no
  scene reading, model assembly or file writing);
- CPU: the whole `pounding run` process (user + system), for comparison with the peer's CPU.
Methods with a `form` setting run in both forms (physical, modal). The size table also gives the
steps and rhs/Jacobian counts. On a shared machine compare CPU, not solver (wall) time.
Measure on a quiet machine: other work on the cores inflates every number.
"""
import argparse
import json
import math
import platform
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench/peers"))
import scipy_paper  # noqa: E402  (the independent peer)
from machine import commit, cpu_model  # noqa: E402

PAPER = ROOT / "examples/paper/paper.toml"
SIZES = [10, 20, 40, 60]  # storeys of each building in the size ladder
SIZE_METHODS = ["cvode-bdf", "cvode-bdf/modal", "exact"]
# Outputs of the two timings: impacts and energy only, and the defaults (history, every peak).
OUTPUTS = {"min": ["--history", "off", "--peaks", "none"], "full": []}


def timed_run(pounding, scene, out, *extra):
    """One `pounding run`: (summary, process CPU s)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run([pounding, "run", str(scene), "--out", str(out), *extra], stdout=subprocess.DEVNULL)
    if done.returncode not in (0, 3):  # 3: a run status other than completed, still timed
        sys.exit(f"pounding run {scene} {' '.join(extra)} failed with exit code {done.returncode}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return json.loads((Path(out) / "summary.json").read_text()), cpu


def timed_outputs(pounding, scene, out, repeat, *extra):
    """`repeat` runs with each of OUTPUTS: the last minimal run's summary and the medians
    {min,full}_{solver,cpu}_s."""
    times, summary = {}, None
    for outputs, options in OUTPUTS.items():
        solver, cpu = [], []
        for k in range(repeat):
            summary_k, c = timed_run(pounding, scene, f"{out}-{outputs}-{k}", *extra, *options)
            solver.append(summary_k["statistics"]["wall_time_s"])
            cpu.append(c)
        summary = summary_k if outputs == "min" else summary
        times[f"{outputs}_solver_s"] = statistics.median(solver)
        times[f"{outputs}_cpu_s"] = statistics.median(cpu)
    return summary, times


def impact_error_s(summary, peer_impacts):
    """Largest impact-time difference to the peer over the impacts before the first hold."""
    ours = []
    for impact in summary["impacts"]:
        ours.append(impact["t_s"])
        if impact.get("starts_sustained_contact"):
            break
    if len(ours) != len(peer_impacts):
        return math.nan
    return max(abs(a - b["t_s"]) for a, b in zip(ours, peer_impacts))


def registry_methods(pounding):
    """Every method of the program's registry (`pounding methods --json`), in its order, as
    "name" and, for those with a `form` setting, also "name/modal"."""
    done = subprocess.run([pounding, "methods", "--json"], check=True, capture_output=True, text=True)
    names = []
    for m in json.loads(done.stdout):
        names.append(m["name"])
        if "form" in m["settings"]:
            names.append(m["name"] + "/modal")
    return names


def method_args(method):
    """Command-line options of a "name" or "name/modal" entry."""
    name, _, form = method.partition("/")
    return ["--method", name] + (["--form", form] if form else [])


def paper_table(pounding, repeat, scratch):
    t_rec, a_rec = scipy_paper.record()
    peer_cpu = []
    for _ in range(repeat):
        start = time.process_time()
        peer, _, _ = scipy_paper.solve(scipy_paper.Scene(0.20, 0.5), t_rec, a_rec, 1e-10, 1e-12, 1e-3)
        peer_cpu.append(time.process_time() - start)
    peer_s = statistics.median(peer_cpu)
    rows = [dict(method="scipy DOP853 peer (rtol 1e-10)", min_solver_s=peer_s, min_cpu_s=peer_s, full_solver_s=peer_s,
                 full_cpu_s=peer_s, error_s=0.0, impacts=len(peer), status="up to the first hold")]
    for method in registry_methods(pounding):
        summary, times = timed_outputs(pounding, PAPER, Path(scratch) / method.replace('/', '-'), repeat,
                                       *method_args(method))
        rows.append(dict(method=method, **times, error_s=impact_error_s(summary, peer),
                         impacts=summary["impact_count"], status=summary["status"]))
    return rows


def sized_scene(storeys, folder):
    """The paper's buildings with `storeys` floors each (the gap is set by size_table)."""
    text = PAPER.read_text()
    text = re.sub(r"^storeys = \d+", f"storeys = {storeys}", text, flags=re.M)
    text = re.sub(r"^frame_factor = .*$", "frame_factor = 1.0", text, flags=re.M)
    text = text.replace('file = "../records/', f'file = "{ROOT}/examples/records/')
    text = re.sub(r'^name = "paper"', f'name = "size-{storeys}"', text, flags=re.M)
    scene = Path(folder) / f"size-{storeys}.toml"
    scene.write_text(text)
    return scene


def size_table(pounding, repeat, scratch, sizes, gap_m):
    rows = []
    for storeys in sizes:
        scene = sized_scene(storeys, scratch)
        for method in SIZE_METHODS:
            summary, times = timed_outputs(pounding, scene, Path(scratch) / f"size{storeys}-{method.replace('/', '-')}",
                                           repeat, *method_args(method), "--gap", str(gap_m), "--max-wall-time", "600")
            s = summary["statistics"]
            rows.append(dict(storeys=storeys, states=12 * storeys, method=method, **times, steps=s["steps"],
                             rhs=s["rhs_evaluations"], jacobians=s["jacobian_evaluations"],
                             impacts=summary["impact_count"]))
    return rows


TIMES = ("min_solver_s", "min_cpu_s", "full_solver_s", "full_cpu_s")


def fitted_exponent(rows, method, key):
    """Least-squares slope of log(time) against log(states)."""
    points = [(math.log(r["states"]), math.log(r[key])) for r in rows if r["method"] == method]
    mx = sum(x for x, _ in points) / len(points)
    my = sum(y for _, y in points) / len(points)
    return sum((x - mx) * (y - my) for x, y in points) / sum((x - mx) ** 2 for x, _ in points)


def markdown(paper, sizes, exponents, where, storeys_list):
    lines = [f"Measured {where}. min: `--history off --peaks none` (the solver's cost: impacts and energy "
             "only); full: the default outputs (history and every peak group).", "",
             "| paper scene, gap 0.20 m | solver, min [s] | CPU, min [s] | solver, full [s] | CPU, full [s] | "
             "impact-time error vs peer [s] | impacts | status |",
             "|---|---|---|---|---|---|---|---|"]
    for r in paper:
        lines.append(f"| {r['method']} | {r['min_solver_s']:.4f} | {r['min_cpu_s']:.3f} | {r['full_solver_s']:.4f} | "
                     f"{r['full_cpu_s']:.3f} | {r['error_s']:.1e} | {r['impacts']} | {r['status']} |")
    lines += ["", "(error: largest impact-time difference over the impacts before the first sustained contact)", "",
              "| storeys (each) | states | method | solver, min [s] | CPU, min [s] | solver, full [s] | CPU, full [s] | "
              "steps | rhs | Jacobians | impacts |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for storeys in storeys_list:
        for r in sizes:
            if r["storeys"] == storeys:
                lines.append(f"| {storeys} | {12 * storeys} | {r['method']} | {r['min_solver_s']:.3f} | "
                             f"{r['min_cpu_s']:.3f} | {r['full_solver_s']:.3f} | {r['full_cpu_s']:.3f} | "
                             f"{r['steps']} | {r['rhs']} | {r['jacobians']} | {r['impacts']} |")
    lines += ["", "| fitted exponent (time ∝ states^p) | " + " | ".join(TIMES) + " |", "|---|---|---|---|---|"]
    for m in SIZE_METHODS:
        lines.append(f"| {m} | " + " | ".join(f"{exponents[m][key]:.2f}" for key in TIMES) + " |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--out", default=str(ROOT / "bench/results"))
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)), help="storeys of the size ladder")
    parser.add_argument("--size-gap", type=float, default=0.5,
                        help="gap (m) of the size ladder; at 0.5 m the 60-storey pair collides, at 1.5 m no size does")
    args = parser.parse_args()
    storeys_list = [int(s) for s in args.sizes.split(",")]
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    where = (f"at commit {commit()} on {cpu_model()} ({platform.node()}), median of {args.repeat}; "
             f"size ladder at gap {args.size_gap} m")
    with tempfile.TemporaryDirectory() as scratch:
        paper = paper_table(args.pounding, args.repeat, scratch)
        sizes = size_table(args.pounding, args.repeat, scratch, storeys_list, args.size_gap)
    exponents = {m: {key: fitted_exponent(sizes, m, key) for key in TIMES} for m in SIZE_METHODS}
    (out / "speed.json").write_text(json.dumps(dict(measured=where, paper=paper, sizes=sizes, exponents=exponents),
                                               indent=2))
    text = markdown(paper, sizes, exponents, where, storeys_list)
    (out / "speed.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
