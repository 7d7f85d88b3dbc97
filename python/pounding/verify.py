"""Validation runs as a feature: the cases of a manifest run and checked against stored or
written expected results, with a table, JUnit XML and a markdown summary.

    python3 -m pounding.verify MANIFEST.toml [--bless] [--jobs N] [--out DIR] [--no-progress]
    pounding.verify.verify("MANIFEST.toml")          # the same from Python; returns a VerifyResult

The manifest (TOML; paths relative to its folder; docs/guide/verify.md):

    name = "paper"                          # absent: the file's name
    expected = "paper.expected.json"        # the blessed results; absent: <manifest stem>.expected.json
    isolate = true                          # each case in a process of its own (or --isolate): a crash
                                            # or a hang fails that case only
    [defaults.checks]                       # merged under every case's checks
    energy_residual = { max_relative = 1e-6 }

    [[case]]
    name = "cvode-bdf"                      # unique; required
    scene = "../examples/paper/paper.toml"  # required
    gap_m = 0.2                             # optional, as load_scene: gap_m, restitution, contact_law,
                                            # contact_stiffness
    record = { file = "...", scale_to_pga_g = 0.3 }   # optional: Scene.with_record's keywords
    method = "cvode-bdf"                    # optional, with its [solver] settings
    settings = { rtol = 1e-10, atol = 1e-12 }
    max_wall_time_s = 600                   # optional: the run's budget
    reference = "other case"                # optional: expect that case's results of this run, not
                                            # the blessed ones (a method against a reference run)
    [case.checks]                           # what to check, each with its tolerance
    status = true                           # the expected status ("completed"); or a name, or a
                                            # list of the statuses allowed
    impact_count = true                     # exactly; or { abs = 2 }
    impact_times = { abs_s = 1e-6 }         # or { scaled = 100 }: 100 × the method's tolerance
    impulses = { rel = 1e-4, abs_kNs = 1e-6 }
    peaks = { rel = 1e-6, abs = 1e-12 }     # every peak of summary.json
    rebound = { rel = 0.01 }                # the first impact's separation / approach speed
    needed_gap = { abs_m = 1e-6 }           # runs `pounding gap` too
    energy_residual = { max_relative = 1e-6 }   # bounds: need no expected value
    interpenetration = { max_m = 1e-9 }
    [case.expected]                         # values written here (closed forms, published numbers)
    impact_count = 45                       # override the blessed ones: status, impact_count,
    first_impact_s = 5.7008                 # first_impact_s, impact_times_s, needed_gap_m, rebound
"""

import argparse
import concurrent.futures
import datetime
import json
import math
import os
import pathlib
import re
import signal
import socket
import subprocess
import sys
import time
import tomllib
import xml.etree.ElementTree as ElementTree

import pounding
from pounding import InputError
from pounding import _input_error as _error  # InputError with the library's message

CASE_KEYS = ("name", "scene", "gap_m", "restitution", "contact_law", "contact_stiffness", "record", "method",
             "settings", "max_wall_time_s", "reference", "checks", "expected")
ISOLATED_BUDGET_S = 600.0  # an isolated case's budget when it gives none
HANG_GRACE_S = 60.0        # an isolated case still running this long after its budget hangs
# Each check kind and its tolerance fields (each a number >= 0).
CHECK_FIELDS = {"status": (), "impact_count": ("abs",), "impact_times": ("abs_s", "scaled", "after_s", "before_s"),
                "impulses": ("rel", "abs_kNs", "after_s", "before_s"),
                "approach_velocity": ("rel", "abs_mps", "after_s", "before_s"), "peaks": ("rel", "abs"), "needed_gap": ("abs_m",),
                "rebound": ("rel", "abs"), "gap_rules": ("rel", "abs_m"),
                "energy_residual": ("max_relative",), "interpenetration": ("max_m",)}
RECORD_KEYS = ("file", "format", "units", "scale_factor", "scale_to_pga_g", "scale_to_sa", "direction_deg", "dt_s",
               "accel_column", "record2", "record2_column")  # Scene.with_record's keywords
# The keys of [case.expected] that may carry their own tolerance, and its name.
WRITTEN_TOLERANCE = {"first_impact_s": "abs_s", "needed_gap_m": "abs_m", "rebound": "abs",
                     "approach_velocity_mps": "abs_mps"}
EXPECTED_KEYS = ("status", "impact_count", "first_impact_s", "impact_times_s", "impulses_kNs", "approach_velocity_mps",
                 "needed_gap_m", "gap_rules_m", "rebound")
MATCH_WINDOW_S = 0.05  # impacts further apart than this at one contact are different impacts


class Manifest:
    """A manifest read and checked: name, file, expected_file, cases (dicts with the keys above,
    paths resolved, checks merged over the defaults)."""

    def __init__(self, path):
        self.file = pathlib.Path(path)
        try:
            self.text = self.file.read_text()
        except OSError as error:
            raise _error(self.file, "manifest", "", f"cannot read it ({error.strerror})") from None
        try:
            document = tomllib.loads(self.text)
        except tomllib.TOMLDecodeError as error:
            raise _error(self.file, "manifest", "", f"not valid TOML ({error})") from None
        self.name = self._text(document.get("name", self.file.stem), "name")
        self.expected_file = self._path(document.get("expected", f"{self.file.stem}.expected.json"), "expected")
        self.isolate = document.get("isolate", False)
        if not isinstance(self.isolate, bool):
            raise self._refuse("isolate", repr(self.isolate), "expected true or false")
        defaults = document.get("defaults", {})
        self._known(document, ("name", "expected", "isolate", "defaults", "case"), "")
        self._known(defaults, ("checks",), "defaults")
        default_checks = self._checks(defaults.get("checks", {}), "defaults.checks")
        cases = document.get("case")
        if not isinstance(cases, list) or not cases:
            raise _error(self.file, "case", "", "a manifest needs at least one [[case]]")
        self.cases, names = [], set()
        for index, case in enumerate(cases, start=1):
            case = self._case(case, f"case[{index}]", default_checks)
            if case["name"] in names:
                raise self._refuse(f"case[{index}].name", case["name"], "given twice")
            names.add(case["name"])
            self.cases.append(case)
        for index, case in enumerate(self.cases, start=1):
            reference = case["reference"]
            if reference is not None and (reference not in names or reference == case["name"]):
                raise self._refuse(f"case[{index}].reference", reference,
                                   "names no other case of this manifest" if reference != case["name"]
                                   else "a case cannot be its own reference")

    def _line(self, key):
        """The manifest line that sets `key` (a path such as case[2].checks.impulses.rel): the first
        line from that case's [[case]] on (the file's start for other keys) where its last part is
        assigned, comments aside; None when not found."""
        lines = [line.split("#")[0] for line in self.text.splitlines()]
        start = 0
        case = re.match(r"case\[(\d+)\]", key)
        if case:
            headers = [i for i, line in enumerate(lines) if line.strip().startswith("[[case]]")]
            start = headers[int(case.group(1)) - 1] if int(case.group(1)) <= len(headers) else 0
        parts = [re.sub(r"\[\d+\]$", "", part) for part in key.split(".")[1 if case else 0:]]
        for depth, part in enumerate(parts):  # each table on the way ([case.checks], checks = {...}), then the key
            assigned = re.compile(rf"(^|[\s{{,]){re.escape(part)}\s*=|^\s*\[[\w.]*\b{re.escape(part)}\]")
            found = next((n for n in range(start, len(lines)) if assigned.search(lines[n])), None)
            if found is None:
                return start + 1 if depth else None
            start = found
        return start + 1

    def _refuse(self, key, value, reason):
        return _error(self.file, key, value, reason, self._line(key))

    def _known(self, table, keys, where):
        if not isinstance(table, dict):
            raise self._refuse(where, repr(table), "expected a table")
        for key in table:
            if key not in keys:
                name = f"{where}.{key}" if where else key
                raise self._refuse(name, "", f"unknown key (expected {', '.join(keys)})")

    def _text(self, value, key):
        if not isinstance(value, str) or not value:
            raise self._refuse(key, repr(value), "expected non-empty text")
        return value

    def _path(self, value, key):
        return (self.file.parent / self._text(value, key)).resolve()

    def _number(self, value, key):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value < math.inf:
            raise self._refuse(key, repr(value), "expected a finite number >= 0")
        return float(value)

    def _numbers(self, value, key):
        if not isinstance(value, list):
            raise self._refuse(key, repr(value), "expected a list of numbers")
        return [self._number(v, f"{key}[{i + 1}]") for i, v in enumerate(value)]

    def _checks(self, table, where):
        self._known(table, tuple(CHECK_FIELDS), where)
        checks = {}
        for kind, spec in table.items():
            if spec is False:  # a default switched off for this case
                checks[kind] = None
                continue
            if kind == "status":
                names = spec if isinstance(spec, list) else [spec]
                if spec is not True and (not names or not all(isinstance(n, str) and n for n in names)):
                    raise self._refuse(f"{where}.status", repr(spec), "expected true, a status name or a list of them")
                checks[kind] = {} if spec is True else {"allowed": names}
                continue
            spec = {} if spec is True else spec
            self._known(spec, CHECK_FIELDS[kind], f"{where}.{kind}")
            checks[kind] = {field: self._number(value, f"{where}.{kind}.{field}") for field, value in spec.items()}
            if kind not in ("status", "impact_count") and not set(checks[kind]) - {"after_s", "before_s"}:
                raise self._refuse(f"{where}.{kind}", "{}", f"give its tolerance ({' or '.join(CHECK_FIELDS[kind])})")
        return checks

    def _written(self, value, key, tolerance):
        """A number written in [case.expected], or {value, <tolerance>} with its own tolerance (a
        published number known to so many digits): the number, or {value, abs}."""
        if not isinstance(value, dict):
            return self._number(value, key)
        self._known(value, ("value", tolerance), key)
        if set(value) != {"value", tolerance}:
            raise self._refuse(key, repr(value), f"expected a number or {{value = ..., {tolerance} = ...}}")
        return {"value": self._number(value["value"], f"{key}.value"), "abs": self._number(value[tolerance], key)}

    def _expected(self, expected, where):
        """[case.expected] checked: each key its type (exit 2 naming it, not a traceback later)."""
        self._known(expected, EXPECTED_KEYS, where)
        result = {}
        for key, value in expected.items():
            name = f"{where}.{key}"
            if key == "status":
                result[key] = self._text(value, name)
            elif key == "impact_count":
                if isinstance(value, bool) or not isinstance(value, int) or value < 0:
                    raise self._refuse(name, repr(value), "expected a whole number >= 0")
                result[key] = value
            elif key in ("impact_times_s", "impulses_kNs"):
                result[key] = self._numbers(value, name)
            elif key == "gap_rules_m":
                self._known(value, ("abs_m", "srss_m", "ddc_m"), name)
                result[key] = {rule: self._number(number, f"{name}.{rule}") for rule, number in value.items()}
            else:
                result[key] = self._written(value, name, WRITTEN_TOLERANCE[key])
        if "impulses_kNs" in result and len(result["impulses_kNs"]) != len(result.get("impact_times_s", [])):
            raise self._refuse(f"{where}.impulses_kNs", f"{len(result['impulses_kNs'])} values",
                               "needs one impulse per impact_times_s entry")
        return result

    def _record(self, record, where):
        """with_record's keywords (file required), paths resolved from the manifest's folder."""
        self._known(record, RECORD_KEYS, where)
        if "file" not in record:
            raise self._refuse(where, repr(record), "a record needs its file")
        record = dict(record)
        for key in ("file", "record2"):
            if key in record:
                record[key] = str(self._path(record[key], f"{where}.{key}"))
        return record

    def _case(self, case, where, default_checks):
        self._known(case, CASE_KEYS, where)
        if "name" not in case or "scene" not in case:
            raise self._refuse(where, "", "a case needs a name and a scene")
        result = {key: case.get(key) for key in CASE_KEYS}
        result["name"] = self._text(case["name"], f"{where}.name")
        result["scene"] = self._path(case["scene"], f"{where}.scene")
        if not result["scene"].is_file():
            raise self._refuse(f"{where}.scene", case["scene"], "no such scene file")
        for key in ("gap_m", "restitution", "contact_stiffness", "max_wall_time_s"):
            if key in case:
                result[key] = self._number(case[key], f"{where}.{key}")
        for key in ("contact_law", "method", "reference"):
            if key in case:
                result[key] = self._text(case[key], f"{where}.{key}")
        result["record"] = self._record(case["record"], f"{where}.record") if "record" in case else None
        settings = case.get("settings", {})
        self._known(settings, pounding._pounding.setting_keys(), f"{where}.settings")
        result["settings"] = dict(settings)
        merged = {**default_checks, **self._checks(case.get("checks", {}), f"{where}.checks")}
        result["checks"] = {kind: spec for kind, spec in merged.items() if spec is not None}
        result["expected"] = self._expected(case.get("expected", {}), f"{where}.expected")
        if not result["checks"]:
            raise self._refuse(f"{where}.checks", "", "nothing to check: give [case.checks]")
        return result


# ------------------------------------------------------------------------------------------------
# Running a case


def _scene(case):
    scene = pounding.load_scene(case["scene"], gap=case["gap_m"], restitution=case["restitution"],
                                contact_law=case["contact_law"], contact_stiffness=case["contact_stiffness"])
    if case["record"]:
        scene = scene.with_record(**case["record"])
    return scene


def _peaks(summary):
    """Every scalar peak of summary.json, named building.floor.quantity (with an index for lists)."""
    values = {}
    for building in summary["peaks"]:
        for floor in building["floors"]:
            prefix = f"{building['building']}.f{floor['floor']}."
            for key, entry in floor.items():
                if isinstance(entry, dict) and "value" in entry:
                    values[prefix + key] = entry["value"]
                elif isinstance(entry, list):
                    for index, item in enumerate(entry, start=1):
                        if isinstance(item, dict) and "value" in item:
                            values[f"{prefix}{key}[{index}]"] = item["value"]
    return values


def _method_tolerance(summary):
    """(kind, value): the used rtol (relative), hht's dt_s (absolute, s) or the exact path's hold_rtol."""
    used = summary["settings"]["used"]
    for key, kind in (("rtol", "relative"), ("dt_s", "absolute"), ("hold_rtol", "relative")):
        if key in used:
            return kind, float(used[key])
    return "absolute", 0.0


def _rebound(impacts):
    """The first impact's separation over approach speed, or None (no impact, or a grazing one)."""
    if not impacts or not impacts[0]["approach_velocity_mps"] > 0:
        return None
    return impacts[0]["separation_velocity_mps"] / impacts[0]["approach_velocity_mps"]


def observe(case):
    """Runs one case; the quantities its checks read (JSON-ready), or {"error": message}."""
    started = time.perf_counter()
    try:
        scene = _scene(case)
        result = pounding.run(scene, method=case["method"], max_wall_time_s=case["max_wall_time_s"],
                              **case["settings"])
        summary = result.summary
        observed = {
            "status": summary["status"], "status_detail": summary["status_detail"],
            "method": summary["method"], "method_tolerance": _method_tolerance(summary),
            "impact_count": summary["impact_count"],
            "impacts": [{key: i[key] for key in ("t_s", "level", "striking_building", "vertex", "struck_edge",
                                                 "approach_velocity_mps", "impulse_kNs")} for i in summary["impacts"]],
            "peaks": _peaks(summary),
            "energy_relative_residual": summary["energy"].get("relative_residual"),
            # The first impact's separation over approach speed: the restitution a law achieves.
            "rebound": _rebound(summary["impacts"]),
            "max_interpenetration_m": summary["statistics"].get("max_interpenetration_m"),
        }
        if "needed_gap" in case["checks"] or "gap_rules" in case["checks"]:
            gap = pounding.needed_gap(scene, max_wall_time_s=case["max_wall_time_s"])
            observed["needed_gap_m"] = gap.needed_gap_m
            observed["gap_rules_m"] = gap.rules  # ABS, SRSS and DDC from the contact-free peaks
    except InputError as error:  # a scene, record or setting the library refuses
        observed = {"error": str(error)}
    except Exception as error:  # noqa: BLE001  (any other failure of one case is that case's error)
        observed = {"error": f"{type(error).__name__}: {error}"}
    observed["wall_time_s"] = time.perf_counter() - started
    return observed


def run_child(command, payload, timeout_s):
    """Runs `command` with `payload` (text) on its standard input: its standard output (JSON), or
    {"error": ...} when it crashed, was killed, wrote no result or ran past timeout_s (a hang)."""
    try:
        done = subprocess.run(command, input=payload, capture_output=True, text=True, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        return {"error": f"hang: no result within {timeout_s:g} s (killed)"}
    if done.returncode < 0:
        name = signal.Signals(-done.returncode).name if -done.returncode in signal.valid_signals() else "?"
        return {"error": f"crashed: signal {-done.returncode} ({name})"}
    try:
        return json.loads(done.stdout.strip().splitlines()[-1])
    except (json.JSONDecodeError, IndexError):
        last = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "no output"
        return {"error": f"exit {done.returncode}, no result: {last}"}


def observe_isolated(case):
    """observe() in a Python process of its own, so that a crash or a hang fails this case alone:
    killed HANG_GRACE_S after its budget (max_wall_time_s, else ISOLATED_BUDGET_S, which it is
    then given)."""
    budget_s = case["max_wall_time_s"] or ISOLATED_BUDGET_S
    payload = json.dumps({**case, "max_wall_time_s": budget_s}, default=str)
    command = [sys.executable, "-c", "import sys, json, pounding.verify as v; "
               "print(json.dumps(v.observe(json.loads(sys.stdin.read()))))"]
    started = time.perf_counter()
    observed = run_child(command, payload, budget_s + HANG_GRACE_S)
    observed.setdefault("wall_time_s", time.perf_counter() - started)
    return observed


# ------------------------------------------------------------------------------------------------
# Checking a case


def _match(expected, observed, window_s):
    """Greedy in time order: each expected impact takes the nearest unused observed impact at the
    same contact (level, striking building and vertex, struck edge) within window_s."""
    used, pairs, missing = set(), [], []
    contact = ("level", "striking_building", "vertex", "struck_edge")
    for e in expected:
        best = None
        for j, o in enumerate(observed):
            if j in used or any(o[k] != e[k] for k in contact if k in e):
                continue
            dt = abs(o["t_s"] - e["t_s"])
            if dt <= window_s and (best is None or dt < best[0]):
                best = (dt, j)
        if best is None:
            missing.append(e)
        else:
            used.add(best[1])
            pairs.append((e, observed[best[1]]))
    extra = [o for j, o in enumerate(observed) if j not in used]
    return pairs, missing, extra


def _impact_text(impact):
    return f"level {impact['level']} at {impact['t_s']:.9f} s" if "level" in impact else f"{impact['t_s']:.9f} s"


def _time_tolerance(spec, observed, t_s):
    if "abs_s" in spec:
        return spec["abs_s"]
    kind, value = observed["method_tolerance"]
    return spec["scaled"] * value * (max(abs(t_s), 1.0) if kind == "relative" else 1.0)


def _expected_impacts(case, blessed):
    """The written impacts (impact_times_s, with impulses_kNs when given), else the stored ones."""
    written = case["expected"]
    if "impact_times_s" in written:
        impulses = written.get("impulses_kNs", [None] * len(written["impact_times_s"]))
        return [{"t_s": float(t), "impulse_kNs": j} for t, j in zip(written["impact_times_s"], impulses)]
    return blessed.get("impacts") if blessed else None


def _inside(impact, spec):
    """Whether the impact lies within [after_s, before_s) of a check (a steady state, or the stretch a
    peer covers)."""
    return spec.get("after_s", -math.inf) <= impact["t_s"] < spec.get("before_s", math.inf)


def _match_in_window(expected, observed, spec):
    """_match over the whole lists, then what the window keeps: the pairs with either side in it and
    the unmatched impacts in it (so an impact just inside the window whose partner lies just outside
    is a pair, not one missing and one extra)."""
    pairs, missing, extra = _match(expected, observed, MATCH_WINDOW_S)
    return ([(e, o) for e, o in pairs if _inside(e, spec) or _inside(o, spec)],
            [e for e in missing if _inside(e, spec)], [o for o in extra if _inside(o, spec)])


def _relative(got, wanted):
    """|got / wanted - 1|, or |got| against a zero expectation."""
    return abs(got / wanted - 1) if wanted else abs(got)


def _checks(case, observed, blessed):
    """[(check name, passed, detail)] of one case."""
    results, checks, written = [], case["checks"], case["expected"]
    blessed = blessed or {}

    def expected_value(key):
        return written[key] if key in written else blessed.get(key)

    def no_expectation(name):
        results.append((name, False, "no expected value: run `pounding verify --bless` or write it in "
                                     "[case.expected]"))

    if "status" in checks:
        allowed = checks["status"].get("allowed") or [expected_value("status")]
        if allowed[0] is None:
            no_expectation("status")
        else:
            results.append(("status", observed["status"] in allowed,
                            f"{observed['status']} (expected {' or '.join(allowed)}) "
                            f"{observed['status_detail']}".strip()))
    if "impact_count" in checks:
        wanted = expected_value("impact_count")
        if wanted is None:
            no_expectation("impact_count")
        else:
            allowed = checks["impact_count"].get("abs", 0.0)
            difference = observed["impact_count"] - wanted
            results.append(("impact_count", abs(difference) <= allowed,
                            f"{observed['impact_count']} impacts, expected {wanted} (allowed ±{allowed:g})"))
    if "impact_times" in checks:
        _check_times(case, observed, blessed, checks["impact_times"], results)
    if "impulses" in checks:
        _check_impulses(case, observed, blessed, checks["impulses"], results, no_expectation)
    if "approach_velocity" in checks:
        _check_approach(case, observed, blessed, checks["approach_velocity"], results, no_expectation)
    if "peaks" in checks:
        _check_peaks(observed, blessed, checks["peaks"], results, no_expectation)
    if "needed_gap" in checks:
        wanted, own_tolerance = _written_value(expected_value("needed_gap_m"))
        if wanted is None:
            no_expectation("needed_gap")
        else:
            got = observed.get("needed_gap_m")
            tolerance = checks["needed_gap"]["abs_m"] if own_tolerance is None else own_tolerance
            ok = got is not None and abs(got - wanted) <= tolerance
            results.append(("needed_gap", ok, f"{got} m, expected {wanted} m ± {tolerance:g} m"
                            + ("" if got is None else f" (differs by {got - wanted:.3e} m)")))
    if "rebound" in checks:
        wanted, own_tolerance = _written_value(expected_value("rebound"))
        if wanted is None:
            no_expectation("rebound")
        else:
            got, spec = observed["rebound"], checks["rebound"]
            spec = spec if own_tolerance is None else {"abs": own_tolerance}
            ok = got is not None and _within(got, wanted, spec, "abs")
            results.append(("rebound", ok, f"first impact's separation/approach speed {got}, expected {wanted:.6g} "
                            f"(rel {spec.get('rel', 0):g}, abs {spec.get('abs', 0):g})"
                            + ("" if got is None else f", differs by {got - wanted:+.3e}")))
    if "gap_rules" in checks:
        wanted = expected_value("gap_rules_m")
        if wanted is None:
            no_expectation("gap_rules")
        else:
            got = observed.get("gap_rules_m") or {}
            failed = [f"{rule} = {got.get(rule)}, expected {value:.9g}" for rule, value in wanted.items()
                      if got.get(rule) is None or not _within(got[rule], value, checks["gap_rules"], "abs_m")]
            worst = max((_relative(got[r], v) for r, v in wanted.items() if got.get(r) is not None), default=0.0)
            results.append(("gap_rules", not failed, f"{', '.join(wanted)}: largest relative difference {worst:.3e}"
                            + ("; " + "; ".join(failed) if failed else "")))
    if "energy_residual" in checks:
        got, bound = observed["energy_relative_residual"], checks["energy_residual"]["max_relative"]
        ok = got is not None and abs(got) <= bound
        results.append(("energy_residual", ok, f"relative residual {'none' if got is None else f'{got:.3e}'}, "
                                               f"at most {bound:g}"))
    if "interpenetration" in checks:
        got, bound = observed["max_interpenetration_m"] or 0.0, checks["interpenetration"]["max_m"]
        results.append(("interpenetration", got <= bound, f"largest overlap {got:.3e} m, at most {bound:g} m"))
    return results


def _check_times(case, observed, blessed, spec, results):
    expected = _expected_impacts(case, blessed)
    if "first_impact_s" in case["expected"]:
        first, tolerance = _written_value(case["expected"]["first_impact_s"])
        got = observed["impacts"][0]["t_s"] if observed["impacts"] else None
        tolerance = _time_tolerance(spec, observed, first) if tolerance is None else tolerance
        ok = got is not None and abs(got - first) <= tolerance
        results.append(("first_impact", ok, f"{got} s, expected {first} s ± {tolerance:.3g} s"
                        + ("" if got is None else f" (differs by {got - first:.3e} s)")))
    if expected is None:
        if "first_impact_s" not in case["expected"]:
            results.append(("impact_times", False, "no expected value: run `pounding verify --bless` or write "
                                                   "impact_times_s in [case.expected]"))
        return
    pairs, missing, extra = _match_in_window(expected, observed["impacts"], spec)
    worst, worst_text = 0.0, ""
    failed = []
    for e, o in pairs:
        tolerance = _time_tolerance(spec, observed, e["t_s"])
        difference = o["t_s"] - e["t_s"]
        if abs(difference) > tolerance:
            failed.append(f"{_impact_text(e)} moved by {difference:.3e} s (tolerance {tolerance:.3g} s)")
        if abs(difference) >= worst:
            worst, worst_text = abs(difference), _impact_text(e)
    failed += [f"expected impact {_impact_text(e)} not found" for e in missing[:5]]
    failed += [f"impact {_impact_text(o)} not expected" for o in extra[:5]]
    detail = f"{len(pairs)} matched, largest difference {worst:.3e} s ({worst_text or 'none'})"
    if missing or extra:
        detail += f"; {len(missing)} expected not found, {len(extra)} not expected"
    results.append(("impact_times", not failed, detail + ("; " + "; ".join(failed[:5]) if failed else "")))


def _written_value(written):
    """(value, its own tolerance or None) of a [case.expected] entry."""
    return (written["value"], written["abs"]) if isinstance(written, dict) else (written, None)


def _within(got, wanted, spec, abs_key):
    return abs(got - wanted) <= max(spec.get(abs_key, 0.0), spec.get("rel", 0.0) * abs(wanted))


def _check_impulses(case, observed, blessed, spec, results, no_expectation):
    expected = _expected_impacts(case, blessed)
    if expected is None or any(e.get("impulse_kNs") is None for e in expected):
        return no_expectation("impulses")
    pairs, missing, _ = _match_in_window(expected, observed["impacts"], spec)
    failed = [f"{_impact_text(e)}: {o['impulse_kNs']:.6g} kN·s, expected {e['impulse_kNs']:.6g}"
              for e, o in pairs if not _within(o["impulse_kNs"], e["impulse_kNs"], spec, "abs_kNs")]
    failed += [f"expected impact {_impact_text(e)} not found" for e in missing[:5]]
    worst = max((abs(o["impulse_kNs"] - e["impulse_kNs"]) for e, o in pairs), default=0.0)
    results.append(("impulses", not failed, f"{len(pairs)} matched impacts, largest difference {worst:.3e} kN·s"
                    + ("; " + "; ".join(failed[:5]) if failed else "")))


def _check_approach(case, observed, blessed, spec, results, no_expectation):
    """Every impact's approach speed (from after_s on): against the written steady value
    approach_velocity_mps, else against the stored impact it matches."""
    if "approach_velocity_mps" in case["expected"]:
        wanted, own = _written_value(case["expected"]["approach_velocity_mps"])
        spec = spec if own is None else {"abs_mps": own}
        pairs = [({"t_s": o["t_s"], "level": o["level"], "approach_velocity_mps": wanted}, o)
                 for o in observed["impacts"] if _inside(o, spec)]
        missing = []
    elif "impacts" in blessed:
        pairs, missing, _ = _match_in_window(blessed["impacts"], observed["impacts"], spec)
    else:
        return no_expectation("approach_velocity")
    failed = [f"{_impact_text(o)}: {o['approach_velocity_mps']:.9g} m/s, expected {e['approach_velocity_mps']:.9g}"
              for e, o in pairs if not _within(o["approach_velocity_mps"], e["approach_velocity_mps"], spec, "abs_mps")]
    failed += [f"expected impact {_impact_text(e)} not found" for e in missing[:5]]
    if not pairs and "approach_velocity_mps" in case["expected"]:
        failed.append("no impact to compare with the steady value")
    worst = max((_relative(o["approach_velocity_mps"], e["approach_velocity_mps"]) for e, o in pairs), default=0.0)
    results.append(("approach_velocity", not failed, f"{len(pairs)} impacts, largest relative difference {worst:.3e}"
                    + ("; " + "; ".join(failed[:5]) if failed else "")))


def _check_peaks(observed, blessed, spec, results, no_expectation):
    if "peaks" not in blessed:
        return no_expectation("peaks")
    failed, worst = [], (0.0, "")
    for name, wanted in blessed["peaks"].items():
        got = observed["peaks"].get(name)
        if got is None:
            failed.append(f"{name} missing")
            continue
        if not _within(got, wanted, spec, "abs"):
            failed.append(f"{name} = {got:.9g}, expected {wanted:.9g}")
        if abs(got - wanted) >= worst[0]:
            worst = (abs(got - wanted), name)
    results.append(("peaks", not failed, f"{len(blessed['peaks'])} peaks, largest difference {worst[0]:.3e} "
                    f"({worst[1] or 'none'})" + ("; " + "; ".join(failed[:5]) if failed else "")))


# ------------------------------------------------------------------------------------------------
# The whole manifest


class VerifyResult:
    """cases: [{name, observed, checks: [(check, passed, detail)], error}]; passed, failures,
    the files written (junit, markdown, json), blessed (the expected file written, or None)."""

    def __init__(self, manifest, cases, out, wall_time_s, blessed):
        self.manifest, self.cases, self.out, self.wall_time_s, self.blessed = manifest, cases, out, wall_time_s, blessed
        self.failures = sum(1 for c in cases for _, ok, _ in c["checks"] if not ok) + sum(
            1 for c in cases if c["error"])
        self.passed = self.failures == 0
        self.junit, self.markdown, self.json = out / "junit.xml", out / "verify.md", out / "verify.json"


def _provenance():
    return {"program_version": pounding.__version__, "git_commit": pounding._pounding.git_commit or None,
            "python": sys.version.split()[0], "host": socket.gethostname(),
            "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")}


def _read_blessed(manifest):
    if not manifest.expected_file.is_file():
        return {}
    try:
        document = json.loads(manifest.expected_file.read_text())
        return document["cases"]
    except (ValueError, KeyError, TypeError):
        raise _error(manifest.expected_file, "cases", "", "not an expected-results file of pounding verify "
                                                          "(write it again with --bless)") from None


def verify(manifest_path, out=None, jobs=None, bless=False, progress=True, isolate=None):
    """Runs every case of the manifest (jobs at a time: threads, the runs release the GIL; with
    isolate, or the manifest's isolate = true, each in a process of its own) and checks it; with
    bless, first writes the observed results as the expected ones (with provenance). A case with
    a reference is checked against that case's results of this run. Writes OUT/junit.xml,
    verify.md and verify.json (default out/verify-<manifest stem>). Returns a VerifyResult.
    @throws InputError for a bad manifest."""
    started = time.perf_counter()
    manifest = Manifest(manifest_path)
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise _error("", "--jobs", repr(jobs), "expected a whole number >= 1")
    out = pathlib.Path(out or pathlib.Path("out") / ("verify-" + re.sub(r"[^A-Za-z0-9_.-]", "-", manifest.name)))
    out.mkdir(parents=True, exist_ok=True)
    observe_one = observe_isolated if (manifest.isolate if isolate is None else isolate) else observe
    observed = _run_all(manifest, jobs or os.cpu_count() or 1, progress, observe_one)
    blessed_file = None
    if bless:  # a case that did not run keeps its earlier expected values
        kept = {name: o for name, o in _read_blessed(manifest).items() if "error" in observed.get(name, {})}
        document = {"manifest": manifest.file.name, "provenance": _provenance(),
                    "cases": {**kept, **{name: o for name, o in observed.items() if "error" not in o}}}
        manifest.expected_file.write_text(json.dumps(document, indent=1) + "\n")
        blessed_file = manifest.expected_file
    blessed = _read_blessed(manifest)
    cases = []
    for case in manifest.cases:
        o = observed[case["name"]]
        expected = observed[case["reference"]] if case["reference"] else blessed.get(case["name"])
        try:
            if "error" in o:
                checks = []
            elif expected is not None and "error" in expected:
                checks = [("reference", False, f"the reference case {case['reference']} did not run: "
                                               f"{expected['error']}")]
            else:
                checks = _checks(case, o, expected)
        except (TypeError, KeyError, ValueError, ZeroDivisionError) as error:  # a stored file of another shape
            checks = [("expected", False, f"cannot compare with the expected results ({type(error).__name__}: "
                                          f"{error}); bless them again")]
        cases.append({"name": case["name"], "observed": o, "checks": checks, "error": o.get("error")})
    result = VerifyResult(manifest, cases, out, time.perf_counter() - started, blessed_file)
    _write_junit(result)
    _write_markdown(result)
    result.json.write_text(json.dumps({"manifest": str(manifest.file.resolve()), "passed": result.passed,
                                       "failures": result.failures, "wall_time_s": result.wall_time_s,
                                       "provenance": _provenance(),
                                       "cases": [{"name": c["name"], "error": c["error"],
                                                  "checks": [{"check": n, "passed": ok, "detail": d}
                                                             for n, ok, d in c["checks"]],
                                                  "wall_time_s": c["observed"]["wall_time_s"]} for c in cases]},
                                      indent=1) + "\n")
    return result


def _run_all(manifest, jobs, progress, observe_one):
    observed, done, failed = {}, 0, 0
    show = progress and sys.stderr.isatty()
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(observe_one, case): case["name"] for case in manifest.cases}
        for future in concurrent.futures.as_completed(futures):
            observed[futures[future]] = future.result()
            done += 1
            failed += "error" in observed[futures[future]]
            if show:
                print(f"\rverify {manifest.name}: {done}/{len(futures)} cases run, {failed} errors",
                      end="", file=sys.stderr, flush=True)
    if show:
        print(file=sys.stderr)
    return observed


def _write_junit(result):
    """JUnit XML as Ant writes it (the schema CI servers read: tests/data/junit/JUnit.xsd): one
    testsuite, one testcase a check; a case that could not run is one testcase with an error."""
    testcases = [(c["name"], n, ok, d, c["observed"]["wall_time_s"]) for c in result.cases for n, ok, d in c["checks"]]
    errors = [c for c in result.cases if c["error"]]
    root = ElementTree.Element("testsuites")
    suite = ElementTree.SubElement(root, "testsuite", {
        "package": "pounding.verify", "id": "0", "name": result.manifest.name,
        "timestamp": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%S"),
        "hostname": socket.gethostname() or "localhost", "tests": str(len(testcases) + len(errors)),
        "failures": str(sum(1 for t in testcases if not t[2])), "errors": str(len(errors)),
        "time": f"{result.wall_time_s:.3f}"})
    properties = ElementTree.SubElement(suite, "properties")
    for name, value in _provenance().items():
        ElementTree.SubElement(properties, "property", {"name": name, "value": str(value)})
    for case, check, ok, detail, seconds in testcases:
        element = ElementTree.SubElement(suite, "testcase", {"classname": f"{result.manifest.name}.{case}",
                                                             "name": check, "time": f"{seconds:.3f}"})
        if not ok:
            ElementTree.SubElement(element, "failure", {"message": detail, "type": "tolerance"}).text = detail
    for case in errors:
        element = ElementTree.SubElement(suite, "testcase", {"classname": f"{result.manifest.name}.{case['name']}",
                                                             "name": "run", "time": "0"})
        ElementTree.SubElement(element, "error", {"message": case["error"], "type": "InputError"}).text = case["error"]
    ElementTree.SubElement(suite, "system-out").text = ""
    ElementTree.SubElement(suite, "system-err").text = ""
    ElementTree.ElementTree(root).write(result.junit, encoding="UTF-8", xml_declaration=True)


def _rows(result):
    for case in result.cases:
        if case["error"]:
            yield case["name"], "run", "ERROR", case["error"]
        for check, ok, detail in case["checks"]:
            yield case["name"], check, "pass" if ok else "FAIL", detail


def _cell(text):
    """Text fit for a markdown table cell."""
    return str(text).replace("|", "/").replace("\n", " ")


def _write_markdown(result):
    lines = [f"# pounding verify: {result.manifest.name}", "",
             f"{'All checks passed' if result.passed else f'{result.failures} failed'}; "
             f"{len(result.cases)} cases in {result.wall_time_s:.1f} s (`{result.manifest.file}`).", "",
             "| case | check | result | detail |", "|---|---|---|---|"]
    lines += [f"| {_cell(c)} | {k} | {r} | {_cell(d)} |" for c, k, r, d in _rows(result)]
    result.markdown.write_text("\n".join(lines) + "\n")


def _print_table(result):
    rows = list(_rows(result))
    width = max((len(c) for c, _, _, _ in rows), default=4)
    for case, check, outcome, detail in rows:
        print(f"{case:<{width}}  {check:<17} {outcome:<5} {detail}")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="pounding verify", description="Run a manifest's cases and check them "
                                     "against stored (--bless) or written expected results; JUnit XML and markdown "
                                     "in OUT; exit 1 when a check fails.")
    parser.add_argument("manifest", help="manifest file (TOML)")
    parser.add_argument("--bless", action="store_true", help="store this run's results as the expected ones first")
    parser.add_argument("--jobs", type=int, help="cases at a time (default: every core)")
    parser.add_argument("--out", help="output folder (default out/verify-<manifest name>)")
    parser.add_argument("--no-progress", action="store_true", help="no progress line")
    parser.add_argument("--isolate", action="store_true", default=None,
                        help="each case in a process of its own: a crash or a hang fails that case only")
    arguments = parser.parse_args(argv)
    try:
        result = verify(arguments.manifest, out=arguments.out, jobs=arguments.jobs, bless=arguments.bless,
                        progress=not arguments.no_progress, isolate=arguments.isolate)
    except InputError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    _print_table(result)
    if result.blessed:
        print(f"Blessed: wrote the expected results to {result.blessed}")
    print(f"{'All checks passed' if result.passed else f'{result.failures} checks failed'} "
          f"({len(result.cases)} cases, {result.wall_time_s:.1f} s); wrote {result.junit}, {result.markdown.name}, "
          f"{result.json.name}")
    return 0 if result.passed else 1


if __name__ == "__main__":
    from pounding.verify import main as _main
    sys.exit(_main())
