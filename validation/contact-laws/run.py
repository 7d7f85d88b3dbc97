#!/usr/bin/python3
"""The two schools side by side: every contact law of the registry (`pounding laws --json`) on
the paper scene, and each compliant law's stiff limit on a two-slab impact. Writes README.md and
its figures into this folder (the page is generated: its text states the numbers of this run).

    validation/contact-laws/run.py [--pounding build/apps/pounding] [--method cvode-bdf]
    validation/contact-laws/run.py --limit-only --check --out DIR   (the ctest contact_laws_limit)

Runs go to out/validation/contact-laws/ (or --out). With --check the exit status is 1 when a
compliant law's post-impact velocity ratio at the largest stiffness is more than LIMIT_TOL away
from the law's closed-form rebound (laws without one are listed, not checked).
"""
import argparse
import csv
import json
import math
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
PAPER = ROOT / "examples/paper/paper.toml"
TWO_SLABS = HERE / "two-slabs.toml"
# Stiffness ladder of the limit check: the law's default times these (5 values over 4 decades).
LADDER = [1e-2, 1e-1, 1.0, 1e1, 1e2]
LIMIT_TOL = 0.01  # relative: velocity ratio against the closed-form rebound at the largest stiffness
WINDOW_S = (-0.01, 0.06)  # the first-impact figure around the first contact's onset (s), at least
FIGURE_INTERVAL_S = 1e-4  # history interval of the first-impact runs (the default 0.01 s misses a contact)


def pounding_json(pounding, *args):
    return json.loads(subprocess.run([pounding, *args], check=True, capture_output=True, text=True).stdout)


def run(pounding, scene, folder, *extra):
    done = subprocess.run([pounding, "run", str(scene), "--out", str(folder), *extra], stdout=subprocess.DEVNULL)
    if done.returncode not in (0, 3):  # 3: the run stopped with a named status; its summary says which
        raise subprocess.CalledProcessError(done.returncode, done.args)
    return json.loads((folder / "summary.json").read_text())


def law_args(law, stiffness=None):
    args = ["--contact-law", law["name"]]
    if stiffness is not None:
        args += ["--contact-stiffness", f"{stiffness:.6g}"]
    return args


def toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return repr(value)


def toml_text(document):
    """The subset of TOML a scene uses: top-level keys, tables, arrays of tables, one level of
    sub-tables inside them."""
    lines, tables = [], []
    for key, value in document.items():
        if isinstance(value, dict):
            tables.append((f"[{key}]", value))
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            tables += [(f"[[{key}]]", item, key) for item in value]
        else:
            lines.append(f"{key} = {toml_value(value)}")
    for header, table, *parent in tables:
        lines.append(header)
        subtables = []
        for key, value in table.items():
            if isinstance(value, dict):
                subtables.append((f"[{parent[0]}.{key}]" if parent else f"[{header[1:-1]}.{key}]", value))
            elif isinstance(value, list) and value and isinstance(value[0], dict):
                subtables += [(f"[[{parent[0]}.{key}]]", item) for item in value]
            else:
                lines.append(f"{key} = {toml_value(value)}")
        for sub_header, sub in subtables:
            lines.append(sub_header)
            lines += [f"{k} = {toml_value(v)}" for k, v in sub.items()]
    return "\n".join(lines) + "\n"


def window_scene(folder, end_s, level):
    """The paper scene cut to end at end_s, its history of `level` every FIGURE_INTERVAL_S."""
    scene = tomllib.loads(PAPER.read_text())
    scene["excitation"]["file"] = str((PAPER.parent / scene["excitation"]["file"]).resolve())
    scene["excitation"]["duration_s"] = end_s
    scene["output"] = {"history_interval_s": FIGURE_INTERVAL_S, "history_floors": [level]}
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "paper-window.toml"
    path.write_text(toml_text(scene))
    return path


def read_csv(path):
    with open(path) as handle:
        return list(csv.DictReader(handle))


def peaks_of(summary):
    """Largest |value| over buildings and floors of the summary's peaks: per building u (m),
    CM drift ratio, worst-corner drift ratio and absolute acceleration (m/s², g)."""
    out = {}
    for b in summary["peaks"]:
        floors = b["floors"]
        def top(key):
            f = max(floors, key=lambda f: abs(f[key]["value"]))
            return abs(f[key]["value"]), f["floor"], f[key]["t_s"]
        drift = max((max(abs(f["drift_x"]["value"]), abs(f["drift_y"]["value"])), f["floor"]) for f in floors)
        corner = max((abs(f["worst_corner_drift"]["value"]), f["floor"], f["worst_corner_drift"]["corner"]) for f in floors)
        accel = max(((math.hypot(f["ax_abs_mps2"]["value"], 0.0), f["floor"], f["ax_abs_mps2"]["t_s"]) for f in floors))
        out[b["building"]] = {"u_m": top("u_m"), "drift": drift, "corner_drift": corner, "accel_mps2": accel}
    return out


def paper_comparison(pounding, laws, out, method):
    rows = []
    for law in laws:
        summary = run(pounding, PAPER, out / f"paper-{law['name']}", "--method", method, *law_args(law))
        impacts = summary["impacts"]
        rows.append({"law": law["name"], "status": summary["status"], "impacts": summary["impact_count"],
                     "first_s": impacts[0]["t_s"] if impacts else None,
                     "first_peak_force_kN": impacts[0]["peak_force_kN"] if impacts else None,
                     "first_duration_s": impacts[0]["duration_s"] if impacts else None,
                     "energy_lost_kJ": summary["energy"]["impact_loss_kJ"],
                     "input_kJ": summary["energy"]["input_kJ"],
                     "wall_time_s": summary["statistics"]["wall_time_s"],
                     "stiffness": summary["contact_law"].get(law["stiffness_key"]) if law["stiffness_key"] else None,
                     "content": summary["accelerations"]["content"],
                     "g": summary["accelerations"]["g_mps2"],
                     "peaks": peaks_of(summary), "summary": summary})
    return rows


def first_impact_figure(pounding, laws, rows, out, method):
    """Each law on the paper scene cut just after its first contact, sampled every 0.1 ms: the
    first contact's normal force (the hold force λ for the impulse law) and the absolute
    acceleration of both slabs at its level."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    first = min(r["first_s"] for r in rows if r["first_s"] is not None)
    # Long enough for the longest first contact (a soft law's lasts a good part of a period).
    end = max([WINDOW_S[1]] + [1.3 * r["first_duration_s"] for r in rows if r["first_s"] == first and r["first_duration_s"]])
    level = next(r["summary"]["impacts"][0]["level"] for r in rows if r["first_s"] == first)
    floors = next(r["summary"]["impacts"][0]["floors"] for r in rows if r["first_s"] == first)
    scene = window_scene(out, first + end + 0.01, level)
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for law in laws:
        folder = out / f"window-{law['name']}"
        summary = run(pounding, scene, folder, "--method", method, *law_args(law))
        history = read_csv(folder / "history.csv")
        t = [float(h["t_s"]) for h in history]
        in_window = [i for i, x in enumerate(t) if first + WINDOW_S[0] <= x <= first + end]
        times = [1e3 * (t[i] - first) for i in in_window]
        contact = summary["impacts"][0] if summary["impacts"] else None
        forces = [f for f in read_csv(folder / "contacts_history.csv")
                  if contact and (int(f["level"]), int(f["striking_building"]), int(f["vertex"])) ==
                  (contact["level"], contact["striking_building"], contact["vertex"]) and
                  first + WINDOW_S[0] <= float(f["t_s"]) <= first + end]
        label = law["name"] + (" (hold force)" if not law["stiffness_key"] else "")
        if forces:
            axes[0].plot([1e3 * (float(f["t_s"]) - first) for f in forces], [float(f["force_kN"]) for f in forces],
                         ".-", ms=2, label=label)
        if not law["stiffness_key"] and contact:
            axes[0].text(0.02, 0.92, f"{law['name']}: impact impulse {contact['impulse_kNs']:.1f} kN·s at 0 ms",
                         transform=axes[0].transAxes, fontsize=8)
        for ax, b in zip(axes[1:], (1, 2)):
            column = f"B{b}_f{floors[b - 1]}_ax_abs_mps2"
            ax.plot(times, [float(history[i][column]) for i in in_window], label=law["name"])
    axes[0].set_ylabel("first contact's normal force (kN)")
    axes[1].set_ylabel(f"B1 floor {floors[0]} abs. accel. x (m/s²)")
    axes[2].set_ylabel(f"B2 floor {floors[1]} abs. accel. x (m/s²)")
    axes[2].set_xlabel(f"time after the first contact at {first:.4f} s (ms)")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_title("Paper scene, first contact (impulse law: smooth part of the acceleration)")
    fig.tight_layout()
    fig.savefig(HERE / "first-impact.png", dpi=110)
    plt.close(fig)
    return first, level


def limit_check(pounding, laws, out, restitution):
    """Each compliant law on the two-slab scene over its stiffness ladder: the first contact's
    velocity ratio, duration and peak force, and the second contact's onset against the impulse
    law run with the law's own rebound as restitution (the trajectory it tends to)."""
    results = {}
    impulse_at = {}
    def impulse_second(e):
        key = f"{e:.12g}"
        if key not in impulse_at:
            s = run(pounding, TWO_SLABS, out / f"limit-impulse-{key}", "--contact-law", "impulse", "--restitution", key)
            impulse_at[key] = s["impacts"][1]["t_s"] if len(s["impacts"]) > 1 else None
        return impulse_at[key]
    for law in laws:
        if not law["stiffness_key"]:
            continue
        rebound = law["rebound"]
        rows = []
        for factor in LADDER:
            k = law["default_stiffness"] * factor
            s = run(pounding, TWO_SLABS, out / f"limit-{law['name']}-{factor:g}", *law_args(law, k))
            first = s["impacts"][0]
            rows.append({"stiffness": k, "factor": factor, "status": s["status"],
                         "ratio": first["separation_velocity_mps"] / first["approach_velocity_mps"],
                         "duration_s": first["duration_s"], "peak_force_kN": first["peak_force_kN"],
                         "second_s": s["impacts"][1]["t_s"] if len(s["impacts"]) > 1 else None})
        # Without a closed form, the ratio the law reaches at its largest stiffness stands in.
        reference = impulse_second(rebound if rebound is not None else rows[-1]["ratio"])
        for r in rows:
            r["second_error_s"] = abs(r["second_s"] - reference) if r["second_s"] and reference else None
        results[law["name"]] = {"rebound": rebound, "rows": rows, "impulse_second_s": reference}
    return results


def limit_figure(results, restitution):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for name, r in results.items():
        k = [row["stiffness"] for row in r["rows"]]
        line, = axes[0].semilogx(k, [row["ratio"] for row in r["rows"]], "o-", label=name)
        if r["rebound"] is not None:
            axes[0].axhline(r["rebound"], color=line.get_color(), ls=":", label=f"{name} closed form {r['rebound']:.4f}")
        axes[1].loglog(k, [row["duration_s"] for row in r["rows"]], "o-", label=name)
        errors = [(row["stiffness"], row["second_error_s"]) for row in r["rows"] if row["second_error_s"]]
        if errors:
            axes[2].loglog(*zip(*errors), "o-", label=name)
    axes[0].axhline(restitution, color="k", ls="--", lw=0.8, label=f"e = {restitution}")
    axes[0].set_ylabel("separation / approach speed, first contact")
    axes[1].set_ylabel("first contact's duration (s)")
    axes[2].set_ylabel("|second onset − impulse law's| (s)")
    for ax in axes:
        ax.set_xlabel("contact stiffness (kN/m or kN/m^1.5: the law's unit)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle("Two-slab impact: compliant laws as their stiffness grows")
    fig.tight_layout()
    fig.savefig(HERE / "stiff-limit.png", dpi=110)
    plt.close(fig)


LOAD = " ".join(Path("/proc/loadavg").read_text().split()[:3])


def fmt(x, spec):
    return "–" if x is None else format(x, spec)


def write_page(laws, rows, first, level, results, restitution, method):
    by = {r["law"]: r for r in rows}
    impulse = by.get("impulse")
    lines = [
        "# Contact laws side by side",
        "",
        "Generated by `validation/contact-laws/run.py` (do not edit: rerun it). Every law of the",
        "registry (`pounding laws --json`) runs the paper scene (`examples/paper/paper.toml`, e = "
        f"{restitution}) with `--method {method}` and its default stiffness; then each compliant law's",
        "stiff limit on a head-on two-slab impact (`two-slabs.toml`). Laws added to the registry appear",
        "here when the page is regenerated.",
        "",
        "## Paper scene",
        "",
        "| law | stiffness | status | impacts | first impact (s) | first: peak force (kN), duration (ms) | "
        "peak u (cm) B1, B2 | peak drift ratio, CM (%) B1, B2 | worst corner (%) B1, B2 | "
        "peak abs. accel. x (g) B1, B2 | energy lost in contacts (kJ) | run time (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    names = [b["building"] for b in rows[0]["summary"]["peaks"]]
    for r in rows:
        p = r["peaks"]
        pair = lambda f: ", ".join(f(p[n]) for n in names)
        force = ("impulse" if r["law"] == "impulse" else
                 f"{fmt(r['first_peak_force_kN'], '.0f')}, {fmt(None if r['first_duration_s'] is None else 1e3 * r['first_duration_s'], '.2f')}")
        lines.append(
            f"| {r['law']} | {fmt(r['stiffness'], '.4g')} | {r['status']} | {r['impacts']} | {fmt(r['first_s'], '.6f')} | {force} | "
            f"{pair(lambda q: format(100 * q['u_m'][0], '.2f'))} | {pair(lambda q: format(100 * q['drift'][0], '.3f'))} | "
            f"{pair(lambda q: format(100 * q['corner_drift'][0], '.3f'))} | "
            f"{pair(lambda q: format(q['accel_mps2'][0] / r['g'], '.2f'))} | {r['energy_lost_kJ']:.1f} | {r['wall_time_s']:.2f} |")
    lines += [
        "",
        f"Run times are wall times on a shared machine (load average {LOAD}): indicative only.",
        "Peaks are the largest over the floors of each building, located on the dense output",
        "(`summary.json`, `accelerations.peaks_located`). Accelerations are absolute (q̈ + r a_g).",
    ]
    if impulse:
        lines.append(
            "**For the impulse law they are the smooth part only**: each impact adds a Dirac impulse to both slabs' "
            "accelerations, which no finite number can show; its impulses are in `impacts.csv` (`impulse_kNs`).")
        for r in rows:
            if r is impulse:
                continue
            ratio = lambda q: max(q[n]["accel_mps2"][0] for n in names)
            lines.append(
                f"With {r['law']} the largest floor acceleration is {ratio(r['peaks']) / r['g']:.2f} g against the "
                f"impulse law's smooth {ratio(impulse['peaks']) / impulse['g']:.2f} g "
                f"(× {ratio(r['peaks']) / ratio(impulse['peaks']):.2f}); the largest CM drift ratio "
                f"{100 * max(r['peaks'][n]['drift'][0] for n in names):.3f} % against "
                f"{100 * max(impulse['peaks'][n]['drift'][0] for n in names):.3f} %; "
                f"{r['impacts']} contacts against {impulse['impacts']} impacts; energy lost in contacts "
                f"{r['energy_lost_kJ']:.1f} kJ against {impulse['energy_lost_kJ']:.1f} kJ.")
    lines += [
        "",
        f"![first impact](first-impact.png)",
        "",
        f"The first contact (at {first:.6f} s, level {level}) rerun with the record cut just after it and a",
        f"history every {FIGURE_INTERVAL_S * 1e3:g} ms: the contact's normal force (for the impulse law the force",
        "holding the sustained contact that follows, if any) and the absolute x-acceleration of both slabs.",
        "The impulse law's smooth part jumps at each impact: the velocity jump acts through the",
        "stiffness-proportional part of the Rayleigh damping (C = a0 M + a1 K).",
        "",
        "## Stiff limit on a two-slab impact",
        "",
        "Building A (100 t, T = 0.5 s) strikes building B (200 t, T = 0.25 s) head-on, in line with both",
        "centres of mass, after a 0.2 s ground pulse (`two-slabs.toml`, e = 0.5). For each compliant law,",
        f"its default stiffness × {', '.join(f'{f:g}' for f in LADDER)}: the first contact's ratio of separation to",
        "approach speed (separation where the law releases the contact), its duration and the second",
        "contact's onset against the impulse law run with the law's closed-form rebound (or, without",
        "one, the ratio reached at the largest stiffness) as its restitution (same first onset; the",
        "second tends to it as the contact becomes an impulse).",
        "",
    ]
    for name, r in results.items():
        rebound = r["rebound"]
        lines += [f"### {name}", "",
                  "| stiffness | velocity ratio | vs closed form | duration (ms) | peak force (kN) | second onset (s) | vs impulse law (s) |",
                  "|---|---|---|---|---|---|---|"]
        for row in r["rows"]:
            off = None if rebound is None else row["ratio"] / rebound - 1
            lines.append(
                f"| {row['stiffness']:.4g} | {row['ratio']:.5f} | {'–' if off is None else f'{100 * off:+.2f} %'} | "
                f"{1e3 * row['duration_s']:.3f} | {row['peak_force_kN']:.0f} | {fmt(row['second_s'], '.6f')} | "
                f"{fmt(row['second_error_s'], '.2e')} |")
        last = r["rows"][-1]
        if rebound is None:
            verdict = (f"No closed-form rebound is known for {name} (`pounding laws --json` gives none): at the "
                       f"largest stiffness its ratio is {last['ratio']:.4f} (e = {restitution}), and the second onset "
                       f"is compared with the impulse law run with that ratio as its restitution.")
        else:
            off = abs(last["ratio"] / rebound - 1)
            verdict = (f"At the largest stiffness the ratio is {last['ratio']:.4f}, {100 * off:.2f} % from the closed form "
                       f"{rebound:.4f} ({'within' if off <= LIMIT_TOL else 'OUTSIDE'} the {100 * LIMIT_TOL:g} % the ctest "
                       f"`contact_laws_limit` allows)")
            if abs(rebound - restitution) > 1e-9:
                verdict += (f"; the closed form differs from e = {restitution} because of how the law releases a "
                            "contact (docs/model.md)")
            verdict += "."
        lines += ["", verdict, ""]
    lines += ["![stiff limit](stiff-limit.png)", ""]
    (HERE / "README.md").write_text("\n".join(lines))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pounding", default=str(ROOT / "build/apps/pounding"))
    parser.add_argument("--method", default="cvode-bdf")
    parser.add_argument("--out", default=str(ROOT / "out/validation/contact-laws"))
    parser.add_argument("--limit-only", action="store_true", help="only the two-slab stiffness limit (no page)")
    parser.add_argument("--check", action="store_true", help="exit 1 when a law misses its closed-form rebound")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    restitution = tomllib.loads(TWO_SLABS.read_text())["contact"]["restitution"]
    laws = pounding_json(args.pounding, "laws", "--json", "--restitution", f"{restitution}")
    results = limit_check(args.pounding, laws, out, restitution)
    failed = []
    for name, r in results.items():
        last = r["rows"][-1]
        if r["rebound"] is None:
            print(f"{name}: ratio {last['ratio']:.5f} at stiffness {last['stiffness']:.4g} (no closed form to check)")
            continue
        off = abs(last["ratio"] / r["rebound"] - 1)
        print(f"{name}: ratio {last['ratio']:.5f} at stiffness {last['stiffness']:.4g}, closed form {r['rebound']:.5f}, "
              f"off by {100 * off:.3f} %")
        if not off <= LIMIT_TOL:
            failed.append(name)
    if not args.limit_only:
        paper_restitution = tomllib.loads(PAPER.read_text())["contact"]["restitution"]
        paper_laws = pounding_json(args.pounding, "laws", "--json", "--restitution", f"{paper_restitution}")
        rows = paper_comparison(args.pounding, paper_laws, out, args.method)
        first, level = first_impact_figure(args.pounding, paper_laws, rows, out, args.method)
        limit_figure(results, restitution)
        write_page(paper_laws, rows, first, level, results, paper_restitution, args.method)
        print(f"wrote {HERE / 'README.md'}, first-impact.png, stiff-limit.png")
    if args.check and failed:
        sys.exit(f"stiff limit missed by: {', '.join(failed)}")


if __name__ == "__main__":
    main()
