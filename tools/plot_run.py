#!/usr/bin/python3
"""Draws the paper's kind of figure from a `pounding run` output folder.

Five panels for one level (a floor of each building at a common elevation): u, v and φ of both
slabs against time, the x-displacement of the contact vertices, and the signed gap g of every
vertex–edge pair of that level (exact rotation) with the zero line and a zoomed inset of one
bounce sequence (the impacts that accumulate before a sustained contact). Impacts at that level
are marked. --compare overlays a second run of the same buildings in grey (e.g. the run without
pounding under the pounding one).

The gap needs each slab's centre of mass, which summary.json does not carry: it is recovered
from history.csv itself, whose vertex columns are u + (cos φ − 1)·a − sin φ·b for the vertex's
lever arm (a, b) about the centre; a least-squares fit over the run gives (a, b) to round-off,
and the fit's residual is checked. The inset needs the flights between impacts, which are
milliseconds long: run the scene with `[output] history_interval_s = 1e-4` (see
scripts/run-example.sh); with the default 0.01 s the flights are drawn as chords, and the
script says so.

    tools/plot_run.py out/paper [--level 7] [--compare out/paper-gap0.50] [--inset T0 T1] [--out figure.png]
"""
import argparse
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

COLOURS = {1: "tab:blue", 2: "tab:red"}
GREY = "0.65"
IMPACT_STYLE = {"color": "tab:green", "lw": 0.6, "ls": ":", "alpha": 0.8}
FIT_RESIDUAL_LIMIT_M = 1e-9  # the vertex columns are exact functions of (u, φ): round-off only


def read_run(folder: Path):
    summary_file, history_file = folder / "summary.json", folder / "history.csv"
    if summary_file.is_file() and not json.loads(summary_file.read_text()).get("outputs", {"history": True})["history"]:
        sys.exit(f"error: {folder} holds no history.csv ([output] history = false, or --history off): run it again "
                 "with --history on")
    for f in (summary_file, history_file):
        if not f.is_file():
            sys.exit(f"error: {f} not found (is {folder} the output folder of `pounding run`?)")
    summary = json.loads(summary_file.read_text())
    with history_file.open() as handle:
        rows = list(csv.reader(handle))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    columns = {name: data[:, i] for i, name in enumerate(header)}
    return summary, columns


def slab_history(summary, columns, building, floor):
    """The one place that knows history.csv's column names and summary.json's vertex list.
    Returns u, v, φ of one slab and its tracked vertices as (rest point, x-displacement)."""
    prefix = f"B{building}_f{floor}_"
    peaks = summary["peaks"][building - 1]
    # history.csv names a vertex by its slab-outline number (summary.json's contact_vertices).
    vertices = [(tuple(p), columns[f"{prefix}vtx{number}_dx_m"])
                for number, p in zip(peaks["contact_vertices"], peaks["contact_vertices_rest"])]
    return {"u": columns[prefix + "u_m"], "v": columns[prefix + "v_m"], "phi": columns[prefix + "phi_rad"],
            "vertices": vertices}


def gap_frame_x(summary, building, x):
    """A rest x-coordinate in a form that does not depend on the run's gap: `--gap` moves building 2
    along x, so its points are given relative to the gap d."""
    return x - summary["gap_m"] if building == 2 else x


def plural(count, noun):
    return f"{count} {noun}" + ("" if count == 1 else "s")


def vertex_label(summary, building, point):
    x, y = gap_frame_x(summary, building, point[0]), point[1]
    if building == 1:
        return f"({x:g}, {y:g})"
    return f"(d, {y:g})" if abs(x) < 1e-9 else f"(d {'+' if x > 0 else '−'} {abs(x):g}, {y:g})"


def centre_of_mass(slab):
    """The slab's centre of mass at rest, recovered from its vertex columns (see the module doc):
    dx − u = (cos φ − 1)·a − sin φ·b with (a, b) = vertex − centre, least squares over the run.
    A slab that never rotates has no such information, and needs none: any centre gives its gaps."""
    if not slab["vertices"]:
        sys.exit("error: a slab of this level has no vertex columns in history.csv")
    if not np.any(slab["phi"]):
        return np.asarray(slab["vertices"][0][0], dtype=float)
    matrix = np.column_stack([np.cos(slab["phi"]) - 1.0, -np.sin(slab["phi"])])
    centres = []
    for point, dx in slab["vertices"]:
        arm, *_ = np.linalg.lstsq(matrix, dx - slab["u"], rcond=None)
        residual = np.max(np.abs(matrix @ arm - (dx - slab["u"])))
        if residual > FIT_RESIDUAL_LIMIT_M:
            sys.exit(f"error: history.csv's column of vertex {point} is not u + (cos φ − 1)·a − sin φ·b "
                     f"(fit residual {residual:.1e} m): cannot recover the centre of mass")
        centres.append(np.asarray(point) - arm)
    return np.mean(centres, axis=0)


def rotate(phi, vector):
    c, s = np.cos(phi), np.sin(phi)
    return np.array([c * vector[0] - s * vector[1], s * vector[0] + c * vector[1]])


def pair_gaps(summary, columns, level, floors):
    """Signed gap of every candidate pair of the level against time, exact rotation:
    g = (r_P − r_Q1)·n with n the struck edge's outward normal (slab outlines are counter-clockwise)."""
    slabs = {b: slab_history(summary, columns, b, floors[b]) for b in (1, 2)}
    centres = {b: centre_of_mass(slabs[b]) for b in (1, 2)}

    def position(b, rest):
        arm = np.asarray(rest) - centres[b]
        moved = rotate(slabs[b]["phi"], arm)
        return centres[b][:, None] + np.array([slabs[b]["u"], slabs[b]["v"]]) + moved

    gaps = []
    for c in (c for c in summary["candidates"] if c["level"] == level):
        a, b = c["striking_building"], c["struck_building"]
        q1, q2 = (np.asarray(p) for p in c["edge_rest"])
        along = (q2 - q1) / np.linalg.norm(q2 - q1)
        normal = rotate(slabs[b]["phi"], np.array([along[1], -along[0]]))
        g = np.sum((position(a, c["vertex_rest"]) - position(b, q1)) * normal, axis=0)
        label = (f"B{a} {vertex_label(summary, a, c['vertex_rest'])} → B{b} edge "
                 f"{vertex_label(summary, b, q1)}–{vertex_label(summary, b, q2)}")
        gaps.append({"striking": a, "vertex": c["vertex"], "label": label, "g": g})
    return gaps


def bounce_sequence(summary, level):
    """The first run of at least three impacts of one pair at the level that ends in a sustained
    contact: (first impact time, hold start, hold end, impact times), or None."""
    impacts = sorted((i for i in summary["impacts"] if i["level"] == level), key=lambda i: i["t_s"])
    for hold in sorted((h for h in summary["sustained_contacts"] if h["level"] == level), key=lambda h: h["start_s"]):
        same = [i["t_s"] for i in impacts if i["striking_building"] == hold["striking_building"]
                and i["vertex"] == hold["vertex"] and i["t_s"] <= hold["start_s"] + 1e-12]
        run = same[-1:]
        for t in reversed(same[:-1]):  # consecutive bounces: each flight shorter than 0.1 s
            if run[0] - t > 0.1:
                break
            run.insert(0, t)
        if len(run) >= 3:
            return run[0], hold["start_s"], hold["release_s"], run
    return None


def resolves_flights(t, impact_times):
    """True when the history has at least 20 rows in the longest flight between the impacts."""
    flights = np.diff(impact_times)
    if not len(flights):
        return True
    k = int(np.argmax(flights))
    return np.count_nonzero((t > impact_times[k]) & (t < impact_times[k + 1])) >= 20


def draw_inset(axis, t, gaps, sequence, window):
    t0, t1 = window
    inset = axis.inset_axes([0.03, 0.5, 0.36, 0.45])
    inside = (t >= t0) & (t <= t1)
    for pair in gaps:
        inset.plot(t[inside], 1000 * pair["g"][inside], color=COLOURS[pair["striking"]], lw=0.9)
    inset.axhline(0.0, color="k", lw=0.6)
    if sequence:
        _, hold_start, hold_end, times = sequence
        shown = [x for x in times if t0 <= x <= t1]
        inset.plot(shown, [0.0] * len(shown), "k.", ms=4)
        inset.axvspan(hold_start, min(hold_end, t1), color="0.85", lw=0)
        inset.set_title(f"g [mm]: {len(times)} impacts in {1000 * (hold_start - times[0]):.0f} ms, then held "
                        f"(shaded) from {hold_start:.4f} s", fontsize=7)
        if not resolves_flights(t, times):
            print("note: fewer than 20 history rows in the longest flight of the inset; the flights are drawn "
                  "as chords (set [output] history_interval_s = 1e-4 to draw the arcs)", file=sys.stderr)
    near = [np.max(1000 * p["g"][inside]) for p in gaps if np.any(inside)]
    inset.set_xlim(t0, t1)
    inset.set_ylim(-0.05 * min(near + [5.0]), 1.1 * min(near + [5.0]))  # the closing pair's arcs, not the far pair
    inset.tick_params(labelsize=7)
    inset.set_xlabel("t [s]", fontsize=7, labelpad=1)
    inset.grid(alpha=0.3)
    _, connectors = axis.indicate_inset_zoom(inset, edgecolor="0.3")
    for k, line in enumerate(connectors):  # the right-hand pair: they do not cross the panel
        line.set_visible(k in (2, 3))


def plot(folder: Path, level, compare, inset_window, out):
    summary, columns = read_run(folder)
    written = summary["history_levels"]
    if not written:  # no common level: every contact is slab to column (docs/model.md 6b)
        sys.exit(f"error: {folder}/history.csv holds no level: plot_run draws the slabs of a level, and this "
                 "scene's slabs meet only columns (its floors' histories are in history.csv, its impacts in "
                 "impacts.csv)")
    if summary.get("pairs"):  # a row (docs/guide/rows.md)
        sys.exit(f"error: {folder} is a row of {len(summary['peaks'])} buildings: plot_run draws one level of two "
                 "buildings; draw the row with `pounding plan` and tools/plot_plan.py --impacts (its histories are "
                 "in history.csv, its impacts in impacts.csv)")
    level = level or written[-1]
    if level not in written:
        sys.exit(f"error: --level {level}: history.csv holds levels {written}")
    where = summary["levels"][level - 1]
    floors = {1: where["floors"][0], 2: where["floors"][1]}  # each building's own floor at that level
    other = read_run(compare) if compare else None
    if other and level not in other[0]["history_levels"]:
        sys.exit(f"error: {compare} has no history of level {level}")
    t = columns["t_s"]
    names = {b: summary["peaks"][b - 1]["building"] for b in (1, 2)}
    slabs = {b: slab_history(summary, columns, b, floors[b]) for b in (1, 2)}
    other_slabs = {b: slab_history(other[0], other[1], b, floors[b]) for b in (1, 2)} if other else None

    fig, axes = plt.subplots(5, 1, figsize=(10, 14), sharex=True,
                             gridspec_kw={"height_ratios": [1, 1, 1, 1, 1.5]})
    for axis, (key, scale, label) in zip(axes, [("u", 100.0, "u [cm]"), ("v", 100.0, "v [cm]"),
                                                ("phi", 1000.0, "φ [mrad]")]):
        for b in (1, 2):
            if other:
                axis.plot(other[1]["t_s"], scale * other_slabs[b][key], color=GREY, lw=1.0)
            axis.plot(t, scale * slabs[b][key], color=COLOURS[b], lw=1.0, label=names[b])
        axis.set_ylabel(label)

    vertex_axis = axes[3]
    for b in (1, 2):
        others = {}
        if other:  # the same material point in the other run, whatever its gap
            others = {(gap_frame_x(other[0], b, p[0]), p[1]): dx for p, dx in other_slabs[b]["vertices"]}
        for k, (point, dx) in enumerate(slabs[b]["vertices"]):
            key = (gap_frame_x(summary, b, point[0]), point[1])
            match = next((v for p, v in others.items() if np.hypot(p[0] - key[0], p[1] - key[1]) < 1e-6), None)
            if match is not None:
                vertex_axis.plot(other[1]["t_s"], 100 * match, color=GREY, lw=1.0)
            vertex_axis.plot(t, 100 * dx, lw=1.0, color=COLOURS[b], ls=["-", "--", ":", "-."][k % 4],
                             label=f"{names[b]} vertex {vertex_label(summary, b, point)}")
    vertex_axis.set_ylabel("vertex x-displacement [cm]")
    vertex_axis.legend(loc="lower left", fontsize=8, ncol=2)

    gap_axis = axes[4]
    gaps = pair_gaps(summary, columns, level, floors)
    other_gaps = pair_gaps(other[0], other[1], level, floors) if other else []
    if other:
        for pair in other_gaps:
            gap_axis.plot(other[1]["t_s"], 100 * pair["g"], color=GREY, lw=1.0)
    for k, pair in enumerate(gaps):
        gap_axis.plot(t, 100 * pair["g"], color=COLOURS[pair["striking"]], lw=1.0, ls=["-", "--"][k % 2],
                      label=pair["label"])
    gap_axis.axhline(0.0, color="k", lw=0.8)
    gap_axis.set_ylabel("signed gap g [cm]")
    gap_axis.set_xlabel("t [s]")
    gap_axis.legend(loc="lower left", fontsize=8)
    impacts = [i["t_s"] for i in summary["impacts"] if i["level"] == level]
    at_impacts = [np.min(np.abs([p["g"][np.argmin(np.abs(t - ti))] for p in gaps])) for ti in impacts]
    if at_impacts:
        print(f"check: largest |g| of the nearest pair at the {len(impacts)} impact rows: {max(at_impacts):.1e} m")
    sequence = bounce_sequence(summary, level)
    if sequence and not inset_window and not resolves_flights(t, sequence[3]):
        print("note: no inset: the history is too sparse to draw the flights of the bounce sequence "
              "(set [output] history_interval_s = 1e-4, or give --inset to draw chords)", file=sys.stderr)
        sequence = None
    if inset_window or sequence:
        if not inset_window:
            first, hold_start, _, _ = sequence
            span = hold_start - first
            inset_window = (first - 0.1 * span, hold_start + 0.25 * span)
        top = max(np.max(100 * p["g"]) for p in gaps + other_gaps)
        gap_axis.set_ylim(-0.05 * top, 1.85 * top)  # the upper part holds the inset
        draw_inset(gap_axis, t, gaps, sequence, inset_window)

    for axis in axes:
        for ti in impacts:
            axis.axvline(ti, **IMPACT_STYLE)
        axis.grid(alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    handles.append(Line2D([], [], **IMPACT_STYLE))
    labels.append(f"impacts at this level ({len(impacts)})")
    if other:
        handles.append(Line2D([], [], color=GREY, lw=1.0))
        labels.append(f"gap {other[0]['gap_m']:g} m, {other[0]['method']} ({plural(other[0]['impact_count'], 'impact')})")
    axes[0].legend(handles, labels, loc="upper left", fontsize=8, ncol=2)

    fig.suptitle(f"{summary['scene']}: level {level} (B1 floor {floors[1]}, B2 floor {floors[2]}, "
                 f"{where['elevation_m']:g} m), gap {summary['gap_m']:g} m, k = {summary['restitution']:g}, "
                 f"{summary['method']}: {plural(len(impacts), 'impact')} at this level, {summary['impact_count']} in all",
                 fontsize=10)
    fig.tight_layout()
    out = out or folder / f"level{level}.png"
    fig.savefig(out, dpi=110)
    print(f"Wrote {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path, help="output folder of `pounding run`")
    parser.add_argument("--level", type=int, help="level to draw (default: the top level in history.csv)")
    parser.add_argument("--compare", type=Path, help="a second run folder drawn in grey underneath")
    parser.add_argument("--inset", type=float, nargs=2, metavar=("T0", "T1"),
                        help="time window of the zoomed gap inset (default: the longest bounce sequence)")
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/levelN.png)")
    args = parser.parse_args()
    plot(args.folder, args.level, args.compare, args.inset, args.out)


if __name__ == "__main__":
    main()
