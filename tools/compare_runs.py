#!/usr/bin/python3
"""Compares two `pounding run` output folders, whatever method made them.

Prints impact-by-impact differences (impacts matched by contact and time, in time order, within
--window seconds), the impacts left unmatched on either side, the differences of the floor
peaks, and the largest difference of the history curves (B interpolated onto A's times).

    tools/compare_runs.py out/cvode out/hht [--window 0.05] [--json diff.json]
"""
import argparse
import bisect
import csv
import json
import sys
from pathlib import Path


def load(folder: Path):
    try:
        summary = json.loads((folder / "summary.json").read_text())
        outputs = summary.get("outputs", {"history": True, "peaks": ["displacements"]})
        if not outputs["history"] or "displacements" not in outputs["peaks"]:
            sys.exit(f"error: {folder} holds no history or no displacement peaks ([output] in docs/scene-format.md): "
                     "run it again with --history on --peaks all")
        with (folder / "history.csv").open() as handle:
            rows = list(csv.reader(handle))
    except FileNotFoundError as error:
        sys.exit(f"error: {error.filename} not found (is {folder} the output folder of `pounding run`?)")
    header, data = rows[0], rows[1:]
    history = {name: [float(r[i]) for r in data] for i, name in enumerate(header)}
    return summary, history


def match_impacts(a, b, window):
    """Greedy in time order: each impact of A takes the nearest unused impact of B at the same
    contact (level, striking building and vertex, struck edge)."""
    used, pairs, unmatched_a = set(), [], []
    for ia in a:
        best = None
        for j, ib in enumerate(b):
            same_contact = all(ib[k] == ia[k] for k in ("level", "striking_building", "vertex", "struck_edge"))
            if j in used or not same_contact:
                continue
            dt = abs(ib["t_s"] - ia["t_s"])
            if dt <= window and (best is None or dt < best[0]):
                best = (dt, j)
        if best is None:
            unmatched_a.append(ia)
        else:
            used.add(best[1])
            pairs.append((ia, b[best[1]]))
    unmatched_b = [ib for j, ib in enumerate(b) if j not in used]
    return pairs, unmatched_a, unmatched_b


def interpolate(times, values, t):
    k = bisect.bisect_left(times, t)
    if k <= 0:
        return values[0]
    if k >= len(times):
        return values[-1]
    if times[k] == t:
        return values[k]
    t0, t1 = times[k - 1], times[k]
    return values[k - 1] + (values[k] - values[k - 1]) * (t - t0) / (t1 - t0)


def history_differences(ha, hb):
    """Largest |A − B| per quantity (u, v, φ, vertex dx) over the common columns and times."""
    t_end = min(ha["t_s"][-1], hb["t_s"][-1])
    worst = {}
    for column in ha:
        if column == "t_s" or column not in hb:
            continue
        quantity = column.split("_", 2)[2]  # e.g. u_m, phi_rad, vtx1_dx_m
        quantity = "vertex_dx_m" if quantity.startswith("vtx") else quantity
        for t, va in zip(ha["t_s"], ha[column]):
            if t > t_end:
                break
            d = abs(va - interpolate(hb["t_s"], hb[column], t))
            if d > worst.get(quantity, (0.0,))[0]:
                worst[quantity] = (d, column, t)
    return worst


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("a", type=Path)
    parser.add_argument("b", type=Path)
    parser.add_argument("--window", type=float, default=0.05, help="largest time difference of a match (s)")
    parser.add_argument("--json", type=Path, help="also write the comparison as JSON")
    args = parser.parse_args()
    if not args.window > 0:
        sys.exit(f"error: --window = {args.window}: must be positive (s)")

    (sa, ha), (sb, hb) = load(args.a), load(args.b)
    print(f"A: {args.a} ({sa['method']}, {sa['impact_count']} impacts)")
    print(f"B: {args.b} ({sb['method']}, {sb['impact_count']} impacts)")

    pairs, only_a, only_b = match_impacts(sa["impacts"], sb["impacts"], args.window)
    print(f"\nMatched impacts: {len(pairs)}; only in A: {len(only_a)}; only in B: {len(only_b)}")
    print(f"{'level':>5} {'t_A [s]':>12} {'t_B - t_A [s]':>14} {'approach A [m/s]':>17} {'approach B':>11} "
          f"{'impulse A [kN s]':>17} {'impulse B':>10}")
    for ia, ib in pairs:
        print(f"{ia['level']:>5} {ia['t_s']:>12.6f} {ib['t_s'] - ia['t_s']:>14.3e} {ia['approach_velocity_mps']:>17.5f} "
              f"{ib['approach_velocity_mps']:>11.5f} {ia['impulse_kNs']:>17.3f} {ib['impulse_kNs']:>10.3f}")
    for label, rest in (("A", only_a), ("B", only_b)):
        for i in rest:
            print(f"  only in {label}: level {i['level']} (floors {i['floors'][0]}/{i['floors'][1]}, "
                  f"{i['elevation_m']:g} m) at {i['t_s']:.6f} s, approach {i['approach_velocity_mps']:.5f} m/s")
    max_dt = max((abs(ib["t_s"] - ia["t_s"]) for ia, ib in pairs), default=0.0)
    print(f"Largest impact-time difference: {max_dt:.3e} s")

    print("\nPeak differences (B − A):")
    peak_rows = []
    for b, (pa, pb) in enumerate(zip(sa["peaks"], sb["peaks"])):
        for fa, fb in zip(pa["floors"], pb["floors"]):
            for key, unit, scale in (("u_m", "cm", 100), ("v_m", "cm", 100), ("phi_rad", "mrad", 1000)):
                d = abs(fb[key]["value"]) - abs(fa[key]["value"])
                peak_rows.append({"building": pa["building"], "floor": fa["floor"], "quantity": key, "difference": d})
        # This building's floor at the top level it meets (a row: its highest floor at any of its levels).
        at = [lv["floors"][side] for lv in sa["levels"] for side, other in enumerate(lv.get("buildings", [1, 2]))
              if other == b + 1]
        if not at:
            continue
        top = pa["floors"][max(at) - 1]
        top_b = pb["floors"][top["floor"] - 1]
        print(f"  {pa['building']} floor {top['floor']}: |u| {100 * abs(top['u_m']['value']):.2f} -> "
              f"{100 * abs(top_b['u_m']['value']):.2f} cm, |v| {100 * abs(top['v_m']['value']):.2f} -> "
              f"{100 * abs(top_b['v_m']['value']):.2f} cm, |phi| {1000 * abs(top['phi_rad']['value']):.3f} -> "
              f"{1000 * abs(top_b['phi_rad']['value']):.3f} mrad")
    worst_peak = max(peak_rows, key=lambda r: abs(r["difference"]), default=None)
    if worst_peak:
        print(f"  largest over all floors: {worst_peak['building']} floor {worst_peak['floor']} "
              f"{worst_peak['quantity']} {worst_peak['difference']:.3e}")

    print("\nLargest history difference |A − B| (B interpolated onto A's samples):")
    worst = history_differences(ha, hb)
    for quantity, (d, column, t) in sorted(worst.items()):
        print(f"  {quantity:>12}: {d:.3e} ({column} at {t:.3f} s)")

    if args.json:
        args.json.write_text(json.dumps({
            "a": str(args.a), "b": str(args.b), "matched": len(pairs), "only_in_a": len(only_a),
            "only_in_b": len(only_b), "max_impact_time_difference_s": max_dt,
            "impact_time_differences_s": [ib["t_s"] - ia["t_s"] for ia, ib in pairs],
            "largest_peak_difference": worst_peak,
            "history_max_difference": {q: {"value": d, "column": c, "t_s": t} for q, (d, c, t) in worst.items()},
        }, indent=2))
        print(f"Wrote {args.json}")


if __name__ == "__main__":
    main()
