#!/usr/bin/python3
"""Writes one self-contained HTML page of a `pounding run` folder: report.html.

The page holds the run's key numbers (gap, k, contact law, impacts, first impact, energy residual,
run time), the plan and elevation of the scene (plan.json; a row's with its impacts marked, then
each pair's results and each building's demands), the storeys' ductility, column shear failures
and residual drift and the drift limit states (where the run has them), the histories of the level with most
impacts (tools/plot_run.py's figure), the impacts and sustained contacts, the peaks of every
floor, the energy balance, the solver's statistics, the settings given and used, the warnings and
the provenance. Figures are embedded as PNG data and nothing is fetched from elsewhere, so the file
can be mailed or archived alone. A few lines of script check, once the page is loaded, that every
figure decoded and count the table rows, and write what they found at the foot of the page (the
project's browser test reads it).

    tools/report_run.py RUN_DIR [--out FILE] [--bracket BRACKET_DIR]

With --bracket, the page also shows the spread of `pounding bracket` on the run's scene: each
demand's least and largest over the contact laws, restitutions and stiffnesses, and whether each
verdict is the same on every run.

RUN_DIR needs summary.json and plan.json (`pounding report RUN_DIR` writes the plan of the run's
scene there and runs this script); history.csv and impacts.csv are used when present.
"""
import argparse
import base64
import contextlib
import html
import io
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import plot_run  # noqa: E402
from animate_run import default_level  # noqa: E402
from plot_plan import plan_figure, read_plan  # noqa: E402

MAX_IMPACT_ROWS = 1000  # the page stays light; impacts.csv holds them all

STYLE = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 75em; color: #222; line-height: 1.4; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 2em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.5em 0; }
th, td { border: 1px solid #ddd; padding: 0.2em 0.5em; text-align: right; }
th { background: #f3f3f3; } td.text, th.text { text-align: left; }
img { max-width: 100%; border: 1px solid #eee; }
pre { background: #f7f7f7; padding: 0.8em; overflow-x: auto; font-size: 0.8em; }
.status-completed { color: #196c1e; } .status-other { color: #b00020; } .note { color: #666; font-size: 0.85em; }
"""

# After load: every figure decoded (naturalWidth > 0) and the rows of each table, written into
# #render-check and as data attributes of <body>, for a reader or a headless browser.
RENDER_CHECK = """
window.addEventListener("load", function () {
  var images = Array.prototype.slice.call(document.images);
  var decoded = images.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  var impacts = document.querySelectorAll("#impacts tbody tr").length;
  document.body.dataset.figures = images.length;
  document.body.dataset.figuresDecoded = decoded;
  document.body.dataset.impactRows = impacts;
  document.getElementById("render-check").textContent =
    "Rendered: " + decoded + " of " + images.length + " figures decoded; " + impacts + " impact rows shown.";
});
"""


def text(value):
    return html.escape(str(value))


def number(value, digits=6):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return text(value if value is not None else "")
    return f"{value:.{digits}g}"


def table(header, rows, table_id=None, text_columns=()):
    """An HTML table; the columns named in text_columns are left-aligned."""
    def cell(tag, column, value):
        klass = ' class="text"' if column in text_columns else ""
        return f"<{tag}{klass}>{value}</{tag}>"
    head = "".join(cell("th", c, text(c)) for c in header)
    body = "".join("<tr>" + "".join(cell("td", c, v) for c, v in zip(header, row)) + "</tr>" for row in rows)
    identity = f' id="{table_id}"' if table_id else ""
    return f"<table{identity}><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def figure_html(fig, alt):
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=90)
    plt.close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return f'<img alt="{text(alt)}" src="data:image/png;base64,{data}">'


def history_figure_html(folder, summary):
    """plot_run's figure of the level with most impacts, or a note saying why there is none."""
    if not summary["outputs"].get("history") or not summary["history_levels"]:
        return '<p class="note">No history in this run (history off): no histories drawn.</p>'
    if summary.get("pairs"):
        return ('<p class="note">A row of buildings: the histories of a level of two buildings are not drawn '
                "(history.csv holds them; tools/plot_plan.py --impacts draws the row's plan and its impacts).</p>")
    level = default_level(summary)
    image = io.BytesIO()  # plot_run saves to any file object: nothing is written into the run folder
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        plot_run.plot(folder, level, None, None, image)
    data = base64.b64encode(image.getvalue()).decode("ascii")
    return (f'<img alt="histories of level {level}" src="data:image/png;base64,{data}">'
            f'<p class="note">Level {level}: u, v, φ of both slabs, the x-displacement of the contact corners and '
            "the signed gap of every corner–edge pair; dotted green lines mark the impacts (tools/plot_run.py).</p>")


def gaps_text(summary):
    """"0.2 m", or a row's "B1:B2 0.2 m, B2:B3 0.1 m" (its impacts per pair after each)."""
    if not summary.get("pairs"):
        return f"{number(summary['gap_m'])} m"
    return text(", ".join(f"{p['names'][0]}:{p['names'][1]} {number(p['gap_m'])} m ({p['impacts']} impacts)"
                          for p in summary["pairs"]))


def key_numbers(summary):
    stats, energy = summary["statistics"], summary["energy"]
    impacts = summary["impacts"]
    rows = [("scene", text(summary["scene"])),
            ("method", text(summary["method"])),
            ("status", f'<span class="status-{"completed" if summary["status"] == "completed" else "other"}">'
                       f'{text(summary["status"])}</span> {text(summary["status_detail"])}'),
            ("clear gap", gaps_text(summary)),
            ("coefficient of restitution k", number(summary["restitution"])),
            ("contact law", text(summary["contact_law"].get("name", ""))),
            ("simulated time", f"{number(summary['start_s'])}–{number(summary['end_s'])} s"),
            ("impacts", f"{summary['impact_count']}"),
            ("first impact", f"{impacts[0]['t_s']:.6f} s at level {impacts[0]['level']}" if impacts else "none"),
            ("impacts by level", text(", ".join(f"level {k}: {v}" for k, v in summary["impacts_by_level"].items())
                                      or "none")),
            ("sustained contacts", f"{len(summary['sustained_contacts'])}"),
            ("largest interpenetration", f"{number(stats.get('max_interpenetration_m', 0.0), 3)} m"),
            ("energy residual", f"{number(energy.get('residual_kJ', 0.0), 3)} kJ "
                                f"({number(energy.get('relative_residual', 0.0), 3)} of the input)"),
            ("run time", f"{number(stats.get('wall_time_s', 0.0), 3)} s")]
    return table(("quantity", "value"), rows, text_columns=("quantity", "value"))


def who(contact):
    """'B1 vertex 3', 'B1 vertex 3 on B3' (a row) or, slab to column, "B1's slab on B2 column 4"."""
    if contact["level"] == 0:
        return f"B{contact['striking_building']}'s slab on B{contact['struck_building']} column {contact['column']}"
    on = f" on B{contact['struck_building']}" if "struck_building" in contact else ""
    return f"B{contact['striking_building']} vertex {contact['vertex']}{on}"


def impacts_table(summary):
    impacts = summary["impacts"]
    if not impacts:
        return '<p>No impact.</p><table id="impacts"><tbody></tbody></table>'
    header = ("t [s]", "level", "striking", "corner at rest [m]", "struck edge", "approach [m/s]",
              "separation [m/s]", "impulse [kN·s]", "peak force [kN]", "energy lost [kJ]", "starts hold")
    rows = [(f"{i['t_s']:.9f}", i["level"], who(i),
             text(f"({i['vertex_rest'][0]:g}, {i['vertex_rest'][1]:g})"), i["struck_edge"],
             number(i["approach_velocity_mps"], 5), number(i["separation_velocity_mps"], 5),
             number(i["impulse_kNs"], 5), number(i["peak_force_kN"], 5), number(i["energy_lost_kJ"], 5),
             "yes" if i["starts_sustained_contact"] else "")
            for i in impacts[:MAX_IMPACT_ROWS]]
    note = (f'<p class="note">The first {MAX_IMPACT_ROWS} of {len(impacts)} impacts; impacts.csv holds all.</p>'
            if len(impacts) > MAX_IMPACT_ROWS else "")
    return table(header, rows, "impacts") + note


def ratio_cell(ratio):
    """A demand over capacity, flagged above 1; '' without a capacity."""
    if ratio is None:
        return ""
    return text(f"{ratio:.3g} EXCEEDED") if ratio > 1.0 else number(ratio, 3)


def total_cells(impact):
    """The shear with the sway, when, the sway then and its ratio; empty for a run written before
    these fields existed."""
    if "column_total_shear_kN" not in impact:
        return "", "", "", ""
    return (number(impact["column_total_shear_kN"], 5), f"{impact['column_total_shear_t_s']:.4f}",
            number(impact["column_sway_shear_kN"], 5), ratio_cell(impact.get("column_total_shear_ratio")))


def struck_columns_table(summary):
    """Per struck column (slab to column): its impacts, the largest peak force with the end shear it
    causes, and the largest shear with the column's sway (docs/model.md 6b), each against the
    column's capacity."""
    columns = {}
    for i in summary["impacts"]:
        if i["level"] != 0:
            continue
        # floors: the slab's floor and the column's storey, in building order (a row: the pair's).
        in_order = sorted((i["striking_building"], i["struck_building"]))
        key = (i["struck_building"], i["column"], i["floors"][in_order.index(i["struck_building"])])
        entry = columns.setdefault(key, {"count": 0, "force": i, "total": i})
        entry["count"] += 1
        if i["peak_force_kN"] > entry["force"]["peak_force_kN"]:
            entry["force"] = i
        if i.get("column_total_shear_kN", 0.0) > entry["total"].get("column_total_shear_kN", 0.0):
            entry["total"] = i
    if not columns:
        return ""
    header = ("column", "storey", "impacts", "peak force [kN]", "impact shear [kN]", "over capacity",
              "with sway [kN]", "at [s]", "sway [kN]", "with sway over capacity")
    rows = [(f"B{b} column {c}", storey, e["count"], number(e["force"]["peak_force_kN"], 5),
             number(e["force"]["column_shear_kN"], 5), ratio_cell(e["force"].get("column_shear_ratio")),
             *total_cells(e["total"]))
            for (b, c, storey), e in sorted(columns.items())]
    watched = summary.get("struck_column_failures")
    if watched is not None:  # the located failures (docs/model.md 6b), the first of each column and storey
        failed = {}
        for f in watched["failures"]:
            failed.setdefault((f["struck_building"], f["column"], f["storey"]), f)
        header += ("failed in shear",)
        rows = [row + (failure_cell(failed.get(key), columns[key]["force"].get("column_shear_ratio") is not None),)
                for row, key in zip(rows, sorted(columns))]
    return table(header, rows, "struck-columns",
                 text_columns=("column", "over capacity", "with sway over capacity", "failed in shear"))


def failure_cell(failure, has_capacity):
    """'FAILED at 4.601653 s along x (loses its stiffness)', 'no' for a column with a capacity that
    held, '' for one without."""
    if failure is None:
        return text("no" if has_capacity else "")
    lost = " (loses its stiffness)" if failure["loses_stiffness"] else ""
    return text(f"FAILED at {failure['t_s']:.6f} s along {failure['axis']}{lost}")


def member_forces_table(summary):
    """Per building and storey, its peak storey shears and torque and its largest column shear and end
    moment (summary.json member_forces, docs/model.md 2c)."""
    forces = summary.get("member_forces")
    if not forces:
        return ""
    header = ("building", "storey", "|Vx| [kN]", "at [s]", "|Vy| [kN]", "at [s]", "|T| [kN m]", "at [s]",
              "largest column |V| [kN]", "column", "largest end |M| [kN m]")

    def peak(entry, key):
        return number(abs(entry[key]["value"]), 5), f"{entry[key]['t_s']:.4f}"

    rows = []
    for building in forces["buildings"]:
        for storey in building["storeys"]:
            columns = storey.get("columns", [])
            shears = [(abs(c[k]["value"]), c["column"]) for c in columns for k in ("Vx_kN", "Vy_kN")]
            moments = [abs(c[k]["value"]) for c in columns for k in ("Mx_kNm", "My_kNm")]
            shear, column = max(shears) if shears else (None, "")
            rows.append((text(building["building"]), storey["storey"], *peak(storey, "Vx_kN"), *peak(storey, "Vy_kN"),
                         *peak(storey, "T_kNm"), number(shear, 5) if shear is not None else "", text(column),
                         number(max(moments), 5) if moments else ""))
    return table(header, rows, "member-forces", text_columns=("building", "column"))


def sustained_table(summary):
    holds = summary["sustained_contacts"]
    if not holds:
        return "<p>No sustained contact.</p>"
    header = ("level", "striking", "start [s]", "release [s]", "release reason", "largest force [kN]")
    rows = [(c["level"], who(c), f"{c['start_s']:.6f}",
             f"{c['release_s']:.6f}", text(c["release_reason"]), number(c["max_force_kN"], 5)) for c in holds]
    return table(header, rows, text_columns=("release reason",))


def pairs_table(summary):
    """A row: per neighbouring pair, its gap and direction, impacts (count, first, the largest
    impulse, approach speed and force), the energy its contacts took and its sustained contacts."""
    header = ("pair", "gap [m]", "direction", "impacts", "first impact [s]", "largest impulse [kN·s]",
              "largest approach [m/s]", "largest force [kN]", "energy lost [kJ]", "sustained contacts")
    rows = []
    for p in summary["pairs"]:
        on = [i for i in summary["impacts"] if sorted((i["striking_building"], i["struck_building"])) == p["buildings"]]
        holds = [c for c in summary["sustained_contacts"] if c["buildings"] == p["buildings"]]
        largest = lambda key: number(max((i[key] for i in on), default=0.0), 5)  # noqa: E731
        rows.append((text(f"{p['names'][0]}:{p['names'][1]}"), number(p["gap_m"]),
                     text(f"({p['direction'][0] + 0.0:g}, {p['direction'][1] + 0.0:g})"), len(on),
                     f"{min(i['t_s'] for i in on):.6f}" if on else "–", largest("impulse_kNs"),
                     largest("approach_velocity_mps"), largest("peak_force_kN"),
                     number(sum(i["energy_lost_kJ"] for i in on), 5), len(holds)))
    return table(header, rows, "pairs", text_columns=("pair", "direction"))


def demands_table(summary):
    """Per building: its largest storey drift ratios and accelerations, where and when, and (where
    columns yield) the largest storey ductility."""
    ductility = {}
    for b in summary.get("yielding", {}).get("buildings", []):
        ductility[b["building"]] = max(((max(s["peak_ductility_x"], s["peak_ductility_y"]), s["storey"])
                                        for s in b["storeys"]), default=None)

    def largest(floors, key):
        best = max((f for f in floors if key in f), key=lambda f: abs(f[key]["value"]), default=None)
        return f"{number(abs(best[key]['value']), 4)} (floor {best['floor']}, {best[key]['t_s']:.3f} s)" if best else "–"

    header = ("building", "largest drift x", "largest drift y", "largest |a_x| [m/s²]", "largest |u| [m]",
              "largest ductility")
    rows = []
    for b, building in enumerate(summary["peaks"], start=1):
        floors = building["floors"]
        mu = ductility.get(b)
        rows.append((text(building["building"]), largest(floors, "drift_x"), largest(floors, "drift_y"),
                     largest(floors, "ax_abs_mps2"), largest(floors, "u_m"),
                     f"{mu[0]:.3g} (storey {mu[1]})" if mu else "–"))
    return table(header, rows, "demands", text_columns=header)


def percent(ratio, digits=3):
    return f"{100.0 * ratio:.{digits}f} %"


def storeys_table(summary):
    """Per building and storey, where the run has them: the columns' ductility and first yield, the
    degrading columns' failures, the column shear failures against their capacity, and the residual
    drift ratio."""
    yielding = {(b["building"], s["storey"]): s for b in summary.get("yielding", {}).get("buildings", [])
                for s in b["storeys"]}
    names = [b["building"] for b in summary["peaks"]]
    residual = {(names.index(b["building"]) + 1, s["storey"]): s
                for b in summary.get("residual_drift", {}).get("buildings", []) for s in b["storeys"]}
    if not yielding and not residual:
        return ""
    shear = any("column_shear" in s for s in yielding.values())
    degrading = any("degrading" in s for s in yielding.values())
    header = ["building", "storey", "ductility x", "ductility y", "first yield [s]"]
    header += ["degrading failures", "first degrading failure [s]"] if degrading else []
    header += ["shear failures", "first failure [s]", "largest demand/capacity"] if shear else []
    header += ["residual drift x (CM)", "residual drift y (CM)", "largest residual"] if residual else []
    rows = []
    for b, name in enumerate(names, start=1):
        for storey in sorted({k[1] for k in list(yielding) + list(residual) if k[0] == b}):
            y, r = yielding.get((b, storey)), residual.get((b, storey))
            row = [text(name), storey]
            row += [number(y["peak_ductility_x"], 4), number(y["peak_ductility_y"], 4),
                    f"{y['first_yield_t_s']:.4f}" if y["first_yield_t_s"] is not None else "elastic"] if y else ["–"] * 3
            if degrading:
                d = (y or {}).get("degrading")
                row += [f"{d['failures']} of {d['springs']}",
                        f"{d['first_failure_t_s']:.4f}" if d["first_failure_t_s"] is not None else "–"] if d else ["–"] * 2
            if shear:
                c = (y or {}).get("column_shear")
                row += [f"{c['failures']} of {c['springs_with_capacity']}",
                        f"{c['first_failure_t_s']:.4f}" if c["first_failure_t_s"] is not None else "–",
                        f"{c['largest_demand_capacity_ratio']:.3f} ({number(c['critical_peak_force_kN'], 4)} kN of "
                        f"{number(c['critical_shear_capacity_kN'], 4)} kN, {text(c['critical_column'])} "
                        f"{c['critical_direction']})"] if c else ["–"] * 3
            if residual:
                row += [percent(r["drift_ratio_x"]), percent(r["drift_ratio_y"]),
                        f"{percent(r['largest_drift_ratio'])} ({text(r['where'])} {r['axis']})"] if r else ["–"] * 3
            rows.append(row)
    notes = []
    for b in summary.get("residual_drift", {}).get("buildings", []):
        state = "at rest" if b["settled"] else "still oscillating"
        damage = b.get("damage_state") or "below DS1"
        notes.append(f"{text(b['building'])}: {state} (oscillation {percent(b['oscillation_ratio'], 4)}), "
                     f"damage state {damage}")
    note = ""
    if notes:
        note = (f'<p class="note">Residual drift: the storey drift ratio at the end of the run, '
                f"t = {summary['residual_drift']['t_s']:.3f} s ({number(summary['residual_drift']['free_vibration_s'])} s "
                f"of quiet tail); {'; '.join(notes)}.</p>")
    return table(header, rows, "storeys", text_columns=("building",)) + note


def limit_states_table(summary):
    """Per building with limit states: its peak storey drift and each level's verdict and margin,
    with contact and, where the run has it, without."""
    states = summary.get("limit_states", {}).get("buildings", [])
    if not states:
        return ""
    header = ("building", "structural type", "run", "peak storey drift", "where", "IO", "LS", "CP")

    def verdict(level):
        word = "exceeded by" if level["exceeded"] else "met, margin"
        return f"{percent(level['drift_ratio_limit'], 2)}: {word} {percent(abs(level['margin']))}"

    rows = []
    for state in states:
        for label, part in (("with contact", state), ("without contact", state.get("without_contact"))):
            if not part:
                continue
            peak = part["peak_storey_drift"]
            rows.append([text(state["building"]), text(state["structural_type"]), label, percent(peak["drift_ratio"]),
                         f"storey {peak['storey']}, {text(peak['where'])} {peak['axis']}, {peak['t_s']:.3f} s"
                         if "t_s" in peak else f"storey {peak['storey']}"] + [verdict(v) for v in part["levels"]])
    return table(header, rows, "limit-states", text_columns=header[:3] + ("where",) + header[5:])


def read_bracket(path, summary):
    """bracket.json of `pounding bracket` (PATH or PATH/bracket.json); exits naming the file when it
    is missing, unreadable or of another scene."""
    file = path / "bracket.json" if path.is_dir() else path
    try:
        document = json.loads(file.read_text())
        scene, spread = document["scene"], document["spread"]
    except (OSError, ValueError, KeyError, TypeError) as error:
        sys.exit(f"error: --bracket {file}: not a bracket.json of `pounding bracket` ({error})")
    if scene != summary["scene"]:
        sys.exit(f"error: --bracket {file}: is the bracket of scene '{scene}', the run is of '{summary['scene']}'")
    return document


def bracket_section(document):
    """The bracket's spread: per demand its least and largest over the runs with the run at each,
    per verdict whether every run gives it, and the runs that did not complete."""
    runs = document["runs"]
    completed = sum(r["status"] == "completed" for r in runs)
    note = (f'<p class="note">{len(runs)} runs ({completed} completed) of laws {text(", ".join(document["laws"]))}, '
            f"restitutions {text(', '.join(f'{e:g}' for e in document['restitutions']))} and stiffness factors "
            f"{text(', '.join(f'{f:g}' for f in document['stiffness_factors']))} (pounding bracket; units in each "
            "name, drifts as ratios).</p>")
    demands = [[text(name), number(e["min"]), text(e["min_run"]), number(e["max"]), text(e["max_run"]),
                "" if e["max_over_min"] is None else number(e["max_over_min"], 3)]
               for name, e in document["spread"]["demands"].items()]
    verdicts = [[text(name), "yes" if e["same_on_all"] else "<b>no</b>",
                 text(", ".join(f"{value} on {count}" for value, count in e["values"].items()))]
                for name, e in document["spread"]["verdicts"].items()]
    others = "".join(f"<li>{text(r['contact_law'])}, e = {r['restitution']:g}: {text(r['status'])} {text(r['message'])}"
                     "</li>" for r in runs if r["status"] != "completed")
    return "".join([
        note,
        table(("demand", "least", "at", "largest", "at", "largest/least"), demands, "bracket-demands",
              text_columns=("demand", "at")),
        table(("verdict", "the same on every run", "values"), verdicts, "bracket-verdicts",
              text_columns=("verdict", "the same on every run", "values")),
        f"<ul>{others}</ul>" if others else ""])


def structural_sections(summary):
    """The storeys' demands, their member forces and the limit states, when the run has any."""
    storeys, forces, limits = storeys_table(summary), member_forces_table(summary), limit_states_table(summary)
    parts = ["<h2>Storeys</h2>", storeys] if storeys else []
    if forces:
        parts += ["<h2>Member forces</h2>",
                  '<p class="note">Peaks over the run\'s step ends, events and history samples: the storeys\' '
                  "shears and torque about the CM, the columns' own forces (no damping, no P-Δ).</p>", forces]
    return parts + (["<h2>Limit states</h2>", limits] if limits else [])


def peaks_tables(summary):
    """Per building, one row a floor: every scalar peak (value at time), whatever the run computed."""
    parts = []
    for building in summary["peaks"]:
        floors = building["floors"]
        keys = [k for k in floors[0] if isinstance(floors[0][k], dict) and "value" in floors[0][k]] if floors else []
        rows = [[f["floor"]] + [f"{number(f[k]['value'], 4)} @ {f[k]['t_s']:.3f} s" for k in keys] for f in floors]
        parts.append(f"<h3>{text(building['building'])}</h3>" + table(["floor"] + keys, rows))
    return "".join(parts)


def dictionary_table(values, unit_note=""):
    rows = [(text(k), number(v) if not isinstance(v, (dict, list)) else f"<code>{text(json.dumps(v))}</code>")
            for k, v in values.items()]
    return table(("quantity", "value"), rows, text_columns=("quantity", "value")) + unit_note


def plan_html(summary, plan):
    """The plan and elevation; a row's plan marks where its impacts struck."""
    impacts = None
    if summary.get("pairs"):
        impacts = [(i["point"][0], i["point"][1], i["striking_building"] - 1) for i in summary["impacts"]]
    return figure_html(plan_figure(plan, impacts), "plan and elevation")


def row_sections(summary):
    """A row: its pairs' results and its buildings' demands (two buildings: none)."""
    if not summary.get("pairs"):
        return []
    return ["<h2>Pairs</h2>", pairs_table(summary),
            "<h2>Demands per building</h2>",
            '<p class="note">Drift ratios of the storey below a floor at its centre of mass; absolute '
            "accelerations (impulse law: the smooth part); ductility: the largest of a storey's columns.</p>",
            demands_table(summary)]


def page(folder, summary, plan, bracket=None):
    warnings = "".join(f"<li>{text(w)}</li>" for w in summary["warnings"]) or "<li>none</li>"
    sections = [
        f"<h1>pounding run: {text(summary['scene'])}</h1>",
        f'<p class="note">{text(folder.resolve())}</p>',
        "<h2>Key numbers</h2>", key_numbers(summary),
        "<h2>Plan and elevation</h2>", plan_html(summary, plan),
        *row_sections(summary),
        *structural_sections(summary),
        *(["<h2>Contact parameters bracketed</h2>", bracket_section(bracket)] if bracket else []),
        "<h2>Histories</h2>", history_figure_html(folder, summary),
        f"<h2>Impacts ({summary['impact_count']})</h2>", impacts_table(summary),
        *(["<h2>Struck columns</h2>",
           '<p class="note">Slab to column: per column its largest impact force and end shear, and its largest '
           "shear with its sway (the larger of the shears below and above the load).</p>",
           struck_columns_table(summary)] if any(i["level"] == 0 for i in summary["impacts"]) else []),
        "<h2>Sustained contacts</h2>", sustained_table(summary),
        "<h2>Peaks</h2>", '<p class="note">Value at its time; units in each name (drifts as ratios).</p>',
        peaks_tables(summary),
        "<h2>Energy balance</h2>", dictionary_table(summary["energy"]),
        "<h2>Solver statistics</h2>", dictionary_table(summary["statistics"]),
        "<h2>Settings</h2>", f"<pre>{text(json.dumps(summary['settings'], indent=2))}</pre>",
        "<h2>Warnings</h2>", f"<ul>{warnings}</ul>",
        "<h2>Provenance</h2>", dictionary_table(summary["provenance"]),
        '<p id="render-check" class="note">Rendered: the check did not run (scripts off).</p>',
    ]
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>pounding: {text(summary['scene'])}</title><style>{STYLE}</style></head>\n<body>\n"
            + "\n".join(sections) + f"\n<script>{RENDER_CHECK}</script>\n</body></html>\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path, help="output folder of `pounding run`, with plan.json")
    parser.add_argument("--out", type=Path, help="HTML file (default: FOLDER/report.html)")
    parser.add_argument("--bracket", type=Path, help="bracket.json of `pounding bracket` on the run's scene, "
                        "or its folder: the page shows its spread")
    args = parser.parse_args()
    summary_file = args.folder / "summary.json"
    if not summary_file.is_file():
        sys.exit(f"error: {summary_file} not found (is {args.folder} the output folder of `pounding run`?)")
    summary = json.loads(summary_file.read_text())
    out = args.out or args.folder / "report.html"
    bracket = read_bracket(args.bracket, summary) if args.bracket else None
    out.write_text(page(args.folder, summary, read_plan(args.folder), bracket), encoding="utf-8")
    print(f"Wrote {out}")


if __name__ == "__main__":
    main()
