"""Seismic pounding of adjacent buildings (two, or a row), from Python: the command line's analyses
returning Python objects and numpy arrays instead of files.

    scene = pounding.load_scene("examples/paper/paper.toml", gap=0.02)
    result = pounding.run(scene, method="cvode-bdf", rtol=1e-8)
    result.status, len(result.impacts), result.impacts_array["impulse_kNs"].max()
    result.history["B1_f7_u_m"]            # numpy array over result.history["t_s"]
    pounding.needed_gap(scene).needed_gap_m
    pounding.sweep("examples/sweep/sweep.toml", workers=2)   # many runs on Dask (pounding/sweep/)
    pounding.modes(scene)[0]["shapes"], pounding.modes(scene)[0]["K"]   # mode shapes, M, K, C
    result.history_frame(), result.impacts_frame()   # pandas DataFrames (Debian python3-pandas)

Units are in the names (m, s, kNs, kJ), as in the command line's files. Bad input raises
pounding.InputError (a ValueError) with the command line's message, naming file, key and value.
run() and needed_gap() release the GIL: runs on several threads proceed in parallel.
"""

import csv as _csv
import io as _io
import json as _json
import numbers as _numbers
import os as _os

import numpy as _np

__all__ = ["InputError", "Scene", "RunResult", "GapResult", "load_scene", "scene_from_dict", "scene_toml",
           "record_list", "modes", "modes_frame",
           "run", "needed_gap", "ground_motion", "response_spectrum", "rotd_spectrum", "methods", "settings", "limits",
           "contact_options", "contact_laws", "output_schema", "sweep", "verify", "bracket", "__version__"]


class InputError(ValueError):
    """Bad input, with the command line's message (str(error)) and its parts: the file, the key
    (a scene key such as `contact.gap_m` or `solver.rtol`, or a load_scene option such as
    `--gap`), the value as text and the reason."""

    def __init__(self, message, file="", key="", value="", reason=""):
        super().__init__(message)
        self.file, self.key, self.value, self.reason = file, key, value, reason

    def __reduce__(self):  # pickled whole, parts included (an error sent back by a worker process)
        return type(self), (str(self), self.file, self.key, self.value, self.reason)


from . import _pounding  # noqa: E402  (after InputError, which its error translator raises)

__version__ = _pounding.__version__
Scene = _pounding.Scene


def _input_error(file, key, value, reason, line=None):
    """InputError with the message the library composes (input_error.cpp):
    FILE[:LINE]: KEY = VALUE: REASON, each part left out when empty."""
    where = f"{file}:{line}" if file and line else str(file or "")
    message = f"{where}: " if where else ""
    message += key + ((" = " if key else "") + value if value else "")
    message += (": " if key or value else "") + reason
    return InputError(message, str(file or ""), key, value, reason)


def _with_record(self, file, format=None, units=None, scale_factor=None, scale_to_pga_g=None,
                 direction_deg=None, dt_s=None, accel_column=None, record2=None, record2_column=None,
                 scale_to_sa=None, read=True):
    """The scene under another record or scaling, as `pounding run --record FILE ...` applies it:
    every argument left None keeps the scene's value; a new file drops the old file's dt_s,
    columns and cut (the arguments may set dt_s and accel_column again); scale_factor and
    scale_to_pga_g each replace the scene's scaling. The record is read now, so an unreadable one
    raises here. The path is used as given (relative to the current folder).
    scale_to_sa="0.5g@T1" (or "0.5g@B1", "0.5g@B2", "0.5g@1.2s") scales the record so that its
    5 %-damped PSA (of a pair: RotD100) at that period is the target, as `--scale-to-sa`;
    "asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2T1" fits it to the ASCE 7 design spectrum over that range.
    record2 (and record2_column) make a pair, as `--record2` and `--record2-column`: the second
    horizontal component, read with the record's format and units, acting along direction_deg + 90;
    a new file without record2 drops the scene's second component.
    Errors name the scene key (`excitation.scale_to_pga_g`, ...) that the argument sets.
    read=False checks the arguments and that the file exists without reading it (as a record list
    is checked); the record is then read by the run."""
    _check_record_types({"file": file, "format": format, "units": units, "scale_factor": scale_factor,
                         "scale_to_pga_g": scale_to_pga_g, "direction_deg": direction_deg, "dt_s": dt_s,
                         "accel_column": accel_column, "second.file": record2, "second.accel_column": record2_column,
                         "scale_to_sa": scale_to_sa})
    return self._with_record(file, format, units, scale_factor, scale_to_pga_g, direction_deg, dt_s,
                             accel_column, record2, record2_column, scale_to_sa, read)


_RECORD_KINDS = {"file": "path", "second.file": "path", "format": "text", "units": "text", "scale_to_sa": "text",
                 "scale_factor": "number", "scale_to_pga_g": "number", "direction_deg": "number", "dt_s": "number",
                 "accel_column": "whole number", "second.accel_column": "whole number"}


# The scene key each with_record argument sets, by the argument's name where it differs.
_RECORD_ARGUMENTS = {"second.file": "record2", "second.accel_column": "record2_column"}


def _check_record_types(arguments):
    """with_record's arguments of the wrong type: InputError naming the call and its argument
    ("Scene.with_record(dt_s=...)") and the scene key it sets (`excitation.dt_s`, ...), not the
    binding's signature dump."""
    accepted = {"path": (str, _os.PathLike), "text": (str,), "number": (_numbers.Real,), "whole number": (_numbers.Integral,)}
    for key, value in arguments.items():
        kind = _RECORD_KINDS[key]
        if value is None or (isinstance(value, accepted[kind]) and not isinstance(value, bool)):
            continue
        text = repr(value) if len(repr(value)) <= 40 else repr(value)[:40] + "..."
        argument = _RECORD_ARGUMENTS.get(key, key)
        raise _input_error(f"Scene.with_record({argument}=...)", f"excitation.{key}", text, f"expected a {kind}")


def _check_settings(settings):
    unknown = sorted(set(settings) - set(_pounding.setting_keys()))
    if unknown:
        raise TypeError(f"unknown settings {', '.join(unknown)}; expected keywords among "
                        f"{', '.join(_pounding.setting_keys() + _pounding.limit_keys())}")
    for name, value in settings.items():
        _check_number(name, value, -2**31, 2**31 - 1)


def _check_number(name, value, smallest, largest):
    """A keyword's number checked before it reaches C++, where a Python int too large for the C type
    raised a cast error without the keyword's name: InputError naming it, with the range of a
    whole number (a float's range is the library's to check, naming the scene key)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return  # text settings (newton, form, ...) and None are the library's to check
    if isinstance(value, int) and not smallest <= value <= largest:
        text = str(value) if len(str(value)) <= 40 else str(value)[:40] + "..."
        raise _input_error("", name, text, f"must lie in [{smallest}, {largest}]")


def _with_method(self, method=None, **settings):
    """The scene with `method` (None: its own) and [solver] settings by their registry names
    replacing its own, checked as run() checks them (InputError naming `solver.<key>`): what
    run(scene, method, **settings) runs."""
    _check_settings(settings)
    return self._with_solver(method, settings)


def _as_method(function, name):
    """`function` as the Scene method `name`: help(Scene) then lists it under its own name."""
    function.__name__, function.__qualname__ = name, f"Scene.{name}"
    setattr(Scene, name, function)


_as_method(_with_record, "with_record")
_as_method(_with_method, "with_method")
def _scene_repr(self):
    return (f"<pounding.Scene {self.name!r}: gap {self.gap_m} m, restitution {self.restitution}, "
            f"method {self.method}, record {str(self.record_file)!r}>")


_as_method(_scene_repr, "__repr__")
Scene.__module__ = "pounding"  # help() and repr name the package, not the bindings


def _gap_options(gap):
    """`gap` as load_scene's (gap_m, gaps): a number, or a row's {"B1:B2": m, ...} (--gap B1:B2=m each)."""
    if isinstance(gap, dict):
        return None, [f"{pair}={float(value)!r}" for pair, value in gap.items()]
    return gap, []


def _contact_keywords(contact):
    """The [contact] options given as keywords (None: not given); an unknown one raises TypeError,
    as a Python function's unknown keyword does."""
    known = _pounding.contact_keywords()
    unknown = sorted(set(contact) - set(known))
    if unknown:
        raise TypeError(f"unknown keywords {', '.join(unknown)}; expected gap or {', '.join(known)}")
    return {keyword: value for keyword, value in contact.items() if value is not None}


def load_scene(path, gap=None, **contact):
    """Reads and validates a scene file, like `pounding run SCENE [--gap G] [--restitution K]
    [--contact-law L] [--contact-stiffness S]` (the same errors, naming those options). `gap` is a
    number (two buildings) or, for a row, a dict {"B1:B2": m, ...} of pair gaps (`--gap B1:B2=m`).
    The other keywords are the [contact] options without `--`, `-` as `_` (restitution,
    contact_law, contact_stiffness: `pounding settings` lists them in its python column).
    Returns a Scene with .name, .file, .gap_m, .pair_gaps, .building_names, .restitution, .method,
    .contact_law, .contact_stiffness (the law's, in its unit; None for impulse), .record_file,
    .history, .peaks ([output]) and the with_gap(m), with_pair_gap(first, second, m),
    with_restitution(k), with_record(path, ...), with_outputs(history=, peaks=) copies. `contact_stiffness` is in the
    law's unit: kN/m for kelvin, kN/m^1.5 for hertzdamp, hertzdamp-ye and jankowski."""
    gap_m, gaps = _gap_options(gap)
    return _pounding.load_scene(path, gap_m, gaps, _contact_keywords(contact))


def scene_from_dict(document, folder=None, gap=None, **contact):
    """A scene built in code: `document` holds the scene file's tables and keys under the same
    names (docs/scene-format.md), as dicts, lists, text, numbers and booleans (numpy numbers and
    arrays too), e.g. {"name": "pair", "building": [{"name": "A", "storeys": 4, ...}, {...}],
    "excitation": {"file": "el-centro.AT2", ...}, "contact": {"gap_m": 0.1}}; tomllib.load() of a
    scene file gives one to change. Relative record paths are taken from `folder` (default: the
    current folder). It is read and checked exactly as a file is (scene_toml(document) is the text),
    so errors name the same keys; the other arguments are load_scene's. The scene has no file: its
    runs' provenance says scene_file null (pounding animate and report then need --scene)."""
    if not isinstance(document, dict):
        raise _input_error("", "scene", type(document).__name__, "expected a dict of the scene file's tables")
    anchor = _os.path.join(_os.fspath(folder) if folder is not None else _os.getcwd(), "(scene from a dict).toml")
    document = document if "name" in document else {"name": "scene", **document}
    gap_m, gaps = _gap_options(gap)
    return _pounding.scene_from_toml(scene_toml(document), anchor, gap_m, gaps, _contact_keywords(contact))


def scene_toml(document):
    """The TOML text of a scene given as a dict (scene_from_dict): one line per top-level key,
    tables inline. Raises InputError naming the key of a value TOML cannot hold."""
    return "".join(f"{_toml_key(key)} = {_toml_value(value, str(key))}\n" for key, value in document.items())


def _toml_key(key):
    text = str(key)
    return text if text and all(c.isalnum() or c in "_-" for c in text) and text.isascii() else _json.dumps(text)


def _toml_value(value, where):
    if isinstance(value, (bool, _np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, _np.integer)):
        return str(int(value))
    if isinstance(value, (float, _np.floating)):
        number = float(value)
        if number != number:
            return "nan"
        return repr(number) if abs(number) != float("inf") else ("inf" if number > 0 else "-inf")
    if isinstance(value, (str, _os.PathLike)):
        # JSON's escapes are TOML basic-string escapes; characters beyond U+FFFF stay as they are
        # (JSON would write surrogate pairs, which TOML refuses).
        return _json.dumps(_os.fspath(value), ensure_ascii=False)
    if isinstance(value, _np.ndarray):
        return _toml_value(value.tolist(), where)  # a 0-d array is a number
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v, f'{where}.{k}')}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, f"{where}[{i + 1}]") for i, v in enumerate(value)) + "]"
    text = repr(value) if len(repr(value)) <= 40 else repr(value)[:40] + "..."
    raise _input_error("", where, text, f"a scene holds text, numbers, booleans, lists and dicts, not "
                                        f"{type(value).__name__}")


def record_list(scene, list_or_folder):
    """The records of a list file or a folder of .AT2 files, as `pounding gap --records` reads them
    for `scene` (the same errors, naming `list:line`, the field and its value): one dict each with
    name, source ("set.txt:12") and the keywords of Scene.with_record (file, format, units, dt_s,
    accel_column, scale_factor, scale_to_pga_g, scale_to_sa, direction_deg; None keeps the scene's), so that
    scene.with_record(**{k: v for k, v in entry.items() if k not in ("name", "source")}) is the
    scene under that record."""
    return _pounding.record_list(scene, list_or_folder)


def __getattr__(name):
    """pounding.sweep, pounding.verify and pounding.bracket, imported on first use: modules
    (`python3 -m pounding.sweep SWEEP.toml`, `-m pounding.verify MANIFEST.toml`, `-m
    pounding.bracket SCENE.toml`; pounding.sweep(SWEEP.toml, ...) is pounding.sweep.run_sweep,
    pounding.verify.verify(MANIFEST.toml) runs a manifest, pounding.bracket.bracket(SCENE.toml)
    brackets a scene's contact parameters). Not imported with the package, so that `-m` runs
    each once."""
    if name in ("sweep", "verify", "bracket"):
        import importlib
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def methods():
    """The registry's method names, the default first."""
    return _pounding.method_names()


def settings():
    """The [solver] settings run() accepts as keywords, in registry order."""
    return _pounding.setting_keys()


def limits():
    """The run limits run() accepts as keywords (max_steps, ...), in the table's order."""
    return _pounding.limit_keys()


def contact_options():
    """The [contact] options load_scene() and scene_from_dict() accept as keywords besides gap
    (restitution, contact_law, contact_stiffness), in the table's order."""
    return _pounding.contact_keywords()


def contact_laws():
    """The contact laws, as `pounding laws` lists them (impulse first): dicts with name,
    stiffness_key (the [contact] key of its stiffness, None for impulse), stiffness_unit,
    default_stiffness (in that unit) and methods (those that run it; empty: every method)."""
    return _pounding.contact_laws()


def output_schema():
    """Every output field, as `pounding outputs --json` prints it: {"history": [{column, unit,
    per, description}], "impacts": [{key, csv_columns, unit, description}], "peaks": [{key, unit,
    group, description}], "energy": [{key, unit, description}]}. history.csv's columns (and
    RunResult.history's keys) are `B{b}_f{f}_` patterns with {n} the vertex or corner number."""
    return _json.loads(_pounding.output_schema_json())


def modes(scene):
    """Modal analysis of both buildings (`pounding modes --json`'s `buildings`): one dict a
    building with the command line's keys (name, storeys, dof, total_mass_t, frame_factor, rayleigh, modes, ...),
    plus numpy arrays over the modes, longest period first: periods_s, frequencies_hz and
    effective_mass_ratio {x, y, rz} (fractions of the total mass); and the model the runs solve,
    M q'' + C q' + K q = -M r a_g, with q = (u1, v1, phi1, u2, ...) floor 1 first about each
    floor's centre of mass (dofs names them as history.csv does: f1_u_m, f1_v_m, f1_phi_rad, ...):
    M (t and t*m^2 on the diagonal), K (kN/m, kN, kN*m/rad), C (Rayleigh, kN*s/m, ...), all
    3N x 3N, and shapes (3N x 3N, column j the mode j of `modes`, mass-normalised: shapes.T @ M @ shapes = I)."""
    buildings = _json.loads(_pounding.modes_json(scene))["buildings"]
    for building, model in zip(buildings, _pounding.building_matrices(scene)):
        building["periods_s"] = _np.array(building["periods_s"])
        building["frequencies_hz"] = _np.array([m["frequency_hz"] for m in building["modes"]])
        building["effective_mass_ratio"] = {
            axis: _np.array([m["effective_mass_ratio"][axis] for m in building["modes"]]) for axis in ("x", "y", "rz")}
        building["dofs"] = [f"f{floor}_{name}" for floor in range(1, building["storeys"] + 1)
                            for name in ("u_m", "v_m", "phi_rad")]
        building.update(model)
    return buildings


def _pandas():
    try:
        import pandas
    except ImportError as error:
        raise ImportError("the *_frame() methods need pandas (Debian: python3-pandas); "
                          "the same data is there as numpy arrays without it") from error
    return pandas


def modes_frame(scene):
    """modes(scene) as one pandas DataFrame, a row a mode: building, mode (from 1, longest period
    first), period_s, frequency_hz, dominant and effective_mass_ratio_{x,y,rz}."""
    rows = [{"building": building["name"], "mode": index, "period_s": mode["period_s"],
             "frequency_hz": mode["frequency_hz"], "dominant": mode["dominant"],
             **{f"effective_mass_ratio_{axis}": mode["effective_mass_ratio"][axis] for axis in ("x", "y", "rz")}}
            for building in _json.loads(_pounding.modes_json(scene))["buildings"]
            for index, mode in enumerate(building["modes"], start=1)]
    return _pandas().DataFrame(rows)


_IMPACT_DTYPES = {"real": _np.float64, "integer": _np.int64, "flag": _np.bool_}


def _columns(table, names):
    """A table's columns as a dict of arrays, by column name."""
    return {name: table[:, c].copy() for c, name in enumerate(names)}


class RunResult:
    """One run (`pounding run`), kept in memory. summary is summary.json's document (the same keys
    and values; its provenance has no command line); impacts, touches, sustained_contacts, peaks,
    energy and statistics are its entries; impacts_array is impacts.csv as a numpy structured
    array; history maps history.csv's columns (t_s first) to numpy arrays, contact_forces
    contacts_history.csv's (one entry per contact carrying a force at a history instant). The
    scene's [output] decides what there is: without history both are empty dicts, and each floor
    of peaks holds the groups summary["outputs"]["peaks"] lists. For a scene whose columns yield,
    yielding is summary.json's yielding section (per storey: ductility, first yield, hysteretic
    energy) and yielding_array yielding.csv as a structured array (one row per column, storey and
    direction); otherwise None and an empty array."""

    def __init__(self, run):
        self._run = run
        self.summary = _json.loads(run.summary_json())
        for key in ("status", "status_detail", "warnings", "impacts", "touches", "sustained_contacts", "peaks",
                    "energy", "statistics"):
            setattr(self, key, self.summary[key])
        self.yielding = self.summary.get("yielding")
        self._impacts_array = None
        self._yielding_array = None
        self._history = None
        self._contact_forces = None

    @property
    def impacts_array(self):
        if self._impacts_array is None:
            columns = _pounding.impact_columns(*self._run.impact_fields())
            table = self._run.impact_table()
            array = _np.zeros(len(table), dtype=[(name, _IMPACT_DTYPES[kind]) for name, kind in columns])
            for index, (name, kind) in enumerate(columns):
                array[name] = table[:, index].astype(_IMPACT_DTYPES[kind])
            self._impacts_array = array
        return self._impacts_array

    @property
    def yielding_array(self):
        if self._yielding_array is None:
            rows = list(_csv.DictReader(_io.StringIO(self._run.yielding_csv())))
            dtype = {"integer": _np.int64, "real": _np.float64, "text": "U64"}
            # The columns this run wrote: some only where some column has a shear capacity.
            schema = output_schema()["yielding"]
            written = rows[0].keys() if rows else [c["column"] for c in schema if "only_when" not in c]
            fields = [(c["column"], dtype[c["kind"]]) for c in schema if c["column"] in written]
            array = _np.zeros(len(rows), dtype=fields)
            for name, _ in fields:
                array[name] = [row[name] if row[name] != "" else "nan" for row in rows]
            self._yielding_array = array
        return self._yielding_array

    @property
    def history(self):
        if not self.summary["outputs"]["history"]:
            return {}
        if self._history is None:
            table = self._run.history_table()
            self._history = _columns(table, self._run.history_columns())
        return self._history

    @property
    def contact_forces(self):
        if not self.summary["outputs"]["history"]:
            return {}
        if self._contact_forces is None:
            table = self._run.contact_force_table()
            self._contact_forces = _columns(table, self._run.contact_force_columns())
        return self._contact_forces

    @property
    def time_s(self):
        """The history's sample times (s): history["t_s"]."""
        return self.history["t_s"]

    def history_frame(self):
        """history as a pandas DataFrame indexed by t_s (empty without history)."""
        history = dict(self.history)
        frame = _pandas().DataFrame(history)
        return frame.set_index("t_s") if "t_s" in frame else frame

    def impacts_frame(self):
        """impacts_array (impacts.csv) as a pandas DataFrame, a row an impact."""
        return _pandas().DataFrame(self.impacts_array)

    def contact_forces_frame(self):
        """contact_forces (contacts_history.csv) as a pandas DataFrame."""
        return _pandas().DataFrame(dict(self.contact_forces))

    def report(self):
        """The report `pounding run` prints (several lines)."""
        return self._run.full_report()

    def brief(self):
        """One line: scene, method, status, impacts, first impact, run time."""
        return self._run.brief_report()

    def __repr__(self):
        return f"<pounding.RunResult {self.brief()}>"


def run(scene, method=None, **keywords):
    """Runs `scene` like `pounding run`: method (a name of methods(); None: the scene's, whose
    [solver] keys for another method are then not used, as with --method), the [solver] settings
    by their registry names (settings(); e.g. rtol=1e-8, dt_s=0.01), and the run limits by their
    keys (max_steps, max_wall_time_s, max_history_values: `pounding settings`' limits, the options
    --max-steps, ...). A setting the method does not use raises InputError naming it, as the
    command line refuses it. The outputs are the scene's
    [output] (Scene.with_outputs changes them). Releases the GIL while it runs.
    Returns a RunResult; a run that did not complete says so in .status, it does not raise."""
    limit_keys = set(_pounding.limit_keys())
    limits = {key: value for key, value in keywords.items() if key in limit_keys and value is not None}
    settings = {key: value for key, value in keywords.items() if key not in limit_keys}
    _check_settings(settings)
    return RunResult(_pounding.run(scene, method, settings, limits))


class GapResult:
    """The needed gap (`pounding gap`): summary is gap.json's document (without provenance);
    status, status_detail, end_s, needed_gap_m, level, floor, t_s, levels and rules are its
    entries (a status other than completed: the run stopped at end_s, the gap is a lower bound); history_t_s and
    history_touch_gap_m (one column a level) are gap_history.csv's touch gaps as numpy arrays.
    With all_angles: all_angles is gap.json's all_angles (the worst angle of incidence and its
    needed gap) and angles_array gap_angles.csv's envelope (angle_deg, needed_gap_m)."""

    def __init__(self, gap):
        self.summary = _json.loads(gap.gap_json())
        for key in ("status", "status_detail", "end_s", "needed_gap_m", "level", "floor", "t_s", "levels", "rules"):
            setattr(self, key, self.summary.get(key))
        self.history_t_s = gap.history_t_s()
        self.history_touch_gap_m = gap.touch_gap_table()
        self.all_angles = self.summary.get("all_angles")
        self.angles_array = _np.array(gap.angles_table()) if self.all_angles else None

    def history_frame(self):
        """gap_history.csv as a pandas DataFrame indexed by t_s, a column touch_gap_level_<n>_m a level
        (touch_gap_B<b>_f<floor>_columns_m a slab facing the other building's columns)."""
        def name(level):
            column = level.get("slab_to_column")
            if column is None:
                return f"touch_gap_level_{level['level']}_m"
            return f"touch_gap_B{column['slab_building']}_f{level['floors'][column['slab_building'] - 1]}_columns_m"
        columns = {name(level): self.history_touch_gap_m[:, index] for index, level in enumerate(self.levels)}
        return _pandas().DataFrame(columns, index=_pandas().Index(self.history_t_s, name="t_s"))

    def __repr__(self):
        where = (f"level {self.level}" if self.level else f"floors {self.floor} (a slab facing columns)" if self.floor
                 else "no pair (none closes)")
        return f"<pounding.GapResult needed gap {self.needed_gap_m} m at {where}, t = {self.t_s} s>"


def ground_motion(scene):
    """The scene's processed ground motion, as its runs see it: a dict with time_s, h1_mps2 (along
    direction_deg), h2_mps2 (a pair's second component along direction_deg + 90, else None) as
    numpy arrays on one time base, direction_deg and record_scale (the factor its scaling applied,
    in the record's own units)."""
    return _pounding.ground_motion(scene)


def response_spectrum(time_s, accel_mps2, periods_s=None, damping_ratio=0.05):
    """Elastic response spectrum of a record, exact for the piecewise-linear record (as `pounding
    spectrum`): a numpy structured array with period_s, sd_m, psv_mps, psa_mps2 and peak_time_s,
    a row per period (default 0.01-10 s, 61 log-spaced). Raises InputError for periods outside
    [0.001, 100] s or a damping ratio outside [0, 1)."""
    periods = [] if periods_s is None else [float(p) for p in periods_s]
    table = _pounding.response_spectrum(list(map(float, time_s)), list(map(float, accel_mps2)),
                                        periods or _pounding.default_periods_s(), float(damping_ratio))
    return _np.rec.fromarrays(table.T, names="period_s,sd_m,psv_mps,psa_mps2,peak_time_s")


def rotd_spectrum(time_s, first_mps2, second_mps2, periods_s=None, damping_ratio=0.05, angle_step_deg=1.0):
    """RotD50 and RotD100 of a pair on one time base (as `pounding spectrum --rotd`): a numpy
    structured array with period_s, rotd50_sd_m, rotd100_sd_m, rotd100_angle_deg,
    rotd50_psa_mps2 and rotd100_psa_mps2, a row per period."""
    periods = [] if periods_s is None else [float(p) for p in periods_s]
    table = _pounding.rotd_spectrum(list(map(float, time_s)), list(map(float, first_mps2)),
                                    list(map(float, second_mps2)), periods or _pounding.default_periods_s(),
                                    float(damping_ratio), float(angle_step_deg))
    return _np.rec.fromarrays(
        table.T, names="period_s,rotd50_sd_m,rotd100_sd_m,rotd100_angle_deg,rotd50_psa_mps2,rotd100_psa_mps2")


def needed_gap(scene, max_wall_time_s=None, all_angles=False):
    """The clear gap that prevents every contact, from one contact-free run (`pounding gap`), with
    the code rules ABS, SRSS and DDC per level; the run stops after max_wall_time_s (None: the
    command line's default, an hour) with status time_limit. all_angles=True: also over every
    angle of incidence (`gap --all-angles`). Releases the GIL while it runs."""
    return GapResult(_pounding.needed_gap(scene, max_wall_time_s, bool(all_angles)))
