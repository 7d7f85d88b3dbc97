"""python3 -m pounding.sweep (and `pounding sweep`): main, its arguments, and a kill that stops the
sweep as Ctrl-C does."""

import argparse
import signal
import sys

from pounding import InputError
from pounding.sweep.driver import run_sweep
from pounding.sweep.schedule import SchedulerUnreachable


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
