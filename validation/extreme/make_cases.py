#!/usr/bin/python3
"""Writes the scenes of the extreme-case suite (issue 9) into validation/extreme/cases/: each a
variant of the paper scene (examples/paper/paper.toml) that stresses one thing, with a header
saying what makes it hard and what the right answer is, and cases/index.json listing them
(name, file, quick, hard, answer) for run_suite.py.

    validation/extreme/make_cases.py [--pounding build/apps/pounding]

The grazing cases need the critical gap of the paper scene (the smallest gap with no contact)
to 1e-11 m: it is found by bisection with the exact path the first time and kept in
critical_gap.json (delete it to measure again). Everything else is computed here.
"""
import argparse
import json
import math
import subprocess
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
CASES = HERE / "cases"
RECORDS = ROOT / "examples/records"

E_KPA = 3.15e7
G = 9.81


def paper_building(number, gap=0.2):
    """The paper's buildings (examples/paper/paper.toml); building 2 stands `gap` m away."""
    if number == 1:
        return {
            "name": "B1", "storeys": 7, "storey_height_m": 3.0,
            "slab": [[-24.0, 0.0], [0.0, 0.0], [0.0, 20.0], [-24.0, 20.0]],
            "centre_of_mass": [-10.8, 11.0], "mass_t": 555.0, "top_floor_mass_t": 530.0,
            "polar_moment_tm2": "uniform", "E_kPa": E_KPA, "frame_factor": 0.746251,
            "column_grid": {"x": [-24.0, -18.0, -12.0, -6.0, 0.0], "y": [0.0, 5.0, 10.0, 15.0, 20.0],
                            "b_m": 0.45, "h_m": 0.45},
            "damping": {"ratio": 0.05, "modes": [1, 3]},
        }
    return {
        "name": "B2", "storeys": 10, "storey_height_m": 3.0,
        "slab": [[gap, 8.0], [28.0 + gap, 8.0], [28.0 + gap, 33.0], [gap, 33.0]],
        "centre_of_mass": [12.6 + gap, 19.25], "mass_t": 845.0, "top_floor_mass_t": 810.0,
        "polar_moment_tm2": "uniform", "E_kPa": E_KPA, "frame_factor": 0.572683,
        "column_grid": {"x": [gap + 7.0 * i for i in range(5)], "y": [8.0, 13.0, 18.0, 23.0, 28.0, 33.0],
                        "b_m": 0.50, "h_m": 0.50},
        "damping": {"ratio": 0.05, "modes": [1, 3]},
    }


def el_centro(**changes):
    """The paper's excitation: El Centro N-S read at 0.05 s, 12.2 s, scaled to 0.32 g."""
    spec = {"file": "../../../examples/records/elcentro1940_ns_0.02s.AT2", "format": "peer-at2", "units": "g",
            "dt_s": 0.05, "duration_s": 12.2, "scale_to_pga_g": 0.32, "g_mps2": G, "direction_deg": 0.0}
    spec.update(changes)
    return spec


def shift_y(building, dy):
    """Moves a building's plan by dy along y (slab, centre of mass, columns)."""
    building["slab"] = [[x, y + dy] for x, y in building["slab"]]
    building["centre_of_mass"][1] += dy
    building["column_grid"]["y"] = [y + dy for y in building["column_grid"]["y"]]
    return building


def column_storey_matrix(building):
    """The 3×3 storey matrix (u, v, φ about the CM) the columns give (docs/scene-format.md):
    Σ Tᵀ diag(k_x, k_y) T, k_x = f·12 E (h b³/12)/H³, k_y = f·12 E (b h³/12)/H³."""
    grid, f, height = building["column_grid"], building["frame_factor"], building["storey_height_m"]
    b, h = grid["b_m"], grid["h_m"]
    kx = f * 12 * building["E_kPa"] * (h * b ** 3 / 12) / height ** 3
    ky = f * 12 * building["E_kPa"] * (b * h ** 3 / 12) / height ** 3
    cx, cy = building["centre_of_mass"]
    k = [[0.0] * 3 for _ in range(3)]
    for x in grid["x"]:
        for y in grid["y"]:
            t = [[1.0, 0.0, -(y - cy)], [0.0, 1.0, x - cx]]
            for i in range(3):
                for j in range(3):
                    k[i][j] += kx * t[0][i] * t[0][j] + ky * t[1][i] * t[1][j]
    return k


def stiffen_first_storey(building, factor):
    """Replaces the columns by storey matrices, the first storey `factor` times stiffer."""
    k = column_storey_matrix(building)
    stiff = [[factor * v for v in row] for row in k]
    for key in ("column_grid", "E_kPa", "frame_factor"):
        building.pop(key)
    building["storey_stiffness"] = [stiff] + [k] * (building["storeys"] - 1)
    return building


# --- TOML -----------------------------------------------------------------------------------

def toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(value)


def toml_scene(scene):
    lines = [f"name = {toml_value(scene['name'])}", f"description = {toml_value(scene['description'])}", ""]
    for building in scene["buildings"]:
        lines.append("[[building]]")
        tables = {k: v for k, v in building.items() if isinstance(v, dict)}
        for key, value in building.items():
            if key not in tables:
                lines.append(f"{key} = {toml_value(value)}")
        if "column_grid" in tables:
            lines.append("[[building.column_grid]]")
            lines += [f"{k} = {toml_value(v)}" for k, v in tables["column_grid"].items()]
        if "damping" in tables:
            lines.append("[building.damping]")
            lines += [f"{k} = {toml_value(v)}" for k, v in tables["damping"].items()]
        lines.append("")
    for table in ("excitation", "contact", "output"):
        if table in scene:
            lines.append(f"[{table}]")
            lines += [f"{k} = {toml_value(v)}" for k, v in scene[table].items()]
            lines.append("")
    return "\n".join(lines)


def comment(text):
    return "\n".join("# " + line if line else "#" for line in text.strip().splitlines())


# --- records ----------------------------------------------------------------------------------

def write_pulse(path, amplitude_g=0.3, rise_s=0.1, hold_s=3.0, total_s=6.0, dt=0.01):
    """A long rectangular pulse (ramped over rise_s): both buildings are pushed the same way for
    seconds, the more flexible one (B2 lags) presses into the other."""
    lines = [f"# Rectangular ground-acceleration pulse, {amplitude_g} g for {hold_s} s (ramps of {rise_s} s),",
             "# written by validation/extreme/make_cases.py. Columns: time (s), acceleration (g)."]
    for i in range(int(round(total_s / dt)) + 1):
        t = i * dt
        if t < rise_s:
            a = amplitude_g * t / rise_s
        elif t < rise_s + hold_s:
            a = amplitude_g
        elif t < 2 * rise_s + hold_s:
            a = amplitude_g * (2 * rise_s + hold_s - t) / rise_s
        else:
            a = 0.0
        lines.append(f"{t:.2f} {a:.6f}")
    path.write_text("\n".join(lines) + "\n")


# --- the critical gap --------------------------------------------------------------------------

def critical_gap(pounding):
    """Smallest gap of the paper scene with no impact, by bisection with the exact path (it
    examines every minimum of a gap inside its steps, so a graze is not missed): the gap at
    which the deepest minimum of the free (contact-free) motion's gap is exactly 0."""
    cache = HERE / "critical_gap.json"
    if cache.exists():
        return json.loads(cache.read_text())["critical_gap_m"]
    scene = ROOT / "examples/paper/paper.toml"
    with tempfile.TemporaryDirectory() as out:
        def contact(gap):
            subprocess.run([pounding, "run", str(scene), "--method", "exact", "--gap", repr(gap), "--out", out],
                           stdout=subprocess.DEVNULL, check=False)
            s = json.loads((Path(out) / "summary.json").read_text())
            return s["impact_count"] > 0
        low, high = 0.30, 0.40
        assert contact(low) and not contact(high)
        while high - low > 1e-11:
            middle = 0.5 * (low + high)
            low, high = (middle, high) if contact(middle) else (low, middle)
    cache.write_text(json.dumps({"critical_gap_m": high, "method": "exact", "bisection_to_m": 1e-11,
                                 "criterion": "impact_count > 0 below"}, indent=1) + "\n")
    return high


# --- the cases ---------------------------------------------------------------------------------

def paper_scene(name, description, gap=0.2, restitution=0.5, excitation=None, **contact):
    scene = {
        "name": name, "description": description,
        "buildings": [paper_building(1), paper_building(2, gap)],
        "excitation": excitation or el_centro(),
        "contact": {"gap_m": gap, "restitution": restitution, **contact},
    }
    return scene


def cases(gap_c):
    """(scene, quick, hard, answer) for every case."""
    out = []

    def add(scene, quick, hard, answer):
        out.append((scene, quick, hard, answer))

    for factor, label in ((1e4, "1e4"), (1e6, "1e6")):
        s = paper_scene(f"stiff-{label}", f"Paper scene, B1's first storey {label} times stiffer")
        stiffen_first_storey(s["buildings"][0], factor)
        add(s, False,
            f"B1's first storey {label}× stiffer: its shortest period falls by ~{math.sqrt(factor):.0f}×, so any step "
            "bound tied to the stiffest mode (rather than to what moves the gaps) costs orders of magnitude more "
            "steps; explicit ERK must resolve the stiff mode for stability.",
            "Floor 1 barely moves; the pounding floors (5–7) respond as in a building with a rigid first storey. "
            "All event-driven paths agree with the reference; implicit BDF/DIRK should need far fewer steps than ERK.")
    add(paper_scene("restitution-0", "Paper scene with k = 0 (plastic impacts)", restitution=0.0), True,
        "k = 0: every impact leaves the pair with zero relative normal speed, i.e. exactly at the sticking "
        "threshold; a hold must start at once, with no bounce sequence.",
        "Each impact starts a sustained contact (starts_sustained_contact), no accumulations; energy balance closes "
        "with impact losses equal to the relative kinetic energy of each approach.")
    add(paper_scene("restitution-1", "Paper scene with k = 1 (elastic impacts)", restitution=1.0), True,
        "k = 1: no energy is lost in impacts, bounces never die out, so a pressed pair chatters instead of "
        "sticking.",
        "impact_loss_kJ = 0 to round-off; separation speed equals approach speed for lone contacts; no holds.")
    for delta, label in ((-1e-6, "minus-1e-6"), (-1e-9, "minus-1e-9"), (1e-9, "plus-1e-9"), (1e-6, "plus-1e-6")):
        gap = gap_c + delta
        add(paper_scene(f"grazing-{label}", f"Paper scene at the critical gap {gap_c:.11f} m {delta:+g} m", gap=gap),
            label == "minus-1e-6",
            f"The gap's deepest minimum over the run is {delta:+g} m: a graze. A step that jumps over the dip, or a "
            "root finder that needs a sign change at step ends, misses it.",
            "Below the critical gap (minus): one impact on floor 7 near 6.775 s with approach speed ~sqrt(2·|g''|·δ) "
            "(tiny). Above it (plus): no impact; at +1e-9 m the minimum lies within 10 nm of contact, which the "
            "event-driven paths report as a touch; at +1e-6 m nothing.")
    corner = paper_scene("corner-on-corner", "Slabs overlapping 1 cm in y: B2's corner meets B1's corner")
    shift_y(corner["buildings"][1], 11.99)
    add(corner, True,
        "The slabs overlap only 1 cm along y, so a few mm of relative y motion or a small rotation carries the "
        "contact vertex past the end of the edge it strikes; at step ends the corners may already have slid past "
        "each other.",
        "CVODE (rtol 1e-8) finds 13 impacts, on floors 5, 6 and 7; every contact point lies within the 1 cm "
        "overlap; no path may record none.")
    face = paper_scene("face-on", "Both slabs span the same y range: face-on contact")
    shift_y(face["buildings"][1], -10.0)
    add(face, True,
        "The facing sides have the same length and ends: the corners of each slab strike the other's face, "
        "two contacts per floor at once (both corners), solved together.",
        "Impacts come in simultaneous pairs on the same floor (B1's and B2's corners); the LCP shares the impulse; "
        "energy balance closes.")
    add(paper_scene("several-floors", "Paper scene at a 1 cm gap: floors 2–7 pound", gap=0.01), False,
        "A 1 cm gap: six floors pound, often within milliseconds of each other, with long sustained contacts.",
        "CVODE (rtol 1e-8) finds about 365 impacts on floors 2–7 (most on floor 7) and the holds that end the "
        "bounce sequences; every path agrees on which floors pound.")
    pulse = paper_scene("pulse-gap-0", "Long rectangular pulse, 0.3 g for 3 s, slabs touching at rest", gap=0.0,
                        excitation={"file": "../records/pulse_0.3g_3s.txt", "format": "columns", "units": "g",
                                    "g_mps2": G, "direction_deg": 0.0})
    add(pulse, True,
        "Zero gap and a long one-sided push: the slabs start in contact and are pressed together for seconds, "
        "the case where a scheme without sustained contact chatters and lets the slabs sink into each other.",
        "The pair is held (sustained contact) for most of the pulse and released when the contact force turns "
        "tensile; no interpenetration beyond the paths' tolerance; energy balance closes.")
    add(paper_scene("zero-gap-at-rest", "Paper scene with the slabs touching at rest (gap 0)", gap=0.0), False,
        "Gap 0: every candidate starts exactly at g = 0, where the root functions are zero at the initial time "
        "(SUNDIALS does not report roots at t0).",
        "The first contact is handled before the first step; many impacts and holds follow; no overlap.")
    dense = paper_scene("long-dense-record", "Chi-Chi 1999 TCU068 N-S, 90 s at 0.005 s, PGA 0.51 g",
                        excitation={"file": "../../../examples/records/chichi1999_tcu068_ns_ew_0.005s_cms2.txt",
                                    "format": "single", "units": "cm/s2", "dt_s": 0.005, "accel_column": 1,
                                    "direction_deg": 0.0})
    add(dense, False,
        "18 000 samples over 90 s with a large long-period pulse: a stop at every sample resets multistep "
        "methods (BDF's order); the run is long.",
        "Heavy pounding on the top common floors (large displacements); all event-driven paths agree with the "
        "reference; BDF should not take many times ERK's run time.")
    for storeys, label in (((28, 40), "40-storeys"), ((42, 60), "60-storeys")):
        s = paper_scene(label, f"Paper plan with {storeys[0]} and {storeys[1]} storeys")
        for building, n in zip(s["buildings"], storeys):
            building["storeys"] = n
        add(s, False,
            f"{storeys[0]} and {storeys[1]} storeys: {3 * sum(storeys)} DOF, {2 * storeys[0]} candidates, long "
            "periods; dense linear algebra and the exact path's eigen-decompositions grow as n³.",
            "A valid run of every path (no hang: the exact path may stop on a budget with a named status); "
            "event-driven paths agree with the reference.")
    ecc = paper_scene("eccentric", "B2's centre of mass moved to near its far corner (25.2, 30.25)")
    ecc["buildings"][1]["centre_of_mass"] = [25.2 + 0.2, 30.25]
    add(ecc, True,
        "B2's centre of mass 12.6 m and 11 m off its plan centre: strong torsion, so the contact vertex "
        "moves along y and the gap's rate depends strongly on the rotation.",
        "Pounding on the top common floors with large rotations of B2; event-driven paths agree with the "
        "reference; the energy balance closes.")
    for angle in (45.0, 90.0):
        s = paper_scene(f"direction-{angle:.0f}", f"Paper scene shaken at {angle:.0f}° in plan",
                        excitation=el_centro(direction_deg=angle))
        add(s, angle == 90.0,
            f"Shaking at {angle:.0f}°: {'only torsion and the y-component drive the gap' if angle == 90 else 'x and y together'}; "
            "contact vertices slide along the struck edges.",
            "At 45°: impacts on the top common floors, fewer than at 0°. At 90°: the x motion comes only from "
            "the eccentricities (coupled torsion); few or no impacts. Paths agree with the reference.")
    add(paper_scene("pga-2g", "Paper scene scaled to PGA 2 g", excitation=el_centro(scale_to_pga_g=2.0)), False,
        "PGA 2 g (six times the paper's): approach speeds of metres per second, long bounce accumulations, "
        "large rotations of the contact geometry.",
        "CVODE (rtol 1e-8) finds about 330 impacts on floors 3–7 and long holds; no path may let the slabs "
        "sink into each other silently (HHT used to report 202 mm).")
    add(paper_scene("tiny-hold-velocity", "Paper scene with a sticking threshold of 1e-7 m/s",
                    hold_velocity_mps=1e-7), False,
        "hold_velocity_mps = 1e-7 m/s: a bounce sequence with k = 0.5 must go on for ~20 more bounces before "
        "the pair is held, each flight ~1e4 times shorter than the first: an accumulation resolved almost to "
        "its limit.",
        "Many more impacts than at the default 1 mm/s, the same holds and peaks. An accumulation resolved "
        "this far may exceed the event-driven paths' 2000 events per simulated second (status event_limit): "
        "a named stop, not a hang.")
    light = paper_scene("light-damping", "Paper scene with 0.1 % damping, gap 1 m (no contact)", gap=1.0)
    for building in light["buildings"]:
        building["damping"]["ratio"] = 0.001
    add(light, True,
        "ζ = 0.001 and no contact: almost all input energy stays in the structure, so any numerical damping "
        "(HHT's α) shows in the energy audit.",
        "No impact. Energy residual ~0 for every path (HHT: its numerical damping appears as "
        "algorithmic_dissipation_kJ, not in the residual).")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    args = parser.parse_args()
    CASES.mkdir(exist_ok=True)
    (HERE / "records").mkdir(exist_ok=True)
    write_pulse(HERE / "records/pulse_0.3g_3s.txt")
    gap_c = critical_gap(args.pounding)
    index = []
    for scene, quick, hard, answer in cases(gap_c):
        top = min(b["storeys"] for b in scene["buildings"])
        scene["output"] = {"history_floors": [top]}
        text = comment(f"{scene['description']}\n\nWhat makes it hard: {hard}\n\nThe right answer: {answer}\n\n"
                       "Written by validation/extreme/make_cases.py; edit that, not this file.")
        path = CASES / f"{scene['name']}.toml"
        path.write_text(text + "\n" + toml_scene(scene))
        index.append({"name": scene["name"], "file": f"cases/{path.name}", "quick": quick, "hard": hard,
                      "answer": answer})
    (CASES / "index.json").write_text(json.dumps(index, indent=1, ensure_ascii=False) + "\n")
    lines = ["# Extreme cases", "", "Written by `validation/extreme/make_cases.py`. Each scene varies the paper scene "
             "(`examples/paper/paper.toml`); `run_suite.py` runs every path on each (`--quick`: the cases marked q).", ""]
    for case in index:
        lines += [f"## {case['name']}{' (q)' if case['quick'] else ''}", "", f"`{case['file']}`", "",
                  f"- What makes it hard: {case['hard']}", f"- The right answer: {case['answer']}", ""]
    (CASES / "README.md").write_text("\n".join(lines))
    print(f"wrote {len(index)} cases to {CASES} (critical gap {gap_c:.11f} m)")


if __name__ == "__main__":
    main()
