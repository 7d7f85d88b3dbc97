#!/usr/bin/python3
"""Draws a `pounding gap` folder.

Left: the needed gap of every common level over height, with the ABS, SRSS and DDC rules beside
it. Middle: the touch gap of the governing pair over time (the clear gap at which that pair
would just touch at each instant; its largest value is the needed gap, marked). Right, when the
folder holds gap_curve.csv (`--curve N`): impacts and energy lost against the gap. When it holds
gap_angles.csv (`--all-angles`): a polar panel of the needed gap against the record's angle, the
worst angle and the record's own marked.

A folder of `pounding gap --records LIST|FOLDER` (records.json, records.csv) is drawn as the
record set instead: each record's needed gap beside the three rules at its governing level, and
the set's median and lognormal 84th percentile; records that did not complete are named in the
title and left out.

    tools/plot_gap.py out/paper-gap [--out gap.png]
"""
import argparse
import csv
import json
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    value = float(text)
    return value if math.isfinite(value) else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path)
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/gap.png)")
    args = parser.parse_args()
    if (args.folder / "records.json").is_file() and not (args.folder / "gap.json").is_file():
        return plot_record_set(args.folder, args.out)
    summary_file = args.folder / "gap.json"
    if not summary_file.is_file():
        sys.exit(f"error: {summary_file} not found (is {args.folder} the output folder of `pounding gap`?)")
    summary = json.load(summary_file.open())
    # By elevation: gap.csv lists the levels, then the slabs facing columns (level 0).
    levels = sorted(csv.DictReader((args.folder / "gap.csv").open()), key=lambda r: float(r["elevation_m"]))
    history = list(csv.DictReader((args.folder / "gap_history.csv").open()))
    curve_file = args.folder / "gap_curve.csv"
    curve = list(csv.DictReader(curve_file.open())) if curve_file.is_file() else []

    angles_file = args.folder / "gap_angles.csv"
    angles = list(csv.DictReader(angles_file.open())) if angles_file.is_file() else []
    panels = 2 + bool(curve) + bool(angles)
    fig = plt.figure(figsize=(6 * panels, 5.5))
    axes = [fig.add_subplot(1, panels, k + 1) for k in range(2 + bool(curve))]
    profile, closure = axes[0], axes[1]
    z = [float(r["elevation_m"]) for r in levels]
    profile.plot([number(r["needed_gap_m"]) for r in levels], z, "k-o", lw=2, label="needed (exact)")
    for key, label, style in (("abs_m", "ABS", "r--s"), ("srss_m", "SRSS", "b--^"), ("ddc_m", "DDC", "g--v")):
        profile.plot([float(r[key]) for r in levels], z, style, label=label)
    profile.set_xlabel("gap [m]")
    profile.set_ylabel("elevation (levels and slabs facing columns) [m]")
    profile.set_title(f"{summary['scene']}: needed gap {summary['needed_gap_m']:.4f} m")
    profile.grid(alpha=0.3)
    profile.legend()

    level = summary["level"]
    if level:
        column = f"touch_gap_level_{level}_m"
        t = [float(r["t_s"]) for r in history]
        closure.plot(t, [number(r[column]) for r in history], "k-", lw=1)
        closure.axhline(summary["needed_gap_m"], color="r", ls="--", label=f"needed gap {summary['needed_gap_m']:.4f} m")
        closure.plot([summary["t_s"]], [summary["needed_gap_m"]], "ro")
        closure.set_title(f"level {level}: {summary['pair']}", fontsize=9)
        closure.legend()
    closure.set_xlabel("t [s]")
    closure.set_ylabel("touch gap of the governing pair [m]")
    closure.grid(alpha=0.3)

    if curve:
        severity = axes[2]
        gaps = [float(r["gap_m"]) for r in curve]
        severity.plot(gaps, [int(r["impacts"]) for r in curve], "k-o", label="impacts")
        severity.set_xlabel("gap [m]")
        severity.set_ylabel("impacts")
        energy = severity.twinx()
        energy.plot(gaps, [float(r["energy_lost_kJ"]) for r in curve], "r-s", label="energy lost")
        energy.set_ylabel("energy lost in impacts [kJ]", color="r")
        severity.axvline(summary["needed_gap_m"], color="g", ls="--", label=f"needed gap {summary['needed_gap_m']:.4f} m")
        lines = severity.get_legend_handles_labels()
        more = energy.get_legend_handles_labels()
        severity.legend(lines[0] + more[0], lines[1] + more[1], loc="upper right")
        severity.set_title("severity below the needed gap")
        severity.grid(alpha=0.3)

    if angles:
        polar = fig.add_subplot(1, panels, panels, projection="polar")
        theta = [math.radians(float(r["angle_deg"])) for r in angles] + [math.radians(float(angles[0]["angle_deg"]))]
        radius = [number(r["needed_gap_m"]) for r in angles] + [number(angles[0]["needed_gap_m"])]
        polar.plot(theta, radius, "k-", lw=1.5, label="needed gap (superposed)" if summary["all_angles"]["method"] ==
                   "superposition" else "needed gap (one run per angle)")
        worst = summary["all_angles"]
        polar.plot([math.radians(worst["angle_deg"])], [worst["needed_gap_m"]], "ro",
                   label=f"worst {worst['needed_gap_m']:.4f} m at {worst['angle_deg']:.1f} deg")
        polar.plot([math.radians(worst["record_angle_deg"])], [summary["needed_gap_m"]], "bs",
                   label=f"record's angle: {summary['needed_gap_m']:.4f} m")
        polar.set_title("needed gap [m] against the record's angle (H1's, from +x)", fontsize=9)
        polar.legend(loc="lower left", fontsize=8, bbox_to_anchor=(0.0, -0.25))

    fig.tight_layout()
    out = args.out or args.folder / "gap.png"
    fig.savefig(out, dpi=120)
    print(f"Wrote {out}")


def plot_record_set(folder, out):
    summary = json.load((folder / "records.json").open())
    done = [r for r in summary["records"] if r["status"] == "completed"]
    if not done:
        sys.exit(f"error: no record of {folder / 'records.json'} completed: nothing to draw")
    done.sort(key=lambda r: r["needed_gap_m"])
    fig, ax = plt.subplots(figsize=(max(8.0, 0.9 * len(done) + 3.0), 5.5))
    rows = range(len(done))
    # Four bars a record, 0.2 high: the needed gap on top, the three rules under it.
    ax.barh([i + 0.3 for i in rows], [r["needed_gap_m"] for r in done], height=0.2, color="k", label="needed (exact)")
    for offset, key, label, colour in ((0.1, "abs_m", "ABS", "tab:red"), (-0.1, "srss_m", "SRSS", "tab:blue"),
                                       (-0.3, "ddc_m", "DDC", "tab:green")):
        ax.barh([i + offset for i in rows], [r["rules"][key] for r in done], height=0.2, color=colour, alpha=0.7,
                label=label)
    ax.set_yticks([i for i in rows], [f"{r['record']}\n(level {r['level']}, {r['pga_g']:.2f} g)" for r in done],
                  fontsize=7)
    stats = summary["statistics"]["needed_gap_m"]
    for key, style, label in (("median", "--", "median"), ("p84_lognormal", ":", "84th percentile (lognormal)")):
        if stats.get(key) is not None:  # a set of one record has no spread
            ax.axvline(stats[key], color="k", ls=style, lw=1, label=f"{label} {stats[key]:.4f} m")
    failed = [r["record"] for r in summary["records"] if r["status"] != "completed"]
    title = f"{summary['scene']}: needed gap over {len(done)} records; worst {summary['worst']}"
    if failed:
        title += f"\nnot completed (left out): {', '.join(failed)}"
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("gap [m]")
    ax.grid(alpha=0.3, axis="x")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    out = out or folder / "records.png"
    fig.savefig(out, dpi=120)
    print(f"Wrote {out}")


if __name__ == "__main__":
    main()
