#!/usr/bin/python3
"""How a row's run time grows with its number of buildings: rows of 2, 4, 8 and 16 buildings.

    bench/rows/ladder.py POUNDING [OUT] [--counts 2 4 8 16] [--methods cvode-bdf arkode-erk] [--law kelvin]

Each row: N five-storey buildings of 3 m storeys along x, 16 m wide slabs 12 and 13 m deep in turn
(the deeper 0.5 m further back) with the centre of mass 0.4 m and 0.3 m off the plan centre, stiffness (frame factor 0.55 ... 0.85) and mass alternating so
that neighbours differ, 0.05 m apart, kelvin law (--law: any other), the paper's El Centro at 0.32 g along 10 degrees
(12.2 s). Per N and method: the DOF, the candidates, the impacts and the run time (summary.json's
wall_time_s, the median of three runs), and the exponent p of time ~ N^p fitted between
consecutive rows and over the ladder. Writes OUT/ladder.csv (default out/bench-rows).
"""
import argparse
import csv
import json
import math
import statistics
import subprocess
import sys
from pathlib import Path

RECORD = Path(__file__).resolve().parents[2] / "examples" / "records" / "elcentro1940_ns_0.02s.AT2"


def building(index, x0):
    # Neighbours' depths differ (12 m and 13 m, the deeper one 0.5 m further back), so no two
    # corners meet at an edge's end (kept so that the ladder's times stay comparable with the ones
    # measured before facades in line ran: docs/model.md §5a).
    width, depth = 16.0, 12.0 + index % 2
    y0 = -0.5 * (index % 2)
    factor = (0.55, 0.85, 0.65, 0.75)[index % 4]
    mass = (420.0, 360.0, 480.0, 390.0)[index % 4]
    xs = ", ".join(f"{x0 + width * k / 3:g}" for k in range(4))
    return f"""[[building]]
name = "B{index + 1}"
storeys = 5
storey_height_m = 3.0
slab = [[{x0:g}, {y0:g}], [{x0 + width:g}, {y0:g}], [{x0 + width:g}, {y0 + depth:g}], [{x0:g}, {y0 + depth:g}]]
centre_of_mass = [{x0 + width / 2 + 0.4:g}, {y0 + depth / 2 + 0.3:g}]
mass_t = {mass}
polar_moment_tm2 = "uniform"
E_kPa = 3.15e7
frame_factor = {factor}
[[building.column_grid]]
x = [{xs}]
y = [{y0:g}, {y0 + depth / 2:g}, {y0 + depth:g}]
b_m = 0.45
h_m = 0.45
[building.damping]
ratio = 0.05
modes = [1, 3]
"""


def scene(count, gap_m=0.05, law="kelvin"):
    parts = [f'name = "row-{count}"\n']
    x0 = 0.0
    for b in range(count):
        parts.append(building(b, x0))
        x0 += 16.0 + gap_m
    parts.append(f"""[excitation]
file = "{RECORD}"
format = "peer-at2"
units = "g"
dt_s = 0.05
duration_s = 12.2
scale_to_pga_g = 0.32
direction_deg = 10.0

[contact]
restitution = 0.5
law = "kelvin"
""")
    if count == 2:
        parts[-1] = parts[-1].replace('law = "kelvin"', f'law = "kelvin"\ngap_m = {gap_m}')
    return "".join(parts).replace('law = "kelvin"', f'law = "{law}"')


def run(pounding, scene_file, method, out):
    times = []
    for repeat in range(3):
        folder = out / f"{scene_file.stem}-{method}-{repeat}"
        done = subprocess.run([pounding, "run", str(scene_file), "--method", method, "--out", str(folder)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"{scene_file} {method}: {done.stderr.strip()}")
        summary = json.loads((folder / "summary.json").read_text())
        times.append(summary["statistics"]["wall_time_s"])
    return summary, statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("pounding")
    parser.add_argument("out", nargs="?", default="out/bench-rows", type=Path)
    parser.add_argument("--counts", nargs="+", type=int, default=[2, 4, 8, 16])
    parser.add_argument("--methods", nargs="+", default=["cvode-bdf", "arkode-erk"])
    parser.add_argument("--law", default="kelvin", help="contact law of every row (default kelvin)")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    for method in args.methods:
        previous = None
        for count in args.counts:
            scene_file = args.out / f"row-{count}.toml"
            scene_file.write_text(scene(count, law=args.law))
            summary, seconds = run(args.pounding, scene_file, method, args.out)
            dof = 15 * count
            exponent = (math.log(seconds / previous[1]) / math.log(count / previous[0])) if previous else float("nan")
            rows.append({"method": method, "law": args.law, "buildings": count, "dof": dof, "candidates": len(summary["candidates"]),
                         "impacts": summary["impact_count"], "steps": summary["statistics"]["steps"], "wall_time_s": seconds, "exponent_from_previous": exponent})
            print(f"{method:11} N = {count:3}: {dof:4} DOF, {len(summary['candidates']):4} candidates, "
                  f"{summary['impact_count']:4} impacts, {summary['statistics']['steps']:6} steps, {seconds:8.3f} s"
                  + ("" if previous is None else f", exponent {exponent:.2f} from N = {previous[0]}"))
            previous = (count, seconds)
        first = next(r for r in rows if r["method"] == method)
        last = rows[-1]
        overall = math.log(last["wall_time_s"] / first["wall_time_s"]) / math.log(last["buildings"] / first["buildings"])
        print(f"{method}: time ~ N^{overall:.2f} over N = {first['buildings']}..{last['buildings']}")
    with open(args.out / "ladder.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print(f"Wrote {args.out / 'ladder.csv'}")


if __name__ == "__main__":
    main()
