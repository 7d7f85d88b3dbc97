"""`pounding bracket SCENE`: one scene run across contact laws, restitutions and contact
stiffnesses, and for every demand the spread over those runs and whether each verdict (limit
state, column shear failure, residual damage state, pounding or not) is the same on all of them.

The contact parameters are the least certain input of a pounding analysis (a struck column's shear
changes severalfold between laws and restitutions): a demand whose spread is wide, or a verdict
that changes, is not decided by the model until those parameters are. docs/guide/bracket.md
explains each number.

Usage: python3 -m pounding.bracket SCENE [--laws L,...] [--restitutions E,...]
       [--stiffness-factors F,...] [--method M] [--out DIR] [--no-progress]
Writes DIR/bracket.csv (a row a run) and DIR/bracket.json (the spread and the verdicts)."""
import argparse
import csv
import json
import math
import pathlib
import sys
import time
import tomllib

import pounding

# Restitutions measured for concrete striking concrete lie about 0.4 to 0.8 (Jankowski 2005 and
# 2010 fit 0.4-0.7 to drop tests; Anagnostopoulos 1988 uses 0.5 to 0.75): the defaults span them.
DEFAULT_RESTITUTIONS = (0.5, 0.65, 0.8)
# A contact stiffness is known to an order of magnitude at best (a slab's axial EA/L against a
# fitted test value): a quarter to four times each law's base stiffness.
DEFAULT_STIFFNESS_FACTORS = (0.25, 1.0, 4.0)
LIMIT_LEVELS = ("IO", "LS", "CP")


def _numbers(text, option, low, high):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise pounding.InputError(f"{option} = {text}: expected numbers separated by commas") from None
    for value in values:
        if not (low <= value <= high) or math.isnan(value):
            raise pounding.InputError(f"{option} = {text}: {value:g} must lie in [{low:g}, {high:g}]")
    if len(set(values)) != len(values):
        raise pounding.InputError(f"{option} = {text}: a value is given twice")
    return values


def base_stiffness(scene, law):
    """The stiffness a law's factors multiply: the scene's when it is the scene's law, else the
    law's default (in the law's unit)."""
    return scene.contact_stiffness if law["name"] == scene.contact_law else law["default_stiffness"]


def combinations(scene, laws, restitutions, factors):
    """(law, restitution, stiffness or None, factor or None) for every run: the laws with a stiffness
    at each factor of their base stiffness, the impulse law once per restitution."""
    table = {law["name"]: law for law in pounding.contact_laws()}
    runs = []
    for name in laws:
        law = table[name]
        base = base_stiffness(scene, law)
        for restitution in restitutions:
            if law["stiffness_key"] is None:
                runs.append((name, restitution, None, None))
            else:
                runs.extend((name, restitution, base * factor, factor) for factor in factors)
    return runs


def _largest(values):
    values = [abs(v) for v in values if v is not None]
    return max(values) if values else None


def peak_storey_drift(building):
    """A building's largest |storey drift ratio| over its storeys, the CM and the slab corners."""
    values = []
    for floor in building["floors"]:
        for key in ("drift_x", "drift_y"):
            values.append(floor[key]["value"])
        for key in ("corner_drift_x", "corner_drift_y"):
            values.extend(corner["value"] for corner in floor[key])
    return _largest(values)


def demands(summary):
    """The run's demands, by name: numbers (None where the run has none of that kind)."""
    impacts = summary["impacts"]
    values = {
        "impact_count": summary["impact_count"],
        "max_impulse_kNs": _largest([i["impulse_kNs"] for i in impacts]) or 0.0,
        "max_approach_speed_mps": _largest([i["approach_velocity_mps"] for i in impacts]) or 0.0,
        # An impulse has no force (its impacts' peak_force_kN is 0): only compliant laws give one.
        "max_contact_force_kN": None if summary["contact_law"]["name"] == "impulse"
        else _largest([i.get("peak_force_kN") for i in impacts]),
        "max_struck_column_shear_kN": _largest([i.get("column_shear_kN") for i in impacts]),
        "max_struck_column_shear_ratio": _largest([i.get("column_shear_ratio") for i in impacts]),
        "max_struck_column_total_shear_kN": _largest([i.get("column_total_shear_kN") for i in impacts]),
        "max_struck_column_total_shear_ratio": _largest([i.get("column_total_shear_ratio") for i in impacts]),
    }
    for building in summary["peaks"]:
        values[f"{building['building']} peak_storey_drift_ratio"] = peak_storey_drift(building)
    yielding = summary.get("yielding")
    for building in yielding["buildings"] if yielding else []:
        name = summary["peaks"][building["building"] - 1]["building"]
        storeys = building["storeys"]
        values[f"{name} max_ductility"] = _largest(
            [s["peak_ductility_x"] for s in storeys] + [s["peak_ductility_y"] for s in storeys])
        ratios = [s["column_shear"]["largest_demand_capacity_ratio"] for s in storeys if "column_shear" in s]
        if ratios:
            values[f"{name} max_column_shear_ratio"] = _largest(ratios)
    for building in (summary.get("residual_drift") or {}).get("buildings", []):
        values[f"{building['building']} residual_drift_ratio"] = building["largest"]["largest_drift_ratio"]
    return values


def verdicts(summary):
    """The run's verdicts, by name: text (a limit state, a damage state, yes or no)."""
    impacts = summary["impacts"]
    values = {"pounding": "yes" if impacts else "no"}
    if any(i.get("column_shear_ratio") is not None for i in impacts):
        values["struck column over capacity"] = "yes" if any(
            (i.get("column_shear_ratio") or 0.0) > 1.0 for i in impacts) else "no"
        values["struck column with its sway over capacity"] = "yes" if any(
            (i.get("column_total_shear_ratio") or 0.0) > 1.0 for i in impacts) else "no"
    for building in (summary.get("limit_states") or {}).get("buildings", []):
        exceeded = [level["level"] for level in building["levels"] if level["exceeded"]]
        values[f"{building['building']} limit state exceeded"] = exceeded[-1] if exceeded else "none"
    yielding = summary.get("yielding")
    for building in yielding["buildings"] if yielding else []:
        storeys = [s for s in building["storeys"] if "column_shear" in s]
        if storeys:
            name = summary["peaks"][building["building"] - 1]["building"]
            failed = any(s["column_shear"]["failures"] > 0 for s in storeys)
            values[f"{name} column shear failure"] = "yes" if failed else "no"
    for building in (summary.get("residual_drift") or {}).get("buildings", []):
        values[f"{building['building']} residual damage state"] = building["damage_state"] or "none"
    return values


def scene_for(scene_file, document, keywords):
    """The scene of one run: the file with the run's [contact] options. A compliant law's
    contact_stiffness replaces the scene's stiffness (load_scene does that); the impulse law takes
    none, so its run leaves out the stiffness keys the scene gave for its own law."""
    contact = document.get("contact", {})
    if "contact_stiffness" in keywords or not any(key.startswith("stiffness_") for key in contact):
        return pounding.load_scene(scene_file, **keywords)
    changed = {**document, "contact": {k: v for k, v in contact.items() if not k.startswith("stiffness_")}}
    return pounding.scene_from_dict(changed, folder=pathlib.Path(scene_file).resolve().parent, **keywords)


def run_all(scene_file, runs, method, progress):
    """Each run's row: its parameters, status, demands and verdicts (a refused combination: its
    reason as message, no results)."""
    try:
        document = tomllib.loads(pathlib.Path(scene_file).read_text())
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        document = {}  # load_scene names what is wrong with the file
    rows = []
    for number, (law, restitution, stiffness, factor) in enumerate(runs, 1):
        row = {"contact_law": law, "restitution": restitution, "contact_stiffness": stiffness,
               "stiffness_factor": factor, "status": "", "message": "", "demands": {}, "verdicts": {}}
        if progress:
            print(f"\rbracket: run {number} of {len(runs)} ({law}, e = {restitution:g})", end="", file=sys.stderr,
                  flush=True)
        keywords = {"contact_law": law, "restitution": restitution}
        if stiffness is not None:
            keywords["contact_stiffness"] = stiffness
        try:
            scene = scene_for(scene_file, document, keywords).with_outputs(history=False, peaks=["drifts"])
            result = pounding.run(scene, method)
        except pounding.InputError as error:
            row.update(status="refused", message=str(error))
            rows.append(row)
            continue
        row["status"] = result.status
        row["message"] = result.summary.get("status_detail") or ""
        row["solver_time_s"] = result.summary["statistics"]["wall_time_s"]
        if result.status == "completed":
            row["demands"] = demands(result.summary)
            row["verdicts"] = verdicts(result.summary)
        rows.append(row)
    if progress:
        print(file=sys.stderr)
    return rows


def _label(row):
    stiffness = "" if row["contact_stiffness"] is None else f", {row['stiffness_factor']:g} x stiffness"
    return f"{row['contact_law']}, e = {row['restitution']:g}{stiffness}"


def spread(rows):
    """Per demand over the completed runs: min and max with the runs at each, and max/min (None
    when the least is 0). Per verdict: the values met with their counts, and whether it is one."""
    done = [row for row in rows if row["status"] == "completed"]
    numbers, texts = {}, {}
    for row in done:
        for name, value in row["demands"].items():
            if value is not None:
                numbers.setdefault(name, []).append((value, row))
        for name, value in row["verdicts"].items():
            texts.setdefault(name, {}).setdefault(value, []).append(_label(row))
    result = {"demands": {}, "verdicts": {}}
    for name, entries in numbers.items():
        low, high = min(entries, key=lambda e: e[0]), max(entries, key=lambda e: e[0])
        result["demands"][name] = {"min": low[0], "min_run": _label(low[1]), "max": high[0],
                                   "max_run": _label(high[1]),
                                   "max_over_min": high[0] / low[0] if low[0] > 0 else None, "runs": len(entries)}
    for name, values in texts.items():
        result["verdicts"][name] = {"same_on_all": len(values) == 1,
                                    "values": {value: len(labels) for value, labels in values.items()},
                                    "runs": {value: labels for value, labels in values.items()}}
    return result


def write_csv(path, rows):
    demand_names = sorted({name for row in rows for name in row["demands"]})
    verdict_names = sorted({name for row in rows for name in row["verdicts"]})
    columns = ["contact_law", "restitution", "contact_stiffness", "stiffness_factor", "status", "message",
               "solver_time_s"] + demand_names + verdict_names
    with open(path, "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(columns)
        for row in rows:
            cells = {**row, **row["demands"], **row["verdicts"]}
            writer.writerow(["" if cells.get(c) is None else repr(cells[c]) if isinstance(cells.get(c), float)
                             else cells[c] for c in columns])


def report(scene_name, rows, summary):
    lines = [f"Bracket of {scene_name}: {len(rows)} runs, "
             f"{sum(r['status'] == 'completed' for r in rows)} completed, "
             f"{sum(r['status'] == 'refused' for r in rows)} refused"]
    for row in rows:
        if row["status"] != "completed":
            lines.append(f"  {_label(row)}: {row['status']} {row['message']}")
    lines.append("Demands (min .. max over the completed runs, max/min):")
    for name, entry in summary["demands"].items():
        ratio = "" if entry["max_over_min"] is None else f", x{entry['max_over_min']:.3g}"
        lines.append(f"  {name}: {entry['min']:.6g} .. {entry['max']:.6g}{ratio}"
                     f" (max at {entry['max_run']})")
    lines.append("Verdicts:")
    for name, entry in summary["verdicts"].items():
        counts = ", ".join(f"{value} {count}" for value, count in entry["values"].items())
        lines.append(f"  {name}: {'the same on every run' if entry['same_on_all'] else 'DIFFERS'} ({counts})")
    return "\n".join(lines)


def bracket(scene_file, laws=None, restitutions=DEFAULT_RESTITUTIONS, stiffness_factors=DEFAULT_STIFFNESS_FACTORS,
            method=None, progress=False):
    """Runs the bracket of `scene_file`; returns {"scene", "method", "laws", "restitutions",
    "stiffness_factors", "runs": [row, ...], "spread": spread(rows)} (bracket.json's document)."""
    scene = pounding.load_scene(scene_file)
    known = [law["name"] for law in pounding.contact_laws()]
    laws = list(known if laws is None else laws)
    for name in laws:
        if name not in known:
            raise pounding.InputError(f"--laws: \"{name}\": expected {', '.join(known)}")
    if method is not None and method not in pounding.methods():  # one refusal, not one a run
        raise pounding.InputError(f"--method: \"{method}\": expected {', '.join(pounding.methods())}")
    started = time.perf_counter()
    rows = run_all(scene_file, combinations(scene, laws, restitutions, stiffness_factors), method, progress)
    return {"scene": scene.name, "scene_file": str(scene_file), "method": method or scene.method, "laws": laws,
            "restitutions": list(restitutions), "stiffness_factors": list(stiffness_factors),
            "base_stiffness": {law["name"]: base_stiffness(scene, law) for law in pounding.contact_laws()
                               if law["stiffness_key"] and law["name"] in laws},
            "wall_time_s": time.perf_counter() - started, "runs": rows, "spread": spread(rows)}


def main(argv=None):
    parser = argparse.ArgumentParser(prog="pounding bracket", description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--laws", help="contact laws, comma-separated (default: every law)")
    parser.add_argument("--restitutions", help="restitutions in [0, 1], comma-separated (default 0.5,0.65,0.8)")
    parser.add_argument("--stiffness-factors", help="multiples of each law's base stiffness, comma-separated "
                        "(default 0.25,1,4)")
    parser.add_argument("--method", help="solution path (default: the scene's)")
    parser.add_argument("--out", help="output folder (default out/bracket-<scene name>)")
    parser.add_argument("--no-progress", action="store_true")
    args = parser.parse_args(argv)
    try:
        document = bracket(
            args.scene, laws=args.laws.split(",") if args.laws else None,
            restitutions=_numbers(args.restitutions, "--restitutions", 0.0, 1.0) if args.restitutions
            else DEFAULT_RESTITUTIONS,
            stiffness_factors=_numbers(args.stiffness_factors, "--stiffness-factors", 1e-3, 1e3)
            if args.stiffness_factors else DEFAULT_STIFFNESS_FACTORS,
            method=args.method, progress=not args.no_progress and sys.stderr.isatty())
    except pounding.InputError as error:
        print(f"pounding bracket: {error}", file=sys.stderr)
        return 2
    out = pathlib.Path(args.out or f"out/bracket-{document['scene']}")
    out.mkdir(parents=True, exist_ok=True)
    write_csv(out / "bracket.csv", document["runs"])
    (out / "bracket.json").write_text(json.dumps(document, indent=2) + "\n")
    print(report(document["scene"], document["runs"], document["spread"]))
    print(f"Wrote {out}/bracket.json, bracket.csv ({document['wall_time_s']:.1f} s)")
    if not any(row["status"] == "completed" for row in document["runs"]):
        print("pounding bracket: no run completed: there is no spread", file=sys.stderr)
        return 3  # as a run that does not complete
    return 0


if __name__ == "__main__":
    sys.exit(main())
