"""The sweep file: its keys, the record tables' fields, and Sweep, the checked file whose axes
make the product of runs."""

import hashlib
import itertools
import math
import os
import pathlib
import tomllib

import pounding
from pounding import InputError
from pounding import _input_error as _error  # InputError with the library's message
from pounding.sweep.table import (ALL_ANGLES, NEEDED_GAP, PARAMETERS, POUNDING_DEMAND, RESULTS, SLAB_TO_COLUMN, TIMINGS,
                                  YIELDING, building_peak_columns, pair_impact_column, pair_needed_gap_column)

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


def _text(value):
    """A sweep file's value as the messages show it (TOML-like)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    return repr(value)


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
