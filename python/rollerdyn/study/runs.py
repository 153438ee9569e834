"""One run of a study: what it is (:class:`RunSpec`), what its result file on disk says
about it (:func:`inspect_run`), and the task that runs it in a Dask worker
(:func:`execute`): fresh, continued from its last checkpoint, or not at all when its file
already holds it to its end time.

A run writes its result file ``<name>.nc`` at its checkpoints (atomically, at most one
every :data:`rollerdyn.simulation.SAVE_INTERVAL` of wall time: see
:class:`rollerdyn.simulation.CheckpointSaver`), so a worker killed mid-run loses at most
that and one checkpoint interval; the next attempt (Dask's retry, or the next invocation
of the study) continues from the file's last checkpoint with ``simulate(..., resume=...)``,
bit for bit.
A run is stopped after ``max_wall`` seconds of wall time (per attempt): its file then holds
everything up to its last output and the attribute ``study_stopped``; the next invocation
continues it from its last checkpoint.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

#: Run states (see :func:`inspect_run`).
ABSENT, FINISHED, FAILED, PARTIAL = "absent", "finished", "failed", "partial"

#: The study folder's lock file (the id of the process running a study in it).
LOCK = ".study.lock"

#: Statuses of a run record (the findings table and the report say these).
COMPLETED, NOT_FINISHED, RUN_FAILED, NOT_RUN = "completed", "not finished", "failed", "not run"


class StudyError(ValueError):
    """A study that cannot start or go on: bad options, a folder holding runs of another
    configuration, a scheduler that cannot be reached. ``str(err)`` is one line naming the
    option (or the folder) and the rule."""


@dataclass(frozen=True)
class RunSpec:
    """One run of a study: its name (the file is ``<name>.nc``), a label for tables and
    legends, the configuration data (SI numbers, ``BearingConfig.model_dump()``), the
    detector, the end time [s] and the configuration hash (to recognise its file)."""

    name: str
    label: str
    data: dict = field(repr=False, compare=False)
    detector: str
    t_end: float
    config_sha256: str
    meta: dict = field(default_factory=dict, compare=False)

    @property
    def file(self) -> str:
        return f"{self.name}.nc"


def time_slack(t: float) -> float:
    """Times this close to ``t`` count as equal (a run's end against the end asked for;
    shared with :mod:`rollerdyn.sweep_resume`)."""
    return 1e-9 * max(abs(t), 1.0)


def open_run(path: Path):
    """The result in ``path`` loaded into memory (None if there is no file); raises
    :class:`StudyError` for a file that cannot be read as a rollerdyn result."""
    from ..report import REQUIRED, ReportError, open_result

    path = Path(path)
    if not path.exists():
        return None
    try:
        return open_result(path, required=(*REQUIRED, "final_state"), recorded_only=True)
    except ReportError as err:
        raise StudyError(
            f"-o {path.parent}: {err}; remove the file or choose another folder"
        ) from None


def read_attrs(path: Path) -> dict | None:
    """The attributes of the result file ``path`` (None if there is none), read without
    its data (fast); raises :class:`StudyError` for a file that is not a result."""
    import h5py
    import numpy as np

    path = Path(path)
    if not path.exists():
        return None
    try:
        with h5py.File(path, "r") as f:
            raw = {k: f.attrs[k] for k in f.attrs}
    except Exception as err:  # h5py raises several kinds for files that are not HDF5
        reason = " ".join(str(err).split()) or type(err).__name__
        raise StudyError(
            f"-o {path.parent}: {path.name} is not a rollerdyn result ({reason}); remove it "
            "or choose another folder"
        ) from None
    attrs = {}
    for key, value in raw.items():
        if isinstance(value, np.ndarray) and value.size == 1:
            value = value.reshape(()).item()
        elif isinstance(value, bytes | np.bytes_):
            value = bytes(value).decode("utf-8", "replace")
        attrs[key] = value
    if "final_time_s" not in attrs:
        raise StudyError(
            f"-o {path.parent}: {path.name} is not a rollerdyn result (no final_time_s); "
            "remove it or choose another folder"
        )
    return attrs


def inspect_run(spec: RunSpec, attrs: dict | None) -> str:
    """State of ``spec`` given its file's attributes (None: no file): ABSENT,
    FINISHED (completed to ``spec.t_end``), FAILED (the solver failed: continuing would
    fail again, bit for bit) or PARTIAL (stopped by the wall-time cap, killed, or run to
    an earlier, shorter end time: to be continued). Raises :class:`StudyError` for a
    file of another configuration or detector, or one that ran beyond ``spec.t_end``."""
    if attrs is None:
        return ABSENT
    folder = "the study folder"
    found = attrs.get("config_sha256")
    if found != spec.config_sha256 or attrs.get("detector") != spec.detector:
        raise StudyError(
            f"{folder} holds {spec.file}, a run of another configuration or detector "
            f"(configuration hash {str(found)[:12]}..., detector {attrs.get('detector')!r}; "
            f"this study's: {spec.config_sha256[:12]}..., {spec.detector!r}); use another "
            "folder (-o) or --overwrite"
        )
    reached = float(attrs["final_time_s"])
    if reached > spec.t_end + time_slack(spec.t_end):
        raise StudyError(
            f"{folder} holds {spec.file}, run to t = {reached:.6g} s, beyond this study's "
            f"end time {spec.t_end:.6g} s (--t-end): it holds a longer study; use another "
            "folder (-o) or --overwrite"
        )
    error = str(attrs.get("error", ""))
    if error and not error.startswith("interrupted"):
        return FAILED
    if attrs.get("study_done"):  # ended by its stop rule (e.g. steady): done
        return FINISHED
    if int(attrs.get("completed", 0)) and reached >= spec.t_end - time_slack(spec.t_end):
        return FINISHED
    return PARTIAL


def record(spec: RunSpec, attrs: dict | None, action: str) -> dict:
    """The record of a run (what the tables show) from its file's attributes (None: never
    ran; a Dataset's ``attrs``).

    ``action``: what this invocation did with it (``ran``, ``continued``, ``reused``,
    ``skipped``). ``status``: COMPLETED, NOT_FINISHED (with the time reached), RUN_FAILED
    or NOT_RUN."""
    rec: dict[str, Any] = {
        "name": spec.name,
        "label": spec.label,
        "detector": spec.detector,
        **{k: v for k, v in spec.meta.items()},
        "t_end [s]": spec.t_end,
        "action": action,
        "file": spec.file if attrs is not None else "",
    }
    if attrs is None:
        rec.update(
            status=NOT_RUN,
            note="",
            **{"reached [s]": math.nan, "wall [s]": math.nan},
            steps=0,
        )
        return rec
    a = attrs
    reached = float(a["final_time_s"])
    state = inspect_run(spec, a)
    if state == FINISHED:
        status, note = COMPLETED, str(a.get("study_done", ""))
    elif state == FAILED:
        status, note = RUN_FAILED, f"failed at t = {reached:.6g} s: {a.get('error', '')}"
    else:
        status = NOT_FINISHED
        if int(a.get("completed", 0)):
            why = "run to an earlier, shorter end time"
        else:
            why = a.get("study_stopped") or "stopped (killed or interrupted)"

        note = f"not finished (reached t = {reached:.6g} s of {spec.t_end:.6g} s; {why})"
    rec.update(
        status=status,
        note=note,
        **{
            "reached [s]": reached,
            "wall [s]": float(a.get("stats_total_seconds", math.nan)),
            "detection [s]": float(a.get("stats_detection_seconds", math.nan)),
        },
        steps=int(a.get("stats_steps", 0)),
        rejected=int(a.get("stats_error_test_failures", 0)),
        rhs=int(a.get("stats_rhs_evaluations", 0)),
        jacobians=int(a.get("stats_jacobian_evaluations", 0)),
    )
    return rec


def lost_record(spec: RunSpec, outdir: Path, err: BaseException) -> dict:
    """The record of a run whose task never returned (its workers died more often than
    Dask retried it): what its file holds, if it has one (a run killed after a checkpoint
    is not finished, and the next invocation continues it), else RUN_FAILED."""
    from ..simulation import failure_note

    why = failure_note(err)
    try:
        attrs = read_attrs(Path(outdir) / spec.file)
    except StudyError:
        attrs = None
    if attrs is None:
        rec = record(spec, None, "ran")
        rec.update(status=RUN_FAILED, note=why)
        return rec
    rec = record(spec, attrs, "ran")
    rec["note"] = f"{rec['note']}; {why}" if rec["note"] else why
    return rec


def _post(topic: str | None, message: dict) -> None:
    """Sends a progress message to the client that runs the study (nothing outside a
    Dask worker, or without a topic)."""
    if topic is None:
        return
    try:
        from distributed import get_worker

        get_worker().log_event(topic, message)
    except (ImportError, ValueError, RuntimeError):  # not in a worker
        pass


def execute(
    spec: RunSpec,
    outdir: str,
    max_wall: float,
    topic: str | None = None,
    stop_rule: Any = None,
    every: float = 1.0,
    force: bool = False,
) -> dict:
    """Runs ``spec`` (as a Dask task, or directly) and returns its :func:`record`; never
    raises for a run's own failure (the record says it).

    Idempotent: a run whose file holds it to its end is not run again (``reused``), a
    failed one is not run again (it would fail the same way), and a partial one continues
    from its file's last checkpoint (``continued``). The run is stopped after
    ``max_wall`` seconds of wall time; progress goes to ``topic`` (see
    :func:`rollerdyn.study.schedule.run_all`) every ``every`` seconds.

    ``stop_rule(ds)``, if given, is asked at every checkpoint with the run so far; a text
    it returns (e.g. "steady at t = 0.12 s") ends the run at its next output as done: the
    file's attribute ``study_done`` keeps the text, and the run counts as finished.
    ``force``: as ``simulate``'s (a run the point law's load check refuses runs, and its
    file says so)."""
    from ..config import parse_config
    from ..simulation import CheckpointSaver, SimulationError, failure_note, simulate, write

    path = Path(outdir) / spec.file
    started = time.monotonic()
    try:
        state = inspect_run(spec, read_attrs(path))
        if state in (FINISHED, FAILED):
            return record(spec, read_attrs(path), "reused")
        previous = open_run(path) if state == PARTIAL else None
        cfg = parse_config(spec.data, si_numbers=True)
        resume = previous if state == PARTIAL else None
        action = "continued" if resume is not None else "ran"
        _post(topic, {"name": spec.name, "t": 0.0, "t_end": spec.t_end, "steps": 0})
        last_post = [0.0]
        done: list[str] = []

        def progress(p) -> bool:
            now = time.monotonic()
            if now - last_post[0] >= every:
                last_post[0] = now
                _post(topic, {"name": spec.name, "t": p.time, "t_end": p.t_end, "steps": p.steps})
            return bool(done) or now - started > max_wall

        saver = CheckpointSaver(path)

        def checkpoint(partial) -> None:
            saver(partial)
            if stop_rule is not None and not done:
                verdict = stop_rule(partial)
                if verdict:
                    done.append(str(verdict))

        try:
            ds = simulate(
                cfg,
                t_end=spec.t_end,
                detector=spec.detector,
                progress=progress,
                resume=resume,
                checkpoint=checkpoint,
                threads=1,  # one run per worker: the runs are the parallelism
                force=force,
            )
        except SimulationError as err:
            ds = err.dataset
        if done and "error" not in ds.attrs:
            ds.attrs["study_done"] = done[0]
        elif not int(ds.attrs.get("completed", 0)) and "error" not in ds.attrs:
            ds.attrs["study_stopped"] = f"stopped after {max_wall:g} s of wall time"
        write(ds, path)
        rec = record(spec, dict(ds.attrs), action)
        if stop_rule is not None and not done and rec["status"] == COMPLETED:
            unmet = getattr(stop_rule, "unmet", None)
            rec["note"] = (
                unmet(spec.t_end)
                if unmet
                else f"not done by its stop rule at its end time, t = {spec.t_end:.6g} s"
            )
        rec["attempt wall [s]"] = time.monotonic() - started
        return rec
    except StudyError as err:
        rec = record(spec, None, "skipped")
        rec.update(status=RUN_FAILED, note=str(err))
        return rec
    except Exception as err:  # a run's failure must not stop the study
        rec = record(spec, None, "ran")
        rec.update(status=RUN_FAILED, note=failure_note(err))
        if path.exists():
            rec["file"] = spec.file
        return rec


def check_unlocked(outdir: Path) -> None:
    """Raises :class:`StudyError` if another living process holds the folder's lock."""
    from ..paths import check_unlocked as check

    check(outdir, LOCK, "study", StudyError)


def lock_folder(outdir: Path) -> Path:
    """Takes the study folder's lock file (``.study.lock`` with this process's id);
    raises :class:`StudyError` if another living process holds it."""
    from ..paths import take_folder_lock

    return take_folder_lock(outdir, LOCK, "study", StudyError)
