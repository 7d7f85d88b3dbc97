#!/usr/bin/python3
"""`pounding animate` and `pounding report` on a run of the paper scene.

    tests/cli/test_animate_report.py POUNDING [CHROMIUM]

Animation (tools/animate_run.py):
- the plan it writes into the run folder is `pounding plan`'s of the same scene and gap (1e-12 m);
- its rigid placement at scale 1, applied to the history's (u, v, φ) of level 7, reproduces the
  history's own corner displacements (vtx*_dx_m, vtx*_dy_m, computed by the program) to 1e-9 m;
- with the motion and the gap both drawn × scale, the drawn striking corner lies on the drawn struck
  edge at every impact instant, within the second-order error of drawing R(sφ) for s(R(φ) - I):
  |drawn gap| <= (s² - s) Σ φ² r_max over both slabs (about 0.04 m here, where the rest gap is drawn
  as s × 0.2 m and widening nothing would leave it at -(s - 1) × 0.2 m);
- a GIF of 0.4 s at --speed 0.1 and --fps 10 has 0.4 × 10 / 0.1 + 1 = 41 frames;
- MP4: with ffmpeg a file whose first box is `ftyp`, without it --format mp4 exits 2 naming ffmpeg;
- a row (the row of three): the film shows all three buildings at the level's elevation, and with
  each pair's gap widened × scale along its direction the drawn striking corner is on the drawn
  struck edge at each impact of both pairs there, within the same bound.
Report (tools/report_run.py): report.html fetches nothing (no http(s) source, no link or external
script), its impacts table has summary.json's impact count, a run without history or impacts also
makes one; with CHROMIUM (Debian's chromium, headless) the page's own check, run by the browser
after load, reads "2 of 2 figures decoded; 45 impact rows shown" (and 1 of 1, 0 rows, for the
run without history at a 0.5 m gap). Bad input exits 2: a folder with no summary.json, a level not
in the history, a scene file changed since the run (accepted again with --scene).
"""
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import animate_run  # noqa: E402
import plot_run  # noqa: E402

POUNDING = sys.argv[1]
CHROMIUM = sys.argv[2] if len(sys.argv) > 2 else ""
SCENE = ROOT / "examples" / "paper" / "paper.toml"
failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def pounding(*arguments, expect=0):
    done = subprocess.run([POUNDING, *map(str, arguments)], capture_output=True, text=True)
    if done.returncode != expect:
        print(done.stdout, done.stderr)
    check(done.returncode == expect, f"pounding {' '.join(map(str, arguments[:2]))} ... exits {expect}")
    return done


def check_plan(run, work):
    pounding("plan", SCENE, "--out", work / "plan", "--no-plot")
    ours = json.loads((run / "plan.json").read_text())
    theirs = json.loads((work / "plan" / "plan.json").read_text())
    error = max(np.max(np.abs(np.asarray(a[key]) - np.asarray(b[key])))
                for a, b in zip(ours["buildings"], theirs["buildings"]) for key in ("slab", "centre_of_mass"))
    check(error <= 1e-12, f"the run's plan.json is pounding plan's (largest difference {error:.1e} m)")
    return ours


def check_kinematics(run, plan):
    summary, columns = plot_run.read_run(run)
    _, slabs = animate_run.level_motion(summary, columns, plan, 7)
    worst = 0.0
    for b in (1, 2):
        peaks = summary["peaks"][b - 1]
        slab = slabs[b - 1]
        for number, rest in zip(peaks["contact_vertices"], peaks["contact_vertices_rest"]):
            prefix = f"B{b}_f{slab['floor']}_vtx{number}_"
            moved = np.array([animate_run.placed([rest], slab["centre"], u, v, phi)[0]
                              for u, v, phi in zip(slab["u"], slab["v"], slab["phi"])])
            worst = max(worst, np.max(np.abs(moved - rest - np.column_stack([columns[prefix + "dx_m"],
                                                                            columns[prefix + "dy_m"]]))))
    check(worst <= 1e-9, f"placed() at scale 1 gives the history's corner displacements (largest error {worst:.1e} m)")
    return summary, columns, slabs


def drawn_gap(summary, columns, slabs, impact, scale):
    """Signed distance of the drawn striking corner from the drawn struck edge's line at the impact,
    with the gaps widened as the film widens them (a row: each pair's along its direction)."""
    drawn = {b: dict(s) for b, s in slabs.items()}
    if summary.get("pairs"):
        animate_run.widen_row_gaps(drawn, summary["pairs"], scale)
    else:
        animate_run.widen_gap(drawn, summary["gap_m"], scale)
    row = int(np.argmin(np.abs(columns["t_s"] - impact["t_s"])))
    candidate = next(c for c in summary["candidates"] if c["level"] == impact["level"]
                     and c["striking_building"] == impact["striking_building"] and c["vertex"] == impact["vertex"]
                     and c["struck_building"] == impact.get("struck_building", c["struck_building"]))

    def place(b, point):
        slab = drawn[b - 1]
        return animate_run.placed([np.asarray(point) + slab["shift"]], slab["centre"], slab["u"][row],
                                  slab["v"][row], slab["phi"][row], scale)[0]
    corner = place(candidate["striking_building"], candidate["vertex_rest"])
    q1, q2 = (place(candidate["struck_building"], p) for p in candidate["edge_rest"])
    along = (q2 - q1) / np.linalg.norm(q2 - q1)
    # Drawing R(sφ) where the motion is s(R(φ) - I) misplaces a point at arm r by (s² - s) φ² r / 2 to
    # second order; twice that over both slabs bounds the drawn gap of slabs that really touch.
    bound = sum((scale**2 - scale) * s["phi"][row] ** 2 * np.max(np.linalg.norm(s["outline"] - s["centre"], axis=1))
                for s in drawn.values())
    return float(np.cross(along, corner - q1)), bound


def check_animation(run, summary, columns, slabs):
    scale = animate_run.default_scale(slabs)
    gaps = [drawn_gap(summary, columns, slabs, i, scale) for i in summary["impacts"] if i["level"] == 7]
    worst = max(abs(g) / bound for g, bound in gaps)
    check(worst <= 1.0, f"drawn × {scale:g}, the striking corner is on the struck edge at each of the {len(gaps)} "
                        f"impacts of level 7 within the second-order bound (largest |drawn gap| "
                        f"{max(abs(g) for g, _ in gaps):.3f} m, {worst:.2f} of its bound; unwidened it would be "
                        f"{-(scale - 1) * summary['gap_m']:.2f} m)")
    done = pounding("animate", run, "--start", 5.6, "--end", 6.0, "--speed", 0.1, "--fps", 10, "--format", "gif")
    film = run / "level7.gif"
    from PIL import Image
    frames = Image.open(film).n_frames if film.is_file() else 0
    check(frames == 41, f"the GIF has 41 frames ({frames}); says: {done.stdout.strip()}")
    if shutil.which("ffmpeg"):
        pounding("animate", run, "--start", 5.6, "--end", 5.8, "--format", "mp4", "--out", run / "film.mp4")
        head = (run / "film.mp4").read_bytes()[:12] if (run / "film.mp4").is_file() else b""
        check(head[4:8] == b"ftyp", "with ffmpeg, --format mp4 writes an MP4 (ftyp box first)")
    else:
        done = pounding("animate", run, "--format", "mp4", expect=2)
        check("ffmpeg" in done.stderr, f"without ffmpeg, --format mp4 is refused naming it: {done.stderr.strip()}")


def check_report(run, impacts, figures):
    page = (run / "report.html").read_text()
    external = re.findall(r'(?:src|href)="(?:https?:)?//[^"]*"|<link\b|<script\s+src', page)
    check(not external, f"{run.name}/report.html fetches nothing ({external[:3]})")
    body = page.split('id="impacts"')[1].split("</table>")[0].split("<tbody>")[1]
    rows = len(re.findall(r"<tr>", body))
    check(rows == impacts, f"{run.name}: the impacts table has {impacts} rows ({rows})")
    if not CHROMIUM:
        return
    dom = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom",
                          (run / "report.html").resolve().as_uri()], capture_output=True, text=True, timeout=120).stdout
    said = re.search(r'id="render-check"[^>]*>([^<]*)<', dom)
    wanted = f"{figures} of {figures} figures decoded; {impacts} impact rows shown."
    check(bool(said) and said.group(1) == f"Rendered: {wanted}",
          f"{run.name}: headless Chromium runs the page's check: {said.group(1) if said else 'no render check'}")


def check_row_film(work):
    """A row's film: every building at the level's elevation, each pair's gap widened along its
    direction, so that the drawn striking corner is on the drawn struck edge at each impact there."""
    scene = work / "row-of-three.toml"
    scene.write_text((ROOT / "examples" / "rows" / "row-of-three.toml").read_text()
                     .replace('"../records/', f'"{ROOT}/examples/records/'))
    run = work / "row"
    pounding("run", scene, "--out", run)
    pounding("plan", scene, "--out", work / "row-plan", "--no-plot")
    summary, columns = plot_run.read_run(run)
    plan = json.loads((work / "row-plan" / "plan.json").read_text())
    # The highest elevation where both pairs have a level (B3 has fewer storeys than B1 and B2).
    elevations = [e["elevation_m"] for e in summary["levels"]]
    level = max((e for e in summary["levels"] if elevations.count(e["elevation_m"]) == 2),
                key=lambda e: e["elevation_m"])["level"]
    levels, slabs = animate_run.level_motion(summary, columns, plan, level)
    check(sorted(slabs) == [0, 1, 2] and len(levels) == 2,
          f"the row's film at level {level} shows buildings {sorted(slabs)} on levels {levels}")
    scale = animate_run.default_scale(slabs)
    gaps = [drawn_gap(summary, columns, slabs, i, scale) for i in summary["impacts"] if i["level"] in levels]
    worst = max((abs(g) / bound for g, bound in gaps), default=0.0)
    check(gaps and worst <= 1.0, f"row drawn × {scale:g}: the striking corner is on the struck edge at each of the "
                                 f"{len(gaps)} impacts at level {level}'s elevation, both pairs, within the bound "
                                 f"({worst:.2f} of it)")
    done = pounding("animate", run, "--level", level, "--start", 4.0, "--end", 7.0, "--fps", 5, "--format", "gif")
    from PIL import Image
    film = run / f"level{level}.gif"
    frames = Image.open(film).n_frames if film.is_file() else 0
    check(frames == 16, f"the row's GIF has 3 s x 5 fps + 1 = 16 frames ({frames}); says: {done.stdout.strip()}")


def check_refusals(run, work):
    done = pounding("animate", work, expect=2)
    check("summary.json" in done.stderr, f"a folder without a run is refused: {done.stderr.strip()}")
    done = pounding("animate", run, "--level", 9, expect=2)
    check("history.csv holds levels" in done.stderr, f"a level not in the history is refused: {done.stderr.strip()}")
    copy = work / "scene.toml"
    copy.write_text(SCENE.read_text().replace('"../records/', f'"{ROOT}/examples/records/'))
    pounding("run", copy, "--out", work / "copy", "--history", "off")
    copy.write_text(copy.read_text() + "\n# edited after the run\n")
    done = pounding("report", work / "copy", expect=2)
    check("scene_sha256" in done.stderr, f"a scene changed since the run is refused: {done.stderr.strip()}")
    pounding("report", work / "copy", "--scene", copy)


def main():
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        run, quiet = work / "run", work / "quiet"
        pounding("run", SCENE, "--out", run)
        pounding("run", SCENE, "--gap", 0.5, "--history", "off", "--out", quiet)
        pounding("report", run)  # writes the run's plan.json too
        pounding("report", quiet)
        plan = check_plan(run, work)
        summary, columns, slabs = check_kinematics(run, plan)
        check_animation(run, summary, columns, slabs)
        check_report(run, summary["impact_count"], 2)
        check_report(quiet, 0, 1)
        check_refusals(run, work)
        check_row_film(work)
    if not CHROMIUM:
        print("note: no Chromium given: the page was not opened in a browser")
    print("FAILED: " + "; ".join(failures) if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
