"""`import pounding` against the command line: the same scene run both ways gives the same
documents bit for bit, bad input the same messages. CTest runs this file with the interpreter of a
virtual environment the package is pip-installed in (POUNDING_INSTALLED_IN names it) and
POUNDING_CLI at the program; by hand, against the build's module folder:
    PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python
"""

import csv
import json
import os
import pathlib
import pickle
import subprocess
import threading
import time

import numpy as np
import pytest

import pounding

SOURCE = pathlib.Path(os.environ.get("POUNDING_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("POUNDING_CLI", str(SOURCE / "build" / "apps" / "pounding"))
PAPER = SOURCE / "examples" / "paper" / "paper.toml"
RECORD = SOURCE / "examples" / "records" / "elcentro1940_ns_peer_RSN6.AT2"

# Fields that differ between two runs of the same scene and settings, and why:
#   provenance.command_line  the module has no command line (null), the CLI writes its own
#   provenance.date_utc      when each run started
#   statistics.wall_time_s   each run's measured run time
#   wall_time_s (gap.json)   the same, for the needed-gap run
# The rest of provenance is compared: the program and the module must come from one build
# (git_commit ends in -dirty for a build from edited sources).
NOT_REPRODUCIBLE = {("provenance", "command_line"), ("provenance", "date_utc"), ("statistics", "wall_time_s"),
                    ("wall_time_s",)}



@pytest.mark.skipif("POUNDING_INSTALLED_IN" not in os.environ, reason="run against the build's module folder")
def test_imported_from_the_installed_package():
    """CTest's runs test the package pip installed, not the source or build tree."""
    where = pathlib.Path(pounding.__file__).resolve()
    assert pathlib.Path(os.environ["POUNDING_INSTALLED_IN"]).resolve() in where.parents, where
    assert not os.environ.get("PYTHONPATH")


def assert_same(a, b, path=()):
    """Equal JSON documents: the same keys in the same order, floats equal bit for bit (float.hex,
    which also tells -0.0 from 0.0), except the NOT_REPRODUCIBLE paths."""
    if path in NOT_REPRODUCIBLE:
        return
    where = ".".join(map(str, path)) or "document"
    assert type(a) is type(b), f"{where}: {a!r} vs {b!r}"
    if isinstance(a, dict):
        assert list(a) == list(b), f"{where}: keys {list(a)} vs {list(b)}"
        for key in a:
            assert_same(a[key], b[key], path + (key,))
    elif isinstance(a, list):
        assert len(a) == len(b), f"{where}: {len(a)} vs {len(b)} entries"
        for index, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, path + (index,))
    elif isinstance(a, float):
        assert a.hex() == b.hex(), f"{where}: {a!r} vs {b!r}"
    else:
        assert a == b, f"{where}: {a!r} vs {b!r}"


def cli(*arguments, expect=0):
    done = subprocess.run([CLI, *map(str, arguments)], capture_output=True, text=True)
    assert done.returncode == expect, f"pounding {' '.join(map(str, arguments))}: exit {done.returncode}\n{done.stderr}"
    return done


def cli_run(folder, *arguments):
    cli("run", *arguments, "--out", folder)
    return json.loads((folder / "summary.json").read_text())


def bits(array):
    return np.ascontiguousarray(array, dtype=np.float64).view(np.uint64)


@pytest.fixture(scope="module")
def paper_pair(tmp_path_factory):
    """The paper scene run by the CLI (its folder) and by the module."""
    folder = tmp_path_factory.mktemp("paper")
    cli_run(folder, PAPER)
    return folder, pounding.run(pounding.load_scene(PAPER))


def test_run_matches_cli_summary(paper_pair):
    folder, result = paper_pair
    expected = json.loads((folder / "summary.json").read_text())
    assert result.summary["impact_count"] > 0  # the comparison covers impacts, not an empty list
    assert_same(result.summary, expected)
    assert result.summary["provenance"]["command_line"] is None
    assert result.status == expected["status"] == "completed"
    assert result.impacts == expected["impacts"] and result.peaks == expected["peaks"]
    assert result.brief().startswith(f"paper: cvode-bdf, completed, {len(result.impacts)} impacts")
    assert result.report().count("\n") > 10


def test_arrays_match_cli_csv(paper_pair):
    folder, result = paper_pair
    with open(folder / "history.csv") as f:
        rows = list(csv.reader(f))
    assert list(result.history) == rows[0]
    table = np.array([[float(x) for x in row] for row in rows[1:]])
    for c, name in enumerate(rows[0]):
        assert np.array_equal(bits(result.history[name]), bits(table[:, c])), name
    assert result.time_s is result.history["t_s"]

    with open(folder / "impacts.csv") as f:
        impacts = list(csv.DictReader(f))
    array = result.impacts_array
    assert list(array.dtype.names) == list(impacts[0]) and len(array) == len(impacts) == len(result.impacts)
    for name in array.dtype.names:
        column = np.array([float(row[name]) for row in impacts])
        assert np.array_equal(bits(array[name].astype(np.float64)), bits(column)), name
    assert array["level"].dtype == np.int64 and array["starts_sustained_contact"].dtype == np.bool_
    assert np.array_equal(array["t_s"], [i["t_s"] for i in result.impacts])

    with open(folder / "contacts_history.csv") as f:
        rows = list(csv.reader(f))
    assert list(result.contact_forces) == rows[0] and len(rows) > 10  # the paper scene holds contacts
    table = np.array([[float(x) for x in row] for row in rows[1:]])
    for c, name in enumerate(rows[0]):
        assert np.array_equal(bits(result.contact_forces[name]), bits(table[:, c])), name


def test_method_settings_and_record_match_cli(tmp_path):
    """Another method with a setting, under another record scaled to a PGA: the keywords do what
    the options do."""
    expected = cli_run(tmp_path, PAPER, "--method", "cvode-adams", "--rtol", "1e-6", "--record", RECORD,
                       "--record-format", "peer-at2", "--units", "g", "--pga-g", "0.25")
    scene = pounding.load_scene(PAPER).with_record(RECORD, format="peer-at2", units="g", scale_to_pga_g=0.25)
    assert scene.record_file == RECORD
    assert_same(pounding.run(scene, method="cvode-adams", rtol=1e-6).summary, expected)


def test_overrides_match_cli(tmp_path):
    expected = cli_run(tmp_path, PAPER, "--gap", "0.05", "--restitution", "0.65")
    scene = pounding.load_scene(PAPER, gap=0.05, restitution=0.65)
    assert (scene.gap_m, scene.restitution) == (0.05, 0.65)
    assert_same(pounding.run(scene).summary, expected)
    # with_gap / with_restitution are the same scene as the options give.
    other = pounding.load_scene(PAPER).with_gap(0.05).with_restitution(0.65)
    assert_same(pounding.run(other).summary, expected)


def test_output_selection_matches_cli(tmp_path, paper_pair):
    """with_outputs does what --history and --peaks do; without history the arrays are empty and
    the impacts are the full run's."""
    expected = cli_run(tmp_path, PAPER, "--history", "off", "--peaks", "drifts,displacements")
    scene = pounding.load_scene(PAPER)
    assert (scene.history, scene.peaks) == (True, ["displacements", "accelerations", "drifts"])
    selected = scene.with_outputs(history=False, peaks=["drifts", "displacements"])
    assert (selected.history, selected.peaks) == (False, ["drifts", "displacements"])
    result = pounding.run(selected)
    assert_same(result.summary, expected)
    assert result.summary["outputs"] == {"history": False, "peaks": ["displacements", "drifts"]}
    assert result.history == {} and result.contact_forces == {}
    assert result.impacts == paper_pair[1].impacts
    assert "ax_abs_mps2" not in result.peaks[0]["floors"][0] and "drift_x" in result.peaks[0]["floors"][0]
    with pytest.raises(pounding.InputError) as error:
        scene.with_outputs(peaks=["speeds"])
    assert error.value.key == "output.peaks[1]" and error.value.value == '"speeds"'


def test_bad_scene_raises_cli_message(tmp_path):
    bad = tmp_path / "bad.toml"
    text = (PAPER.read_text().replace("restitution = 0.5", "restitution = 1.5")
            .replace('file = "', f'file = "{PAPER.parent}/'))  # the record path stays valid in the copy
    assert text.count("restitution = 1.5") == 1
    bad.write_text(text)
    message = cli("check", bad, expect=2).stderr
    with pytest.raises(pounding.InputError) as raised:
        pounding.load_scene(bad)
    assert message == f"error: {raised.value}\n"
    assert isinstance(raised.value, ValueError)
    assert (raised.value.file, raised.value.key, raised.value.value) == (str(bad), "contact.restitution", "1.5")

    # An override: the same message as `check --gap`.
    message = cli("check", PAPER, "--gap", "20", expect=2).stderr
    with pytest.raises(pounding.InputError) as raised:
        pounding.load_scene(PAPER, gap=20)
    assert message == f"error: {raised.value}\n"
    # A missing file.
    message = cli("check", tmp_path / "missing.toml", expect=2).stderr
    with pytest.raises(pounding.InputError) as raised:
        pounding.load_scene(tmp_path / "missing.toml")
    assert message == f"error: {raised.value}\n"


def test_bad_copies_name_the_key():
    scene = pounding.load_scene(PAPER)
    with pytest.raises(pounding.InputError) as raised:
        scene.with_gap(20.0)
    assert raised.value.key == "contact.gap_m" and raised.value.file == str(PAPER)
    with pytest.raises(pounding.InputError) as raised:
        scene.with_restitution(-0.1)
    assert raised.value.key == "contact.restitution"
    with pytest.raises(pounding.InputError) as raised:
        scene.with_record(RECORD, format="peer-at2", scale_to_pga_g=-1.0)
    assert raised.value.key == "excitation.scale_to_pga_g" and raised.value.value == "-1"
    assert scene.gap_m == 0.2  # the copies failed; the scene is unchanged
    copy = pickle.loads(pickle.dumps(raised.value))
    assert (str(copy), copy.key, copy.value, copy.file) == (str(raised.value), "excitation.scale_to_pga_g", "-1",
                                                           str(PAPER))


def test_inapplicable_setting_raises_naming_it():
    scene = pounding.load_scene(PAPER)
    message = cli("run", PAPER, "--method", "hht", "--rtol", "1e-6", expect=2).stderr
    with pytest.raises(pounding.InputError) as raised:
        pounding.run(scene, method="hht", rtol=1e-6)
    assert raised.value.key == "solver.rtol" and raised.value.value == "1e-06"
    assert "does not apply to method hht" in str(raised.value) and raised.value.reason in message
    with pytest.raises(pounding.InputError) as raised:
        pounding.run(scene, method="no-such-method")
    assert raised.value.key == "solver.method"
    with pytest.raises(pounding.InputError) as raised:
        pounding.run(scene, order="2")
    assert raised.value.key == "solver.order"
    with pytest.raises(TypeError, match="rtoll"):
        pounding.run(scene, rtoll=1e-6)


def test_whole_numbers_too_large_for_c_raise_naming_the_keyword():
    # 2**63 reached pybind11's cast and raised "Unable to cast Python instance" without a name.
    scene = pounding.load_scene(PAPER)
    for keywords, key in ((dict(method="cvode-bdf", order=2**63), "order"), (dict(order=-2**63), "order"),
                          (dict(max_steps=2**70), "max_steps"), (dict(max_history_values=0), "max_history_values")):
        with pytest.raises(pounding.InputError) as raised:
            pounding.run(scene, **keywords)
        assert raised.value.key == key and "must lie in" in str(raised.value), keywords


def test_keywords_of_the_wrong_type_raise_naming_them():
    # run(S, max_steps=1.5) gave pybind11's "incompatible function arguments" without a name, and
    # with_record(units=5) named the scene key but not the argument.
    scene = pounding.load_scene(PAPER)
    for keywords, key, words in ((dict(max_steps=1.5), "max_steps", "whole number"),
                                 (dict(max_wall_time_s="x"), "max_wall_time_s", "a number")):
        with pytest.raises(pounding.InputError) as raised:
            pounding.run(scene, **keywords)
        assert raised.value.key == key and words in str(raised.value), keywords
    with pytest.raises(pounding.InputError) as raised:
        scene.with_record(SOURCE / "examples" / "records" / "elcentro1940_ns_0.02s.AT2", units=5)
    assert raised.value.key == "excitation.units" and str(raised.value).startswith("Scene.with_record(units=...)")


def test_modes_match_cli(tmp_path):
    cli("modes", PAPER, "--json", tmp_path / "modes.json")
    expected = json.loads((tmp_path / "modes.json").read_text())["buildings"]
    buildings = pounding.modes(pounding.load_scene(PAPER))
    for building, reference in zip(buildings, expected, strict=True):
        periods = np.array([m["period_s"] for m in reference["modes"]])
        assert np.array_equal(bits(building["periods_s"]), bits(periods))
        assert np.array_equal(bits(building["frequencies_hz"]), bits([m["frequency_hz"] for m in reference["modes"]]))
        assert np.all(np.diff(building["periods_s"]) <= 0) and building["effective_mass_ratio"]["x"].sum() <= 1 + 1e-12
        assert building["name"] == reference["name"] and building["dof"] == reference["dof"] == len(periods)
        assert_same(building["modes"], reference["modes"])


def test_needed_gap_matches_cli(tmp_path):
    cli("gap", PAPER, "--out", tmp_path)
    expected = json.loads((tmp_path / "gap.json").read_text())
    del expected["provenance"]
    gap = pounding.needed_gap(pounding.load_scene(PAPER))
    assert gap.needed_gap_m.hex() == expected["needed_gap_m"].hex() and gap.status == "completed"
    assert_same(gap.summary, expected)
    with open(tmp_path / "gap_history.csv") as f:
        rows = list(csv.reader(f))
    table = np.array([[float(x) for x in row] for row in rows[1:]])
    assert np.array_equal(bits(gap.history_t_s), bits(table[:, 0]))
    assert np.array_equal(bits(gap.history_touch_gap_m), bits(table[:, 1:]))


def test_threads_give_serial_results_and_release_the_gil():
    scenes = [pounding.load_scene(PAPER), pounding.load_scene(PAPER, gap=0.05, restitution=0.65)]
    serial = [pounding.run(scene).summary for scene in scenes]
    assert serial[0]["impacts"] != serial[1]["impacts"]  # two different runs, so a mix-up would show

    results = [None, None]

    def work(index):
        results[index] = pounding.run(scenes[index]).summary

    # While both runs go on, this thread keeps running Python: with the GIL held by a run it would
    # stall for the whole run. Its longest stall must stay well under one run's time.
    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    start = time.perf_counter()
    ticks = [start]
    for thread in threads:
        thread.start()
    while any(thread.is_alive() for thread in threads):
        time.sleep(0.001)
        ticks.append(time.perf_counter())
    for thread in threads:
        thread.join()
    shortest_run_s = min(s["statistics"]["wall_time_s"] for s in serial)
    longest_stall_s = max(np.diff(ticks))
    assert shortest_run_s > 0.05, "runs too short to tell a stall"
    assert longest_stall_s < 0.5 * shortest_run_s, (longest_stall_s, shortest_run_s)
    for parallel, alone in zip(results, serial):
        assert_same(parallel, alone)


def test_budget_ends_runs_with_a_status():
    """A run over its wall-time budget ends early with status time_limit (no exception), as the
    command line's --max-wall-time does; a budget that is not positive is bad input."""
    scene = pounding.load_scene(PAPER)
    result = pounding.run(scene, max_wall_time_s=1e-6)
    assert result.status == "time_limit" and result.summary["end_s"] < 12.0
    gap = pounding.needed_gap(scene, max_wall_time_s=1e-6)
    assert gap.status == "time_limit" and gap.end_s < 12.0
    for call in (lambda: pounding.run(scene, max_wall_time_s=0.0), lambda: pounding.needed_gap(scene, max_wall_time_s=0.0)):
        with pytest.raises(pounding.InputError) as raised:
            call()
        assert "max_wall_time_s" in raised.value.key


def test_contact_and_limit_keywords_come_from_their_tables():
    """load_scene's [contact] keywords and run's limit keywords are the rows of `pounding settings
    --json` (their option without `--`; their key), applied and checked as the options are."""
    table = json.loads(subprocess.run([CLI, "settings", "--json"], capture_output=True, text=True, check=True).stdout)
    options = {row["python"] for row in table["contact"] if row["option"] and row["option"] != "--gap"}
    assert set(pounding.contact_options()) == options
    assert pounding.limits() == [row["key"] for row in table["limits"]]
    scene = pounding.load_scene(PAPER, restitution=0.6, contact_law="kelvin", contact_stiffness=5e4)
    assert (scene.restitution, scene.contact_law) == (0.6, "kelvin")
    assert "50000" in subprocess.run([CLI, "check", PAPER, "--contact-law", "kelvin", "--contact-stiffness", "5e4"],
                                     capture_output=True, text=True, check=True).stdout
    with pytest.raises(TypeError, match="restitutio"):
        pounding.load_scene(PAPER, restitutio=0.5)
    with pytest.raises(pounding.InputError) as raised:
        pounding.load_scene(PAPER, restitution=1.5)
    assert raised.value.key == "--restitution" and "[0, 1]" in str(raised.value)
    with pytest.raises(pounding.InputError) as raised:
        pounding.load_scene(PAPER, contact_law=3)
    assert raised.value.key == "contact_law" and "a string" in str(raised.value)
    for row in table["limits"]:
        with pytest.raises(pounding.InputError) as raised:
            too_large = row["range"]["max"] * 2
            pounding.run(scene, **{row["key"]: int(too_large) if row["type"] == "integer" else too_large})
        assert raised.value.key == row["key"] and "must lie in" in str(raised.value), row["key"]
