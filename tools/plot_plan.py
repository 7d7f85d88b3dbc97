#!/usr/bin/python3
"""Draws a `pounding plan` folder (plan.json) as plan.png.

Left, the plan at rest: the slab outlines (two, or a row's), their columns to scale, each centre
of mass (+) and storey 1's centre of stiffness (x, the other storeys' as small dots when they
differ), and every contact candidate: the striking vertex (o) joined to the middle of the edge it
may strike, with the clear gap. With --impacts RUN, the points where that run's impacts struck
(stars, coloured by the striking building). Right, the elevation: each building's floors at their
heights, side by side, the levels where floors meet joined across (only those can touch), floors
at no level in grey.

    tools/plot_plan.py FOLDER [--out FILE] [--impacts RUN_DIR]
"""
import argparse
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown", "tab:pink", "tab:olive", "tab:cyan")


def colour(b):
    return COLOURS[b % len(COLOURS)]


def level_buildings(level):
    """A level's two buildings (0-based): a row's plan names them, two buildings' are 0 and 1."""
    return [b - 1 for b in level.get("buildings", [1, 2])]


def gaps_text(plan):
    if plan.get("pairs"):
        names = [b["name"] for b in plan["buildings"]]
        return "gaps " + ", ".join(f"{names[p['buildings'][0] - 1]}:{names[p['buildings'][1] - 1]} {p['gap_m']:.3g} m"
                                   for p in plan["pairs"])
    return f"clear gap {plan['gap_m']:g} m"


def read_impacts(run):
    """(x, y, striking building 0-based) of each impact in RUN/impacts.csv."""
    with open(Path(run) / "impacts.csv", newline="") as f:
        return [(float(r["point_x_m"]), float(r["point_y_m"]), int(r["striking_building"]) - 1)
                for r in csv.DictReader(f)]


def draw_plan(ax, plan, impacts=None):
    for b, building in enumerate(plan["buildings"]):
        colour_b = colour(b)
        ax.add_patch(Polygon(building["slab"], closed=True, facecolor=colour_b, alpha=0.15, edgecolor=colour_b, lw=1.5,
                             label=f"B{b + 1} {building['name']}"))
        for c in building["columns"]:
            ax.add_patch(Rectangle((c["x_m"] - c["b_m"] / 2, c["y_m"] - c["h_m"] / 2), c["b_m"], c["h_m"],
                                   color=colour_b, alpha=0.8))
        cm = building["centre_of_mass"]
        ax.plot(*cm, "+", color="k", ms=12, mew=2)
        centres = building["centres_of_stiffness"]
        if centres:
            ax.plot(*centres[0], "x", color=colour_b, ms=10, mew=2)
            others = [c for c in centres[1:] if abs(c[0] - centres[0][0]) + abs(c[1] - centres[0][1]) > 1e-9]
            if others:
                ax.plot([c[0] for c in others], [c[1] for c in others], ".", color=colour_b, ms=4)
    shown = set()
    for c in plan["candidates"]:  # every level repeats the same pairs: draw each once
        key = (tuple(c["vertex"]), tuple(map(tuple, c["edge"])))
        if key in shown:
            continue
        shown.add(key)
        (x1, y1), (x2, y2) = c["edge"]
        ax.plot([c["vertex"][0], (x1 + x2) / 2], [c["vertex"][1], (y1 + y2) / 2], "r-", lw=1)
        ax.plot(*c["vertex"], "o", color="r", ms=5)
    if impacts:
        for b in sorted({i[2] for i in impacts}):
            mine = [i for i in impacts if i[2] == b]
            ax.plot([i[0] for i in mine], [i[1] for i in mine], "*", color=colour(b), mec="k", mew=0.5, ms=11,
                    label=f"impacts struck by B{b + 1} ({len(mine)})")
    ax.plot([], [], "k+", ms=10, mew=2, label="centre of mass")
    ax.plot([], [], "kx", ms=8, mew=2, label="centre of stiffness (storey 1)")
    ax.plot([], [], "r-o", ms=4, label=f"contact candidates ({len(shown)} pairs a level)")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"{plan['scene']}: plan at rest, {gaps_text(plan)}")
    ax.grid(alpha=0.3)
    if len(plan["buildings"]) > 2:  # a row: below the plan, clear of the slabs
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3)
    else:
        ax.legend(fontsize=8, loc="best")


def draw_elevation(ax, plan):
    count = len(plan["buildings"])
    met = [set() for _ in range(count)]
    for level in plan["levels"]:
        for side, b in enumerate(level_buildings(level)):
            met[b].add(level["floors"][side])
    for b, building in enumerate(plan["buildings"]):
        x0 = 1.4 * b
        ax.plot([x0, x0 + 1], [0, 0], "k-", lw=2)
        for floor, z in enumerate(building["floor_elevations_m"], start=1):
            ax.plot([x0, x0 + 1], [z, z], "-", color=colour(b) if floor in met[b] else "0.6", lw=2)
        top = building["floor_elevations_m"][-1]
        ax.plot([x0, x0], [0, top], "-", color=colour(b), lw=1)
        ax.plot([x0 + 1, x0 + 1], [0, top], "-", color=colour(b), lw=1)
        ax.text(x0 + 0.5, top * 1.02 + 0.3, f"B{b + 1} {building['name']}\nT1 = {building['periods_s'][0]:.3f} s",
                ha="center", va="bottom", fontsize=8)
    for level in plan["levels"]:
        first, second = level_buildings(level)
        z2 = plan["buildings"][second]["floor_elevations_m"][level["floors"][1] - 1]
        ax.plot([1.4 * first + 1.0, 1.4 * second], [level["elevation_m"], z2], "r-", lw=1.5)
    ax.set_xlim(-0.3, 1.4 * count - 0.1)
    ax.set_ylim(-0.5, 1.18 * max(b["floor_elevations_m"][-1] for b in plan["buildings"]) + 1.0)
    ax.set_xticks([])
    ax.set_ylabel("elevation [m]")
    ax.set_title(f"elevation: {len(plan['levels'])} levels where floors meet (red),\nfloors at no level in grey",
                 fontsize=10)
    ax.grid(alpha=0.3, axis="y")


def read_plan(folder: Path):
    plan_file = folder / "plan.json"
    if not plan_file.is_file():
        sys.exit(f"error: {plan_file} not found (is {folder} the output folder of `pounding plan`, or of a run "
                 "given to `pounding animate` or `pounding report`?)")
    return json.loads(plan_file.read_text())


def plan_figure(plan, impacts=None):
    """The plan (left) and the elevation (right) in one figure."""
    wide = max(1.0, len(plan["buildings"]) / 2)
    fig, (plan_ax, elevation_ax) = plt.subplots(1, 2, figsize=(14 * wide ** 0.5, 6),
                                                gridspec_kw={"width_ratios": [2.2, wide]})
    draw_plan(plan_ax, plan, impacts)
    draw_elevation(elevation_ax, plan)
    fig.tight_layout()
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path)
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/plan.png)")
    parser.add_argument("--impacts", type=Path, help="a run's folder: mark where its impacts struck")
    args = parser.parse_args()
    fig = plan_figure(read_plan(args.folder), read_impacts(args.impacts) if args.impacts else None)
    out = args.out or args.folder / "plan.png"
    fig.savefig(out, dpi=120)
    print(f"Wrote {out}")


if __name__ == "__main__":
    main()
