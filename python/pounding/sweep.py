"""Sweeps: the Cartesian product scenes × records × gaps × restitutions × methods × contact laws
of a sweep file, one run each, on Dask distributed, into one tidy table.

    python3 -m pounding.sweep SWEEP.toml [--workers N | --scheduler tcp://HOST:PORT | --serial] [--out DIR]
    pounding.sweep("SWEEP.toml", workers=2)          # the same from Python; returns a SweepResult

The sweep file (TOML; paths relative to its folder; README, "Sweeps"):

    scenes = ["../paper/el-centro-true-time.toml"]   # required
    records = "../records/set.txt"     # a record list, a folder of .AT2 files, or a list of paths
                                       # and tables {file, format, units, dt_s, accel_column, scale,
                                       # pga_g, direction_deg}; absent: each scene's own record
    directions_deg = [0, 45, 90]       # the records' angles (H1's; a pair's H2 at + 90); absent: as each record says
    gaps_m = [0.05, 0.1]               # absent: the scene's gap; a row's: tables of pair gaps,
                                       # [{"B1:B2" = 0.1, "B2:B3" = 0.05}] (each pair named is moved)
    restitutions = [0.5]               # absent: the scene's
    methods = ["cvode-bdf", {name = "arkode-erk", rtol = 1e-8}]   # absent: the scene's
    contact_laws = ["impulse", {name = "kelvin", stiffness_kN_per_m = 1e5},
                    {name = "hertzdamp", stiffness_kN_per_m1_5 = 1e7}]  # absent: the scene's
    needed_gap = true                  # also the needed gap of each scene under each record;
                                       # "all_angles": and over every angle (gap --all-angles)
    max_wall_time_s = 600              # each run's budget (absent: the module's default, an hour)
    out = "../../out/sweep"            # absent: out/<sweep file name> in the current folder

Workers get parameters (paths and numbers) and build their scene themselves: Scene objects do not
pickle. Each finished run is appended to sweep.csv at once (flushed), a failed run as a row with
its status and message; a sweep started again skips the runs its table already holds (the key is
the parameter columns). The needed gap does not depend on the gap, the restitution, the method or
the contact law, so it is run once per scene and record, and the runs of that pair wait for it.
"""

import argparse
import csv
import datetime
import hashlib
import io
import itertools
import json
import logging
import math
import os
import re
import pathlib
import signal
import socket
import sys
import time
import tomllib
import types

import pounding
from pounding import InputError
from pounding import _input_error as _error  # InputError with the library's message

# The keys of a sweep file, and what each record table may set (the record list's fields).
SWEEP_KEYS = ("scenes", "records", "directions_deg", "gaps_m", "restitutions", "methods", "contact_laws", "needed_gap",
              "max_wall_time_s", "out")
RECORD_FIELDS = {"file": "file", "format": "format", "units": "units", "dt_s": "dt_s",
                 "accel_column": "accel_column", "scale_factor": "scale_factor", "scale_to_pga_g": "scale_to_pga_g",
                 "scale_to_sa": "scale_to_sa", "direction_deg": "direction_deg", "record2": "record2",
                 "record2_column": "record2_column",
                 "scale": "scale_factor", "pga_g": "scale_to_pga_g", "sa": "scale_to_sa"}  # the short names last
# field -> Scene.with_record keyword: the scaling fields under the scene's names, or the record
# list's short ones (scale, pga_g, sa)
SECOND_KEYS = {"excitation.second.file": "record2", "excitation.second.accel_column": "record2_column"}
STIFFNESS_KEYS = ("stiffness_kN_per_m", "stiffness_kN_per_m1_5")  # kelvin; the Hertz laws
LAW_KEYS = ("name", *STIFFNESS_KEYS)

# Columns of sweep.csv after the parameters (which are PARAMETERS, then one column a [solver]
# setting the sweep sets). Timings last: the only columns two sweeps of one file may differ in.
PARAMETERS = ("scene_file", "scene", "record", "record_source", "gap_m", "restitution", "contact_law",
              "contact_stiffness", "method")
RESULTS = ("status", "message", "impact_count", "touch_count", "sustained_contact_count", "first_impact_s",
           "max_impulse_kNs", "max_approach_speed_mps", "impact_loss_kJ",
           "b1_peak_u_m", "b1_peak_v_m", "b1_peak_phi_rad", "b2_peak_u_m", "b2_peak_v_m", "b2_peak_phi_rad", "steps")
NEEDED_GAP = ("needed_gap_m", "needed_gap_level", "needed_gap_t_s", "needed_gap_status")
# needed_gap = "all_angles": also the needed gap over every angle of incidence and its angle.
ALL_ANGLES = ("all_angles_needed_gap_m", "all_angles_angle_deg")
# Written when some scene of the sweep has yielding columns: each building's largest storey
# ductility, the energy the columns dissipated and their branch changes.
YIELDING = ("b1_max_ductility", "b2_max_ductility", "hysteretic_kJ", "yield_events")
# Written when some scene of the sweep has slabs that can strike columns: how many impacts were
# slab to column, the largest shear they caused in a column and (with a capacity) its ratio.
SLAB_TO_COLUMN = ("slab_to_column_impact_count", "max_column_shear_kN", "max_column_shear_ratio")
# Written when some scene of the sweep asks for the run without contact ([output]
# contact_free_reference): each building's largest storey drift ratio at the CM (over x and y),
# with contact and without.
POUNDING_DEMAND = ("b1_max_drift_ratio", "b1_max_drift_ratio_no_contact", "b2_max_drift_ratio",
                   "b2_max_drift_ratio_no_contact")
TIMINGS = ("solver_time_s", "wall_time_s")
# A row's columns, written when some scene of the sweep is a row: the peaks of its buildings
# beyond the second (b3_peak_u_m, ...), then per neighbouring pair its impacts and, with
# needed_gap, its needed gap ("impact_count B1:B2", "needed_gap_m B1:B2").
PEAK_QUANTITIES = ("u_m", "v_m", "phi_rad")


def building_peak_columns(count):
    """The peak columns of buildings 3 ... count (1 and 2 are in RESULTS)."""
    return [f"b{k}_peak_{quantity}" for k in range(3, count + 1) for quantity in PEAK_QUANTITIES]


def pair_impact_column(pair):
    return f"impact_count {pair}"


def pair_needed_gap_column(pair):
    return f"needed_gap_m {pair}"


def _text(value):
    """A sweep file's value as the messages show it (TOML-like)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    return repr(value)


# ------------------------------------------------------------------------------------------------
# The sweep file


def _refuse_nul(file, value, key=""):
    """InputError naming the first string of the document that holds a NUL character (TOML's
    "\u0000"): no path or name may hold one, and the operating system refuses it with a
    ValueError that names nothing."""
    if isinstance(value, str) and "\0" in value:
        raise _error(file, key, _text(value), "holds a NUL character")
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    for part, item in items:
        _refuse_nul(file, item, f"{key}.{part}" if isinstance(part, str) and key else
                    part if isinstance(part, str) else f"{key}[{part + 1}]")


class Sweep:
    """A checked sweep file: the product's axes as plain values (what the workers get)."""

    def __init__(self, file):
        self.file = pathlib.Path(file)
        self.folder = self.file.resolve().parent
        try:
            raw = self.file.read_bytes()
        except OSError as error:
            raise _error(self.file, "", "", f"cannot read the sweep file: {error.strerror}") from None
        self.sha256 = hashlib.sha256(raw).hexdigest()
        try:
            document = tomllib.loads(raw.decode("utf-8"))
        except (UnicodeDecodeError, tomllib.TOMLDecodeError) as error:
            raise _error(self.file, "", "", f"not a TOML file: {error}") from None
        _refuse_nul(self.file, document)
        for key in document:
            if key not in SWEEP_KEYS:
                raise _error(self.file, key, _text(document[key]), f"unknown key (expected {', '.join(SWEEP_KEYS)})")
        self.document = document

        self.scene_files = self._paths("scenes", required=True)
        self.scenes = {}  # scene_file as written -> loaded Scene (driver only)
        for scene_file in self.scene_files:
            self.scenes[scene_file] = pounding.load_scene(self._resolve(scene_file))
        self.directions = self._numbers("directions_deg")
        self.gaps_m = self._numbers("gaps_m")
        self.restitutions = self._numbers("restitutions")
        self.laws = self._laws()
        self.methods = self._methods()
        self.setting_keys = [k for k in pounding.settings() if any(k in m["settings"] for m in self.methods)]
        self.all_angles = self.document.get("needed_gap") == "all_angles"
        self.needed_gap = True if self.all_angles else self._flag("needed_gap")
        self.max_wall_time_s = None
        if "max_wall_time_s" in document:
            value = document["max_wall_time_s"]
            if not _is_number(value) or not value > 0 or not math.isfinite(value):
                raise _error(self.file, "max_wall_time_s", _text(value), "expected a finite number of seconds > 0")
            self.max_wall_time_s = float(value)
        self.out = None
        if "out" in document:
            if not isinstance(document["out"], str) or not document["out"]:
                raise _error(self.file, "out", _text(document["out"]), "expected a folder's path")
            self.out = self._resolve(document["out"])
        self.records = self._records()
        self._check_combinations()

    def _resolve(self, path):
        """An absolute path: relative ones from the sweep file's folder."""
        return str((self.folder / path).resolve())

    def _list(self, key, required=False):
        if key not in self.document:
            if required:
                raise _error(self.file, key, "", "missing (a list)")
            return None
        value = self.document[key]
        if not isinstance(value, list) or not value:
            raise _error(self.file, key, _text(value), "expected a list that is not empty")
        return value

    def _paths(self, key, required=False):
        values = self._list(key, required)
        for index, value in enumerate(values):
            if not isinstance(value, str) or not value:
                raise _error(self.file, f"{key}[{index + 1}]", _text(value), "expected a file's path")
            if not os.path.isfile(self._resolve(value)):
                raise _error(self.file, f"{key}[{index + 1}]", _text(value), "no such file")
            if self._resolve(value) in map(self._resolve, values[:index]):
                raise _error(self.file, f"{key}[{index + 1}]", _text(value), "given twice")
        return values

    def _numbers(self, key):
        values = self._list(key)
        if values is None:
            return [None]
        for index, value in enumerate(values):
            pair_gaps = key == "gaps_m" and isinstance(value, dict) and value and all(map(_is_number, value.values()))
            if not _is_number(value) and not pair_gaps:
                raise _error(self.file, f"{key}[{index + 1}]", _text(value),
                             "expected a number (gaps_m: or a row's table of pair gaps, {\"B1:B2\" = m, ...})")
            for scene_file in self.scene_files:  # each scene checks its own range (a gap must fit its plan)
                try:
                    if key == "directions_deg":
                        self.scenes[scene_file].with_direction(float(value))
                        continue
                    option = {"gaps_m": "gap", "restitutions": "restitution"}[key]
                    pounding.load_scene(self._resolve(scene_file), **{option: _number_or_pairs(value)})
                except InputError as error:
                    raise _error(self.file, f"{key}[{index + 1}]", _text(value),
                                 f"{error.reason} (scene {scene_file})") from None
        values = [_number_or_pairs(v) for v in values]
        if len({_gap_text(v) for v in values}) != len(values):
            raise _error(self.file, key, _text(values), "a value is given twice")
        return values

    def _flag(self, key):
        value = self.document.get(key, False)
        if not isinstance(value, bool):
            raise _error(self.file, key, _text(value), "expected true or false")
        return value

    def _named_entries(self, key, allowed):
        """A list of names or tables {name, ...}; returns dicts with a name."""
        entries = []
        for index, item in enumerate(self._list(key)):
            where = f"{key}[{index + 1}]"
            if isinstance(item, str):
                item = {"name": item}
            if not isinstance(item, dict) or not isinstance(item.get("name"), str):
                raise _error(self.file, where, _text(item), "expected a name or a table with a name")
            for field, value in item.items():
                if allowed is not None and field not in allowed:
                    raise _error(self.file, f"{where}.{field}", _text(value),
                                 f"unknown field (expected {', '.join(allowed)})")
            entries.append(dict(item))
        return entries

    def _laws(self):
        if "contact_laws" not in self.document:
            return [{"name": None, "stiffness": None}]
        laws = []
        for index, entry in enumerate(self._named_entries("contact_laws", LAW_KEYS)):
            law = {"name": entry["name"], "stiffness": self._law_stiffness(index, entry)}
            for scene_file in self.scene_files:
                try:
                    pounding.load_scene(self._resolve(scene_file), contact_law=law["name"],
                                        contact_stiffness=law["stiffness"])
                except InputError as error:
                    field = _stiffness_field(entry) if error.key == "--contact-stiffness" else "name"
                    raise _error(self.file, f"contact_laws[{index + 1}].{field}", error.value,
                                 f"{error.reason} (scene {scene_file})") from None
            if law in laws:
                raise _error(self.file, f"contact_laws[{index + 1}]", _text(entry), "given twice")
            laws.append(law)
        return laws

    def _law_stiffness(self, index, entry):
        """The entry's stiffness, given under the law's own key (its unit: kN/m or kN/m^1.5)."""
        field = _stiffness_field(entry)
        if field is None:
            return None
        stiffness = entry[field]
        try:
            expected = pounding._pounding.contact_law_stiffness_key(entry["name"])
        except InputError as error:
            raise _error(self.file, f"contact_laws[{index + 1}].name", error.value, error.reason) from None
        if field != expected:
            raise _error(self.file, f"contact_laws[{index + 1}].{field}", _text(stiffness),
                         f"not a stiffness of {entry['name']}" + (f" (its key is {expected})" if expected else ""))
        if not _is_number(stiffness):
            raise _error(self.file, f"contact_laws[{index + 1}].{field}", _text(stiffness), "expected a number")
        return float(stiffness)

    def _methods(self):
        if "methods" not in self.document:
            return [{"name": None, "settings": {}}]
        methods = []
        keys = ["name", *pounding.settings()]
        for index, entry in enumerate(self._named_entries("methods", keys)):
            method = {"name": entry.pop("name"), "settings": entry}
            for scene_file, scene in self.scenes.items():
                try:
                    scene.with_method(method["name"], **method["settings"])
                except InputError as error:
                    field = error.key.removeprefix("solver.")
                    field = "name" if field == "method" else field
                    raise _error(self.file, f"methods[{index + 1}].{field}", error.value,
                                 f"{error.reason} (scene {scene_file})") from None
            if method in methods:
                raise _error(self.file, f"methods[{index + 1}]", _text(method["name"]), "given twice")
            methods.append(method)
        return methods

    def _records(self):
        """One dict a record: name, source and the with_record keywords (None: the scene's record)."""
        if "records" not in self.document:
            return [None]
        value = self.document["records"]
        if isinstance(value, str):
            return self._record_list(value)
        records = []
        for index, item in enumerate(self._list("records")):
            where = f"records[{index + 1}]"
            if isinstance(item, str):
                item = {"file": item}
            if not isinstance(item, dict) or not isinstance(item.get("file"), str):
                raise _error(self.file, where, _text(item), "expected a record's path or a table with a file")
            choice = dict.fromkeys(RECORD_FIELDS.values())
            for field, given in item.items():
                if field not in RECORD_FIELDS:
                    raise _error(self.file, f"{where}.{field}", _text(given),
                                 f"unknown field (expected {', '.join(list(RECORD_FIELDS)[:-3])}; scale, pga_g "
                                 "and sa are short for the scaling fields)")
                if choice[RECORD_FIELDS[field]] is not None:  # scale_to_pga_g and pga_g both given
                    other = next(f for f in item if f != field and RECORD_FIELDS.get(f) == RECORD_FIELDS[field])
                    raise _error(self.file, f"{where}.{field}", _text(given), f"given twice (also as {other})")
                choice[RECORD_FIELDS[field]] = given
            choice["file"] = self._resolve(item["file"])
            if isinstance(choice["record2"], str):  # a pair's second component, from the sweep file's folder
                choice["record2"] = self._resolve(choice["record2"])
            for scene_file, scene in self.scenes.items():  # checked as a record list's line is, not read
                try:
                    scene.with_record(**choice, read=False)
                except (InputError, TypeError) as error:
                    key = getattr(error, "key", "")
                    key = SECOND_KEYS.get(key, key.removeprefix("excitation."))
                    field = next((f for f in item if RECORD_FIELDS.get(f) == key), key)  # as the table spelled it
                    raise _error(self.file, f"{where}.{field}" if field else where,
                                 getattr(error, "value", _text(item)),
                                 f"{getattr(error, 'reason', str(error))} (scene {scene_file})") from None
            name = os.path.basename(item["file"])
            if isinstance(item.get("record2"), str):
                name += "+" + os.path.basename(item["record2"])
            records.append({"name": name, "source": f"{self.file.name}:{where}", **choice})
        seen = {}
        for index, record in enumerate(records):  # the same file with the same options: one run twice
            same = tuple(sorted((k, str(v)) for k, v in record.items() if k not in ("name", "source")))
            if same in seen:
                raise _error(self.file, f"records[{index + 1}]", _text(value[index]),
                             f"the same record as records[{seen[same] + 1}]: a record is given twice")
            seen[same] = index
        return records

    def _record_list(self, path):
        resolved = self._resolve(path)
        lists = []
        for scene_file, scene in self.scenes.items():
            try:
                entries = pounding.record_list(scene, resolved)
            except InputError as error:
                if error.key == "--records":
                    raise _error(self.file, "records", _text(path), error.reason) from None
                raise  # a line of the list: the error names list:line, the field and the value
            lists.append(entries)
        for entries in lists:
            for entry in entries:  # "set.txt:12" with the list named as the sweep file names it
                entry["source"] = path + entry["source"].removeprefix(resolved)
        if any(entries != lists[0] for entries in lists):
            raise _error(self.file, "records", _text(path), "its records differ from scene to scene")
        return lists[0]

    def _check_combinations(self):
        """Each law with each method on each scene (kelvin does not run on hht or exact)."""
        for scene_file in self.scene_files:
            for law_index, law in enumerate(self.laws):
                scene = pounding.load_scene(self._resolve(scene_file), contact_law=law["name"],
                                            contact_stiffness=law["stiffness"])
                for method_index, method in enumerate(self.methods):
                    try:
                        scene.with_method(method["name"], **method["settings"])
                    except InputError as error:
                        raise _error(self.file, f"methods[{method_index + 1}]", _text(method["name"]),
                                     f"{error.reason} (contact_laws[{law_index + 1}], scene {scene_file})") from None

    def parameter_columns(self):
        """PARAMETERS, with direction_deg after the record's columns when the sweep turns records."""
        if self.directions == [None]:
            return list(PARAMETERS)
        at = PARAMETERS.index("record_source") + 1
        return [*PARAMETERS[:at], "direction_deg", *PARAMETERS[at:]]

    def columns(self):
        yielding = YIELDING if any(scene.yielding for scene in self.scenes.values()) else ()
        columns = SLAB_TO_COLUMN if any(scene.slab_to_column for scene in self.scenes.values()) else ()
        demand = POUNDING_DEMAND if any(scene.contact_free_reference for scene in self.scenes.values()) else ()
        rows = [scene for scene in self.scenes.values() if len(scene.building_names) > 2]
        pairs = list(dict.fromkeys(pair for scene in rows for pair, _ in scene.pair_gaps))
        buildings = max((len(scene.building_names) for scene in rows), default=2)
        return [*self.parameter_columns(), *self.setting_keys, *RESULTS, *building_peak_columns(buildings),
                *map(pair_impact_column, pairs), *yielding, *columns, *demand,
                *(NEEDED_GAP if self.needed_gap else ()),
                *(map(pair_needed_gap_column, pairs) if self.needed_gap else ()),
                *(ALL_ANGLES if self.all_angles else ()),
                *TIMINGS]

    def runs(self):
        """Every run of the product, as (row parameters, task parameters), in product order."""
        for scene_file, scene in self.scenes.items():
            for record, direction in itertools.product(self.records, self.directions):
                for gap_m in self.gaps_m:
                    for restitution in self.restitutions:
                        for law in self.laws:
                            for method in self.methods:
                                yield self._run(scene_file, scene, (record, direction), gap_m, restitution, law,
                                                method)

    def _run(self, scene_file, scene, turned_record, gap_m, restitution, law, method):
        record, direction = turned_record
        # The row names the scene's own value where the sweep leaves one to the scene; the task
        # gets None there, so the worker runs the scene file as it is.
        row = {"scene_file": scene_file, "scene": scene.name,
               "record": record["name"] if record else os.path.basename(str(scene.record_file)),
               "record_source": record["source"] if record else "scene",
               **({} if direction is None else {"direction_deg": direction}),
               "gap_m": _gap_text(_scene_gap(scene) if gap_m is None else gap_m),
               "restitution": scene.restitution if restitution is None else restitution,
               "contact_law": law["name"] or scene.contact_law,
               "contact_stiffness": law["stiffness"],
               "method": method["name"] or scene.method}
        row.update({key: method["settings"].get(key) for key in self.setting_keys})
        task = {"scene_file": self._resolve(scene_file), "gap_m": gap_m, "restitution": restitution,
                "contact_law": law["name"], "contact_stiffness": law["stiffness"],
                "record": _record_keywords(record), "direction_deg": direction, "all_angles": self.all_angles,
                "method": method["name"],
                "settings": method["settings"],
                "max_wall_time_s": self.max_wall_time_s}
        return row, task

    def parameters(self):
        """The resolved axes, for sweep.json."""
        return {"scenes": self.scene_files, "records": [r and {"name": r["name"], "source": r["source"]} for r in
                                                        self.records],
                "directions_deg": self.directions, "gaps_m": self.gaps_m, "restitutions": self.restitutions, "contact_laws": self.laws,
                "methods": self.methods, "needed_gap": "all_angles" if self.all_angles else self.needed_gap,
                "max_wall_time_s": self.max_wall_time_s}


def _stiffness_field(entry):
    """Which stiffness key a contact_laws entry gives, or None."""
    given = [key for key in STIFFNESS_KEYS if key in entry]
    return given[0] if given else None


def _number_or_pairs(value):
    """A gap (float) or a row's pair gaps ({"B1:B2": float, ...})."""
    return {str(k): float(v) for k, v in value.items()} if isinstance(value, dict) else float(value)


def _scene_gap(scene):
    """The scene's own gap: two buildings' number, a row's pair gaps."""
    return dict(scene.pair_gaps) if len(scene.building_names) > 2 else scene.gap_m


def _gap_text(gap):
    """The gap_m column: the number, or a row's "B1:B2=0.1;B2:B3=0.05"."""
    return ";".join(f"{pair}={value!r}" for pair, value in gap.items()) if isinstance(gap, dict) else gap


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _record_keywords(record):
    return None if record is None else {k: v for k, v in record.items() if k not in ("name", "source")}


# ------------------------------------------------------------------------------------------------
# What a worker runs: plain parameters in, a plain dict out; never raises for a run's failure.


def _scene(task):
    scene = pounding.load_scene(task["scene_file"], gap=task.get("gap_m"), restitution=task.get("restitution"),
                                contact_law=task.get("contact_law"),
                                contact_stiffness=task.get("contact_stiffness"))
    if task["record"] is not None:
        scene = scene.with_record(**task["record"])
    if task.get("direction_deg") is not None:
        scene = scene.with_direction(task["direction_deg"])
    return scene


def _failure(error):
    return str(error) if isinstance(error, InputError) else f"{type(error).__name__}: {error}"


def needed_gap_task(task):
    """The needed gap of the task's scene (its own gap and tolerances) under its record; of a row,
    each neighbouring pair's (`pounding gap` on a row), the largest in needed_gap_m."""
    try:
        scene = _scene({"scene_file": task["scene_file"], "record": task["record"],
                        "direction_deg": task.get("direction_deg")})
        if len(scene.building_names) > 2:
            return _row_needed_gaps(scene, task)
        gap = pounding.needed_gap(scene, max_wall_time_s=task.get("max_wall_time_s"),
                                  all_angles=task.get("all_angles", False))
    except Exception as error:  # noqa: BLE001  (a record that cannot be read: the rows say so)
        failed = {"needed_gap_m": None, "needed_gap_level": None, "needed_gap_t_s": None,
                  "needed_gap_status": "failed: " + _failure(error)}
        return {**failed, **({key: None for key in ALL_ANGLES} if task.get("all_angles") else {})}
    finite = gap.needed_gap_m is not None and math.isfinite(gap.needed_gap_m)
    row = {"needed_gap_m": gap.needed_gap_m if finite else None, "needed_gap_level": gap.level or None,
           "needed_gap_t_s": gap.t_s if finite else None, "needed_gap_status": gap.status}
    if gap.all_angles:
        row.update({"all_angles_needed_gap_m": gap.all_angles["needed_gap_m"],
                    "all_angles_angle_deg": gap.all_angles["angle_deg"]})
    return row


def _row_needed_gaps(scene, task):
    """A row's needed gaps, pair by pair (each pair's own contact-free run: the buildings move
    independently without contact): a column each, and in needed_gap_m and _t_s the pair that
    needs the most; the status the first pair's that did not complete, or "completed"."""
    if task.get("all_angles"):
        raise _error(task["scene_file"], "needed_gap", '"all_angles"',
                     "takes scenes of two buildings; this one is a row (run it on one pair's scene)")
    row, worst, status = {}, None, "completed"
    for pair, _, two in scene.pair_scenes():
        gap = pounding.needed_gap(two, max_wall_time_s=task.get("max_wall_time_s"))
        finite = gap.needed_gap_m is not None and math.isfinite(gap.needed_gap_m)
        row[pair_needed_gap_column(pair)] = gap.needed_gap_m if finite else None
        if gap.status != "completed" and status == "completed":
            status = f"{pair}: {gap.status}"
        if finite and (worst is None or gap.needed_gap_m > worst.needed_gap_m):
            worst = gap
    # The pair's level numbers are its own scene's, not the row's: left empty.
    row.update({"needed_gap_m": worst.needed_gap_m if worst else None, "needed_gap_level": None,
                "needed_gap_t_s": worst.t_s if worst else None, "needed_gap_status": status})
    return row


def run_task(task, needed_gap=None):
    """One run of the sweep: its result columns (RESULTS, TIMINGS and, given, the needed gap's)."""
    start = time.perf_counter()
    row = dict.fromkeys(RESULTS)
    try:
        # A row keeps impact statistics and displacement peaks only (_summarise): the run computes
        # no history and no other peaks, but the drifts a contact-free reference compares.
        scene = _scene(task)
        scene = scene.with_outputs(history=False,
                                   peaks=["displacements", *(["drifts"] if scene.contact_free_reference else [])])
        result = pounding.run(scene, method=task["method"], max_wall_time_s=task.get("max_wall_time_s"),
                              **task["settings"])
        row.update(_summarise(result))
    except Exception as error:  # noqa: BLE001  (a failed run is a row with its message, never a lost row)
        row.update(status="failed", message=_failure(error))
    if needed_gap is not None:
        row.update(needed_gap)
    row["wall_time_s"] = time.perf_counter() - start
    return row


def _summarise(result):
    impacts = result.impacts
    row = {"status": result.status, "message": result.status_detail or "",
           "impact_count": len(impacts), "touch_count": len(result.touches),
           "sustained_contact_count": len(result.sustained_contacts),
           "first_impact_s": min((i["t_s"] for i in impacts), default=None),
           "max_impulse_kNs": max((abs(i["impulse_kNs"]) for i in impacts), default=0.0),
           "max_approach_speed_mps": max((abs(i["approach_velocity_mps"]) for i in impacts), default=0.0),
           "impact_loss_kJ": result.energy["impact_loss_kJ"],
           "steps": result.statistics["steps"], "solver_time_s": result.statistics["wall_time_s"]}
    for number, building in enumerate(result.peaks, start=1):
        for quantity in PEAK_QUANTITIES:
            row[f"b{number}_peak_{quantity}"] = max(abs(f[quantity]["value"]) for f in building["floors"])
    for pair, count in result.summary.get("impacts_by_pair", {}).items():
        row[pair_impact_column(pair)] = count
    if result.yielding is not None:
        for building in result.yielding["buildings"]:
            row[f"b{building['building']}_max_ductility"] = max(
                max(s["peak_ductility_x"], s["peak_ductility_y"]) for s in building["storeys"])
        row["hysteretic_kJ"] = result.yielding["hysteretic_kJ"]
        row["yield_events"] = result.yielding["yield_events"]
    if "pounding_demand" in result.summary:
        for prefix, building in zip(("b1", "b2"), result.summary["pounding_demand"]["buildings"][:2]):
            for suffix, side in (("", "with"), ("_no_contact", "without")):
                row[f"{prefix}_max_drift_ratio{suffix}"] = max(
                    max(s["drift_x"][side], s["drift_y"][side]) for s in building["storeys"])
    if "impacts_slab_to_column" in result.summary:
        on_columns = [i for i in impacts if i["level"] == 0]
        row["slab_to_column_impact_count"] = len(on_columns)
        row["max_column_shear_kN"] = max((i["column_shear_kN"] for i in on_columns), default=0.0)
        ratios = [i["column_shear_ratio"] for i in on_columns if i["column_shear_ratio"] is not None]
        row["max_column_shear_ratio"] = max(ratios) if ratios else None
    return row


def _worker_identity():
    return pounding.__version__, pounding._pounding.git_commit


def _probe_identity():
    """A worker's pounding (version, commit), or ("not importable", why). The probe is built inside
    a function so that Dask (cloudpickle) sends its code, not a reference into pounding.sweep: a
    worker without the module answers instead of logging a traceback while unpickling it."""
    def probe():
        try:
            import pounding as module
            import pounding._pounding as extension
        except ImportError as error:
            return "not importable", f"{type(error).__name__}: {error}"
        return module.__version__, extension.git_commit
    return probe


# ------------------------------------------------------------------------------------------------
# The table


def _cell(value):
    """A CSV cell: floats as repr (the shortest text that reads back to the same bits), None empty."""
    if value is None:
        return ""
    if isinstance(value, float):
        return "" if math.isnan(value) else repr(value)
    return str(value)


def _create_no_follow(path):
    """A new text handle on `path` created afresh: whatever stands there (a file, or a symbolic link
    planted in a shared results folder) is unlinked — the link itself, never its target — and the
    file is created with O_EXCL | O_NOFOLLOW, so nothing is ever written through a link."""
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o666)
    return os.fdopen(fd, "w", newline="")


def _replace_no_follow(path, text):
    """Writes `text` to `path` whole: into PATH.partial created afresh, then renamed over `path`
    (a rename replaces a link standing at `path`, it never follows it)."""
    partial = pathlib.Path(str(path) + ".partial")
    with _create_no_follow(partial) as handle:
        handle.write(text)
    partial.replace(path)


class Table:
    """sweep.csv, appended a row at a time and flushed; reads back the keys of the rows it holds."""

    def __init__(self, path, columns, key_columns):
        self.path, self.columns, self.key_columns = pathlib.Path(path), list(columns), list(key_columns)
        self.keys = set()
        self.rows = 0
        if self.path.is_symlink():
            raise _error("", "out", str(self.path.parent),
                         f"{self.path.name} is a symbolic link; pounding writes only files of its own there: remove it")
        if self.path.exists():
            self._read_existing()
        if self.path.exists():  # a regular file (links refused above): appended, never followed
            fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_NOFOLLOW | os.O_CLOEXEC)
            self.handle = os.fdopen(fd, "a", newline="")
        else:
            self.handle = _create_no_follow(self.path)
        if self.rows == 0 and self.path.stat().st_size == 0:
            self._write(self.columns)

    def _read_existing(self):
        text = self.path.read_text()
        if text and not text.endswith("\n"):  # a row cut off by a kill: drop it, the run is redone
            text = text[: text.rfind("\n") + 1]
            _replace_no_follow(self.path, text)
        rows = list(csv.reader(io.StringIO(text)))
        if not rows:
            return
        if rows[0] != self.columns:
            raise _error("", "out", str(self.path.parent),
                         f"{self.path.name} holds another sweep's columns ({', '.join(rows[0])}); "
                         "remove it or choose another output folder")
        for cells in rows[1:]:
            self.keys.add(tuple(cells[self.columns.index(c)] for c in self.key_columns))
            self.rows += 1

    def key(self, row):
        return tuple(_cell(row.get(c)) for c in self.key_columns)

    def _write(self, cells):
        text = io.StringIO()
        csv.writer(text, lineterminator="\n").writerow(cells)
        self.handle.write(text.getvalue())
        self.handle.flush()

    def append(self, row):
        self._write([_cell(row.get(c)) for c in self.columns])
        self.keys.add(self.key(row))
        self.rows += 1

    def close(self):
        self.handle.close()


TEXT_COLUMNS = {"scene_file", "scene", "record", "record_source", "contact_law", "method", "status", "message",
                "needed_gap_status"}
INTEGER_COLUMNS = {"impact_count", "touch_count", "sustained_contact_count", "steps", "needed_gap_level",
                   "yield_events", "slab_to_column_impact_count"}


def _typed(column, text):
    """A cell of sweep.csv as the value it was written from: None for an empty cell, text for the
    TEXT_COLUMNS and a row's pair gaps, int for the INTEGER_COLUMNS, float for the other results and parameters, and for
    a [solver] setting's column an int, a float or its text, whichever reads (order, rtol, newton)."""
    if text == "":
        return None
    if column in TEXT_COLUMNS:
        return text
    if column in INTEGER_COLUMNS or column.startswith("impact_count "):
        return int(text)
    if column == "gap_m" and "=" in text:  # a row's pair gaps, "B1:B2=0.2;B2:B3=0.1"
        return text
    if column in RESULTS or column in NEEDED_GAP or column in YIELDING or column in SLAB_TO_COLUMN \
            or column in POUNDING_DEMAND or column in TIMINGS \
            or column in PARAMETERS \
            or column in ALL_ANGLES or column == "direction_deg" \
            or column.startswith("needed_gap_m ") or re.fullmatch(r"b\d+_peak_[a-z_]+", column):
        return float(text)
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def read_table(path, typed=True):
    """sweep.csv as a list of dicts, a row a run: with typed, each cell as its type (_typed: None,
    str, int or float; floats bit for bit as run); without, as text (empty cells for missing values)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [{column: _typed(column, text) for column, text in row.items()} for row in rows] if typed else rows


# ------------------------------------------------------------------------------------------------
# Running


class SweepResult:
    """What run_sweep did: the table's path, its rows (dicts of typed values, as read back:
    read_table; frame() is the same table as a pandas DataFrame), how many runs
    this call executed and skipped (already in the table), how many rows did not complete, and
    whether runs of the product are still missing (interrupted)."""

    def __init__(self, out, executed, skipped, interrupted):
        self.out = pathlib.Path(out)
        self.csv = self.out / "sweep.csv"
        self.rows = read_table(self.csv)
        self.executed, self.skipped, self.interrupted = executed, skipped, interrupted
        # A run that did not complete, or whose needed gap failed, is a failed row.
        self.failed = sum(row["status"] != "completed" or str(row.get("needed_gap_status") or "").startswith("failed")
                          for row in self.rows)

    def frame(self):
        """The rows as a pandas DataFrame (Debian python3-pandas), a column a sweep.csv column."""
        import pandas
        return pandas.DataFrame(self.rows, columns=list(self.rows[0]) if self.rows else None)

    def __repr__(self):
        return (f"<pounding.sweep.SweepResult {len(self.rows)} rows in {self.csv}: {self.executed} run now, "
                f"{self.skipped} skipped, {self.failed} not completed>")


def run_sweep(sweep_file, out=None, workers=None, scheduler=None, progress=True, max_runs=None):
    """Runs the sweep file's product into `out` (default: the file's `out`, else out/<file stem>
    from the current folder): sweep.csv (a row a run, appended as runs finish), sweep.parquet when
    pyarrow imports, sweep.json (provenance and counts).

    workers: None, every core of a LocalCluster (processes, one thread each); N > 0, N of them;
    0, no Dask at all: the runs in this process, one after another. scheduler: the address of a
    running Dask scheduler (tcp://HOST:PORT) instead of a LocalCluster; its workers need
    `pounding` importable (the same build) and the sweep's files at the same paths.
    max_runs: stop after this many runs (then the sweep is incomplete, as if interrupted).
    Runs already in sweep.csv are skipped. Returns a SweepResult.
    @throws InputError for a bad sweep file (naming the file, the key and the value)."""
    started = time.perf_counter()
    date_utc = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    sweep = Sweep(sweep_file)
    if workers is not None and (not isinstance(workers, int) or isinstance(workers, bool) or workers < 0):
        raise _error("", "--workers", _text(workers), "expected a whole number >= 0")
    if scheduler is not None and workers is not None:
        raise _error("", "--workers", _text(workers), "not with --scheduler (the cluster has its workers)")
    if max_runs is not None and (not isinstance(max_runs, int) or max_runs < 0):
        raise _error("", "max_runs", _text(max_runs), "expected a whole number >= 0")
    out = pathlib.Path(out or sweep.out or pathlib.Path("out") / sweep.file.stem)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:  # a file of that name, a folder without permission, ...
        raise _error("", "out", str(out), f"cannot create this folder: {error.strerror}") from None

    key_columns = [*sweep.parameter_columns(), *sweep.setting_keys]
    table = Table(out / "sweep.csv", sweep.columns(), key_columns)
    runs = list(sweep.runs())
    todo = [(row, task) for row, task in runs if table.key(row) not in table.keys]
    skipped = len(runs) - len(todo)
    if max_runs is not None:
        todo = todo[:max_runs]
    executed, failures, interrupted, where, bar = 0, 0, False, "serial", None
    try:
        if workers == 0:
            results = _serial(sweep, todo)
        else:
            client, where = _client(workers, scheduler)
            results = _distributed(client, sweep, todo)
        bar = _progress_bar(len(todo), len(runs), progress)  # after the cluster: its refusals print alone
        try:
            for row, result in results:
                row = {**row, **result}
                table.append(row)
                executed += 1
                failures += row["status"] != "completed"
                bar.set_postfix_str(f"{failures} not completed", refresh=False)
                bar.update(1)
        finally:
            results.close()  # ends the cluster this sweep started
    except KeyboardInterrupt:
        interrupted = True
    finally:
        if bar is not None:
            bar.close()
        table.close()
    # Incomplete when a run of the product has no row yet: interrupted, stopped by max_runs, or a
    # worker lost with its result.
    incomplete = interrupted or any(table.key(row) not in table.keys for row, _ in runs)
    result = SweepResult(out, executed, skipped, incomplete)
    _write_parquet(out)
    _write_json(out, sweep, result, runs, where, date_utc, time.perf_counter() - started)
    return result


def _progress_bar(count, total, enabled):
    from tqdm import tqdm  # Debian python3-tqdm
    return tqdm(total=count, unit="run", desc=f"sweep ({total - count} of {total} done before)" if count < total
                else "sweep", disable=not enabled, file=sys.stderr, dynamic_ncols=True)


def _serial(sweep, todo):
    """The runs in this process, one after another, the needed gaps computed once per pair."""
    gaps = {}
    for row, task in todo:
        gap = None
        if sweep.needed_gap:
            pair = (task["scene_file"], row["record_source"], task["direction_deg"])
            if pair not in gaps:
                gaps[pair] = needed_gap_task(task)
            gap = gaps[pair]
        yield row, run_task(task, gap)


SCHEDULER_TIMEOUT_S = 10


def _connect(distributed, scheduler):
    """A client of the scheduler at `scheduler`, or an InputError: exit 2 for an address that is
    not one, 3 (ConnectionError) for one where nothing answers within SCHEDULER_TIMEOUT_S."""
    if not isinstance(scheduler, str) or "://" not in scheduler or not scheduler.split("://", 1)[1]:
        raise _error("", "--scheduler", _text(scheduler), "expected an address such as tcp://HOST:8786")
    try:
        return distributed.Client(scheduler, timeout=SCHEDULER_TIMEOUT_S)
    except (OSError, TimeoutError) as error:
        raise SchedulerUnreachable(f"--scheduler = {scheduler}: no Dask scheduler answered within "
                                   f"{SCHEDULER_TIMEOUT_S} s ({type(error).__name__})") from None
    except ValueError as error:
        raise _error("", "--scheduler", _text(scheduler), f"not a scheduler address ({error})") from None


class SchedulerUnreachable(ConnectionError):
    """The scheduler address is well formed but nothing answered there (exit 3, as an interrupted sweep)."""


def _client(workers, scheduler):
    """A Dask client: of the scheduler at `scheduler`, or of a new LocalCluster of `workers`
    processes (None: every core), one thread each; the client closes the cluster it started."""
    import dask.distributed  # Debian python3-distributed
    if scheduler is not None:
        client = _connect(dask.distributed, scheduler)
        mine = _worker_identity()
        try:
            identities = client.run(_probe_identity())
        except Exception as error:  # noqa: BLE001  (a worker lost while answering)
            client.close()
            raise _error("", "--scheduler", scheduler, f"a worker did not answer ({type(error).__name__}: {error})") \
                from None
        for worker, identity in identities.items():
            if identity[0] == "not importable":
                client.close()
                module_parent = pathlib.Path(pounding.__file__).resolve().parents[1]
                raise _error("", "--scheduler", scheduler,
                             f"worker {worker} cannot import pounding ({identity[1]}): start the workers with "
                             f"PYTHONPATH={module_parent} (this build's module)")
            if tuple(identity) != mine:
                client.close()
                raise _error("", "--scheduler", scheduler,
                             f"worker {worker} runs pounding {identity}, this process {mine}: use one build")
        return client, scheduler
    # Worker processes import pounding from where this process did.
    package_parent = str(pathlib.Path(pounding.__file__).resolve().parents[1])
    path = os.environ.get("PYTHONPATH", "")
    if package_parent not in path.split(os.pathsep):
        os.environ["PYTHONPATH"] = package_parent + (os.pathsep + path if path else "")
    count = workers or os.cpu_count() or 1
    # Ctrl-C reaches the whole process group: the workers, started with SIGINT ignored (a
    # disposition a new process keeps, and under which Python installs no KeyboardInterrupt), leave
    # it to this process, which closes the cluster, instead of each printing a traceback. A Ctrl-C
    # while the cluster starts (about half a second) is therefore lost: press it again. (Blocking
    # SIGINT instead, to keep it pending, does not reach the workers: Dask spawns them from threads
    # of its own, which do not inherit the block.)
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        cluster = dask.distributed.LocalCluster(n_workers=count, threads_per_worker=1, processes=True,
                                                dashboard_address=":0", silence_logs=logging.ERROR)  # any free port
    finally:
        signal.signal(signal.SIGINT, previous)
    client = dask.distributed.Client(cluster)
    client._pounding_cluster = cluster
    return client, f"LocalCluster({count} workers x 1 thread)"


def _distributed(client, sweep, todo):
    """Submits every run (and every needed gap, once per pair, the runs of the pair depending on
    it) and yields (row, result) as runs finish. Closing the generator cancels what is left."""
    import dask.distributed
    try:
        gaps = {}
        futures = {}
        for row, task in todo:
            gap = None
            if sweep.needed_gap:
                pair = (task["scene_file"], row["record_source"], task["direction_deg"])
                if pair not in gaps:
                    gaps[pair] = client.submit(needed_gap_task, task, pure=False)
                gap = gaps[pair]
            futures[client.submit(run_task, task, gap, pure=False)] = row
        lost = 0
        for future in dask.distributed.as_completed(futures):
            row = futures.pop(future)
            try:
                result = future.result()
            except dask.distributed.KilledWorker as error:  # the run killed every worker it was given
                result = dict.fromkeys(RESULTS)
                result.update(status="failed", message=f"the run killed its worker process: {error}")
            except Exception:  # noqa: BLE001  (a connection lost, a worker stopped by Ctrl-C)
                # run_task never raises, so this is the cluster's failure, not the run's: no row,
                # and a sweep started again runs it.
                lost += 1
                continue
            yield row, result
        if lost:
            print(f"{lost} runs lost with their workers; start the sweep again to run them", file=sys.stderr)
    finally:
        client.cancel(list(futures))
        cluster = getattr(client, "_pounding_cluster", None)
        client.close()
        if cluster is not None:
            cluster.close()


def _write_parquet(out):
    """sweep.parquet, the same table, when pyarrow is installed (not a Debian 12 package)."""
    try:
        import pyarrow.csv
        import pyarrow.parquet
    except ImportError:
        return
    pyarrow.parquet.write_table(pyarrow.csv.read_csv(out / "sweep.csv"), out / "sweep.parquet")


def _write_json(out, sweep, result, runs, where, date_utc, wall_time_s):
    import dask
    document = {
        "sweep_file": str(sweep.file.resolve()), "sweep_sha256": sweep.sha256,
        "runs": len(runs), "rows": len(result.rows), "executed": result.executed, "skipped": result.skipped,
        "not_completed": result.failed, "complete": len(result.rows) == len(runs),
        "interrupted": result.interrupted, "cluster": where, "wall_time_s": wall_time_s,
        "parameters": sweep.parameters(), "columns": sweep.columns(),
        "provenance": {"program_version": pounding.__version__,
                       "git_commit": pounding._pounding.git_commit or None,
                       "python": sys.version.split()[0], "dask": dask.__version__,
                       "host": socket.gethostname(), "date_utc": date_utc}}
    _replace_no_follow(out / "sweep.json", json.dumps(document, indent=2) + "\n")


# ------------------------------------------------------------------------------------------------
# python3 -m pounding.sweep


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="pounding sweep",
        description="Run a sweep file's product of scenes, records, gaps, restitutions, methods and contact laws "
                    "on Dask, one row a run in OUT/sweep.csv; a sweep started again skips the runs already there.")
    parser.add_argument("sweep_file", help="sweep file (TOML)")
    parser.add_argument("--workers", type=int, help="LocalCluster worker processes (default: every core); "
                                                    "0: no Dask, the runs one after another in this process")
    parser.add_argument("--serial", action="store_true", help="the same as --workers 0")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://HOST:8786")
    parser.add_argument("--out", help="output folder (default: the file's out, else out/<sweep file name>)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    arguments = parser.parse_args(argv)
    workers = 0 if arguments.serial else arguments.workers
    signal.signal(signal.SIGTERM, _stop)  # a kill stops the sweep as Ctrl-C does: the cluster closed
    try:
        result = run_sweep(arguments.sweep_file, out=arguments.out, workers=workers, scheduler=arguments.scheduler,
                           progress=not arguments.no_progress)
    except InputError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    except SchedulerUnreachable as error:  # a refusal, as a bad sweep file is: nothing ran
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(f"{len(result.rows)} rows in {result.csv} ({result.executed} run now, {result.skipped} already there, "
          f"{result.failed} not completed)")
    if result.interrupted:
        print("interrupted: run the same command again to finish the sweep", file=sys.stderr)
        return 3
    return 3 if result.failed else 0


def _stop(signal_number, frame):
    raise KeyboardInterrupt


class _CallableModule(types.ModuleType):
    """pounding.sweep(...) is pounding.sweep.run_sweep(...)."""

    def __call__(self, *args, **kwargs):
        return run_sweep(*args, **kwargs)


if __name__ == "__main__":
    # Run the functions of the module `pounding.sweep`, not of `__main__`: Dask sends its workers
    # references to them by module name.
    from pounding.sweep import main as _main
    sys.exit(_main())
else:
    sys.modules[__name__].__class__ = _CallableModule
