#!/usr/bin/python3
"""Draws the paper's kind of figure from a `pounding run` output folder.

Four panels for one level (a floor of each building at a common elevation): u, v and φ of both
slabs against time, and the x-displacement of the contact vertices; impacts at that level are
marked. --compare overlays a second run of the same buildings in grey (e.g. the no-pounding run
under the pounding one).

    tools/plot_run.py out/paper [--level 7] [--compare out/paper-0.5] [--out figure.png]
"""
import argparse
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_run(folder: Path):
    summary_file, history_file = folder / "summary.json", folder / "history.csv"
    for f in (summary_file, history_file):
        if not f.is_file():
            sys.exit(f"error: {f} not found (is {folder} the output folder of `pounding run`?)")
    summary = json.loads(summary_file.read_text())
    with history_file.open() as handle:
        rows = list(csv.reader(handle))
    header, data = rows[0], rows[1:]
    columns = {name: [float(r[i]) for r in data] for i, name in enumerate(header)}
    return summary, columns


def floor_columns(columns, building, floor):
    prefix = f"B{building}_f{floor}_"
    return {name[len(prefix):]: values for name, values in columns.items() if name.startswith(prefix)}


def plot(folder: Path, level, compare, out):
    summary, columns = read_run(folder)
    written = summary["history_levels"]
    level = level or written[-1]
    if level not in written:
        sys.exit(f"error: --level {level}: history.csv holds levels {written}")
    where = summary["levels"][level - 1]
    floors = {1: where["floors"][0], 2: where["floors"][1]}  # each building's own floor at that level
    other = read_run(compare) if compare else None

    fig, axes = plt.subplots(4, 1, figsize=(10, 11), sharex=True)
    panels = [("u_m", 100.0, "u [cm]"), ("v_m", 100.0, "v [cm]"), ("phi_rad", 1000.0, "φ [mrad]")]
    colours = {1: "tab:blue", 2: "tab:red"}
    names = {1: summary["peaks"][0]["building"], 2: summary["peaks"][1]["building"]}
    for axis, (key, scale, label) in zip(axes, panels):
        for b in (1, 2):
            if other:
                values = floor_columns(other[1], b, floors[b])
                axis.plot(other[1]["t_s"], [scale * x for x in values[key]], color="0.7", lw=1.0)
            values = floor_columns(columns, b, floors[b])
            axis.plot(columns["t_s"], [scale * x for x in values[key]], color=colours[b], lw=1.0,
                      label=f"{names[b]}")
        axis.set_ylabel(label)
        axis.grid(alpha=0.3)
    axes[0].legend(loc="upper right")

    vertex_axis = axes[3]
    for b in (1, 2):
        vertices = summary["peaks"][b - 1]["contact_vertices_rest"]
        numbers = summary["peaks"][b - 1]["contact_vertices"]  # slab-outline numbers, as history.csv names them
        values = floor_columns(columns, b, floors[b])
        for k, (number, vertex) in enumerate(zip(numbers, vertices), start=1):
            key = f"vtx{number}_dx_m"
            if other:
                vertex_axis.plot(other[1]["t_s"], [100 * x for x in floor_columns(other[1], b, floors[b])[key]],
                                 color="0.7", lw=1.0)
            vertex_axis.plot(columns["t_s"], [100 * x for x in values[key]], lw=1.0,
                             color=colours[b], ls="-" if k == 1 else "--",
                             label=f"{names[b]} vertex ({vertex[0]:g}, {vertex[1]:g})")
    vertex_axis.set_ylabel("vertex x-displacement [cm]")
    vertex_axis.set_xlabel("t [s]")
    vertex_axis.grid(alpha=0.3)
    vertex_axis.legend(loc="upper right", fontsize=8)

    impacts = [i["t_s"] for i in summary["impacts"] if i["level"] == level]
    for axis in axes:
        for t in impacts:
            axis.axvline(t, color="k", lw=0.5, alpha=0.4)
    title = (f"{summary['scene']}: level {level} (B1 floor {floors[1]}, B2 floor {floors[2]}, "
             f"{where['elevation_m']:g} m), gap {summary['gap_m']} m, k = {summary['restitution']}, "
             f"{summary['method']} — {len(impacts)} impacts at this level ({summary['impact_count']} in all)")
    if compare:
        title += f"\ngrey: {compare} ({other[0]['impact_count']} impacts)"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    out = out or folder / f"level{level}.png"
    fig.savefig(out, dpi=110)
    print(f"Wrote {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path, help="output folder of `pounding run`")
    parser.add_argument("--level", type=int, help="level to draw (default: the top level in history.csv)")
    parser.add_argument("--compare", type=Path, help="a second run folder drawn in grey underneath")
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/levelN.png)")
    args = parser.parse_args()
    plot(args.folder, args.level, args.compare, args.out)


if __name__ == "__main__":
    main()
