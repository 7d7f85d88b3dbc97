"""The sweep's other files, sweep.parquet and sweep.json, and the writes every output of the sweep
goes through, which never follow a symbolic link."""

import json
import os
import pathlib
import socket
import sys

import pounding


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
