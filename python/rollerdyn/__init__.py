"""rollerdyn: dynamic simulation of full-complement cylindrical roller bearings.

The physics runs in a Rust core (``rollerdyn._core``); this package is its front end:
configuration (:mod:`rollerdyn.config`), the force laws on numpy arrays
(:mod:`rollerdyn.tribology`), the model's derived parameters (:mod:`rollerdyn.model`),
the validation cases (:mod:`rollerdyn.validation`), runs of the dynamic model
(:mod:`rollerdyn.simulation`), the names it shares with the core (:mod:`rollerdyn.names`),
figures (:mod:`rollerdyn.plots`), the HTML report (:mod:`rollerdyn.report`), parameter
sweeps (:mod:`rollerdyn.sweep`), the quasi-static analysis (:mod:`rollerdyn.statics`), the
paper's study and operating maps (:mod:`rollerdyn.study`), the modes of the equations of
motion at a run's state (:mod:`rollerdyn.modes`) and the command line
(:mod:`rollerdyn.cli`).

The names below are imported when first used, so that the command line starts (and can
be interrupted) before the heavy libraries load.
"""

from __future__ import annotations

import importlib
import sys
import types

# typing costs ~10 ms of the command's start, in which Ctrl-C is still Python's; the
# annotations below are strings (PEP 563), so it is imported for type checkers only.
TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

__version__ = "0.1.0"

#: Public name -> module that defines it.
_LAZY = {
    "BearingConfig": ".config",
    "ConfigError": ".config",
    "load_config": ".config",
    "parse_config": ".config",
    "configuration_notes": ".notes",
}


#: Subpackages reached as attributes of the package (``rollerdyn.study.paper(...)``)
#: without an import of their own.
_SUBPACKAGES = ("study",)


def __getattr__(name: str) -> Any:
    if name in _SUBPACKAGES:
        return importlib.import_module(f".{name}", __name__)
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rollerdyn' has no attribute {name!r}")


class _Package(types.ModuleType):
    """``rollerdyn.report`` and ``rollerdyn.sweep`` are the functions, though modules of
    the same names exist: properties of the package, whose setters ignore the import
    system's binding of the submodules (``from rollerdyn.report import ...`` still
    reaches the modules through ``sys.modules``)."""

    @property
    def report(self) -> Any:
        """:func:`rollerdyn.report.report`."""
        return importlib.import_module(".report", __name__).report

    @report.setter
    def report(self, _module: Any) -> None:
        pass

    @property
    def sweep(self) -> Any:
        """:func:`rollerdyn.sweep.sweep`."""
        return importlib.import_module(".sweep", __name__).sweep

    @sweep.setter
    def sweep(self, _module: Any) -> None:
        pass


sys.modules[__name__].__class__ = _Package


def simulate(
    config,
    t_end=None,
    detector=None,
    progress=None,
    resume=None,
    checkpoint=None,
    threads=None,
    force=False,
    notice=None,
):
    """Run the dynamic model of ``config`` (a BearingConfig or the path of a TOML file);
    see :func:`rollerdyn.simulation.simulate`, whose arguments it takes."""
    from .simulation import simulate as _simulate

    return _simulate(
        config,
        t_end=t_end,
        detector=detector,
        progress=progress,
        resume=resume,
        checkpoint=checkpoint,
        threads=threads,
        force=force,
        notice=notice,
    )


__all__ = [
    "BearingConfig",
    "ConfigError",
    "configuration_notes",
    "load_config",
    "parse_config",
    "report",
    "simulate",
    "study",
    "sweep",
    "__version__",
]
