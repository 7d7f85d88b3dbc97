#!/usr/bin/python3
"""Draws a sweep's table (`pounding sweep`, sweep.csv): the probability of pounding against the
gap over the record set and the severity of the impacts against the gap.

    tools/plot_sweep.py DIR [--out FILE]      (default DIR/sweep.png; the fit goes to DIR/sweep_fit.json)

Top row: the fraction of records whose needed gap exceeds d (the empirical step curve), the
lognormal fit 1 − Φ((ln d − m)/s) with m and s the mean and sample standard deviation (divisor
n − 1) of ln(needed gap) over the records (as `pounding gap --records`), the fit's median exp(m)
and 84th percentile exp(m + s) marked, and the fraction of the sweep's runs at each gap that had an
impact (dots). Then the largest impulse and the largest approach speed of each run against its
gap, a thin line per record and their median. One column per value of what varies across the
table besides the record and the gap (restitution, method, its settings, contact law, scene).
Needs the sweep's `needed_gap = true` for the top row's curve; without it only the dots are drawn.
"""

import argparse
import csv
import json
import math
import pathlib
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Columns that are the run's result, not its parameters (pounding.sweep writes them after the
# parameters, from `status` on); the record and the gap are the axes inside a panel.
AXES = ("record", "record_source", "gap_m")


def read(folder):
    with open(folder / "sweep.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"error: {folder / 'sweep.csv'} holds no row")
    columns = list(rows[0])
    parameters = columns[: columns.index("status")]
    return rows, parameters


def panels(rows, parameters):
    """Rows grouped by the parameters that vary, besides the record and the gap."""
    varying = [c for c in parameters if c not in AXES and c != "scene" and len({r[c] for r in rows}) > 1]
    groups = {}
    for row in rows:
        groups.setdefault(tuple(row[c] for c in varying), []).append(row)
    titles = {key: ", ".join(f"{c} = {v or 'scene'}" for c, v in zip(varying, key)) or "every run" for key in groups}

    def order(key):  # numbers by value, text by name
        return [(0, float(v), "") if _is_number(v) else (1, 0.0, v) for v in key]
    return varying, dict(sorted(groups.items(), key=lambda item: order(item[0]))), titles


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def needed_gaps(rows):
    """One needed gap a record (m; 0 where no pair ever closes), from rows whose analysis completed."""
    gaps = {}
    for row in rows:
        if row.get("needed_gap_status") == "completed":
            gaps[(row["scene_file"], row["record_source"])] = float(row["needed_gap_m"] or 0.0)
    return list(gaps.values())


def lognormal(values):
    positive = [math.log(v) for v in values if v > 0]
    if len(positive) < 2:
        return None
    m, s = statistics.fmean(positive), statistics.stdev(positive)
    return {"count": len(positive), "log_mean": m, "log_std": s, "median_m": statistics.median(values),
            "median_lognormal_m": math.exp(m), "p84_lognormal_m": math.exp(m + s)}


def exceedance(fit, d_m, fraction_positive):
    if d_m <= 0:
        return fraction_positive
    return fraction_positive * 0.5 * math.erfc((math.log(d_m) - fit["log_mean"]) / (fit["log_std"] * math.sqrt(2)))


def by_gap(rows, column):
    """{record source: ([gaps], [values])} over the completed runs, by increasing gap."""
    lines = {}
    for row in sorted(rows, key=lambda r: float(r["gap_m"])):
        if row["status"] == "completed":
            x, y = lines.setdefault(row["record_source"], ([], []))
            x.append(float(row["gap_m"]))
            y.append(float(row[column]))
    return lines


def draw_probability(axis, rows, gaps, fit, d_max, repeated_from=None):
    """The share of records whose needed gap exceeds d, its lognormal fit and the observed share
    of runs with an impact. `repeated_from`: the title of an earlier panel with the same needed
    gaps (the needed gap is contact-free, so restitution, law and method do not change it): the
    curve is then drawn there only, and here in grey for reference."""
    if repeated_from is not None:
        if fit:
            grid = [d_max * k / 400 for k in range(401)]
            fraction = fit["count"] / len(gaps)
            axis.plot(grid, [exceedance(fit, g, fraction) for g in grid], color="0.7", lw=1,
                      label=f"lognormal fit as for {repeated_from}")
    elif gaps:
        # The fraction exceeding d, constant from one needed gap to the next (right-continuous).
        n = len(gaps)
        x = [0.0, *sorted(v for v in gaps if 0 < v < d_max), d_max]
        y = [sum(v > xi for v in gaps) / n for xi in x]
        axis.step(x, y, where="post", color="k", lw=1.5, label=f"records ({n}) whose needed gap > d")
    if fit and repeated_from is None:
        fraction = fit["count"] / len(gaps)
        grid = [d_max * k / 400 for k in range(401)]
        axis.plot(grid, [exceedance(fit, g, fraction) for g in grid], color="C3", lw=1.2, label="lognormal fit")
        # The values go in the legend: text beside two close lines would overlap.
        for value, name, style in ((fit["median_lognormal_m"], "median", "--"),
                                   (fit["p84_lognormal_m"], "84th percentile", ":")):
            axis.axvline(value, color="C3", ls=style, lw=1, label=f"{name} {value:.3f} m")
    observed = {}
    for row in rows:
        if row["status"] == "completed":
            observed.setdefault(float(row["gap_m"]), []).append(int(row["impact_count"]) > 0)
    if observed:
        xs = sorted(observed)
        axis.plot(xs, [sum(observed[x]) / len(observed[x]) for x in xs], "o", color="C0", ms=5,
                  label="runs with an impact")
    axis.set_ylim(-0.02, 1.02)
    axis.set_ylabel("probability of pounding [-]")
    axis.legend(fontsize=7, loc="lower left")


def draw_severity(axis, rows, column, label):
    lines = by_gap(rows, column)
    for x, y in lines.values():
        axis.plot(x, y, color="0.6", lw=0.8)
    gaps = sorted({g for x, _ in lines.values() for g in x})
    median = [statistics.median(y[x.index(g)] for x, y in lines.values() if g in x) for g in gaps]
    axis.plot(gaps, median, "o-", color="C1", lw=2, label="median over the records (grey: each record)")
    axis.set_ylabel(label)
    axis.legend(fontsize=7)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=pathlib.Path, help="a sweep's output folder (sweep.csv)")
    parser.add_argument("--out", type=pathlib.Path, help="figure file (default FOLDER/sweep.png)")
    arguments = parser.parse_args()
    rows, parameters = read(arguments.folder)
    varying, groups, titles = panels(rows, parameters)

    columns = len(groups)
    figure, axes = plt.subplots(3, columns, figsize=(4.2 * columns + 0.8, 9.5), sharex=True, squeeze=False)
    d_max = max(float(r["gap_m"]) for r in rows)
    all_gaps = needed_gaps(rows)
    d_max = 1.15 * max([d_max, *all_gaps])
    fits = []
    drawn = {}  # needed gaps already drawn -> the title of their panel
    for column, (key, group) in enumerate(groups.items()):
        gaps = needed_gaps(group)
        fit = lognormal(gaps)
        fits.append({"panel": dict(zip(varying, key)), "records": len(gaps), "fit": fit})
        same = tuple(sorted(gaps))
        draw_probability(axes[0, column], group, gaps, fit, d_max, drawn.get(same))
        drawn.setdefault(same, titles[key])
        axes[0, column].set_title(titles[key], fontsize=9)
        draw_severity(axes[1, column], group, "max_impulse_kNs", "largest impulse [kN·s]")
        draw_severity(axes[2, column], group, "max_approach_speed_mps", "largest approach speed [m/s]")
        axes[2, column].set_xlabel("clear gap d [m]")
        axes[2, column].set_xlim(0, d_max)
        if fit:
            print(f"{titles[key]}: {len(gaps)} records, needed gap median {fit['median_m']:.4f} m, lognormal fit: "
                  f"median {fit['median_lognormal_m']:.4f} m, 84th percentile {fit['p84_lognormal_m']:.4f} m")
    failed = sum(r["status"] != "completed" for r in rows)
    figure.suptitle(f"{arguments.folder.name}: {len(rows)} runs"
                    + (f", {failed} not completed (left out)" if failed else ""), fontsize=10)
    figure.tight_layout()
    out = arguments.out or arguments.folder / "sweep.png"
    figure.savefig(out, dpi=110)
    (arguments.folder / "sweep_fit.json").write_text(json.dumps(fits, indent=2) + "\n")
    print(f"wrote {out} and {arguments.folder / 'sweep_fit.json'}")


if __name__ == "__main__":
    main()
