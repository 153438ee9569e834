"""The runs of a study on Dask: which of them still need running (their files on disk
decide, :func:`pending_runs`), the cluster (a ``LocalCluster`` or a running scheduler,
:func:`rollerdyn.sweep`'s machinery), one task per run (:func:`.runs.execute`) and one
stream of progress messages for the whole study (the workers send them with
``log_event``; :func:`run_all` hands them to its ``progress`` callback).
"""

from __future__ import annotations

import contextlib
import math
import time
import uuid
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ..names import GRADIENT
from .plan import DISTRIBUTED_LAW
from .runs import (
    ABSENT,
    FAILED,
    FINISHED,
    RunSpec,
    StudyError,
    execute,
    inspect_run,
    lost_record,
    read_attrs,
)

#: A progress callback: called with one dict per event (see :func:`run_all`).
ProgressCallback = Callable[[dict], Any]


def check_scheduler(scheduler: Any, timeout: float = 10.0) -> None:
    """Raises :class:`StudyError` (one line naming --scheduler) unless ``scheduler`` is
    None, a ``distributed.Client`` or the address of a Dask scheduler that answers within
    ``timeout`` seconds."""
    from ..sweep import check_reachable

    if scheduler is None or not isinstance(scheduler, str):
        return
    with _scheduler_errors():
        check_reachable(scheduler, timeout)


@contextlib.contextmanager
def _scheduler_errors():
    """sweep's :class:`~rollerdyn.sweep.SweepError` ``scheduler = 'ADDRESS': ...`` raised
    as :class:`StudyError` ``--scheduler 'ADDRESS': ...``."""
    from ..sweep import SweepError

    try:
        yield
    except SweepError as err:
        text, prefix = str(err), "scheduler = "
        text = "--scheduler " + text[len(prefix) :] if text.startswith(prefix) else text
        raise StudyError(text) from None


def pending_runs(specs: Sequence[RunSpec], outdir: Path) -> tuple[list[RunSpec], dict]:
    """(runs still to run or to continue, {name: attributes} of every run with a file),
    from the files in ``outdir``; raises :class:`StudyError` for a file of another
    configuration (see :func:`.runs.inspect_run`)."""
    pending, found = [], {}
    for spec in specs:
        attrs = read_attrs(Path(outdir) / spec.file)
        state = inspect_run(spec, attrs)
        if attrs is not None:
            found[spec.name] = attrs
        if state not in (FINISHED, FAILED):
            pending.append(spec)
    return pending, found


def check_workers(workers: Any) -> None:
    """:func:`rollerdyn.sweep.check_workers` for ``--workers``, as a :class:`StudyError`."""
    from ..sweep import SweepError
    from ..sweep import check_workers as check

    try:
        check(workers, "--workers")
    except SweepError as err:
        raise StudyError(str(err)) from None


def _connect(scheduler: Any, workers: int, timeout: float):
    """:func:`rollerdyn.sweep.connect`, its refusal naming --scheduler."""
    from ..sweep import connect

    with _scheduler_errors():
        return connect(scheduler, workers, timeout)


def _longest_first(specs: Sequence[RunSpec]) -> list[RunSpec]:
    """``specs`` in the order to start them: the gradient detector's runs first (they take
    4-5 times a semi-analytical run's time: B1's whole runs 200-325 s against 45-65 s),
    the tightest tolerance first among them (the tight pair's gradient run takes about
    1.5 times the others'), then the smallest Δt_max; then the runs with the distributed
    flange law (about twice the point law's time); then the rest, again the tightest
    tolerance first, in the order given. Starting the
    longest first keeps a long run from ending alone at the tail of the study (B1's whole
    study: the last gradient run ran alone for 190 s of its 757 s when it started last)."""

    def key(item: tuple[int, RunSpec]) -> tuple:
        i, spec = item
        gradient = spec.detector == GRADIENT
        dt_max = (spec.data.get("solver") or {}).get("dt_max", math.inf) if gradient else 0.0
        law = (spec.data.get("surfaces") or {}).get("flange_law")
        rtol = (spec.data.get("solver") or {}).get("rtol", math.inf)
        return (not gradient, law != DISTRIBUTED_LAW, rtol, dt_max, i)

    return [spec for _, spec in sorted(enumerate(specs), key=key)]


def run_all(
    specs: Sequence[RunSpec],
    outdir: Path,
    *,
    max_wall: float,
    scheduler: Any = None,
    workers: int = 2,
    progress: ProgressCallback | None = None,
    retries: int = 2,
    connect_timeout: float = 10.0,
    stop_rules: dict | None = None,
    force: bool = False,
) -> dict[str, dict]:
    """Runs every spec whose file does not already hold it (one Dask task each, started
    longest first, :func:`_longest_first`) and returns {name: record} of all of them in
    the order given (:func:`.runs.record`).

    No cluster is started when nothing is left to run. ``scheduler``: None starts a
    ``LocalCluster`` of ``workers`` processes with one thread each; an address or a
    ``distributed.Client`` uses that cluster (its workers must see ``outdir``).
    ``progress(event)`` receives dicts: ``{"kind": "plan", "total", "pending",
    "reused"}`` once, ``{"kind": "update", "name", "t", "t_end", "steps"}`` from the runs
    (about once a second each), ``{"kind": "done", "name", "record"}`` as each ends
    (an operating map sends ``{"kind": "prepare", "done", "total"}`` before, while it
    checks its points).
    ``retries``: how many more times Dask runs a task whose worker died. ``stop_rules``:
    {name: rule} handed to :func:`.runs.execute` (a run ends early when its rule says).
    ``force``: every run as ``simulate(force=True)`` (the point law's load check skipped).
    First it removes the temporary files a killed writer left beside the runs' files
    (:func:`rollerdyn.paths.remove_stale_temporaries`)."""
    from distributed import as_completed

    from ..paths import remove_stale_temporaries
    from ..sweep import disconnect
    from .runs import record

    outdir = Path(outdir)
    for spec in specs:
        # what a worker stopped while writing a run's file left beside it (Ctrl-C, kill -9)
        remove_stale_temporaries(outdir / spec.file)
    pending, found = pending_runs(specs, outdir)
    records: dict[str, dict] = {}
    waiting = {s.name for s in pending}
    for spec in specs:
        if spec.name not in waiting:
            records[spec.name] = record(spec, found[spec.name], "reused")
    emit = progress or (lambda event: None)
    emit(
        {
            "kind": "plan",
            "total": len(specs),
            "pending": [s.name for s in pending],
            "reused": [s.name for s in specs if s.name not in waiting],
            "t_end": {s.name: s.t_end for s in specs},
        }
    )
    if not pending:
        return {s.name: records[s.name] for s in specs}
    # no more workers than runs to make: each costs a process
    client, cluster = _connect(
        scheduler, min(workers, len(pending)) if scheduler is None else workers, connect_timeout
    )
    topic = f"rollerdyn-study-{uuid.uuid4().hex}"
    try:
        client.subscribe_topic(topic, lambda event: emit({"kind": "update", **event[1]}))
        queue = iter(_longest_first(pending))
        by_key: dict[str, RunSpec] = {}

        def submit_next():
            """The next run of the queue as a task (None when all are submitted)."""
            spec = next(queue, None)
            if spec is None:
                return None
            fut = client.submit(
                execute,
                spec,
                str(outdir.resolve()),
                max_wall,
                topic,
                (stop_rules or {}).get(spec.name),
                force=force,
                pure=False,
                retries=retries,
                key=f"study-{spec.name}-{uuid.uuid4().hex[:8]}",
            )
            by_key[fut.key] = spec
            return fut

        # As many tasks as the cluster has threads, the next when one ends: Dask assigns a
        # task to a worker when it is submitted, so submitting all at once would start
        # them in another order than the queue's (measured on B1's study).
        slots = sum(client.nthreads().values()) or len(pending)
        started = [f for f in (submit_next() for _ in range(slots)) if f is not None]
        running = as_completed(started)
        for fut in running:
            spec = by_key[fut.key]
            try:
                rec = fut.result()
            except Exception as err:  # its workers died more often than retried
                rec = lost_record(spec, outdir, err)
            records[spec.name] = rec
            emit({"kind": "done", "name": spec.name, "record": rec})
            following = submit_next()
            if following is not None:
                running.add(following)
    finally:
        try:
            client.unsubscribe_topic(topic)
        except Exception:  # the client may be gone already
            pass
        disconnect(client, cluster, scheduler)
    return {s.name: records[s.name] for s in specs}


def timing(records: dict[str, dict], wall: float, workers: int) -> dict:
    """The study's wall time, the sum of its runs' wall times in this invocation (runs
    reused from disk excluded; a run refused before its first step has no wall time and
    counts nothing) and the parallel efficiency: sum / (wall x workers)."""
    ran = [r for r in records.values() if r["action"] in ("ran", "continued")]
    walls = [r.get("attempt wall [s]", math.nan) for r in ran]
    total = sum(w for w in walls if math.isfinite(w))
    return {
        "study wall [s]": wall,
        "runs run": len(ran),
        "sum of run walls [s]": total,
        "workers": workers,
        "parallel efficiency": (
            total / (wall * workers) if ran and wall > 0 and workers else math.nan
        ),
    }


class Clock:
    """Wall time since creation, in s."""

    def __init__(self) -> None:
        self.start = time.perf_counter()

    def __call__(self) -> float:
        return time.perf_counter() - self.start


__all__ = ["ABSENT", "check_scheduler", "pending_runs", "run_all", "timing", "Clock"]
