#!/usr/bin/python3
"""Sweep throughput: runs per second of one fixed small sweep (the paper scene at 12 gaps and
2 restitutions, 24 runs of about 0.2 s each, its own record) with no Dask (in-process, one after
another) and on a LocalCluster of 1, 2 and every core's worker processes.

    PYTHONPATH=build/python bench/sweep_throughput.py [--out bench/results] [--repeat N]

Writes sweep_throughput.md (the table for the README) and sweep_throughput.json into --out, with
the date, commit, CPU, core count and load average. Each configuration runs --repeat times
(default 2) into a fresh folder and the fastest is kept; "start-up" is a LocalCluster of that many
workers started and closed alone, which the sweep's wall time includes.
"""

import argparse
import datetime
import json
import os
import pathlib
import tempfile
import time

import pounding
from machine import commit, cpu_model

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAPER = ROOT / "examples" / "paper" / "paper.toml"
GAPS_M = [round(0.02 * k, 2) for k in range(1, 13)]  # 0.02 … 0.24 m: most runs pound
RESTITUTIONS = [0.5, 0.7]


def cluster_start_s(workers):
    import logging

    import dask.distributed
    start = time.perf_counter()
    with dask.distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                       dashboard_address=":0", silence_logs=logging.ERROR) as cluster:
        with dask.distributed.Client(cluster) as client:
            client.wait_for_workers(workers)
    return time.perf_counter() - start


def measure(sweep_file, workers, repeat):
    best = None
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as out:
            start = time.perf_counter()
            result = pounding.sweep(sweep_file, out=out, workers=workers, progress=False)
            wall_s = time.perf_counter() - start
            solver_s = sum(float(r["solver_time_s"]) for r in result.rows)
        assert result.executed == len(GAPS_M) * len(RESTITUTIONS) and result.failed == 0, result
        if best is None or wall_s < best["wall_s"]:
            best = {"wall_s": wall_s, "solver_s": solver_s}
    best["runs"] = len(GAPS_M) * len(RESTITUTIONS)
    best["runs_per_s"] = best["runs"] / best["wall_s"]
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "bench" / "results")
    parser.add_argument("--repeat", type=int, default=2)
    arguments = parser.parse_args()
    arguments.out.mkdir(parents=True, exist_ok=True)
    cores = os.cpu_count() or 1
    configurations = [("no Dask (in-process)", 0), ("LocalCluster, 1 worker", 1), ("LocalCluster, 2 workers", 2)]
    if cores > 2:
        configurations.append((f"LocalCluster, {cores} workers (every core)", cores))
    else:
        configurations[-1] = (f"LocalCluster, 2 workers (every core)", 2)

    load_before = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        sweep_file = pathlib.Path(folder) / "throughput.toml"
        sweep_file.write_text(f'scenes = ["{PAPER}"]\ngaps_m = {GAPS_M}\nrestitutions = {RESTITUTIONS}\n')
        for name, workers in configurations:
            row = {"configuration": name, "workers": workers, **measure(sweep_file, workers, arguments.repeat)}
            row["start_up_s"] = cluster_start_s(workers) if workers else 0.0
            rows.append(row)
            print(f"{name}: {row['runs']} runs in {row['wall_s']:.2f} s = {row['runs_per_s']:.2f} runs/s "
                  f"(solver time {row['solver_s']:.2f} s, cluster start-up {row['start_up_s']:.2f} s)", flush=True)
    load_after = os.getloadavg()

    machine = {"date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
               "commit": commit(), "cpu": cpu_model(), "cores": cores,
               "load_average_1min": [load_before[0], load_after[0]], "program_version": pounding.__version__}
    (arguments.out / "sweep_throughput.json").write_text(json.dumps({"machine": machine, "rows": rows}, indent=2) + "\n")
    lines = [f"Sweep throughput, {machine['date_utc']}, commit {machine['commit']}, {machine['cpu']}, "
             f"{cores} cores, load average {load_before[0]:.1f} → {load_after[0]:.1f}; the paper scene at "
             f"{len(GAPS_M)} gaps × {len(RESTITUTIONS)} restitutions ({rows[0]['runs']} runs), best of "
             f"{arguments.repeat}:", "",
             "| configuration | wall time [s] | runs per second | solver time, sum [s] | cluster start-up [s] |",
             "|---|---|---|---|---|"]
    lines += [f"| {r['configuration']} | {r['wall_s']:.2f} | {r['runs_per_s']:.2f} | {r['solver_s']:.2f} | "
              f"{r['start_up_s']:.2f} |" for r in rows]
    (arguments.out / "sweep_throughput.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
