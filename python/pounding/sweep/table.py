"""The result table sweep.csv: its columns, Table (appended a row at a time, read back for the
keys of the runs done) and read_table (its cells as typed values)."""

import csv
import io
import math
import os
import pathlib
import re

from pounding import _input_error as _error  # InputError with the library's message
from pounding.sweep.writers import _create_no_follow, _replace_no_follow

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
# slab to column, the largest shear they caused in a column and (with a capacity) its ratio, and
# the same with the columns' sway shear (docs/model.md 6b).
SLAB_TO_COLUMN = ("slab_to_column_impact_count", "max_column_shear_kN", "max_column_shear_ratio",
                  "max_column_total_shear_kN", "max_column_total_shear_ratio")
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


def _cell(value):
    """A CSV cell: floats as repr (the shortest text that reads back to the same bits), None empty."""
    if value is None:
        return ""
    if isinstance(value, float):
        return "" if math.isnan(value) else repr(value)
    return str(value)


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
