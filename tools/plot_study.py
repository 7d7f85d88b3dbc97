#!/usr/bin/python3
"""Draws the work–precision plot of a `pounding study` folder: error against run time, log–log,
one line per method (event-driven methods over rtol, HHT variants over Δt).

Left: the largest impact-time error before the first sustained contact, where the exact path is
exact to round-off. Right: the largest error of the floor displacements u over the whole run,
which includes the exact path's linearised holds (its floor is marked).

    tools/plot_study.py out/paper-study [--out study.png]
"""
import argparse
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402



def styles(folder):
    """Colour and marker of each study line, as the method registry (src/analysis/methods.cpp)
    wrote them into study.json."""
    study_json = folder / "study.json"
    if not study_json.is_file():
        return {}
    return {label: (s["colour"], s["marker"]) for label, s in json.loads(study_json.read_text()).get("styles", {}).items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path)
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/work-precision.png)")
    args = parser.parse_args()
    study_file = args.folder / "study.csv"
    if not study_file.is_file():
        sys.exit(f"error: {study_file} not found (is {args.folder} the output folder of `pounding study`?)")
    rows = list(csv.DictReader(study_file.open()))
    style_of = styles(args.folder)

    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.5))
    for method in dict.fromkeys(r["method"] for r in rows):
        mine = sorted((r for r in rows if r["method"] == method), key=lambda r: float(r["run_time_s"]))
        colour, marker = style_of.get(method, ("black", "."))
        times = [float(r["run_time_s"]) for r in mine]
        for axis, key in ((left, "impact_time_error_before_hold_s"), (right, "history_u_error_m")):
            errors = [max(float(r[key]), 1e-16) for r in mine]
            axis.loglog(times, errors, marker=marker, color=colour, label=method)
            for t, e, r in zip(times, errors, mine):
                axis.annotate(f"{float(r['value']):g}", (t, e), fontsize=6, color=colour,
                              xytext=(3, 3), textcoords="offset points")
    left.set_title("impact-time error before the first sustained contact")
    left.set_ylabel("max |t − t_exact| [s]")
    right.set_title("largest error of u on the contact floors, whole run")
    right.set_ylabel("max |u − u_exact| [m]")
    floor = min(float(r["history_u_error_m"]) for r in rows if float(r["history_u_error_m"]) > 0)
    right.axhline(floor, color="0.5", ls=":", lw=1)
    right.annotate("reference's own error (linearised holds)", (right.get_xlim()[0], floor), fontsize=7,
                   color="0.4", xytext=(5, 4), textcoords="offset points")
    for axis in (left, right):
        axis.set_xlabel("run time [s] (median)")
        axis.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=8)
    fig.suptitle("Work–precision: every path against the exact path (labels: rtol or Δt in s)", fontsize=11)
    fig.tight_layout()
    out = args.out or args.folder / "work-precision.png"
    fig.savefig(out, dpi=110)
    print(f"Wrote {out}")


if __name__ == "__main__":
    main()
