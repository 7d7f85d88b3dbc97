"""What the scipy peers (tests/solvers/test_*_scipy.py) share: running `pounding run` on a scene and a
record written for the test, reading what the run wrote, and the closing report. The physics stays
in each peer: a peer shares no code with the program, nor with another peer, so each is its own
check. Import it from a test script with

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
    import program_run
"""
import csv
import json
import subprocess
import sys
import time

import numpy as np


class ProgramRun:
    """What one `pounding run` wrote: summary.json (with `exit_code` added), impacts.csv's rows by
    onset (dicts of text), history.csv's times `t` and the asked-for columns `q` (one row a
    sample), and with forces contacts_history.csv as dicts (t, candidate, force)."""

    def __init__(self, summary, impacts, t, q, forces=None):
        self.summary, self.impacts, self.t, self.q, self.forces = summary, impacts, t, q, forces


def write_record(path, accel):
    """One acceleration a line, every digit (repr): the program reads what the peer integrates."""
    path.write_text("\n".join(repr(float(a)) for a in accel) + "\n")


def run_scene(program, folder, scene_text, accel, options=(), columns=(), record_name="pulse.txt",
              accept_any_exit=False, forces=False):
    """Writes `accel` to folder/record_name and scene_text(that path) to folder/scene.toml, runs
    `pounding run` on them into folder/run with `options` and reads the run. Returns (ProgramRun,
    None), or (None, the program's message) when the run failed (an exit other than 0; with
    accept_any_exit, no summary.json: a run that stopped early still wrote one) or history.csv lacks
    one of `columns`."""
    folder.mkdir(parents=True, exist_ok=True)
    write_record(folder / record_name, accel)
    (folder / "scene.toml").write_text(scene_text(folder / record_name))
    run = subprocess.run([str(program), "run", str(folder / "scene.toml"), "--out", str(folder / "run"),
                          "--no-progress", *options], capture_output=True, text=True)
    failed = not (folder / "run/summary.json").exists() if accept_any_exit else run.returncode != 0
    if failed:
        return None, f"exit {run.returncode}: " + (run.stderr + run.stdout).strip()[-600:]
    with open(folder / "run/history.csv") as f:
        history = list(csv.DictReader(f))
    missing = [c for c in columns if c not in history[0]]
    if missing:
        return None, f"history.csv has no column {', '.join(missing)}"
    summary = json.loads((folder / "run/summary.json").read_text())
    summary["exit_code"] = run.returncode
    with open(folder / "run/impacts.csv") as f:
        impacts = sorted(csv.DictReader(f), key=lambda r: float(r["t_s"]))  # stable: simultaneous rows keep their order
    t = np.array([float(r["t_s"]) for r in history])
    q = np.array([[float(r[c]) for c in columns] for r in history])
    contact_forces = None
    if forces:
        with open(folder / "run/contacts_history.csv") as f:
            contact_forces = [dict(t=float(r["t_s"]), candidate=int(r["candidate"]), force=float(r["force_kN"]))
                              for r in csv.DictReader(f)]
    return ProgramRun(summary, impacts, t, q, contact_forces), None


def finish(failures, started=None, width=None):
    """Prints each failure (cut to `width` characters if given) and, with the start time, the count
    and the time taken; exits 1 if anything failed, else 0."""
    for failure in failures:
        print("FAIL:", failure if width is None or len(failure) < width else failure[:width] + " ...")
    if started is not None:
        print(f"{'FAILED' if failures else 'passed'}: {len(failures)} failures in {time.time() - started:.1f} s")
    sys.exit(1 if failures else 0)
