"""pounding.sweep: a sweep on a 2-worker LocalCluster gives the serial sweep's table, each row
is the run and the needed gap the module gives alone, an interrupted sweep resumes without
redoing runs, a failed run is a row, a bad sweep file names file, key and value, and the CLI's
`pounding sweep` runs it. CTest runs this file as `python_sweep` (PYTHONPATH at the build's module
folder, POUNDING_CLI at the program); by hand:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python/test_sweep.py
Tiny sweeps (2 records × 2 gaps of the paper scene under 6 s synthetic records) keep it short.
"""

import csv
import hashlib
import json
import math
import os
import pathlib
import signal
import subprocess
import time

import numpy as np
import pytest

import pounding
from pounding import sweep as sweeps

SOURCE = pathlib.Path(os.environ.get("POUNDING_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("POUNDING_CLI", str(SOURCE / "build" / "apps" / "pounding"))
PAPER = SOURCE / "examples" / "paper" / "paper.toml"
TIMINGS = set(sweeps.TIMINGS)
# The needed gaps of the two records (the scene scales both to its 0.32 g) lie between the two
# gaps: 0.44 and 0.62 m, found by the module (test_rows_are_the_module_s_runs checks them).
GAPS_M = (0.3, 0.5)


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """Two 6 s records (one column of g every 0.02 s: windowed sines of 0.8 and 1.1 s) and the
    sweep of the paper scene under them at GAPS_M, with the needed gap."""
    folder = tmp_path_factory.mktemp("sweep")
    t_s = np.arange(0.0, 6.0, 0.02)
    for name, period_s in (("pulse_a.txt", 0.8), ("pulse_b.txt", 1.1)):
        np.savetxt(folder / name, 0.3 * np.sin(2 * np.pi * t_s / period_s) * np.sin(np.pi * t_s / 6.0) ** 2)
    write_sweep(folder / "sweep.toml")
    return folder


def write_sweep(path, records=None, extra=""):
    records = records or ['{file = "pulse_a.txt", format = "single", units = "g", dt_s = 0.02}',
                          '{file = "pulse_b.txt", format = "single", units = "g", dt_s = 0.02}']
    path.write_text(f'scenes = ["{PAPER}"]\nrecords = [{", ".join(records)}]\n'
                    f"gaps_m = [{GAPS_M[0]}, {GAPS_M[1]}]\nneeded_gap = true\n{extra}")
    return path


def without_timings(rows):
    """The rows sorted by their parameters, every column but the timings."""
    key = [*sweeps.PARAMETERS]
    return sorted(({k: v for k, v in row.items() if k not in TIMINGS} for row in rows),
                  key=lambda row: [row[k] for k in key])


@pytest.fixture(scope="module")
def serial(folder):
    return pounding.sweep(folder / "sweep.toml", out=folder / "serial", workers=0, progress=False)


def test_two_workers_give_the_serial_table(folder, serial):
    assert serial.executed == 4 and serial.skipped == 0 and not serial.interrupted
    distributed = pounding.sweep(folder / "sweep.toml", out=folder / "two", workers=2, progress=False)
    assert distributed.executed == 4
    assert without_timings(distributed.rows) == without_timings(serial.rows)
    assert list(distributed.rows[0]) == list(serial.rows[0])  # the same columns in the same order
    provenance = json.loads((folder / "two" / "sweep.json").read_text())
    assert provenance["cluster"].startswith("LocalCluster(2 workers")
    assert provenance["sweep_sha256"] == hashlib.sha256((folder / "sweep.toml").read_bytes()).hexdigest()
    assert provenance["complete"] and provenance["rows"] == 4
    assert provenance["provenance"]["program_version"] == pounding.__version__


def test_rows_are_the_module_s_runs(folder, serial):
    """Each row holds what the module's run and needed_gap give for that scene alone (floats bit for
    bit through the CSV), and the needed gap divides the gaps that pound from those that do not."""
    scene = pounding.load_scene(PAPER)
    pounded = set()
    for row in serial.rows:
        record = scene.with_record(folder / row["record"], format="single", units="g", dt_s=0.02)
        gap = pounding.needed_gap(record)
        assert float(row["needed_gap_m"]).hex() == gap.needed_gap_m.hex()
        assert int(row["needed_gap_level"]) == gap.level and row["needed_gap_status"] == "completed"

        result = pounding.run(record.with_gap(float(row["gap_m"])))
        assert row["status"] == result.status == "completed"
        assert int(row["impact_count"]) == len(result.impacts)
        impulse = max((abs(i["impulse_kNs"]) for i in result.impacts), default=0.0)
        assert float(row["max_impulse_kNs"]).hex() == impulse.hex()
        top_u = max(abs(f["u_m"]["value"]) for f in result.peaks[1]["floors"])
        assert float(row["b2_peak_u_m"]).hex() == top_u.hex()
        assert float(row["solver_time_s"]) > 0 and float(row["wall_time_s"]) >= float(row["solver_time_s"])
        # No contact beyond the needed gap; impacts below it (these gaps are far from it).
        assert (int(row["impact_count"]) > 0) == (float(row["gap_m"]) < gap.needed_gap_m)
        if int(row["impact_count"]):
            pounded.add((row["record"], row["gap_m"]))
    assert 0 < len(pounded) < 4, "the sweep should hold runs with and without pounding"


def test_rows_are_typed(folder, serial):
    """Rows hold numbers as numbers (read back bit for bit from the CSV's text), names as text;
    frame() is the same table in pandas."""
    with open(folder / "serial" / "sweep.csv", newline="") as f:
        text_rows = list(csv.DictReader(f))
    for row, text in zip(serial.rows, text_rows):
        assert isinstance(row["record"], str) and isinstance(row["method"], str)
        assert isinstance(row["impact_count"], int) and row["impact_count"] == int(text["impact_count"])
        for column in ("gap_m", "restitution", "needed_gap_m", "b1_peak_u_m", "wall_time_s"):
            assert isinstance(row[column], float) and repr(row[column]) == text[column], column
        assert row["needed_gap_level"] == int(text["needed_gap_level"])
    pandas = pytest.importorskip("pandas")
    frame = serial.frame()
    assert list(frame.columns) == list(text_rows[0]) and len(frame) == len(text_rows)
    assert frame["impact_count"].tolist() == [row["impact_count"] for row in serial.rows]
    assert pandas.api.types.is_float_dtype(frame["gap_m"])


def test_interrupted_sweep_resumes_without_redoing_runs(folder, serial):
    out = folder / "resumed"
    first = pounding.sweep(folder / "sweep.toml", out=out, workers=0, progress=False, max_runs=1)
    assert (first.executed, len(first.rows), first.interrupted) == (1, 1, True)
    second = pounding.sweep(folder / "sweep.toml", out=out, workers=2, progress=False)
    assert (second.executed, second.skipped, second.interrupted) == (3, 1, False)
    assert without_timings(second.rows) == without_timings(serial.rows)

    # A process killed while writing leaves a row cut short: it is dropped and run again.
    table = (out / "sweep.csv").read_text()
    last = table.rstrip("\n").rfind("\n")
    (out / "sweep.csv").write_text(table[: last + 1] + table[last + 1: last + 40])
    third = pounding.sweep(folder / "sweep.toml", out=out, workers=0, progress=False)
    assert (third.executed, third.skipped, third.interrupted) == (1, 3, False)
    assert without_timings(third.rows) == without_timings(serial.rows)
    fourth = pounding.sweep(folder / "sweep.toml", out=out, workers=0, progress=False)
    assert (fourth.executed, fourth.skipped, len(fourth.rows)) == (0, 4, 4)


def test_a_failed_run_is_a_row(folder):
    """A record that exists but cannot be read fails its runs and its needed gap: rows with the
    reader's message; the other record's runs complete."""
    (folder / "broken.AT2").write_text("not a PEER record\n")
    path = write_sweep(folder / "broken.toml",
                       ['{file = "pulse_a.txt", format = "single", units = "g", dt_s = 0.02}', '"broken.AT2"'])
    result = pounding.sweep(path, out=folder / "broken", workers=0, progress=False)
    assert len(result.rows) == 4 and not result.interrupted
    failed = [row for row in result.rows if row["record"] == "broken.AT2"]
    assert len(failed) == 2 and result.failed == 2
    for row in failed:
        assert row["status"] == "failed" and "broken.AT2" in row["message"] and "PEER" in row["message"]
        assert row["impact_count"] is None and row["needed_gap_m"] is None
        assert row["needed_gap_status"].startswith("failed: ") and "broken.AT2" in row["needed_gap_status"]
    assert all(row["status"] == "completed" for row in result.rows if row["record"] == "pulse_a.txt")


@pytest.mark.parametrize("text, key, value, reason", [
    ("gap_m = [0.1]", "gap_m", "[0.1]", "unknown key"),
    ('scenes = ["missing.toml"]', "scenes[1]", '"missing.toml"', "no such file"),
    (f'scenes = ["{PAPER}", "{PAPER.parent}/../paper/paper.toml"]', "scenes[2]", "../paper/paper.toml", "given twice"),
    ("gaps_m = [0.1, 20.0]", "gaps_m[2]", "20.0", "must lie in [0, 10] m (scene"),
    ('gaps_m = [0.1, "wide"]', "gaps_m[2]", '"wide"', "expected a number"),
    ("restitutions = [1.5]", "restitutions[1]", "1.5", "must lie in [0, 1]"),
    ('methods = [{name = "hht", rtol = 1e-6}]', "methods[1].rtol", "1e-06", "does not apply to method hht"),
    ('methods = [{name = "cvode-bdf", rtoll = 1e-6}]', "methods[1].rtoll", "1e-06", "unknown field"),
    ('methods = ["rk4"]', "methods[1].name", '"rk4"', "expected"),
    ('methods = ["hht"]\ncontact_laws = ["kelvin"]', "methods[1]", '"hht"', "(contact_laws[1], scene"),
    ('contact_laws = [{name = "kelvin", stiffness_kN_per_m = -1.0}]', "contact_laws[1].stiffness_kN_per_m", "-1",
     "must lie in"),
    ('contact_laws = [{name = "hertzdamp", stiffness_kN_per_m = 1e7}]', "contact_laws[1].stiffness_kN_per_m", "10000000.0",
     "not a stiffness of hertzdamp (its key is stiffness_kN_per_m1_5)"),
    ('records = ["pulse_a.txt", {file = "pulse_b.txt", units = "furlongs"}]', "records[2].units", "furlongs",
     "expected"),
    ('records = ["nowhere.AT2"]', "records[1].file", "", "no such"),
    ('records = "nowhere.txt"', "records", '"nowhere.txt"', "no such record list or folder"),
    ("needed_gap = 1", "needed_gap", "1", "expected true or false"),
    ("max_wall_time_s = inf", "max_wall_time_s", "inf", "expected a finite number of seconds"),
    ('records = ["pulse_a.txt", {file = "pulse_a.txt"}]', "records[2]", "pulse_a.txt", "a record is given twice"),
    ("directions_deg = [0, 400]", "directions_deg[2]", "400", "[-360, 360]"),
    ("directions_deg = [30, 30]", "directions_deg", "30", "given twice"),
    ('records = [{file = "pulse_a.txt", record2 = "nowhere.txt"}]', "records[1].record2", "nowhere.txt", "no such"),
    # The scaling fields under the scene's names, the short ones aliases: errors spell them as given.
    ('records = [{file = "pulse_a.txt", scale_to_pga_g = -1.0}]', "records[1].scale_to_pga_g", "-1", "must lie in"),
    ('records = [{file = "pulse_a.txt", pga_g = 0.3, scale_to_pga_g = 0.2}]', "records[1].scale_to_pga_g", "0.2",
     "given twice (also as pga_g)"),
    ('records = [{file = "pulse_a.txt", pga_g = "x"}]', "records[1].pga_g", "x", "expected a number"),
])
def test_bad_sweep_file_names_file_key_and_value(folder, tmp_path, text, key, value, reason):
    path = folder / "bad.toml"
    lines = {"scenes": f'scenes = ["{PAPER}"]', "records": 'records = ["pulse_a.txt"]'}
    lines.update({line.split(" = ")[0]: line for line in text.split("\n")})  # the case's lines replace these
    path.write_text("\n".join(lines.values()) + "\n")
    with pytest.raises(pounding.InputError) as raised:
        pounding.sweep(path, out=tmp_path / "never", workers=0, progress=False)
    error = raised.value
    assert (error.file, error.key) == (str(path), key), str(error)
    assert value in error.value and reason in error.reason, str(error)
    assert str(error).startswith(f"{path}: {key}") and not (tmp_path / "never").exists()


def test_a_bad_line_of_a_record_list_names_the_line(folder):
    (folder / "set.txt").write_text("pulse_a.txt format=single units=g dt_s=0.02\npulse_b.txt dt_s=fast\n")
    path = folder / "list.toml"
    path.write_text(f'scenes = ["{PAPER}"]\nrecords = "set.txt"\n')
    with pytest.raises(pounding.InputError) as raised:
        pounding.sweep(path, out=folder / "never", workers=0, progress=False)
    assert not (folder / "never").exists()
    assert raised.value.file == f"{folder / 'set.txt'}:2" and raised.value.key == "dt_s"
    assert raised.value.value == "fast"


def test_cli_runs_the_sweep_and_refuses_a_bad_file(folder, serial):
    done = subprocess.run([CLI, "sweep", folder / "sweep.toml", "--workers", "2", "--no-progress", "--out",
                           folder / "cli"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "4 rows in" in done.stdout
    assert without_timings(sweeps.read_table(folder / "cli" / "sweep.csv")) == without_timings(serial.rows)

    (folder / "typo.toml").write_text(f'scenes = ["{PAPER}"]\ngaps = [0.1]\n')
    with pytest.raises(pounding.InputError) as raised:
        pounding.sweep(folder / "typo.toml", workers=0, progress=False)
    done = subprocess.run([CLI, "sweep", folder / "typo.toml", "--serial"], capture_output=True, text=True)
    assert done.returncode == 2 and done.stderr == f"error: {raised.value}\n"


def test_front_end_errors_are_messages_not_tracebacks(folder, tmp_path):
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    for arguments, status, words in ((["--scheduler", "garbage"], 2, "--scheduler = \"garbage\": expected an address"),
                                     (["--scheduler", ""], 2, "--scheduler: an empty value is not allowed"),
                                     # nothing listens on port 1: exit 3 after the bounded wait (10 s)
                                     (["--scheduler", "tcp://127.0.0.1:1"], 2, "no Dask scheduler answered within"),
                                     (["--serial", "--out", str(a_file)], 2, "cannot create this folder")):
        done = subprocess.run([CLI, "sweep", folder / "sweep.toml", "--no-progress"] + arguments,
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == status and words in done.stderr, (arguments, done.returncode, done.stderr)
        assert "Traceback" not in done.stderr, done.stderr


def test_ctrl_c_stops_a_cluster_sweep_without_worker_tracebacks(tmp_path):
    # Ctrl-C signals the whole process group; the Dask workers each printed a KeyboardInterrupt
    # traceback. 200 runs keep the sweep going when the signal comes, after its first rows.
    gaps = ", ".join(f"{0.05 + 0.001 * i:.3f}" for i in range(200))
    (tmp_path / "long.toml").write_text(f'scenes = ["{PAPER}"]\ngaps_m = [{gaps}]\nmethods = ["exact"]\n')
    table = tmp_path / "out" / "sweep.csv"
    sweep = subprocess.Popen([CLI, "sweep", tmp_path / "long.toml", "--workers", "2", "--no-progress", "--out",
                              tmp_path / "out"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             start_new_session=True)
    deadline = time.monotonic() + 120
    while sweep.poll() is None and time.monotonic() < deadline:
        if table.exists() and table.read_text().count("\n") >= 3:
            break
        time.sleep(0.1)
    assert sweep.poll() is None, "the sweep ended before the signal: nothing checked"
    os.killpg(sweep.pid, signal.SIGINT)
    out, err = sweep.communicate(timeout=120)
    assert sweep.returncode == 3 and "interrupted" in err, (sweep.returncode, err)
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err


def test_a_worker_without_the_module_is_named_without_tracebacks(tmp_path):
    # A worker started without this build's module on PYTHONPATH: the sweep exits 2 naming the
    # worker and the PYTHONPATH to use, and the worker's own log holds no traceback (the probe
    # travels as code, so the worker has nothing of pounding to unpickle).
    environment = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    address_file = tmp_path / "scheduler.json"
    scheduler = subprocess.Popen(["/usr/bin/dask-scheduler", "--scheduler-file", address_file, "--port", "0",
                                  "--dashboard-address", ":0"], cwd=tmp_path, env=environment,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker_log = (tmp_path / "worker.log").open("w")
    worker = None
    try:
        deadline = time.monotonic() + 60
        while not address_file.exists() and time.monotonic() < deadline:
            time.sleep(0.1)
        worker = subprocess.Popen(["/usr/bin/dask-worker", "--scheduler-file", address_file, "--nthreads", "1",
                                   "--nworkers", "1", "--no-dashboard"], cwd=tmp_path, env=environment,
                                  stdout=worker_log, stderr=subprocess.STDOUT)
        address = json.loads(address_file.read_text())["address"]
        while time.monotonic() < deadline and "Registered to" not in (tmp_path / "worker.log").read_text():
            time.sleep(0.1)
        (tmp_path / "s.toml").write_text(f'scenes = ["{PAPER}"]\ngaps_m = [0.2]\n')
        done = subprocess.run([CLI, "sweep", tmp_path / "s.toml", "--scheduler", address, "--out", tmp_path / "out"],
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 2, done.stderr
        assert "cannot import pounding (ModuleNotFoundError" in done.stderr, done.stderr
        named = done.stderr.split("PYTHONPATH=")[1].split(" ")[0]  # the submitting program's module folder
        assert (pathlib.Path(named) / "pounding" / "sweep" / "__init__.py").is_file(), done.stderr
    finally:
        for process in (worker, scheduler):
            if process is not None:
                process.terminate()
                process.wait(timeout=60)
        worker_log.close()
    assert "Traceback" not in (tmp_path / "worker.log").read_text()


def test_plot_sweep_fits_the_needed_gaps(folder, serial):
    """tools/plot_sweep.py on the serial table: its lognormal fit of two needed gaps g1, g2 has the
    closed form median √(g1·g2) and 84th percentile exp(m + s), s = |ln g1 − ln g2| / √2."""
    figure = folder / "sweep.png"
    done = subprocess.run(["/usr/bin/python3", SOURCE / "tools" / "plot_sweep.py", folder / "serial", "--out", figure],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert figure.stat().st_size > 10_000
    fits = json.loads((folder / "serial" / "sweep_fit.json").read_text())
    assert len(fits) == 1 and fits[0]["records"] == 2  # one panel: only the record and the gap vary
    g1, g2 = sorted({float(row["needed_gap_m"]) for row in serial.rows})
    fit = fits[0]["fit"]
    assert fit["median_lognormal_m"] == pytest.approx(math.sqrt(g1 * g2), rel=1e-14)
    s = abs(math.log(g1) - math.log(g2)) / math.sqrt(2)
    assert fit["p84_lognormal_m"] == pytest.approx(math.sqrt(g1 * g2) * math.exp(s), rel=1e-14)
    assert fit["median_m"] == pytest.approx((g1 + g2) / 2, rel=1e-15)
    assert f"median {fit['median_lognormal_m']:.4f} m" in done.stdout


def test_yielding_scenes_add_their_columns(folder, serial, tmp_path):
    """A sweep over a scene whose columns yield writes each building's largest storey ductility,
    the hysteretic energy and the branch changes, as the run itself reports them; an elastic
    sweep has none of these columns."""
    assert not set(sweeps.YIELDING) & set(serial.rows[0])
    yielding = SOURCE / "examples" / "paper" / "paper-yielding.toml"
    path = tmp_path / "sweep.toml"
    path.write_text(f'scenes = ["{yielding}"]\ngaps_m = [0.05]\n')
    result = pounding.sweep(path, out=tmp_path / "out", workers=0, progress=False)
    row = result.rows[0]
    run = pounding.run(pounding.load_scene(yielding, gap=0.05))
    storeys = {b["building"]: b["storeys"] for b in run.yielding["buildings"]}
    for b in (1, 2):
        assert row[f"b{b}_max_ductility"] == max(max(s["peak_ductility_x"], s["peak_ductility_y"]) for s in storeys[b])
    assert row["hysteretic_kJ"] == run.energy["hysteretic_kJ"]
    assert row["yield_events"] == run.yielding["yield_events"] > 0


def test_slab_to_column_scenes_add_their_columns(serial, tmp_path):
    """A sweep over a scene whose slabs strike columns writes how many impacts did and the largest
    column shear, as the run's impacts give them; without a capacity the ratio is empty."""
    assert not set(sweeps.SLAB_TO_COLUMN) & set(serial.rows[0])
    scene = SOURCE / "examples" / "levels" / "ground-storey-columns.toml"
    path = tmp_path / "sweep.toml"
    path.write_text(f'scenes = ["{scene}"]\ngaps_m = [0.2]\n')
    row = pounding.sweep(path, out=tmp_path / "out", workers=0, progress=False).rows[0]
    run = pounding.run(pounding.load_scene(scene))
    assert row["slab_to_column_impact_count"] == run.summary["impacts_slab_to_column"] == len(run.impacts) > 0
    assert row["max_column_shear_kN"] == max(i["column_shear_kN"] for i in run.impacts)
    assert row["max_column_shear_ratio"] is None
    assert row["max_column_total_shear_kN"] == max(i["column_total_shear_kN"] for i in run.impacts) > 0
    assert row["max_column_total_shear_ratio"] is None


def test_a_contact_free_reference_adds_the_pounding_induced_drifts(serial, tmp_path):
    """A sweep over a scene that asks for the run without contact ([output] contact_free_reference)
    completes (it used to fail every row: the sweep's runs kept no drift peaks) and writes each
    building's largest storey drift ratio with and without contact, as the run's summary gives them."""
    assert not set(sweeps.POUNDING_DEMAND) & set(serial.rows[0])
    text = PAPER.read_text().replace("[contact]", "[output]\ncontact_free_reference = true\n\n[contact]")
    scene = tmp_path / "paper-reference.toml"
    scene.write_text(text.replace('"../records/', f'"{SOURCE / "examples" / "records"}/'))
    path = tmp_path / "sweep.toml"
    path.write_text(f'scenes = ["{scene}"]\ngaps_m = [0.2]\n')
    result = pounding.sweep(path, out=tmp_path / "out", workers=0, progress=False)
    row = result.rows[0]
    assert row["status"] == "completed" and result.failed == 0
    demand = pounding.run(pounding.load_scene(scene)).summary["pounding_demand"]["buildings"]
    for b, building in zip((1, 2), demand):
        for suffix, side in (("", "with"), ("_no_contact", "without")):
            expected = max(max(s["drift_x"][side], s["drift_y"][side]) for s in building["storeys"])
            assert row[f"b{b}_max_drift_ratio{suffix}"] == pytest.approx(expected, rel=1e-12)
    assert row["b2_max_drift_ratio"] != row["b2_max_drift_ratio_no_contact"]  # the pair pounds at 0.2 m


def test_directions_cross_the_records(folder, tmp_path):
    """directions_deg crosses every record with every angle: each row is the run, and its needed gap
    the needed gap, of the scene turned to that angle (Scene.with_direction, as --direction-deg)."""
    path = write_sweep(folder / "turned.toml", records=['{file = "pulse_a.txt", format = "single", units = "g", '
                                                       'dt_s = 0.02}'], extra="directions_deg = [0, 60]\n")
    result = pounding.sweep(path, out=tmp_path / "turned", workers=0, progress=False)
    assert result.executed == 4
    columns = list(result.rows[0])
    assert columns[columns.index("record_source") + 1] == "direction_deg"
    scene = pounding.load_scene(PAPER).with_record(folder / "pulse_a.txt", format="single", units="g", dt_s=0.02)
    for row in result.rows:
        turned = scene.with_direction(row["direction_deg"]).with_gap(row["gap_m"])
        run = pounding.run(turned.with_outputs(history=False))
        assert row["impact_count"] == len(run.impacts)
        assert row["needed_gap_m"] == pounding.needed_gap(scene.with_direction(row["direction_deg"])).needed_gap_m
    assert {row["direction_deg"] for row in result.rows} == {0.0, 60.0}
    # without directions_deg the table keeps its columns (the module's own sweep above)
    assert "direction_deg" not in sweeps.PARAMETERS


def test_needed_gap_over_every_angle_in_a_sweep(folder, tmp_path):
    """needed_gap = "all_angles" adds the worst angle's needed gap and angle to each row, as
    needed_gap(scene, all_angles=True) finds them; other sweeps keep their columns."""
    path = folder / "angles.toml"
    path.write_text(f'scenes = ["{PAPER}"]\nrecords = [{{file = "pulse_a.txt", format = "single", units = "g", '
                    'dt_s = 0.02}]\nneeded_gap = "all_angles"\n')
    result = pounding.sweep(path, out=tmp_path / "angles", workers=0, progress=False)
    row = result.rows[0]
    scene = pounding.load_scene(PAPER).with_record(folder / "pulse_a.txt", format="single", units="g", dt_s=0.02)
    expected = pounding.needed_gap(scene, all_angles=True).all_angles
    assert row["all_angles_needed_gap_m"] == expected["needed_gap_m"]
    assert row["all_angles_angle_deg"] == expected["angle_deg"]
    assert row["all_angles_needed_gap_m"] >= row["needed_gap_m"]
    assert not set(sweeps.ALL_ANGLES) & set(pounding.sweep(folder / "sweep.toml", out=tmp_path / "plain", workers=0,
                                                           progress=False).rows[0])
