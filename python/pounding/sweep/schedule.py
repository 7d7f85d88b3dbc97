"""Running the runs: in this process one after another, or on Dask distributed (a LocalCluster or a
running scheduler, its workers checked to run this build), with a progress bar."""

import logging
import os
import pathlib
import signal
import sys

import pounding
from pounding import _input_error as _error  # InputError with the library's message
from pounding.sweep.file import _text
from pounding.sweep.table import RESULTS
from pounding.sweep.tasks import needed_gap_task, run_task


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
