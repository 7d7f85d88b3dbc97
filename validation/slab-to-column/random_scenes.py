#!/usr/bin/python3
"""Slab-to-column contact on random scenes (docs/model.md §6b): two buildings of 1-12 storeys
whose floors mostly stand at different elevations (storey heights 2.6-5.0 m: one height for
all, a taller ground storey, or one per storey), rectangular slabs facing each other along x at
a random clear gap (0 in about a tenth of the cases, else 0.01-0.3 m) over a random common range
of y, off-centre centres of mass, column grids (sections 0.3-0.8 m, some not square) with columns
on the facing edge and at the slab corners, random E, frame factor or target period, damping,
sometimes yielding columns (bilinear or Bouc-Wen) and a column shear capacity; a random record
of examples/records cut to 4-8 s around its strong motion, scaled to a PGA of 0.1-1.0 g along a
random direction; a random compliant law (kelvin, hertzdamp, jankowski) with a random
restitution, sometimes a very stiff or very soft contact stiffness; a random method among
cvode-bdf, cvode-adams, arkode-erk and arkode-dirk. Special cases on purpose: a slab 1.5-5 mm
from a floor of the other building (just outside level_tolerance_m = 1 mm, height ratio near 0
or 1), a floor at a common elevation, one building taller than the whole other one, one-storey
buildings, identical buildings with floors half a storey apart, `law = "impulse"` (must be
refused with exit 2, naming contact.law and slab_to_column, when a slab faces columns) and
`slab_to_column = "off"` (only levels touch; no level at all is refused with exit 2).

Each scene is checked (`pounding check`) and run (`pounding run SCENE --out DIR --no-progress`,
history off) under a timeout. A case fails on: a crash (an exit code other than 0, 2 or 3, or a
signal), a hang (the timeout), an exit 2 without an `error:` message naming a key or where the
scene is valid, an exit 3 without a summary.json or with a status other than the named ones
(solver_failure and non_finite count as failures), NaN or inf in impacts.csv or summary.json
(except the documented empty/null column_shear_ratio), an energy audit of a completed run whose
residual exceeds 1e-4 of the input (or disagrees with its own terms), and slab-to-column
impacts (level 0) that lack a column > 0, a height ratio in (0, 1), a shear >= 0, or disagree
with the geometry: the slab's floor and the struck storey, the height ratio, the column's point
on the facade, the end shear and moment of the fixed-fixed column under the peak force, the
shear ratio against the capacity; `check`'s list of slabs striking columns must match the
floors computed from the storey heights. Prints a table and a summary line; exits 1 on any
failure. Failing scenes stay in their case folders.

    validation/slab-to-column/random_scenes.py [--pounding build/apps/pounding] [--count 60]
                                               [--seed 1] [--start 0] [--out out/slab-to-column-random]
                                               [--timeout 300]
"""
import argparse
import csv
import json
import math
import random
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RECORDS = ROOT / "examples/records"
METHODS = ("cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk")
LAWS = ("kelvin", "hertzdamp", "jankowski")
STATUSES = {"completed", "collapse", "event_limit", "step_limit", "time_limit", "unresolved_overlap"}
TOL = 1e-3  # contact.level_tolerance_m default
# file, format keys, time of the peak (s, from PROVENANCE.md), length (s)
RECORD_LIST = (
    ("elcentro1940_ns_0.02s.AT2", 'format = "peer-at2"\nunits = "g"', 2.02, 31.16),
    ("elcentro1940_ns_peer_RSN6.AT2", 'format = "peer-at2"\nunits = "g"', 2.18, 53.71),
    ("northridge1994_newhall360_peer_RSN1044.AT2", 'format = "peer-at2"\nunits = "g"', 4.32, 39.98),
    ("lomaprieta1989_corralitos000_peer_RSN753.AT2", 'format = "peer-at2"\nunits = "g"', 2.625, 39.98),
    ("kobe1995_jma_ns_ew_0.005s_cms2.txt", 'format = "single"\nunits = "cm/s2"\ndt_s = 0.005\naccel_column = 1', 8.54, 29.995),
    ("kobe1995_jma_ns_ew_0.005s_cms2.txt", 'format = "single"\nunits = "cm/s2"\ndt_s = 0.005\naccel_column = 2', 8.455, 29.995),
    ("northridge1994_sylmar_360_090_0.005s_cms2.txt", 'format = "single"\nunits = "cm/s2"\ndt_s = 0.005\naccel_column = 1', 4.2, 29.995),
    ("chichi1999_tcu068_ns_ew_0.005s_cms2.txt", 'format = "single"\nunits = "cm/s2"\ndt_s = 0.005\naccel_column = 1', 35.18, 89.995),
    ("chichi1999_tcu068_ns_ew_0.005s_cms2.txt", 'format = "single"\nunits = "cm/s2"\ndt_s = 0.005\naccel_column = 2', 35.22, 89.995),
)
KEY = re.compile(r"\b[a-z_0-9]+(\[\d+\])?(\.[a-z_0-9]+(\[\d+\])?)+\b|\b[a-z]+_[a-z_0-9]+\b|--[a-z-]+")


def loguniform(rng, lo, hi):
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def elevations(heights):
    z, out = 0.0, []
    for h in heights:
        z += h
        out.append(z)
    return out


def random_heights(rng, n):
    mode = rng.choice(("one", "ground", "each"))
    if mode == "one":
        return [round(rng.uniform(2.6, 5.0), 2)] * n, "one"
    if mode == "ground":
        h = round(rng.uniform(2.6, 4.2), 2)
        return [round(rng.uniform(h + 0.3, 5.0), 2)] + [h] * (n - 1), "ground"
    return [round(rng.uniform(2.6, 5.0), 3) for _ in range(n)], "each"


def shift_floor(rng, ha, hb, delta):
    """Move one floor of A (heights ha) to a floor of B's elevation + delta by changing one
    storey height of A; returns the new heights or None."""
    za, zb = elevations(ha), elevations(hb)
    pairs = [(f, j) for f in range(len(ha)) for j in range(len(hb))]
    rng.shuffle(pairs)
    for f, j in pairs:
        h = round(ha[f] + (zb[j] + delta - za[f]), 4)
        if 2.6 <= h <= 5.0:
            new = list(ha)
            new[f] = h
            return new
    return None


def building(rng, side, n, heights, gap, x_face, y_lo, y_hi, length, common):
    """A rectangular building facing the other along x; side 1: x in [x_face - length, x_face],
    side 2: x in [x_face + gap, x_face + gap + length]."""
    x0 = round(x_face - length if side == 1 else x_face + gap, 4)
    x1 = round(x0 + length, 4)
    facing_x = x_face if side == 1 else x_face + gap
    slab = [[x0, y_lo], [x1, y_lo], [x1, y_hi], [x0, y_hi]]
    width = y_hi - y_lo
    cm = [round(x0 + length * rng.uniform(0.3, 0.7), 3), round(y_lo + width * rng.uniform(0.3, 0.7), 3)]
    nx, ny = rng.randint(2, 5), rng.randint(2, 6)
    xs = [round(x0 + length * i / (nx - 1), 4) for i in range(nx)]
    xs[0], xs[-1] = x0, x1
    ys = [round(y_lo + width * i / (ny - 1), 4) for i in range(ny)]
    ys[0], ys[-1] = y_lo, y_hi
    b = round(rng.uniform(0.3, 0.8), 2)
    h = b if rng.random() < 0.6 else round(rng.uniform(0.3, 0.8), 2)
    columns = []  # (x, y, b, h) in the program's numbering: `columns` first, then each grid y-major
    explicit = []
    if rng.random() < 0.4:  # a few extra columns near the facing edge, some just inside it
        for _ in range(rng.randint(1, 3)):
            cb, ch = round(rng.uniform(0.3, 0.8), 2), round(rng.uniform(0.3, 0.8), 2)
            inset = rng.choice((0.0, round(0.4 * max(cb, ch), 3), round(0.7 * max(cb, ch), 3)))
            cx = facing_x - inset if side == 1 else facing_x + inset
            cy = round(rng.uniform(*common), 3)  # within the common range of y
            if all(abs(cy - y) > 0.05 for y in ys):
                explicit.append([round(cx, 4), cy, cb, ch])
    columns += explicit
    for y in ys:
        for x in xs:
            columns.append((x, y, b, h))
    mass = round(loguniform(rng, 100.0, 2000.0), 1)
    lines = [
        "[[building]]", f'name = "B{side}"', f"storeys = {n}",
        "storey_height_m = " + (repr(heights[0]) if len(set(heights)) == 1 else "[" + ", ".join(map(repr, heights)) + "]"),
        "slab = [" + ", ".join(f"[{p[0]!r}, {p[1]!r}]" for p in slab) + "]",
        f"centre_of_mass = [{cm[0]!r}, {cm[1]!r}]", f"mass_t = {mass!r}",
    ]
    if rng.random() < 0.5:
        lines.append(f"top_floor_mass_t = {round(mass * rng.uniform(0.7, 1.0), 1)!r}")
    if explicit:
        lines.append("columns = [" + ", ".join(f"[{c[0]!r}, {c[1]!r}, {c[2]!r}, {c[3]!r}]" for c in explicit) + "]")
    E = round(rng.uniform(2.0e7, 4.0e7), -5)
    lines.append(f"E_kPa = {E!r}")
    if rng.random() < 0.5:
        lines.append(f"frame_factor = {round(loguniform(rng, 0.05, 2.0), 4)!r}")
    else:
        lines.append(f"target_period_s = {round(rng.uniform(0.07, 0.15) * n + 0.05, 3)!r}")
    capacity = None
    if rng.random() < 0.4:
        capacity = round(loguniform(rng, 50.0, 1e4), 1)
        lines.append(f"column_shear_capacity_kN = {capacity!r}")
    lines += ["[[building.column_grid]]", "x = [" + ", ".join(map(repr, xs)) + "]",
              "y = [" + ", ".join(map(repr, ys)) + "]", f"b_m = {b!r}", f"h_m = {h!r}"]
    ratio = rng.choice((0.0, 0.02, 0.05, 0.05, 0.1))
    lines += ["[building.damping]", f"ratio = {ratio!r}", "modes = [1, 3]"]
    hyst = None
    if rng.random() < 0.3:
        hyst = rng.choice(("bilinear", "bouc-wen"))
        lines += ["[building.hysteresis]", f'law = "{hyst}"',
                  f"yield_drift_ratio = {round(loguniform(rng, 1e-3, 1e-2), 5)!r}",
                  f"hardening_ratio = {rng.choice((0.0, 0.02, 0.1))!r}"]
        if hyst == "bouc-wen":
            beta = round(rng.uniform(0.1, 0.9), 3)
            gamma = max(round(rng.uniform(-beta, beta), 3), round(-beta + 0.001, 3))
            lines += [f"n = {rng.choice((1.0, 2.0, 5.0, 20.0))!r}", f"beta = {beta!r}", f"gamma = {gamma!r}"]
    info = {"heights": heights, "slab": slab, "columns": columns, "facing_x": facing_x, "E": E,
            "capacity": capacity, "hyst": hyst, "y": (y_lo, y_hi)}
    return "\n".join(lines) + "\n", info


def make_case(rng, k):
    """One random scene: (text, case description, geometry info)."""
    special = rng.choices(("random", "near", "common", "taller", "one-storey", "half", "impulse", "off"),
                          weights=(50, 10, 6, 6, 5, 5, 6, 7))[0]
    n1, n2 = rng.randint(1, 12), rng.randint(1, 12)
    h1, m1 = random_heights(rng, n1)
    h2, m2 = random_heights(rng, n2)
    note = f"{m1}/{m2}"
    if special == "one-storey":
        n1 = n2 = 1
        h1, h2 = [round(rng.uniform(2.6, 5.0), 3)], [round(rng.uniform(2.6, 5.0), 3)]
        note = "1/1"
    elif special == "half":
        n1 = n2 = rng.randint(2, 12)
        h = round(rng.uniform(2.6, 3.33), 3)
        h1 = [h] * n1
        h2 = [round(1.5 * h, 4)] + [h] * (n2 - 1)
        if rng.random() < 0.5:
            h1, h2 = h2, h1
        note = "half"
    elif special == "taller":
        n1, n2 = rng.randint(1, 4), rng.randint(6, 12)
        h1 = [round(rng.uniform(2.6, 3.2), 3)] * n1
        h2 = [round(rng.uniform(3.3, 5.0), 3)] * n2
        if rng.random() < 0.5:
            n1, n2, h1, h2 = n2, n1, h2, h1
        note = "taller"
    elif special in ("near", "common", "off", "impulse"):
        delta = 0.0
        if special == "near":
            delta = round(rng.choice((-1, 1)) * rng.uniform(0.0015, 0.005), 4)
        if special != "near" and rng.random() < (0.3 if special == "off" else 0.5):
            delta = None  # plain random heights (with "off", mostly refused: nothing could touch)
        if delta is not None:
            if rng.random() < 0.5:
                new = shift_floor(rng, h1, h2, delta)
                if new:
                    h1 = new
            else:
                new = shift_floor(rng, h2, h1, delta)
                if new:
                    h2 = new
            note += f" d={delta}"
    x_face = round(rng.uniform(-30.0, 30.0), 2)
    gap = 0.0 if rng.random() < 0.1 else round(rng.uniform(0.01, 0.3), 4)
    l1, l2 = round(rng.uniform(8.0, 30.0), 2), round(rng.uniform(8.0, 30.0), 2)
    w1, w2 = round(rng.uniform(8.0, 30.0), 2), round(rng.uniform(8.0, 30.0), 2)
    y1 = round(rng.uniform(-20.0, 20.0), 2)
    overlap = rng.uniform(0.15, 1.0) * min(w1, w2)  # common range of y
    y2 = round(y1 + w1 - overlap if rng.random() < 0.5 else y1 - w2 + overlap, 2)
    if special == "half":  # identical buildings
        l2, w2, y2 = l1, w1, y1
    seed1, seed2 = rng.random(), rng.random()
    if special == "half":  # the same draws: the same columns, masses, stiffness, damping
        seed2 = seed1
    rng_b1, rng_b2 = random.Random(seed1), random.Random(seed2)
    common = (max(y1, y2), min(y1 + w1, y2 + w2))
    b1, i1 = building(rng_b1, 1, n1, h1, gap, x_face, y1, round(y1 + w1, 2), l1, common)
    b2, i2 = building(rng_b2, 2, n2, h2, gap, x_face, y2, round(y2 + w2, 2), l2, common)
    law = "impulse" if special == "impulse" else rng.choice(LAWS)
    restitution = rng.choice((0.0, 1.0, round(rng.uniform(0.0, 1.0), 3), round(rng.uniform(0.0, 1.0), 3)))
    if law == "jankowski" and restitution <= 0.0:
        restitution = round(rng.uniform(0.01, 1.0), 3)
    stiffness = ""
    r = rng.random()
    if law == "kelvin" and r < 0.3:
        stiffness = f"stiffness_kN_per_m = {round(loguniform(rng, 1e3, 1e4) if r < 0.15 else loguniform(rng, 1e8, 1e10), -1)!r}"
    elif law in ("hertzdamp", "jankowski") and r < 0.3:
        stiffness = f"stiffness_kN_per_m1_5 = {round(loguniform(rng, 1e4, 1e5) if r < 0.15 else loguniform(rng, 1e9, 1e11), -1)!r}"
    name, fmt, t_peak, length = rng.choice(RECORD_LIST)
    duration = round(rng.uniform(4.0, 8.0), 2)
    start = round(max(0.0, t_peak - rng.uniform(1.0, 4.0)), 3)
    start = min(start, round(length - duration - 0.1, 3))
    pga = round(rng.uniform(0.1, 1.0), 3)
    direction = round(rng.uniform(-180.0, 180.0), 1)
    method = rng.choice(METHODS)
    slab_to_column = "off" if special == "off" else None
    if special == "off" and rng.random() < 0.3:
        law = "impulse"  # allowed when slabs do not strike columns
    contact = ["[contact]", f"gap_m = {gap!r}", f"restitution = {restitution!r}", f'law = "{law}"']
    if stiffness and law != "impulse":
        contact.append(stiffness)
    if slab_to_column:
        contact.append(f'slab_to_column = "{slab_to_column}"')
    elif rng.random() < 0.1:
        contact.append('slab_to_column = "on"')
    text = "\n".join([
        f'name = "case{k:03d}"',
        f'description = "random slab-to-column scene {k}: {special}"', "",
        b1, b2,
        "[excitation]", f'file = "{RECORDS / name}"', fmt, f"start_s = {start!r}", f"duration_s = {duration!r}",
        f"scale_to_pga_g = {pga!r}", f"direction_deg = {direction!r}", "",
        "\n".join(contact), "",
        "[solver]", f'method = "{method}"', ""])
    case = {"special": special, "note": note, "n": (n1, n2), "gap": gap, "law": law, "e": restitution,
            "stiff": stiffness.split("= ")[-1] if stiffness and law != "impulse" else "", "method": method,
            "record": name.split("_")[0] + (":2" if "accel_column = 2" in fmt else ""), "pga": pga,
            "stc": slab_to_column or "on", "hyst": "/".join(x or "-" for x in (i1["hyst"], i2["hyst"]))}
    return text, case, (i1, i2)


def expected_pairs(info):
    """{(A, floor, B, storey): ratio} for every floor of A between two floors of B below B's
    roof (neither within TOL), and the set of (A, floor) at a level."""
    pairs, levels = {}, set()
    for a, b in ((0, 1), (1, 0)):
        za, zb = elevations(info[a]["heights"]), [0.0] + elevations(info[b]["heights"])
        for f, z in enumerate(za, 1):
            if any(abs(z - w) <= TOL for w in zb[1:]):
                levels.add((a + 1, f))
                continue
            for j in range(len(zb) - 1):
                if zb[j] < z < zb[j + 1]:
                    pairs[(a + 1, f, b + 1, j + 1)] = (z - zb[j]) / (zb[j + 1] - zb[j])
    return pairs, levels


def facade_points(info_b, col, info_a):
    """The column's points on B's facade (docs/scene-format.md, slab to column): its centre's
    projection onto every edge of B's outline that faces A's slab (some vertex of A in front of
    it), when the centre lies within half its larger section side of the edge and projects onto
    it. Returns {point: edge}, the edge the facing one ("x") or a side one ("y")."""
    x, y, b, h = col
    reach = max(b, h) / 2.0
    slab, other = info_b["slab"], info_a["slab"]
    points = {}
    for e in range(4):
        q1, q2 = slab[e], slab[(e + 1) % 4]
        tx, ty = q2[0] - q1[0], q2[1] - q1[1]
        length = math.hypot(tx, ty)
        nx, ny = ty / length, -tx / length
        if not any((v[0] - q1[0]) * nx + (v[1] - q1[1]) * ny > 0.0 for v in other):
            continue
        along = ((x - q1[0]) * tx + (y - q1[1]) * ty) / length ** 2
        if abs((x - q1[0]) * nx + (y - q1[1]) * ny) > reach + 1e-12 or not 0.0 <= along <= 1.0:
            continue
        point = (round(q1[0] + along * tx, 6), round(q1[1] + along * ty, 6))
        points.setdefault(point, "x" if tx == 0.0 and q1[0] == info_b["facing_x"] else "y")
    return points


def parse_check(text):
    """check's slab-to-column floors {(A, floor, B, storey): ratio} and column candidates
    {(B, column): {(x, y), ...}} (a column near a corner has a point on each facing face)."""
    floors, cands = {}, {}
    for m in re.finditer(r"^\s+B(\d) floor (\d+) \([^)]*\) -> B(\d) storey (\d+) \([^)]*\) at height ratio "
                         r"([0-9.eE+-]+): columns (.*) \(number", text, re.M):
        flex = {int(c): float(v) for c, v in re.findall(r"(\d+) \(([0-9.eE+-]+) mm/MN\)", m[6])}
        floors[(int(m[1]), int(m[2]), int(m[3]), int(m[4]))] = (float(m[5]), flex)
    for m in re.finditer(r"level 0: B(\d) column (\d+) \(([-0-9.eE+]+), ([-0-9.eE+]+)\) storey (\d+)", text):
        cands.setdefault((int(m[1]), int(m[2])), set()).add((float(m[3]), float(m[4])))
    return floors, cands


def finite_json(value, path=""):
    """Paths of non-finite numbers in a parsed JSON value (column_shear_ratio may be null)."""
    bad = []
    if isinstance(value, dict):
        for key, item in value.items():
            bad += finite_json(item, f"{path}.{key}")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            bad += finite_json(item, f"{path}[{i}]")
    elif isinstance(value, float) and not math.isfinite(value):
        bad.append(path)
    return bad


def check_geometry(case, info, check_text, problems):
    """check's slab-to-column floors and columns against the storey heights and the columns."""
    pairs, _ = expected_pairs(info)
    floors, cands = parse_check(check_text)
    if case["stc"] == "off":
        if floors or cands:
            problems.append(f"slab_to_column off but check lists {len(floors)} floors, {len(cands)} column candidates")
        return pairs, cands
    for key, (ratio, flex) in floors.items():
        if key not in pairs:
            problems.append(f"check lists B{key[0]} floor {key[1]} -> B{key[2]} storey {key[3]}, not expected")
            continue
        if abs(pairs[key] - ratio) > 6e-5:
            problems.append(f"check: B{key[0]} floor {key[1]} ratio {ratio}, expected {pairs[key]:.6f}")
        a, b = key[0] - 1, key[2] - 1
        L = info[b]["heights"][key[3] - 1]
        for number, value in flex.items():  # a column struck along x only: f = a^3 b^3 / (3 E L^3) / I_x
            points = cands.get((key[2], number), set())
            if not any(abs(p[0] - info[b]["facing_x"]) <= 1e-9 and info[a]["y"][0] < p[1] < info[a]["y"][1]
                       for p in points):
                continue
            _, _, bc, hc = info[b]["columns"][number - 1]
            aa = pairs[key] * L
            f = aa ** 3 * (L - aa) ** 3 / (3.0 * info[b]["E"] * L ** 3) / (hc * bc ** 3 / 12.0) * 1e6  # mm/MN
            if abs(f - value) > 0.01 * f + 1e-12:
                problems.append(f"check: B{key[2]} column {number} storey {key[3]} flexibility {value} mm/MN, expected {f:.4g}")
    for key in pairs:  # a floor facing a column on the facing edge within the common range of y must be listed
        a, b = key[0] - 1, key[2] - 1
        lo, hi = max(info[0]["y"][0], info[1]["y"][0]), min(info[0]["y"][1], info[1]["y"][1])
        if any(c[0] == info[b]["facing_x"] and lo + 1e-6 < c[1] < hi - 1e-6 for c in info[b]["columns"]) and key not in floors:
            problems.append(f"check misses B{key[0]} floor {key[1]} -> B{key[2]} storey {key[3]} (ratio {pairs[key]:.4f})")
    for (b, number), points in cands.items():
        cols = info[b - 1]["columns"]
        if not 1 <= number <= len(cols):
            problems.append(f"check: B{b} column {number} beyond its {len(cols)} columns")
            continue
        expected = facade_points(info[b - 1], cols[number - 1], info[2 - b])
        def near(point):
            return [p for p in expected if abs(p[0] - point[0]) <= 1e-3 and abs(p[1] - point[1]) <= 1e-3]
        for point in points:
            if not near(point):
                problems.append(f"check: B{b} column {number} {list(cols[number - 1])} at {point}, not a facade point "
                                f"(expected {sorted(expected)})")
        # A column on the facing facade has its point there (a candidate whenever the other slab's
        # facing edge lies within reach of it).
        facing = [p for p, side in expected.items() if side == "x"]
        if facing and not any(expected[n] == "x" for point in points for n in near(point)):
            problems.append(f"check: B{b} column {number} {list(cols[number - 1])} is on the facing facade (point "
                            f"{facing[0]}) but its points {sorted(points)} are all on side edges")
    return pairs, cands


def check_impacts(case, info, pairs, cands, rows, summary, problems):
    level0 = [r for r in rows if r["level"] == "0"]
    if case["stc"] == "off" and level0:
        problems.append(f"slab_to_column off but {len(level0)} level-0 impacts")
    if summary.get("impact_count") != len(rows):
        problems.append(f"impacts.csv has {len(rows)} rows, summary impact_count {summary.get('impact_count')}")
    if level0 and summary.get("impacts_slab_to_column") != len(level0):
        problems.append(f"{len(level0)} level-0 rows, impacts_slab_to_column {summary.get('impacts_slab_to_column')}")
    for r in rows:
        for key, value in r.items():
            if key in ("column_shear_ratio", "column_total_shear_ratio") and value == "":
                continue
            try:
                if not math.isfinite(float(value)):
                    problems.append(f"impacts.csv t={r['t_s']}: {key} = {value}")
            except ValueError:
                problems.append(f"impacts.csv t={r['t_s']}: {key} = {value!r} not a number")
    for r in level0:
        try:
            t, column, ratio = r["t_s"], int(r["column"]), float(r["height_ratio"])
            shear, moment, force = float(r["column_shear_kN"]), float(r["column_moment_kNm"]), float(r["peak_force_kN"])
            a, b = int(r["striking_building"]), int(r["struck_building"])  # the slab's building, the column's
            slab_floor, storey = int(r[f"floors_b{a}"]), int(r[f"floors_b{b}"])
        except (KeyError, ValueError) as error:
            problems.append(f"level-0 impact row unreadable: {error}")
            continue
        if not (column > 0 and 0.0 < ratio < 1.0 and shear >= 0.0):
            problems.append(f"level-0 impact t={t}: column {column}, height_ratio {ratio}, shear {shear}")
            continue
        key = (a, slab_floor, b, storey)
        if key not in pairs:
            problems.append(f"level-0 impact t={t}: B{a} floor {slab_floor} on B{b} storey {storey}: no such slab-to-column pair")
            continue
        if abs(pairs[key] - ratio) > 1e-9:
            problems.append(f"level-0 impact t={t}: height_ratio {ratio}, expected {pairs[key]!r}")
        z = elevations(info[a - 1]["heights"])[slab_floor - 1]
        if abs(float(r["elevation_m"]) - z) > 1e-9:
            problems.append(f"level-0 impact t={t}: elevation {r['elevation_m']}, slab at {z}")
        if (b, column) not in cands:
            problems.append(f"level-0 impact t={t}: B{b} column {column} is not a listed candidate")
        else:
            points = cands[(b, column)]
            rest = (float(r["vertex_rest_x_m"]), float(r["vertex_rest_y_m"]))
            if not any(abs(rest[0] - p[0]) <= 1e-3 and abs(rest[1] - p[1]) <= 1e-3 for p in points):
                problems.append(f"level-0 impact t={t}: vertex_rest {rest}, column points {sorted(points)}")
        L = info[b - 1]["heights"][storey - 1]
        aa, bb = ratio * L, L - ratio * L
        v = max(force * bb ** 2 * (3 * aa + bb) / L ** 3, force * aa ** 2 * (aa + 3 * bb) / L ** 3)
        mm = max(force * aa * bb ** 2 / L ** 2, force * aa ** 2 * bb / L ** 2, 2 * force * aa ** 2 * bb ** 2 / L ** 3)
        if abs(v - shear) > 1e-6 * max(1.0, v):
            problems.append(f"level-0 impact t={t}: column_shear_kN {shear}, expected {v} from peak force {force}")
        if abs(mm - moment) > 1e-6 * max(1.0, mm):
            problems.append(f"level-0 impact t={t}: column_moment_kNm {moment}, expected {mm}")
        capacity = info[b - 1]["capacity"]
        given = r.get("column_shear_ratio", "")
        if capacity is None and given != "":
            problems.append(f"level-0 impact t={t}: column_shear_ratio {given} without a capacity")
        if capacity is not None and (given == "" or abs(float(given) - shear / capacity) > 1e-9 * max(1.0, shear / capacity)):
            problems.append(f"level-0 impact t={t}: column_shear_ratio {given!r}, expected {shear / capacity}")
        # With the sway (docs/model.md 6b): max(|V_s + N1 F n_a|, |V_s - N2 F n_a|) is at least |V_s|.
        total, sway = float(r["column_total_shear_kN"]), float(r["column_sway_shear_kN"])
        if not total >= abs(sway) - 1e-9 * max(1.0, total):
            problems.append(f"level-0 impact t={t}: column_total_shear_kN {total} below its sway part {sway}")
        given = r.get("column_total_shear_ratio", "")
        if (capacity is None) != (given == "") or (
                capacity is not None and abs(float(given) - total / capacity) > 1e-9 * max(1.0, total / capacity)):
            problems.append(f"level-0 impact t={t}: column_total_shear_ratio {given!r} (capacity {capacity})")


def check_energy(summary, problems):
    e = summary.get("energy", {})
    try:
        terms = sum(e.get(k, 0.0) for k in ("kinetic_final_kJ", "strain_final_kJ", "damping_kJ", "impact_loss_kJ",
                                            "algorithmic_dissipation_kJ", "hysteretic_kJ"))
        residual = e["input_kJ"] + e.get("constraint_work_kJ", 0.0) - terms
        if abs(residual - e["residual_kJ"]) > 1e-9 * max(1.0, abs(e["input_kJ"])) + 1e-6:
            problems.append(f"energy residual_kJ {e['residual_kJ']}, its terms give {residual}")
        if abs(e["relative_residual"]) > 1e-4:
            problems.append(f"energy relative_residual {e['relative_residual']:.2e}")
        return e["relative_residual"]
    except (KeyError, TypeError) as error:
        problems.append(f"energy audit unreadable: {error}")
        return float("nan")


def run_case(args, k, text, case, info, folder):
    """Check and run one scene; returns (row, problems)."""
    problems = []
    scene = folder / "scene.toml"
    scene.write_text(text)
    row = {"k": k, "status": "", "impacts": 0, "column_impacts": 0, "residual": float("nan"), "elapsed": 0.0, "refused": ""}
    # the scene as the compliant law would see it, to know whether a slab faces columns
    probe_text = text.replace('law = "impulse"', 'law = "kelvin"') if case["law"] == "impulse" else text
    probe = folder / "probe.toml"
    probe.write_text(probe_text)
    try:
        checked = subprocess.run([args.pounding, "check", str(probe)], capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return row, ["hang in check"]
    if checked.returncode < 0 or checked.returncode not in (0, 2):
        problems.append(f"check crashed: exit {checked.returncode} {checked.stderr.strip()[-300:]}")
        return row, problems
    _, cands = parse_check(checked.stdout) if checked.returncode == 0 else ({}, {})
    pairs = {}
    if checked.returncode == 0:
        pairs, cands = check_geometry(case, info, checked.stdout, problems)
    expect_refusal = None
    if case["law"] == "impulse" and case["stc"] == "on" and cands:
        expect_refusal = ("contact.law", "slab_to_column")
    pairs_all, levels = expected_pairs(info)
    if case["stc"] == "off" and not levels:
        expect_refusal = ("slab_to_column",)
    if case["law"] == "impulse":  # check refuses what run refuses
        try:
            own = subprocess.run([args.pounding, "check", str(scene)], capture_output=True, text=True, timeout=args.timeout)
            if (own.returncode == 2) != (expect_refusal is not None):
                problems.append(f"check of the impulse scene: exit {own.returncode}, expected a refusal: {expect_refusal is not None}")
        except subprocess.TimeoutExpired:
            problems.append("hang in check")
    command = [args.pounding, "run", str(scene), "--out", str(folder / "run"), "--no-progress", "--history", "off",
               "--max-wall-time", str(args.max_wall_time)]
    start = time.monotonic()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        row["elapsed"] = time.monotonic() - start
        problems.append(f"hang: no exit within {args.timeout} s")
        return row, problems
    row["elapsed"] = time.monotonic() - start
    (folder / "stderr.txt").write_text(done.stderr)
    code = done.returncode
    if code < 0 or code not in (0, 2, 3):
        problems.append(f"crash: exit {code} {done.stderr.strip()[-300:]}")
        return row, problems
    if code == 2:
        message = done.stderr.strip()
        row["status"], row["refused"] = "refused", message.splitlines()[-1][:160] if message else ""
        if "error:" not in message or not KEY.search(message.split("error:", 1)[-1]):
            problems.append(f"exit 2 without an error naming a key: {message[-300:]!r}")
        if expect_refusal is None:
            problems.append(f"refused a valid scene: {message[-300:]}")
        elif not all(word in message for word in expect_refusal):
            problems.append(f"refusal does not name {' and '.join(expect_refusal)}: {message[-300:]}")
        if checked.returncode == 0 and case["law"] != "impulse":
            problems.append("check accepted the scene, run refused it")
        return row, problems
    if expect_refusal:
        problems.append(f"expected a refusal naming {' and '.join(expect_refusal)}, got exit {code}")
    summary_file = folder / "run/summary.json"
    if not summary_file.exists():
        problems.append(f"exit {code} but no summary.json: {done.stderr.strip()[-300:]}")
        return row, problems
    summary_text = summary_file.read_text()
    try:
        summary = json.loads(summary_text, parse_constant=lambda c: float(c))
    except ValueError as error:
        problems.append(f"summary.json unreadable: {error}")
        return row, problems
    bad = finite_json(summary)
    if bad:
        problems.append(f"summary.json non-finite at {bad[:5]}")
    status = summary.get("status")
    row["status"] = status
    if status not in STATUSES:
        problems.append(f"status {status}: {summary.get('status_detail', '')}"[:300])
    if (code == 0) != (status == "completed"):
        problems.append(f"exit {code} with status {status}")
    rows = []
    impacts_file = folder / "run/impacts.csv"
    if impacts_file.exists():
        with open(impacts_file, newline="") as handle:
            rows = list(csv.DictReader(handle))
    elif summary.get("impact_count"):
        problems.append("no impacts.csv")
    row["impacts"] = len(rows)
    row["column_impacts"] = sum(1 for r in rows if r.get("level") == "0")
    check_impacts(case, info, pairs_all, cands, rows, summary, problems)
    if status == "completed":
        row["residual"] = check_energy(summary, problems)
    elif status != "refused":
        row["detail"] = summary.get("status_detail", "")
    return row, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    parser.add_argument("--count", type=int, default=60)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--start", type=int, default=0, help="first case to run (the scenes before it are drawn, not run)")
    parser.add_argument("--out", default=str(ROOT / "out/slab-to-column-random"))
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds before a run counts as a hang")
    parser.add_argument("--max-wall-time", type=float, default=240.0, help="the runs' --max-wall-time")
    args = parser.parse_args()
    rng = random.Random(args.seed)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    failures, rows = [], []
    print(f"{'case':>4} {'kind':<10} {'storeys':<7} {'heights':<14} {'gap':<6} {'law':<9} {'e':<5} {'stiffness':<12} "
          f"{'method':<11} {'record':<12} {'pga':<5} {'hyst':<18} {'s2c':<3}: {'status':<12} {'imp':>4} {'col':>4} "
          f"{'residual':>9} {'time':>6}", flush=True)
    for k in range(args.start + args.count):
        text, case, info = make_case(rng, k)
        if k < args.start:
            continue
        folder = out / f"case{k:03d}"
        folder.mkdir(exist_ok=True)
        row, problems = run_case(args, k, text, case, info, folder)
        rows.append(row)
        for problem in problems:
            failures.append(f"case {k} ({folder / 'scene.toml'}): {problem}")
        print(f"{k:4d} {case['special']:<10} {case['n'][0]:>2}/{case['n'][1]:<4} {case['note']:<14.14} {case['gap']:<6} "
              f"{case['law']:<9} {case['e']:<5} {case['stiff']:<12} {case['method']:<11} {case['record']:<12.12} "
              f"{case['pga']:<5} {case['hyst']:<18} {case['stc']:<3}: {row['status'] or '-':<12} {row['impacts']:4d} "
              f"{row['column_impacts']:4d} {row['residual']:+9.1e} {row['elapsed']:5.1f}s"
              + ("  FAIL" if problems else "") + (f"  [{row['refused'][:90]}]" if row["refused"] else ""), flush=True)
    statuses = {}
    for row in rows:
        statuses[row["status"] or "none"] = statuses.get(row["status"] or "none", 0) + 1
    residuals = [abs(r["residual"]) for r in rows if r["status"] == "completed" and math.isfinite(r["residual"])]
    longest = max(rows, key=lambda r: r["elapsed"]) if rows else None
    print(f"{len(rows)} cases, statuses {statuses}, {sum(r['column_impacts'] for r in rows)} slab-to-column impacts, "
          f"largest |residual| of completed runs {max(residuals, default=0.0):.1e}, longest run "
          f"{longest['elapsed'] if longest else 0.0:.1f} s (case {longest['k'] if longest else '-'}); {len(failures)} failures")
    for row in rows:  # named statuses other than completed: not failures, but worth reading
        if row.get("detail"):
            print(f"NOTE: case {row['k']} {row['status']}: {row['detail'][:240]}")
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
