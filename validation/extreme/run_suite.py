#!/usr/bin/python3
"""Runs every solution path on every extreme case (cases/index.json, written by make_cases.py)
and writes the table: status, impacts, touches, holds, largest overlap, energy residual, steps,
run time and the error against a reference run (CVODE BDF at rtol 1e-12, atol 1e-14), compared
with tools/compare_runs.py.

    validation/extreme/run_suite.py [--quick] [--pounding build/apps/pounding] [--timeout 120]
                                    [--reference-timeout 600]
                                    [--methods cvode-bdf,hht,...] [--cases name,...] [--out out/extreme]

Runs go to OUT/<case>/<method>/; the table to OUT/table.md and OUT/table.csv, and, for a full
run (no --quick, --cases or --methods), also to validation/extreme/table.md and table.csv.
Every run gets --timeout seconds as its wall-time budget (--max-wall-time; the reference gets
--reference-timeout) and then ends with status `time_limit`; a run still going a minute later is
killed and listed as `hang`; a run that crashes is listed with its exit code. Nothing is tuned: what fails, fails in the table.
--quick: the cases marked quick in the index (meant for CI: under 2 minutes on 2 cores).
--check: exit 1 if any run hangs, crashes or writes NaN; named statuses (time_limit too) pass.
"""
import argparse
import csv
import json
import math
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PY = "/usr/bin/python3"
REFERENCE = ("reference", ["--method", "cvode-bdf", "--rtol", "1e-12", "--atol", "1e-14"])
COLUMNS = ["case", "method", "status", "impacts", "touches", "holds", "largest_overlap_m", "energy_residual",
           "steps", "run_time_s", "matched", "only_in_reference", "only_in_run", "impact_time_error_s",
           "u_error_m"]


HANG_GRACE_S = 60.0


def run(pounding, scene, folder, options, timeout):
    """One `pounding run`; returns the summary (or None) and the status to show."""
    folder.mkdir(parents=True, exist_ok=True)
    summary_file = folder / "summary.json"
    summary_file.unlink(missing_ok=True)
    start = time.monotonic()
    try:
        # The run's own budget ends it with status time_limit (and its outputs); the kill, a
        # minute later, only catches a run that ignores its budget: a hang.
        done = subprocess.run([pounding, "run", str(scene), "--out", str(folder), "--max-wall-time", f"{timeout:g}",
                               *options],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                              timeout=timeout + HANG_GRACE_S)
    except subprocess.TimeoutExpired:
        return None, f"hang (killed {timeout + HANG_GRACE_S:g} s)", time.monotonic() - start
    elapsed = time.monotonic() - start
    if done.returncode not in (0, 3) or not summary_file.exists():
        message = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ""
        return None, f"exit {done.returncode} {message}"[:80], elapsed
    summary = json.loads(summary_file.read_text())
    status = summary["status"]
    if has_nan(summary):
        status += " (NaN in output)"
    return summary, status, elapsed


def has_nan(value):
    if isinstance(value, float):
        return math.isnan(value) or math.isinf(value)
    if isinstance(value, dict):
        return any(has_nan(v) for v in value.values())
    if isinstance(value, list):
        return any(has_nan(v) for v in value)
    return False


def compare(reference_folder, folder):
    """tools/compare_runs.py's JSON for the two runs, or None."""
    out = folder / "vs-reference.json"
    done = subprocess.run([PY, str(ROOT / "tools/compare_runs.py"), str(reference_folder), str(folder), "--json",
                           str(out)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return json.loads(out.read_text()) if done.returncode == 0 and out.exists() else None


def row(case, method, summary, status, elapsed, diff):
    r = {"case": case, "method": method, "status": status}
    if summary:
        r.update({
            "impacts": summary["impact_count"], "touches": len(summary["touches"]),
            "holds": len(summary["sustained_contacts"]),
            "largest_overlap_m": summary["statistics"].get("max_interpenetration_m", ""),
            "energy_residual": summary["energy"]["relative_residual"],
            "steps": summary["statistics"]["steps"], "run_time_s": summary["statistics"]["wall_time_s"],
        })
    else:
        r["run_time_s"] = elapsed
    if diff:
        r.update({"matched": diff["matched"], "only_in_reference": diff["only_in_a"], "only_in_run": diff["only_in_b"],
                  "impact_time_error_s": diff["max_impact_time_difference_s"],
                  "u_error_m": diff["history_max_difference"].get("u_m", {}).get("value", "")})
    return r


def fmt(value, kind):
    if value == "" or value is None:
        return ""
    if kind == "g":
        return f"{value:.2e}" if value else "0"
    if kind == "t":
        return f"{value:.3g}"
    return str(value)


def markdown(rows, title):
    kinds = {"largest_overlap_m": "g", "energy_residual": "g", "impact_time_error_s": "g", "u_error_m": "g",
             "run_time_s": "t"}
    lines = [title, "", "| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for r in rows:
        lines.append("| " + " | ".join(fmt(r.get(c, ""), kinds.get(c, "")) for c in COLUMNS) + " |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    parser.add_argument("--quick", action="store_true", help="only the cases marked quick")
    parser.add_argument("--timeout", type=float, default=120.0, help="per run (s)")
    parser.add_argument("--reference-timeout", type=float, default=600.0, help="per reference run (s)")
    parser.add_argument("--methods", help="comma-separated subset of the methods `pounding methods` lists")
    parser.add_argument("--cases", help="comma-separated case names")
    parser.add_argument("--out", type=Path, default=ROOT / "out/extreme")
    parser.add_argument("--check", action="store_true", help="exit 1 on a hang, crash or NaN")
    args = parser.parse_args()
    for name in ("timeout", "reference_timeout"):
        if not getattr(args, name) > 0:
            sys.exit(f"error: --{name.replace('_', '-')} = {getattr(args, name)}: must be positive (s)")
    index = json.loads((HERE / "cases/index.json").read_text())
    # Every method of the program's registry (src/analysis/methods.cpp), in its order.
    known = [m["name"] for m in json.loads(subprocess.run([args.pounding, "methods", "--json"], check=True,
                                                          capture_output=True, text=True).stdout)]
    methods = args.methods.split(",") if args.methods else known
    unknown = [m for m in methods if m not in known]
    if unknown:
        sys.exit(f"error: --methods: unknown {', '.join(unknown)}; expected some of {', '.join(known)}")
    cases = [c for c in index if (not args.quick or c["quick"]) and (not args.cases or c["name"] in args.cases.split(","))]
    if not cases:
        sys.exit("error: no case selected")

    rows, started = [], time.monotonic()
    for case in cases:
        scene = HERE / case["file"]
        case_dir = args.out / case["name"]
        reference, ref_status, elapsed = run(args.pounding, scene, case_dir / REFERENCE[0], REFERENCE[1],
                                             args.reference_timeout)
        rows.append(row(case["name"], "reference (bdf 1e-12)", reference, ref_status, elapsed, None))
        print(f"{case['name']}: reference {ref_status}", flush=True)
        for method in methods:
            folder = case_dir / method
            summary, status, elapsed = run(args.pounding, scene, folder, ["--method", method], args.timeout)
            diff = compare(case_dir / REFERENCE[0], folder) if summary and reference else None
            rows.append(row(case["name"], method, summary, status, elapsed, diff))
            print(f"  {method}: {status}, {rows[-1].get('impacts', '-')} impacts", flush=True)

    args.out.mkdir(parents=True, exist_ok=True)
    title = (f"# Extreme cases: every path{' (quick subset)' if args.quick else ''}\n\n"
             f"Written by `validation/extreme/run_suite.py{' --quick' if args.quick else ''}` "
             f"(per-run wall-time budget {args.timeout:g} s, reference {args.reference_timeout:g} s; "
             f"{time.monotonic() - started:.0f} s in all). Each case's "
             "scene file (cases/) says what makes it hard and what the right answer is. Errors are "
             "against the reference run (CVODE BDF, rtol 1e-12, atol 1e-14) by tools/compare_runs.py: "
             "impacts matched within 0.05 s at the same contact, the largest impact-time difference of "
             "the matched ones, and the largest difference of u over the history floor (the top common "
             "floor). largest_overlap_m: statistics.max_interpenetration_m (the deepest overlap of a pair not held); "
             "energy_residual: of the input; run_time_s: the solver's own.")
    outputs = [args.out]
    if not (args.quick or args.cases or args.methods):
        outputs.append(HERE)
    for folder in outputs:
        (folder / "table.md").write_text(markdown(rows, title))
        with (folder / "table.csv").open("w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=COLUMNS)
            writer.writeheader()
            writer.writerows(rows)
        print(f"Wrote {folder / 'table.md'} and table.csv")
    bad = [r for r in rows if r["status"].startswith(("hang", "exit")) or "NaN" in r["status"]]
    for r in bad:
        print(f"FAILED: {r['case']} {r['method']}: {r['status']}")
    if args.check and bad:
        sys.exit(1)


if __name__ == "__main__":
    main()
