#!/usr/bin/python3
"""Draws the work–precision plot of a `pounding study` folder: error against run time, log–log,
one line per method (event-driven methods over rtol, HHT variants over Δt).

Left: the largest impact-time error before the first sustained contact, where the exact path is
exact to round-off (a study of yielding columns is measured against cvode-bdf at rtol 1e-12
instead, which study.json names as its reference). Right: the largest error of the floor displacements u over the whole run;
points at or below twice the reference's own error estimate (the study's "at ref") are drawn
hollow, the estimate as a dotted line. Each point is labelled with its rtol or Δt where the label
fits without overlapping another; the subtitle names the processor and core count the timings
were taken on, from machine.txt (written at study time by scripts/run-study.sh) or, without it,
from /proc/cpuinfo at plot time, and says which.

A second figure, stiffness.png (when the study ran the contact-stiffness ladder), shows per
compliant law the steps and the run time of each event-driven method against the contact
stiffness; a run that stopped (time_limit, ...) is marked with a cross and its status.

    tools/plot_study.py out/paper-study [--out study.png]
"""
import argparse
import csv
import json
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Label positions tried around a point, in points: right-above, right-below, left-above, left-below, above, below.
OFFSETS = [((4, 2), "left", "bottom"), ((4, -2), "left", "top"), ((-4, 2), "right", "bottom"),
           ((-4, -2), "right", "top"), ((0, 6), "center", "bottom"), ((0, -6), "center", "top")]


def machine(folder: Path):
    """'processor, N cores (...)' and where it was read."""
    record = folder / "machine.txt"
    if record.is_file():
        fields = dict(line.split(": ", 1) for line in record.read_text().splitlines() if ": " in line)
        load = fields.get("load_before", "").split()
        busy = f"; shared with other jobs, load average {load[0]} at its start" if load else ""
        return f"{fields.get('cpu', '?')}, {fields.get('cores', '?')} cores{busy} (recorded at study time)"
    model = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                  if line.startswith("model name")), "unknown processor")
    return f"{model}, {os.cpu_count()} cores (read at plot time: the study's machine was not recorded)"


def overlaps(box, boxes):
    return any(box.overlaps(other) for other in boxes)


def label_points(fig, axis, points):
    """Places each (x, y, text, colour) label at the first offset where it overlaps no other label
    and no marker and stays inside the axes; a label that fits nowhere is left out (counted)."""
    renderer = fig.canvas.get_renderer()
    frame = axis.get_window_extent(renderer)
    markers = []
    for x, y, _, _ in points:
        px, py = axis.transData.transform((x, y))
        markers.append(matplotlib.transforms.Bbox.from_extents(px - 4, py - 4, px + 4, py + 4))
    placed, dropped = [], 0
    for (x, y, text, colour), own in zip(points, markers):
        others = [m for m in markers if m is not own]
        for offset, ha, va in OFFSETS:
            note = axis.annotate(text, (x, y), xytext=offset, textcoords="offset points", fontsize=6.5,
                                 color=colour, ha=ha, va=va)
            box = note.get_window_extent(renderer).expanded(1.05, 1.1)
            inside = frame.containsx(box.x0) and frame.containsx(box.x1) and frame.containsy(box.y0) \
                and frame.containsy(box.y1)
            if inside and not overlaps(box, placed) and not overlaps(box, others):
                placed.append(box)
                break
            note.remove()
        else:
            dropped += 1
    return dropped


def plot_stiffness(study, style_of, folder: Path):
    """steps and run time against contact stiffness, one column per compliant law; None if no ladder."""
    ladder = study.get("stiffness_ladder", [])
    if not ladder:
        return None
    laws = list(dict.fromkeys(r["law"] for r in ladder))
    fig, axes = plt.subplots(2, len(laws), figsize=(max(4.6 * len(laws), 9.5), 7.5), squeeze=False)
    for column, law in enumerate(laws):
        mine = [r for r in ladder if r["law"] == law]
        steps_axis, time_axis = axes[0][column], axes[1][column]
        for method in dict.fromkeys(r["method"] for r in mine):
            runs = sorted((r for r in mine if r["method"] == method), key=lambda r: r["stiffness"])
            colour, marker = style_of.get(method, ("black", "."))
            k = [r["stiffness"] for r in runs]
            for axis, key in ((steps_axis, "steps"), (time_axis, "run_time_s")):
                values = [max(float(r[key]), 1e-6) for r in runs]
                axis.loglog(k, values, color=colour, marker=marker, ms=6, lw=1.2,
                            label=method if column == 0 and axis is steps_axis else None)
                for x, y, r in zip(k, values, runs):
                    if r["status"] != "completed":
                        axis.plot(x, y, "x", color="red", ms=10)
                        axis.annotate(r["status"], (x, y), xytext=(4, 4), textcoords="offset points", fontsize=7,
                                      color="red")
        unit = mine[0]["stiffness_unit"]
        steps_axis.set_title(f"{law}", fontsize=11)
        steps_axis.set_ylabel("integrator steps")
        time_axis.set_ylabel("run time [s] (median of the repeats)")
        for axis in (steps_axis, time_axis):
            axis.set_xlabel(f"contact stiffness [{unit}]")
            axis.grid(True, which="both", alpha=0.25)
    fig.legend(*axes[0][0].get_legend_handles_labels(), loc="lower center", ncol=4, fontsize=9, frameon=False)
    fig.suptitle(f"What each event-driven method pays as the contact stiffens, '{study['scene']}' at gap "
                 f"{study['gap_m']:g} m\n(red cross: the run stopped). Timed on {machine(folder)}", fontsize=9)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    out = folder / "stiffness.png"
    fig.savefig(out, dpi=110)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path)
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/work-precision.png)")
    args = parser.parse_args()
    study_file, summary_file = args.folder / "study.csv", args.folder / "study.json"
    for f in (study_file, summary_file):
        if not f.is_file():
            sys.exit(f"error: {f} not found (is {args.folder} the output folder of `pounding study`?)")
    rows = list(csv.DictReader(study_file.open()))
    study = json.loads(summary_file.read_text())
    reference = study["reference"]
    exact = reference["method"] == "exact"
    ref_name = "exact" if exact else "ref"
    # Colour and marker of each line, as the method registry (src/analysis/methods.cpp) wrote them.
    style_of = {label: (s["colour"], s["marker"]) for label, s in study.get("styles", {}).items()}

    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 6.2))
    labels = {left: [], right: []}
    for method in dict.fromkeys(r["method"] for r in rows):
        mine = sorted((r for r in rows if r["method"] == method), key=lambda r: float(r["run_time_s"]))
        colour, marker = style_of.get(method, ("black", "."))
        times = [float(r["run_time_s"]) for r in mine]
        for axis, key, at_ref in ((left, "impact_time_error_before_hold_s", None),
                                  (right, "history_u_error_m", "history_u_at_reference")):
            errors = [max(float(r[key]), 1e-16) for r in mine]
            axis.loglog(times, errors, color=colour, lw=1.2, marker=marker, ms=6,
                        label=method if axis is left else None)
            for t, e, r in zip(times, errors, mine):
                hollow = at_ref and r[at_ref] == "true"
                if hollow:
                    axis.plot(t, e, marker=marker, ls="none", ms=6, color=colour, mfc="white")
                else:  # the hollow ones crowd the reference's floor; the legend explains them
                    labels[axis].append((t, e, f"{float(r['value']):g}", colour))
    left.set_title("impact-time error before the first sustained contact", fontsize=11)
    left.set_ylabel(f"max |t − t_{ref_name}| [s]")
    right.set_title("largest error of u on the contact floors, whole run", fontsize=11)
    right.set_ylabel(f"max |u − u_{ref_name}| [m]")
    estimate = reference["error_estimate"]["history_u_m"]
    right.axhline(estimate, color="0.4", ls=":", lw=1)
    right.plot([], [], "o", mfc="white", color="0.4",
               label=f"at or below 2× the reference's own error ({estimate:.1e} m, dotted)")
    for axis in (left, right):
        axis.set_xlabel("run time [s] (median of the repeats)")
        axis.grid(True, which="both", alpha=0.25)
    fig.legend(*[sum(x, []) for x in zip(left.get_legend_handles_labels(), right.get_legend_handles_labels())],
               loc="lower center", ncol=4, fontsize=8.5, frameon=False)
    against = "the exact path" if exact else reference["method"]
    fig.suptitle(f"Work–precision of every path on '{study['scene']}' at gap {study['gap_m']:g} m, against {against} "
                 f"({reference['impacts']} impacts). Labels: rtol, or Δt in s.\n"
                 f"Timed on {machine(args.folder)}", fontsize=10)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.canvas.draw()
    dropped = sum(label_points(fig, axis, labels[axis]) for axis in (left, right))
    if dropped:
        print(f"note: {dropped} labels left out where they would overlap")
    out = args.out or args.folder / "work-precision.png"
    fig.savefig(out, dpi=110)
    print(f"Wrote {out}")
    stiffness = plot_stiffness(study, style_of, args.folder)
    if stiffness:
        print(f"Wrote {stiffness}")


if __name__ == "__main__":
    main()
