#!/usr/bin/python3
"""Regenerates validation/paper/report.md and its figures: the reconstructed published example
run at the published gaps, the minimum gap, the work–precision study and the paper-style
figures, next to what the paper reports (docs/paper-example.md).

    validation/paper/make_report.py [--pounding build/apps/pounding] [--repeat 3]

Runs go to out/validation/; only the report, its figures, study.csv and truncation.csv are committed.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
SCENE = ROOT / "examples/paper/paper.toml"
OUT = ROOT / "out/validation"
PY = "/usr/bin/python3"

# What the paper reports (docs/paper-example.md); compared with, never tuned to.
PAPER = {
    0.50: "no pounding; floor 7 CM peaks u = 20.1 cm (B1), 16.2 cm (B2), v = 2 cm (B1), 0.9 cm (B2); "
          "floor 7 corner x-peaks 24.2 and 18.8 cm (B1), 21.2 and 13.4 cm (B2); peaks near 6.7–7.3 s",
    0.37: "no pounding",
    0.35: "2 impacts on floor 7, at 6.62 s and 6.72 s",
    0.20: "11 impacts (8 on floor 7, 2 on floor 6, 1 on floor 5), the first at 3.1257 s on floor 7; "
          "one further contact on floor 7 without impact",
}


def run(pounding, gap, folder, *extra):
    folder = OUT / folder
    done = subprocess.run([pounding, "run", str(SCENE), "--gap", f"{gap}", "--out", str(folder), *extra],
                          stdout=subprocess.DEVNULL)
    if done.returncode not in (0, 3):  # 3: the run did not complete cleanly; its summary says why
        raise subprocess.CalledProcessError(done.returncode, done.args)
    return json.loads((folder / "summary.json").read_text())


def record_machine(folder: Path, when: str):
    """Appends to FOLDER/machine.txt what tools/plot_study.py names: the processor and core count
    the study is timed on, and the load average (a shared machine slows every run)."""
    load = " ".join(Path("/proc/loadavg").read_text().split()[:3])
    lines = f"load_{when}: {load}\n"
    if when == "before":
        model = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                      if line.startswith("model name")), "unknown processor")
        lines = f"cpu: {model}\ncores: {os.cpu_count()}\n" + lines
        (folder / "machine.txt").write_text(lines)
    else:
        with (folder / "machine.txt").open("a") as handle:
            handle.write(lines)
    return load


def needed_gap(pounding):
    """`pounding gap`: the smallest gap with no contact, exact from one contact-free run (it agrees
    with a bisection on full runs to 1e-6 m: tests/analysis/test_needed_gap.cpp), and the rules."""
    folder = OUT / "gap"
    subprocess.run([pounding, "gap", str(SCENE), "--out", str(folder)], check=True, stdout=subprocess.DEVNULL)
    return json.loads((folder / "gap.json").read_text())


def floor7(summary, building):
    peaks = summary["peaks"][building]
    floor = peaks["floors"][6]
    corners = ", ".join(f"{100 * abs(p['value']):.1f}" for p in floor["vertex_dx_m"])
    return (f"u = {100 * abs(floor['u_m']['value']):.1f} cm at {floor['u_m']['t_s']:.2f} s, "
            f"v = {100 * abs(floor['v_m']['value']):.1f} cm; corner x-peaks {corners} cm")


def describe(summary):
    impacts = summary["impacts"]
    if not impacts:
        return f"no impact; {len(summary['touches'])} touches"
    # The paper's buildings have equal storeys: level j is floor j of both.
    by_floor = ", ".join(f"{n} on floor {f}" for f, n in sorted(summary["impacts_by_level"].items(), reverse=True))
    times = ", ".join(f"{i['t_s']:.3f} s" for i in impacts[:3])
    noun = "impact" if len(impacts) == 1 else "impacts"
    return (f"{len(impacts)} {noun} ({by_floor}), the first at {impacts[0]['t_s']:.4f} s on floor "
            f"{impacts[0]['floors'][0]} (first ones at {times}); {len(summary['sustained_contacts'])} sustained "
            f"contacts; {len(summary['touches'])} touches")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    if not Path(args.pounding).is_file():
        sys.exit(f"error: {args.pounding} not found: build first (./scripts/bootstrap.sh)")
    OUT.mkdir(parents=True, exist_ok=True)
    figures = HERE / "figures"
    figures.mkdir(exist_ok=True)

    runs = {gap: run(args.pounding, gap, f"gap{gap:.2f}") for gap in (0.50, 0.37, 0.35, 0.20)}
    exact = {gap: run(args.pounding, gap, f"exact-gap{gap:.2f}", "--method", "exact") for gap in (0.35, 0.20)}
    hht = run(args.pounding, 0.20, "hht-gap0.20", "--method", "hht")
    gap_report = needed_gap(args.pounding)
    needed = gap_report["needed_gap_m"]

    for gap in (0.20, 0.35):
        subprocess.run([PY, ROOT / "tools/plot_run.py", OUT / f"gap{gap:.2f}", "--compare", OUT / "gap0.50",
                        "--out", figures / f"floor7-gap{gap:.2f}-vs-0.50.png"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([PY, ROOT / "tools/plot_run.py", OUT / "hht-gap0.20", "--compare", OUT / "gap0.20",
                    "--out", figures / "floor7-gap0.20-hht-vs-cvode.png"], check=True, stdout=subprocess.DEVNULL)
    (OUT / "study").mkdir(exist_ok=True)
    load_before = record_machine(OUT / "study", "before")
    subprocess.run([args.pounding, "study", str(SCENE), "--repeat", str(args.repeat), "--out", str(OUT / "study")],
                   check=True, stdout=subprocess.DEVNULL)
    record_machine(OUT / "study", "after")
    machine = dict(line.split(": ", 1) for line in (OUT / "study/machine.txt").read_text().splitlines())
    subprocess.run([PY, ROOT / "tools/plot_study.py", OUT / "study", "--out", figures / "work-precision.png"],
                   check=True, stdout=subprocess.DEVNULL)
    shutil.copy(OUT / "study/study.csv", HERE / "study.csv")
    shutil.copy(OUT / "study/truncation.csv", HERE / "truncation.csv")
    study = json.loads((OUT / "study/study.json").read_text())

    lines = [
        "# Validation: the published example",
        "",
        "Generated by `validation/paper/make_report.py` (do not edit by hand). Scene:",
        "`examples/paper/paper.toml`, the reconstruction fixed in `docs/paper-example.md` (the paper",
        "does not give the plan, so results should agree in kind, not to the digit). Runs use the",
        "default method (CVODE BDF, rtol 1e-8) unless stated.",
        "",
        "## The paper's figures and this program's",
        "",
        "| gap | the paper | this program | difference |",
        "|---|---|---|---|",
    ]
    for gap, summary in runs.items():
        ours = describe(summary)
        if gap == 0.50:
            ours += f"; floor 7: B1 {floor7(summary, 0)}; B2 {floor7(summary, 1)}"
        same_kind = (summary["impact_count"] == 0) == ("no pounding" in PAPER[gap])
        diff = "same kind (pounding or not)" if same_kind else "differs in kind"
        lines.append(f"| {gap:.2f} m | {PAPER[gap]} | {ours} | {diff} |")
    lines += [
        f"| needed gap | 0.37 m | {needed:.4f} m (`pounding gap`: the smallest gap with no contact, from one "
        f"contact-free run; rules ABS {gap_report['rules']['abs_m']:.4f} m, SRSS {gap_report['rules']['srss_m']:.4f} m, "
        f"DDC {gap_report['rules']['ddc_m']:.4f} m) | {100 * (needed - 0.37):+.1f} cm |",
        "",
        "At 0.20 m the paper counts single impacts of its Δt = 0.05 s scheme; the event-driven solution",
        "resolves each collision into a bounce sequence whose approach speed halves (k = 0.5) until the",
        "pair is held in sustained contact. The published scheme run here (`--method hht`, Δt = 0.05 s)",
        f"reports {hht['impact_count']} impacts, its first at {hht['impacts'][0]['t_s']:.4f} s: the",
        "timings differ from the paper's because the plan is a reconstruction, not because of the scheme.",
        f"Its status is `{hht['status']}`: without sustained contact, the bounce sequences it cannot",
        f"resolve let the slabs sink up to {1000 * hht['statistics']['max_interpenetration_m']:.2f} mm into each "
        f"other ({hht['statistics']['max_interpenetration_pair']}, {hht['statistics']['max_interpenetration_t_s']:.3f} "
        "s), beyond its "
        f"{1000 * hht['settings']['used']['contact_tolerance_m']:.1f} mm contact tolerance.",
        "",
        "## Exact path against CVODE",
        "",
    ]
    for gap, summary in exact.items():
        ref = runs[gap]["impacts"]
        diffs = [abs(a["t_s"] - b["t_s"]) for a, b in zip(ref, summary["impacts"])]
        worst = max(diffs) if diffs else 0.0
        lines.append(f"- gap {gap:.2f} m: {summary['impact_count']} impact(s) (CVODE {len(ref)}); largest "
                     f"impact-time difference {worst:.2e} s; energy residual "
                     f"{summary['energy']['relative_residual']:.1e} of the input.")
    lines += [
        "",
        "Both solve the same model: the exact path propagates free flight in closed form and integrates",
        "held stretches (nonlinear: the contact geometry rotates with the slabs) at rtol 1e-12, so the",
        "difference is CVODE's error at rtol 1e-8 (the work–precision table below measures both).",
        "",
        "## Figures",
        "",
        "Floor 7 of both buildings, pounding (colour) over the run without pounding (grey, 0.50 m):",
        "",
        "![gap 0.20 m](figures/floor7-gap0.20-vs-0.50.png)",
        "",
        "![gap 0.35 m](figures/floor7-gap0.35-vs-0.50.png)",
        "",
        "The published HHT-α scheme (colour) over the event-driven solution (grey), gap 0.20 m:",
        "",
        "![hht vs cvode](figures/floor7-gap0.20-hht-vs-cvode.png)",
        "",
        "## Work–precision",
        "",
        f"Every path against the exact path (gap {study['gap_m']} m, median of {args.repeat} runs; the table is",
        f"`study.csv` beside this report). Timed on {machine['cpu']}, {machine['cores']} cores, load average",
        f"{load_before.split()[0]} at the start and {machine['load_after'].split()[0]} at the end: on a machine "
        "shared with other jobs the run times",
        "are several times an idle machine's and noisy; the errors do not depend on it.",
        "",
        "![work-precision](figures/work-precision.png)",
        "",
        "| method | setting | run time [s] | impacts | impact-time error before the first hold [s] | "
        "largest u error [m] |",
        "|---|---|---|---|---|---|",
    ]
    for row in study["rows"]:
        lines.append(f"| {row['method']} | {row['setting']} = {row['value']:g} | {row['run_time_s']:.3f} | "
                     f"{row['impacts']} | {row['impact_time_error_before_hold_s']:.2e} | {row['history_u_error_m']:.2e} |")
    (HERE / "report.md").write_text("\n".join(lines) + "\n")
    print(f"Wrote {HERE / 'report.md'} (needed gap {needed:.4f} m)")


if __name__ == "__main__":
    main()
