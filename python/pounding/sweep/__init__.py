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

# The package's modules, one concern each: file (reading and checking the sweep file: Sweep), tasks
# (what a worker runs: run_task, needed_gap_task), table (sweep.csv's columns, Table, read_table),
# schedule (the runs in this process or on Dask: the client, the progress bar), writers (sweep.json,
# sweep.parquet and the writes that never follow a link), driver (run_sweep, SweepResult), command
# (main: python3 -m pounding.sweep, run by __main__).

import sys
import types

from pounding import InputError
from pounding.sweep.command import main
from pounding.sweep.driver import SweepResult, run_sweep
from pounding.sweep.file import LAW_KEYS, RECORD_FIELDS, SECOND_KEYS, STIFFNESS_KEYS, SWEEP_KEYS, Sweep
from pounding.sweep.schedule import SCHEDULER_TIMEOUT_S, SchedulerUnreachable
from pounding.sweep.table import (ALL_ANGLES, INTEGER_COLUMNS, NEEDED_GAP, PARAMETERS, PEAK_QUANTITIES,
                                  POUNDING_DEMAND, RESULTS, SLAB_TO_COLUMN, TEXT_COLUMNS, TIMINGS, YIELDING, Table,
                                  building_peak_columns, pair_impact_column, pair_needed_gap_column, read_table)
from pounding.sweep.tasks import needed_gap_task, run_task

# The public names of the single module pounding.sweep this package was (InputError: what run_sweep raises).
__all__ = ["SWEEP_KEYS", "RECORD_FIELDS", "SECOND_KEYS", "STIFFNESS_KEYS", "LAW_KEYS", "PARAMETERS", "RESULTS",
           "NEEDED_GAP", "ALL_ANGLES", "YIELDING", "SLAB_TO_COLUMN", "POUNDING_DEMAND", "TIMINGS", "PEAK_QUANTITIES",
           "building_peak_columns", "pair_impact_column", "pair_needed_gap_column", "Sweep", "needed_gap_task",
           "run_task", "Table", "TEXT_COLUMNS", "INTEGER_COLUMNS", "read_table", "SweepResult", "run_sweep",
           "SCHEDULER_TIMEOUT_S", "SchedulerUnreachable", "main", "InputError"]


class _CallableModule(types.ModuleType):
    """pounding.sweep(...) is pounding.sweep.run_sweep(...)."""

    def __call__(self, *args, **kwargs):
        return run_sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
