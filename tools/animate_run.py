#!/usr/bin/python3
"""Films a `pounding run` folder: the two slabs of one level in plan, moving (a row: every
building's slab at that level's elevation, each pair's gap widened along its direction).

Each slab is drawn where history.csv puts it: its outline at rest moved rigidly by the slab's
(u, v, φ) about its centre of mass, with the motion multiplied by --scale so that centimetres show
on a plan of tens of metres (displacements and the rotation alike, so the drawing is the exact
rigid motion of a slab whose motion is that many times larger). The clear gap at rest is drawn
× scale too (building 2 shifted along x, the direction the gap is measured in), so the drawn slabs
touch when the real ones do: exactly for translation, to first order in φ. The rest outlines, so
shifted, are dashed. Each impact at the level flashes a star at the striking corner, sized by its impulse,
and the count of impacts so far is shown; a sustained contact is named while it lasts.

Frames are sampled from history.csv by linear interpolation, `--speed` simulated seconds per second
of film at `--fps` frames a second: a history written every 0.01 s (the default) is finer than a
frame at speeds up to 0.2 × fps. MP4 needs ffmpeg (Debian's package ffmpeg); without it the film
is a GIF (Pillow, which matplotlib brings).

    tools/animate_run.py RUN_DIR [--level N] [--scale F] [--fps 20] [--speed 1] [--start S] [--end S]
                         [--format auto|mp4|gif] [--out FILE]

RUN_DIR needs history.csv and plan.json: `pounding animate RUN_DIR` writes the plan of the run's
scene there and runs this script.
"""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import animation  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402

from plot_plan import COLOURS, read_plan  # noqa: E402
from plot_run import read_run  # noqa: E402

MAX_FRAMES = 20000          # about 17 min of film at 20 fps: more is a slip of --speed
FLASH_FILM_S = 0.4          # how long an impact's star stays, in seconds of film
PLAN_FRACTION_OF_MOTION = 8  # default scale: the largest corner displacement drawn as 1/8 of the plan


def refuse(message):
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def building_label(plan, b):
    """B1, or B1 'name' when the scene names the building otherwise."""
    name = plan["buildings"][b]["name"]
    return f"B{b + 1}" if name == f"B{b + 1}" else f"B{b + 1} '{name}'"


def default_level(summary):
    """The history level with the most impacts (the higher one of a tie), else the top one. A row:
    a level at the elevation whose levels (one per pair) have most impacts together, the higher
    elevation of a tie."""
    written = summary["history_levels"]
    impacts = {int(level): count for level, count in summary["impacts_by_level"].items()}
    if not summary.get("pairs"):
        return max(written, key=lambda level: (impacts.get(level, 0), level))
    elevation = {entry["level"]: entry["elevation_m"] for entry in summary["levels"]}
    at = {}
    for level in written:
        at.setdefault(round(elevation[level], 6), []).append(level)
    best = max(at, key=lambda z: (sum(impacts.get(level, 0) for level in at[z]), z))
    return min(at[best])


def placed(rest_points, centre, u, v, phi, scale=1.0):
    """Rest points (n × 2) of a rigid slab moved by (u, v, φ) about its centre of mass `centre`,
    the motion multiplied by `scale`: centre + scale·(u, v) + R(scale·φ)·(p − centre)."""
    arm = np.asarray(rest_points, dtype=float) - np.asarray(centre, dtype=float)
    c, s = np.cos(scale * phi), np.sin(scale * phi)
    return np.asarray(centre) + scale * np.array([u, v]) + arm @ np.array([[c, s], [-s, c]])


def level_motion(summary, columns, plan, level):
    """The slabs the film shows, by building (0-based): for two buildings the level's floors; in a
    row every building's floor at the level's elevation (the levels there, one per pair, name
    them). Returns the levels shown and, per building, its floor, outline, centre of mass and the
    u, v, φ columns of that floor."""
    chosen = next(entry for entry in summary["levels"] if entry["level"] == level)
    if summary.get("pairs"):
        levels = [entry for entry in summary["levels"] if abs(entry["elevation_m"] - chosen["elevation_m"]) < 1e-6
                  and entry["level"] in summary["history_levels"]]
    else:
        levels = [{**chosen, "buildings": [1, 2]}]
    floors = {}
    for entry in levels:
        for building, floor in zip(entry["buildings"], entry["floors"]):
            floors[building - 1] = floor
    slabs = {}
    for b in sorted(floors):
        building, prefix = plan["buildings"][b], f"B{b + 1}_f{floors[b]}_"
        slabs[b] = {"floor": floors[b], "shift": np.zeros(2), "outline": np.asarray(building["slab"], dtype=float),
                    "centre": np.asarray(building["centre_of_mass"], dtype=float),
                    "u": columns[prefix + "u_m"], "v": columns[prefix + "v_m"], "phi": columns[prefix + "phi_rad"]}
    return [entry["level"] for entry in levels], slabs


def shifted(slab, shift):
    return {**slab, "outline": slab["outline"] + shift, "centre": slab["centre"] + shift, "shift": slab["shift"] + shift}


def widen_gap(slabs, gap_m, scale):
    """Shifts building 2 along x, away from building 1, so that the gap at rest is scale × gap_m."""
    away = np.sign(slabs[1]["centre"][0] - slabs[0]["centre"][0]) or 1.0
    slabs[1] = shifted(slabs[1], np.array([away * (scale - 1.0) * gap_m, 0.0]))


def widen_row_gaps(slabs, pairs, scale):
    """A row: each pair's second building, and every building beyond it, moved along the pair's
    direction so that the pair's gap at rest is scale × its gap (as --gap places a row)."""
    shifts, todo = {0: np.zeros(2)}, [0]
    while todo:
        first = todo.pop()
        for p in pairs:
            a, b = (x - 1 for x in p["buildings"])
            if a == first and b not in shifts:
                shifts[b] = shifts[a] + (scale - 1.0) * p["gap_m"] * np.asarray(p["direction"], dtype=float)
                todo.append(b)
    for b in slabs:
        slabs[b] = shifted(slabs[b], shifts.get(b, np.zeros(2)))


def default_scale(slabs):
    """The largest corner displacement of either slab over the run drawn as 1/8 of the plan's
    extent, rounded to two significant digits; 1 for slabs that never move."""
    corners = np.vstack([s["outline"] for s in slabs.values()])
    extent = np.max(np.ptp(corners, axis=0))
    largest = 0.0
    for slab in slabs.values():
        for corner in slab["outline"]:
            arm = corner - slab["centre"]
            c, s = np.cos(slab["phi"]), np.sin(slab["phi"])
            dx = slab["u"] + (c - 1) * arm[0] - s * arm[1]
            dy = slab["v"] + s * arm[0] + (c - 1) * arm[1]
            largest = max(largest, float(np.max(np.hypot(dx, dy))))
    if largest == 0.0:
        return 1.0
    wanted = extent / PLAN_FRACTION_OF_MOTION / largest
    return float(f"{wanted:.2g}")


def choose_writer(requested, out, fps):
    """(extension, writer): mp4 with ffmpeg, else gif; --out's suffix decides under auto."""
    has_ffmpeg = animation.FFMpegWriter.isAvailable()
    suffix = out.suffix.lower()[1:] if out is not None else None
    if out is not None and suffix not in ("mp4", "gif"):
        refuse(f"--out {out}: the film is an .mp4 or a .gif file")
    if requested == "auto" and suffix:
        requested = suffix
    if suffix and requested != suffix:
        refuse(f"--out {out} is a .{suffix} file but --format is {requested}")
    if requested == "mp4" and not has_ffmpeg:
        refuse("--format mp4 needs ffmpeg (Debian: apt-get install ffmpeg); --format gif needs nothing more")
    use = "mp4" if requested == "mp4" or (requested == "auto" and has_ffmpeg) else "gif"
    if use == "mp4":
        return use, animation.FFMpegWriter(fps=fps, bitrate=2400, metadata={"comment": "pounding animate"})
    return use, animation.PillowWriter(fps=fps)


def frame_times(t, start, end, fps, speed):
    first, last = float(t[0]), float(t[-1])
    start = first if start is None else start
    end = last if end is None else end
    if not first <= start < end <= last + 1e-9:
        refuse(f"--start {start:g} s and --end {end:g} s must satisfy {first:g} <= start < end <= {last:g} "
               "(the run's history)")
    count = int(np.floor((end - start) * fps / speed + 1e-6)) + 1  # 12.2 s × 20 fps is 244 frames after 0
    if count > MAX_FRAMES:
        refuse(f"{count} frames ({(end - start):g} s at --speed {speed:g} and --fps {fps:g}): at most {MAX_FRAMES}; "
               "narrow --start/--end or raise --speed")
    return start + np.arange(count) * speed / fps


def film(folder, level, scale, fps, speed, start, end, requested_format, out):
    summary, columns = read_run(folder)
    plan = read_plan(folder)
    if not summary["history_levels"]:
        refuse(f"{folder}/history.csv holds no level")
    row = bool(summary.get("pairs"))  # a row (docs/guide/rows.md): every building at the level's elevation
    level = level or default_level(summary)
    if level not in summary["history_levels"]:
        refuse(f"--level {level}: {folder}/history.csv holds levels {summary['history_levels']}")
    levels, slabs = level_motion(summary, columns, plan, level)
    scale = scale or default_scale(slabs)
    if row:
        widen_row_gaps(slabs, summary["pairs"], scale)
    else:
        widen_gap(slabs, summary["gap_m"], scale)
    t = columns["t_s"]
    times = frame_times(t, start, end, fps, speed)
    extension, writer = choose_writer(requested_format, out, fps)
    out = out or folder / f"level{level}.{extension}"

    impacts = [i for i in summary["impacts"] if i["level"] in levels]
    holds = [c for c in summary["sustained_contacts"] if c["level"] in levels]
    largest_impulse = max((i["impulse_kNs"] for i in impacts), default=0.0) or 1.0
    flash_s = FLASH_FILM_S * speed

    fig, ax = plt.subplots(figsize=(7.2, 6.0))
    shapes = {}
    for b, slab in slabs.items():
        colour = COLOURS[b % len(COLOURS)]
        ax.add_patch(Polygon(slab["outline"], closed=True, fill=False, edgecolor="0.6", ls="--", lw=0.8))
        shape = Polygon(slab["outline"], closed=True, facecolor=colour, alpha=0.35, edgecolor=colour, lw=1.5,
                        label=f"{building_label(plan, b)}, floor {slab['floor']}")
        ax.add_patch(shape)
        shapes[b] = shape
    stars = ax.scatter([], [], marker="*", color="red", zorder=5, label="impact (size: impulse)")
    clock = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", fontsize=10, family="monospace")
    corners = np.vstack([s["outline"] for s in slabs.values()])
    margin = 0.1 * np.max(np.ptp(corners, axis=0))
    ax.set_xlim(corners[:, 0].min() - margin, corners[:, 0].max() + margin)
    ax.set_ylim(corners[:, 1].min() - margin, corners[:, 1].max() + 2 * margin)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    elevation = next(entry["elevation_m"] for entry in summary["levels"] if entry["level"] == level)
    where = (f"{len(slabs)} buildings at {elevation:g} m, gaps "
             + ", ".join(f"{p['names'][0]}:{p['names'][1]} {p['gap_m']:g} m" for p in summary["pairs"])
             if row else f"level {level} ({elevation:g} m), gap {summary['gap_m']:g} m")
    ax.set_title(f"{summary['scene']}: {where}, k = {summary['restitution']:g}, {summary['method']}\n"
                 f"motion and gaps drawn × {scale:g}; rest outlines dashed", fontsize=10)
    fig.tight_layout()

    def draw(time_s):
        moved = {}
        for b, slab in slabs.items():
            u, v, phi = (np.interp(time_s, t, slab[key]) for key in ("u", "v", "phi"))
            shapes[b].set_xy(placed(slab["outline"], slab["centre"], u, v, phi, scale))
            moved[b] = (u, v, phi)
        flashing = [i for i in impacts if i["t_s"] <= time_s < i["t_s"] + flash_s]
        points = [placed([np.asarray(i["vertex_rest"]) + slabs[i["striking_building"] - 1]["shift"]],
                         slabs[i["striking_building"] - 1]["centre"], *moved[i["striking_building"] - 1], scale)[0]
                  for i in flashing]
        stars.set_offsets(np.array(points).reshape(-1, 2))
        stars.set_sizes([80 + 320 * i["impulse_kNs"] / largest_impulse for i in flashing])
        so_far = sum(1 for i in impacts if i["t_s"] <= time_s)
        held = any(c["start_s"] <= time_s < c["release_s"] for c in holds)
        clock.set_text(f"t = {time_s:7.3f} s   impacts so far: {so_far}" + ("   sustained contact" if held else ""))
        return [*shapes.values(), stars, clock]

    player = animation.FuncAnimation(fig, draw, frames=times, blit=False)
    player.save(out, writer=writer, dpi=90)
    plt.close(fig)
    print(f"Wrote {out}: {len(times)} frames at {fps:g} fps ({len(times) / fps:.1f} s of film) for "
          f"{times[0]:.3f}–{times[-1]:.3f} s simulated, level {level}{' and its elevation' if row else ''}, "
          f"motion × {scale:g}, "
          f"{sum(1 for i in impacts if times[0] <= i['t_s'] <= times[-1])} impacts shown")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path, help="output folder of `pounding run`, with plan.json")
    parser.add_argument("--level", type=int, help="level to film (default: the history level with most impacts)")
    parser.add_argument("--scale", type=float, help="motion exaggeration (default: largest displacement = 1/8 plan)")
    parser.add_argument("--fps", type=float, default=20.0, help="frames per second of film")
    parser.add_argument("--speed", type=float, default=1.0, help="simulated seconds per second of film")
    parser.add_argument("--start", type=float, help="first simulated time (s)")
    parser.add_argument("--end", type=float, help="last simulated time (s)")
    parser.add_argument("--format", choices=("auto", "mp4", "gif"), default="auto")
    parser.add_argument("--out", type=Path, help="film file (default: FOLDER/levelN.mp4 or .gif)")
    args = parser.parse_args()
    if not (args.fps > 0 and args.speed > 0 and (args.scale is None or args.scale > 0)):
        refuse("--fps, --speed and --scale must be positive")
    film(args.folder, args.level, args.scale, args.fps, args.speed, args.start, args.end, args.format, args.out)


if __name__ == "__main__":
    main()
