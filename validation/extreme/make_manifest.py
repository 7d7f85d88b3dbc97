#!/usr/bin/python3
"""Writes the extreme-case suite as a `pounding verify` manifest: validation/extreme/extreme.verify.toml.

    validation/extreme/make_manifest.py [--all]

For each case of cases/index.json marked quick (--all: every case), a reference run (cvode-bdf at
rtol 1e-12, atol 1e-14) and one run of every method, each in a process of its own (isolate), so
that a crash or a hang fails that run alone. Checks, with tolerances from the suite's own table
(validation/extreme/table.csv, where the largest impact-time error of an event-driven method on a
quick case is 1.4e-5 s and the largest energy residual 1.3e-6):
  - the reference completes and its energy audit closes to 1e-8;
  - every event-driven method (CVODE, ARKODE, exact) ends as the reference does, with the same
    impacts matched at times within 1e-4 s, and its audit closes to 1e-5; on pulse-gap-0, a long
    chattering sequence where single impacts of a sustained contact come and go with the
    tolerance, only the count is checked (within 5, 2 %) with the audit;
  - hht, the published fixed-step scheme, ends with a named status (it ends unresolved_overlap on
    four of these cases: validation/extreme/table.md says why) and nothing more is asked of it.
The manifest needs no blessed results: every expectation is the reference run of the same verify.
"""
import argparse
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
EVENT_DRIVEN = ("cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk", "exact")
NAMED_STATUSES = ("completed", "unresolved_overlap", "event_limit", "step_limit", "time_limit", "collapse")
BUDGET_S = 120  # each run's wall-time budget (run_suite.py's --timeout)


def case_block(name, scene, method, settings, reference, checks):
    lines = ["[[case]]", f'name = "{name}"', f'scene = "{scene}"', f'method = "{method}"',
             f"max_wall_time_s = {BUDGET_S}"]
    if settings:
        lines.append("settings = { " + ", ".join(f"{k} = {v}" for k, v in settings.items()) + " }")
    if reference:
        lines.append(f'reference = "{reference}"')
    lines.append("[case.checks]")
    lines += [f"{kind} = {spec}" for kind, spec in checks.items()]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--all", action="store_true", help="every case, not only the quick ones")
    args = parser.parse_args()
    cases = [c for c in json.loads((HERE / "cases/index.json").read_text()) if args.all or c["quick"]]
    blocks = []
    for case in cases:
        name, scene = case["name"], case["file"]
        reference = f"{name}/reference"
        blocks.append(f"# {name}: {case['hard']}\n" + case_block(
            reference, scene, "cvode-bdf", {"rtol": "1e-12", "atol": "1e-14"}, None,
            {"status": '"completed"', "energy_residual": "{ max_relative = 1e-8 }"}))
        for method in EVENT_DRIVEN:
            checks = {"status": "true"}
            if name == "pulse-gap-0":
                checks["impact_count"] = "{ abs = 5 }"
            else:
                checks["impact_count"] = "true"
                checks["impact_times"] = "{ abs_s = 1e-4 }"
            checks["energy_residual"] = "{ max_relative = 1e-5 }"
            blocks.append(case_block(f"{name}/{method}", scene, method, {}, reference, checks))
        statuses = "[" + ", ".join(f'"{s}"' for s in NAMED_STATUSES) + "]"
        blocks.append(case_block(f"{name}/hht", scene, "hht", {}, None, {"status": statuses}))
    header = ('# The extreme-case suite as a `pounding verify` manifest, written by make_manifest.py (which says\n'
              '# what is checked and why); run it with `pounding verify validation/extreme/extreme.verify.toml`.\n'
              f'name = "extreme{"" if args.all else "-quick"}"\n'
              "isolate = true\n\n")
    out = HERE / ("extreme-all.verify.toml" if args.all else "extreme.verify.toml")
    out.write_text(header + "\n".join(blocks))
    print(f"Wrote {out} ({len(blocks)} cases)")


if __name__ == "__main__":
    main()
