"""run_sweep: a sweep file's runs not yet in its table, run and appended, then sweep.parquet and
sweep.json; SweepResult, what it did."""

import datetime
import pathlib
import time

from pounding import _input_error as _error  # InputError with the library's message
from pounding.sweep.file import Sweep, _text
from pounding.sweep.schedule import _client, _distributed, _progress_bar, _serial
from pounding.sweep.table import Table, read_table
from pounding.sweep.writers import _write_json, _write_parquet


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
