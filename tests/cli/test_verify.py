#!/usr/bin/python3
"""`pounding verify` on a small manifest of the paper scene, and `pounding compare`.

    tests/cli/test_verify.py POUNDING

- blessed, the manifest passes on its own results (exit 0) and its JUnit XML validates against the
  JUnit schema (tests/data/junit/JUnit.xsd, with lxml), as does that of a failing run;
- each quantity kind fails (exit 1) with a message naming the case, the check and the difference
  when its expected value is moved beyond the tolerance: status, impact count, an impact time (by
  3 × its tolerance), an impulse, an approach speed, a peak, the first impact's rebound, the needed gap written in the
  manifest, and the two
  bounds (energy residual, overlap) tightened below the run's value;
- a case that cannot run is an error testcase, not a crash;
- a malformed manifest is refused with exit 2 naming the file, the line and the key (an unknown
  key, a missing tolerance, a scene that does not exist, TOML that does not parse);
- `pounding compare` of a run with itself reports zero differences.
"""
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from lxml import etree

ROOT = Path(__file__).resolve().parents[2]
POUNDING = sys.argv[1]
SCHEMA = etree.XMLSchema(etree.parse(str(ROOT / "tests" / "data" / "junit" / "JUnit.xsd")))
PAPER = ROOT / "examples" / "paper" / "paper.toml"
MANIFEST = f"""name = "small"
[defaults.checks]
status = true
impact_count = true
energy_residual = {{ max_relative = 1e-5 }}
interpenetration = {{ max_m = 1e-6 }}

[[case]]
name = "bdf"
scene = "{PAPER}"
settings = {{ rtol = 1e-10, atol = 1e-12 }}
[case.checks]
impact_times = {{ scaled = 100 }}
impulses = {{ rel = 1e-5 }}
peaks = {{ rel = 1e-6, abs = 1e-12 }}
rebound = {{ rel = 1e-6 }}
approach_velocity = {{ rel = 1e-6 }}

[[case]]
name = "gap"
scene = "{PAPER}"
[case.checks]
needed_gap = {{ abs_m = 1e-6 }}
[case.expected]
needed_gap_m = 0.364275
"""
failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def verify(manifest, *options):
    return subprocess.run([POUNDING, "verify", manifest, "--no-progress", "--jobs", "2", *options],
                          capture_output=True, text=True)


def junit_is_valid(folder):
    document = etree.parse(str(folder / "junit.xml"))
    return SCHEMA.validate(document), str(SCHEMA.error_log)


def failed_line(done, case, check_name):
    """The table row of case/check when it failed, else None."""
    return next((line for line in done.stdout.splitlines() if re.match(rf"{case}\s+{check_name}\s+FAIL", line)), None)


def perturbed(work, manifest, name, change):
    """Verifies a copy of the manifest whose expected results `change` edits."""
    folder = work / name
    folder.mkdir()
    copy = folder / "small.toml"
    copy.write_text(manifest.read_text())
    expected = json.loads((work / "small.expected.json").read_text())
    change(expected["cases"]["bdf"])
    (folder / "small.expected.json").write_text(json.dumps(expected))
    return verify(copy, "--out", folder / "out"), folder / "out"


def check_perturbations(work, manifest):
    blessed = json.loads((work / "small.expected.json").read_text())["cases"]["bdf"]
    first_impact = blessed["impacts"][0]["t_s"]
    tolerance = 100 * 1e-10 * first_impact
    cases = {
        "status": lambda e: e.update(status="time_limit"),
        "impact_count": lambda e: e.update(impact_count=e["impact_count"] + 1),
        "impact_times": lambda e: e["impacts"][0].update(t_s=first_impact + 3 * tolerance),
        "impulses": lambda e: e["impacts"][3].update(impulse_kNs=e["impacts"][3]["impulse_kNs"] * (1 + 1e-4)),
        "peaks": lambda e: e["peaks"].update({"B1.f7.u_m": e["peaks"]["B1.f7.u_m"] * (1 + 1e-5)}),
        "rebound": lambda e: e.update(rebound=e["rebound"] * (1 + 1e-4)),
        "approach_velocity": lambda e: e["impacts"][2].update(
            approach_velocity_mps=e["impacts"][2]["approach_velocity_mps"] * (1 + 1e-4)),
    }
    for kind, change in cases.items():
        done, out = perturbed(work, manifest, kind, change)
        line = failed_line(done, "bdf", kind)
        check(done.returncode == 1 and line is not None, f"a moved {kind} fails: {line}")
        if kind == "impact_times":
            check(line is not None and "moved by -" in line and "tolerance" in line,
                  "the impact-time failure says by how much and the tolerance")
        valid, log = junit_is_valid(out)
        check(valid, f"the failing run's JUnit XML validates ({log[:200]})")


def check_written_and_bounds(work):
    folder = work / "written"
    folder.mkdir()
    manifest = folder / "small.toml"
    manifest.write_text(MANIFEST.replace("needed_gap_m = 0.364275", "needed_gap_m = 0.37")
                        .replace("max_relative = 1e-5", "max_relative = 1e-15")
                        .replace("max_m = 1e-6", "max_m = 1e-18"))
    done = verify(manifest, "--bless", "--out", folder / "out")
    for case, kind in (("gap", "needed_gap"), ("bdf", "energy_residual"), ("bdf", "interpenetration")):
        line = failed_line(done, case, kind)
        check(done.returncode == 1 and line is not None, f"{case} {kind} out of bounds fails: {line}")


def check_error_case(work):
    folder = work / "broken"
    folder.mkdir()
    (folder / "scene.toml").write_text(PAPER.read_text().replace("mass_t = 555.0", "mass_t = -555.0")
                                       .replace('"../records/', f'"{PAPER.parent.parent}/records/'))
    manifest = folder / "m.toml"
    manifest.write_text('[[case]]\nname = "bad"\nscene = "scene.toml"\n[case.checks]\nstatus = true\n')
    done = verify(manifest, "--out", folder / "out")
    check(done.returncode == 1 and re.search(r"bad\s+run\s+ERROR .*mass_t = -555", done.stdout) is not None,
          f"a case that cannot run is an error: {done.stdout.strip()[:160]}")
    valid, log = junit_is_valid(folder / "out")
    check(valid and "<error" in (folder / "out" / "junit.xml").read_text(), f"its JUnit has an error element ({log})")


def check_refusals(work):
    base = MANIFEST.splitlines()
    bad = {
        "unknown key": ("\n".join(base).replace("settings = {", "setings = {"), "case[1].setings", ":11:"),
        "missing tolerance": ("\n".join(base).replace("impulses = { rel = 1e-5 }", "impulses = {}"),
                              "case[1].checks.impulses", ":14:"),
        "missing scene": ("\n".join(base).replace(f'scene = "{PAPER}"\nsettings', 'scene = "nowhere.toml"\nsettings'),
                          "case[1].scene", ":10:"),
        "broken TOML": ("\n".join(base).replace('name = "bdf"', 'name = "bdf'), "manifest", "not valid TOML"),
        "second case's key": ("\n".join(base).replace("needed_gap = { abs_m = 1e-6 }", "needed_gap = { abs_m = -1 }"),
                              "case[2].checks.needed_gap.abs_m", ":23:"),
        "record not a table": ("\n".join(base).replace('name = "gap"', 'name = "gap"\nrecord = "x"'),
                               "case[2].record", ":21:"),
        "expected of the wrong type": ("\n".join(base).replace("needed_gap_m = 0.364275", 'needed_gap_m = "far"'),
                                       "case[2].expected.needed_gap_m", ":25:"),
    }
    for label, (text, key, where) in bad.items():
        manifest = work / f"{label.replace(' ', '-')}.toml"
        manifest.write_text(text)
        done = verify(manifest, "--out", work / "never")
        said = done.stderr.strip()
        check(done.returncode == 2 and str(manifest) in said and key in said and where in said,
              f"{label}: exit 2 naming the file, line and key: {said}")


def check_compare(work):
    run = work / "run"
    subprocess.run([POUNDING, "run", PAPER, "--out", run, "--quiet"], capture_output=True, check=True)
    done = subprocess.run([POUNDING, "compare", run, run, "--json", work / "same.json"], capture_output=True, text=True)
    same = json.loads((work / "same.json").read_text()) if done.returncode == 0 else {}
    check(done.returncode == 0 and same.get("matched") == 45 and same.get("max_impact_time_difference_s") == 0.0,
          f"pounding compare of a run with itself: {same.get('matched')} matched, no difference")


def main():
    with tempfile.TemporaryDirectory() as folder:
        work = Path(folder)
        manifest = work / "small.toml"
        manifest.write_text(MANIFEST)
        done = verify(manifest, "--bless", "--out", work / "blessed")
        check(done.returncode == 0 and (work / "small.expected.json").is_file(),
              f"--bless writes the expected results and passes: {done.stdout.strip().splitlines()[-1:]}")
        done = verify(manifest, "--out", work / "again")
        check(done.returncode == 0 and "All checks passed" in done.stdout, "the manifest passes on its blessed results")
        valid, log = junit_is_valid(work / "again")
        check(valid, f"its JUnit XML validates against the JUnit schema ({log[:200]})")
        check((work / "again" / "verify.md").read_text().count("| pass |") >= 10, "verify.md lists the checks")
        check_perturbations(work, manifest)
        check_written_and_bounds(work)
        check_error_case(work)
        check_refusals(work)
        check_compare(work)
    print("FAILED: " + "; ".join(failures) if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
