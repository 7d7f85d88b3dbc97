"""pounding.verify's impact matching with a window ([after_s, before_s)): pairs are made over the
whole lists first, so an impact just inside the window whose partner lies just outside is one
pair, not one missing and one extra; unmatched impacts outside the window are not counted."""
from pounding import verify


def impact(t_s, level=7):
    return {"t_s": t_s, "level": level, "striking_building": 2, "vertex": 1, "struck_edge": 2}


def test_a_pair_straddling_the_window_edge_is_one_pair():
    expected, observed = [impact(9.9999999)], [impact(10.0000001)]
    pairs, missing, extra = verify._match_in_window(expected, observed, {"before_s": 10.0})
    assert len(pairs) == 1 and not missing and not extra


def test_impacts_outside_the_window_do_not_count():
    expected = [impact(1.0), impact(5.0)]
    observed = [impact(1.0), impact(5.0), impact(20.0)]  # 20 s: after the stretch the expected cover
    pairs, missing, extra = verify._match_in_window(expected, observed, {"before_s": 10.0})
    assert len(pairs) == 2 and not missing and not extra
    pairs, missing, extra = verify._match_in_window(expected, observed, {"after_s": 2.0})
    assert len(pairs) == 1 and not missing and [o["t_s"] for o in extra] == [20.0]


def test_an_impact_at_another_contact_is_not_a_partner():
    pairs, missing, extra = verify._match_in_window([impact(1.0, level=6)], [impact(1.0, level=7)], {})
    assert not pairs and len(missing) == 1 and len(extra) == 1


# Isolated cases (manifest isolate = true, --isolate): a case runs in a child process, so that a
# crash or a hang is that case's error and the others still run.
def test_a_child_that_crashes_is_an_error_naming_its_signal():
    import sys
    crash = [sys.executable, "-c", "import os, signal; os.kill(os.getpid(), signal.SIGSEGV)"]
    assert verify.run_child(crash, "", 60)["error"] == "crashed: signal 11 (SIGSEGV)"


def test_a_child_past_its_time_is_killed_as_a_hang():
    import sys
    import time
    started = time.monotonic()
    observed = verify.run_child([sys.executable, "-c", "import time; time.sleep(30)"], "", 0.5)
    assert observed["error"].startswith("hang: no result within 0.5 s") and time.monotonic() - started < 10


def test_a_child_result_is_its_last_line_of_json():
    import sys
    echo = [sys.executable, "-c", "import sys, json; print('noise'); print(json.dumps({'got': sys.stdin.read()}))"]
    assert verify.run_child(echo, "case", 60) == {"got": "case"}
    failing = [sys.executable, "-c", "import sys; sys.exit('cannot run')"]
    assert verify.run_child(failing, "", 60)["error"] == "exit 1, no result: cannot run"


def manifest(tmp_path, cases):
    (tmp_path / "scene.toml").write_text("")  # only its existence is checked when reading
    path = tmp_path / "m.verify.toml"
    path.write_text("".join(f'[[case]]\nname = "{name}"\nscene = "scene.toml"\n{extra}\n[case.checks]\n'
                            f"status = {status}\n\n" for name, extra, status in cases))
    return path


def test_a_reference_must_name_another_case(tmp_path):
    import pytest
    for reference, reason in (("nowhere", "names no other case"), ("b", "its own reference")):
        path = manifest(tmp_path, [("a", "", "true"), ("b", f'reference = "{reference}"', "true")])
        with pytest.raises(verify.InputError) as refused:
            verify.Manifest(path)
        assert "case[2].reference" in str(refused.value) and reason in str(refused.value)
        assert "m.verify.toml:11:" in str(refused.value), str(refused.value)  # the reference line


def test_a_status_list_allows_any_of_its_statuses(tmp_path):
    path = manifest(tmp_path, [("a", "", '["completed", "unresolved_overlap"]')])
    case = verify.Manifest(path).cases[0]
    for status, passed in (("unresolved_overlap", True), ("event_limit", False)):
        (name, ok, detail), = verify._checks(case, {"status": status, "status_detail": ""}, None)
        assert name == "status" and ok == passed, detail
