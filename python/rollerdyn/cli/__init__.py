"""The ``rollerdyn`` command line.

Commands: ``validate`` (every model against published values), ``check`` (validate a
configuration file and show its derived quantities), ``bench`` (time the hot paths),
``run``, ``plot``, ``sweep``, ``report``, ``compare`` (two runs output by output), ``modes``
(the fastest growing modes at a run's final state), ``statics`` (quasi-static
analysis) and ``new`` (a starting configuration for another bearing); ``rollerdyn
--version`` prints the version and the git commit a result file would record. All inputs
and outputs are SI unless a column says otherwise.

Bad input (an option value, a configuration, a file that is no result, an output path that
cannot or must not be written, see :mod:`rollerdyn.paths`) exits with status 2 and one
message naming the option or field, the value and the rule, before any work. Every message
is printed as plain text (:func:`.common.say`, :func:`.common.error`): text from files and
options is never read as rich markup.

This package builds the typer :data:`app` and registers the commands, one module each:
:mod:`.validate` (``validate``, ``check``), :mod:`.bench` (its targets in
:mod:`.bench_targets`), :mod:`.run`, :mod:`.plot`, :mod:`.sweep`, :mod:`.report`,
:mod:`.statics` and :mod:`.new`; :mod:`.common` holds the console and what the commands
share. It is the only part of rollerdyn that imports typer.
"""

from __future__ import annotations

from typing import Annotated

import typer

from . import bench, compare, modes, new, plot, report, run, statics, study, sweep, validate
from .common import say

# rich_markup_mode=None: help texts are plain text (a "[s]" or "[arrays]" stays as typed)
# and click wraps each paragraph once to the terminal's width.
app = typer.Typer(
    help="rollerdyn: dynamics of full-complement cylindrical roller bearings.",
    no_args_is_help=True,
    add_completion=False,
    rich_markup_mode=None,
)


def _print_version(value: bool) -> None:
    """``--version``: rollerdyn's version and the git commit of the source it runs from."""
    if not value:
        return
    from .. import __version__
    from ..provenance import git_commit

    commit = git_commit()
    say(f"rollerdyn {__version__}" + (f" (git {commit})" if commit else ""))
    raise typer.Exit()


@app.callback()
def _main(
    version: Annotated[
        bool,
        typer.Option(
            "--version",
            help="Print rollerdyn's version and the git commit of its source, and exit.",
            callback=_print_version,
            is_eager=True,
        ),
    ] = False,
) -> None:
    """rollerdyn: dynamics of full-complement cylindrical roller bearings."""


app.command("validate")(validate.validate)
app.command("check")(validate.check)
app.command("bench")(bench.bench)
app.command("run")(run.run)
app.command("plot")(plot.plot)
app.command("sweep")(sweep.sweep_command)
app.command("report")(report.report_command)
app.command("compare")(compare.compare_command)
app.command("modes")(modes.modes_command)
app.command("statics")(statics.statics_command)
app.command("new")(new.new_command)
app.add_typer(study.app, name="study")

__all__ = ["app"]
