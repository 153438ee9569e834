"""``rollerdyn study paper``: the runs behind the paper's sect. 5 (figs. 8-14) on Dask, the
paper's findings checked on them, their figures and one HTML report.

:func:`paper` does it all and returns a :class:`PaperStudy`. The folder (default
``results/study``) holds ``study.json`` (what study of which configuration), ``runs/``
(one result file per run, written at its checkpoints), ``runs.csv`` (every run: status,
time reached, wall time, steps), ``findings.csv`` and ``findings.json``,
``runtime_study.csv`` (fig. 14), ``figures/`` (PNG and SVG) and ``report.html``.
Invoked again on the same folder it runs only what is missing: finished runs are
reused, runs stopped by the wall-time cap or killed continue from their last checkpoint.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..limits import DEFAULT_MAX_WALL
from .findings import Finding, check_findings
from .folder import prepare_folder, record_files, replace_figures
from .plan import DEFAULT_LOADS, Plan, build_plan
from .runs import StudyError, lock_folder, open_run, record
from .schedule import Clock, check_scheduler, check_workers, run_all, timing

DEFAULT_CONFIG = "examples/b1.toml"
DEFAULT_OUTDIR = "results/study"


@dataclass
class PaperStudy:
    """What :func:`paper` made: the plan, a record per run (a ``pandas.DataFrame``), the
    findings, the study's timing, the report and the figures written."""

    outdir: Path
    plan: Plan
    runs: Any
    findings: list[Finding]
    timing: dict
    report: Path | None
    figures: list[Path] = field(default_factory=list)

    @property
    def records(self) -> dict[str, dict]:
        return {r["name"]: r for r in self.runs.to_dict("records")}


def default_workers() -> int:
    """All cores (one run per core)."""
    from ..simulation import default_threads

    return default_threads()


def _source_name(config) -> str | None:
    return None if not isinstance(config, str | os.PathLike) else str(config)


def check_arguments(progress: Any, **flags: Any) -> None:
    """Refuses (:class:`StudyError`, naming the argument) a ``progress`` that is not a
    function (or None) and ``flags`` (overwrite, force, ...) that are not True or False,
    before any work: ``overwrite="no"`` would be true and remove the earlier study."""
    if progress is not None and not callable(progress):
        raise StudyError(f"progress = {progress!r}: must be a function (or None)")
    for name, value in flags.items():
        if not isinstance(value, bool):
            raise StudyError(f"{name} = {value!r}: must be True or False")


def paper(
    config: Any = DEFAULT_CONFIG,
    outdir: str | os.PathLike = DEFAULT_OUTDIR,
    *,
    t_end: float | str | None = None,
    loads: Sequence[float] = DEFAULT_LOADS,
    dt_max: Sequence[float] | None = None,
    free_tilt: bool = True,
    gradient: bool = True,
    distributed: bool = True,
    tight: bool = True,
    max_wall: float = DEFAULT_MAX_WALL,
    scheduler: Any = None,
    workers: int | None = None,
    overwrite: bool = False,
    run: bool = True,
    report: bool = True,
    figures: bool = True,
    progress: Callable[[dict], Any] | None = None,
) -> PaperStudy:
    """The paper's study of ``config`` (a TOML path or a ``BearingConfig``) in ``outdir``.

    ``t_end``: end time of every run (s, or a time such as ``"20 ms"``; default the
    configuration's, 1.288 s for B1). ``loads``: axial loads of figs. 10-13 [N] (the
    configuration's own is always added). ``dt_max``: Δt_max of fig. 14 [s] (default 0.2,
    0.5 and 1 times ``solver.dt_max``; ``()``: none). ``free_tilt``/``gradient``: include
    the free-tilt run (figs. 8, 9) and the gradient-detector runs (sect. 5.1, 5.3, fig.
    14). ``distributed``: with the point law, run the axial loads once more with the
    distributed flange law (a second series of figs. 10-13; the free tilt's pair of figs.
    8, 9 has that law in any case). ``tight``: with the gradient runs, run the
    configuration with both detectors once more at ten times tighter tolerances
    (``solver.rtol`` and ``solver.atol`` × 0.1; the check ``tight_agreement``).
    ``max_wall``: wall-time cap of each run in this invocation [s]; a run stopped by it is
    reported as not finished and continued at the next invocation. ``scheduler``:
    None (a ``LocalCluster`` of ``workers`` processes, default all cores), an address or a
    ``distributed.Client``. ``overwrite``: start afresh (removes the files the earlier
    study's ``study.json`` lists, nothing else; a folder without one that holds files a
    study writes is refused either way).
    ``run=False``: run nothing, analyse what the folder holds. ``report``/``figures``:
    write the HTML report and the PNG/SVG figures. ``progress(event)``: see
    :func:`rollerdyn.study.schedule.run_all`.

    Raises :class:`StudyError` (a ``ValueError``, one line naming the option) before any
    run for bad options, a folder of another study or configuration, or a scheduler that
    cannot be reached; :class:`rollerdyn.ConfigError` for an invalid configuration."""
    from ..simulation import as_config
    from ..units import parse_time

    clock = Clock()
    check_arguments(
        progress,
        free_tilt=free_tilt,
        gradient=gradient,
        distributed=distributed,
        tight=tight,
        overwrite=overwrite,
        run=run,
        report=report,
        figures=figures,
    )
    cfg = as_config(config)
    if t_end is not None:
        try:
            t_end = parse_time(t_end, "--t-end")
        except ValueError as err:
            raise StudyError(str(err)) from None
    if not (isinstance(max_wall, int | float) and max_wall > 0 and math.isfinite(max_wall)):
        raise StudyError(f"--max-wall = {max_wall!r}: must be a positive number of seconds")
    workers = default_workers() if workers is None else workers
    check_workers(workers)
    plan = build_plan(
        cfg,
        t_end,
        loads,
        dt_max,
        free_tilt=free_tilt,
        gradient=gradient,
        distributed=distributed,
        tight=tight,
    )
    if run:
        check_scheduler(scheduler)
    out = prepare_folder(
        Path(outdir),
        "paper",
        cfg,
        overwrite=overwrite,
        source=_source_name(config),
        files=[f"runs/{spec.file}" for spec in plan.specs],
    )
    runs_dir = out / "runs"
    runs_dir.mkdir(exist_ok=True)
    lock = lock_folder(out)
    try:
        if run:
            records = run_all(
                plan.specs,
                runs_dir,
                max_wall=float(max_wall),
                scheduler=scheduler,
                workers=workers,
                progress=progress,
            )
        else:
            records = {}
        # the study's own time: until its runs ended (the figures and the report follow)
        study_timing = timing(records, clock(), workers if scheduler is None else 0)
        sets = {}
        for spec in plan.specs:
            ds = open_run(runs_dir / spec.file)
            if ds is not None:
                sets[spec.name] = ds
            if spec.name not in records:
                attrs = None if ds is None else dict(ds.attrs)
                records[spec.name] = record(spec, attrs, "reused" if ds is not None else "skipped")
        findings = check_findings(plan, sets, records)
        written, page = _write_outputs(
            out, plan, sets, records, findings, study_timing, report, figures
        )
        # what --overwrite may remove; with the figures drawn, the earlier plan's that
        # this one did not draw again removed
        (replace_figures if figures else record_files)(out, written)
    finally:
        lock.unlink(missing_ok=True)
    import pandas as pd

    frame = pd.DataFrame([records[s.name] for s in plan.specs])
    return PaperStudy(out, plan, frame, findings, study_timing, page, written)


def _write_outputs(
    out: Path, plan: Plan, sets, records, findings, study_timing, report: bool, figures: bool
):
    """runs.csv, findings.csv/.json, runtime_study.csv, the figures and the report."""
    import pandas as pd

    from .figures import runtime_frame, write_figures
    from .report_page import build_page, write_page

    frame = pd.DataFrame([records[s.name] for s in plan.specs])
    frame.to_csv(out / "runs.csv", index=False)
    pd.DataFrame([f.as_row() for f in findings]).to_csv(out / "findings.csv", index=False)
    (out / "findings.json").write_text(
        json.dumps(
            {
                "findings": [
                    {"key": f.key, "status": f.status, "numbers": f.numbers, "values": f.values}
                    for f in findings
                ],
                "timing": study_timing,
            },
            indent=1,
            default=_jsonable,
        ),
        encoding="utf-8",
    )
    runtime_frame(plan, records).to_csv(out / "runtime_study.csv", index=False)
    written = write_figures(plan, records, out) if figures else []
    page = None
    if report:
        title = f"rollerdyn study: the paper's sect. 5 for {plan.config.name}"
        html = build_page(plan, sets, records, findings, study_timing, title)
        page = write_page(out / "report.html", html)
    return written, page


def _jsonable(value):
    """JSON for numpy numbers and float keys' values (NaN stays NaN)."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return str(value)


__all__ = ["PaperStudy", "StudyError", "paper"]
