#!/usr/bin/python3
"""Draws the spectra of a `pounding spectrum` output folder: pseudo-acceleration PSA (g) and
displacement Sd (m) against period, log-scaled, one line per record, RotD50/RotD100 of a pair
dashed, and the periods of the scene's buildings (`--scene`) as vertical lines labelled with
their mode.

    tools/plot_spectrum.py out/spectrum [--out figure.png]
"""
import argparse
import io
import json
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def plot(folder, out):
    report = json.loads((folder / "spectrum.json").read_text())
    fig, (ax_a, ax_d) = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
    for number, record in enumerate(report["records"], start=1):
        periods = [o["period_s"] for o in record["ordinates"]]
        column = f" column {record['accel_column']}" if record.get("accel_column") else ""
        label = f"{number}: {Path(record['file']).name}{column} (PGA {record['peak_accel_g']:.3f} g)"
        ax_a.plot(periods, [o["psa_g"] for o in record["ordinates"]], label=label)
        ax_d.plot(periods, [o["sd_m"] for o in record["ordinates"]], label=label)
    if "rotd" in report:
        periods = [o["period_s"] for o in report["rotd"]]
        for key, style in (("rotd50", "--"), ("rotd100", ":")):
            ax_a.plot(periods, [o[f"{key}_psa_g"] for o in report["rotd"]], "k" + style, label=key.replace("rotd", "RotD"))
            ax_d.plot(periods, [o[f"{key}_sd_m"] for o in report["rotd"]], "k" + style, label=key.replace("rotd", "RotD"))
    # Every marked mode as a line; only each building's first labelled (higher modes crowd it).
    for marked in report["marked_periods"]:
        first = " T1 " in marked["label"]
        for ax in (ax_a, ax_d):
            ax.axvline(marked["period_s"], color="0.45" if first else "0.75", lw=0.9 if first else 0.6,
                       ls="-" if first else ":")
        if first:
            ax_a.annotate(marked["label"], (marked["period_s"], 0.98), xycoords=("data", "axes fraction"),
                          rotation=90, va="top", ha="right", fontsize=7, color="0.3")
    damping = 100 * report["damping_ratio"]
    ax_a.set(xscale="log", xlabel="period T (s)", ylabel="PSA (g)", title=f"Pseudo-acceleration, {damping:g} % damping")
    ax_d.set(xscale="log", yscale="log", xlabel="period T (s)", ylabel="Sd (m)", title="Relative displacement")
    for ax in (ax_a, ax_d):
        ax.grid(True, which="both", lw=0.3)
    ax_a.legend(fontsize=7)
    image = io.BytesIO()
    fig.savefig(image, dpi=110, format="png")
    write_no_follow(out, image.getvalue())
    return out


def write_no_follow(path, data):
    """Writes `data` to `path` created afresh: a file or a symbolic link already there (a shared
    results folder) is unlinked, never followed, and O_EXCL | O_NOFOLLOW refuses anything that
    reappears under the name."""
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o666)
    with os.fdopen(fd, "wb") as handle:
        handle.write(data)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", type=Path, help="output folder of `pounding spectrum`")
    parser.add_argument("--out", type=Path, help="image file (default: FOLDER/spectrum.png)")
    args = parser.parse_args()
    if not (args.folder / "spectrum.json").is_file():
        sys.exit(f"error: {args.folder}: no spectrum.json (not an output folder of `pounding spectrum`)")
    print(f"Wrote {plot(args.folder, args.out or args.folder / 'spectrum.png')}")


if __name__ == "__main__":
    main()
