"""rollerdyn: dynamic simulation of full-complement cylindrical roller bearings.

The physics runs in a Rust core (``rollerdyn._core``); this package is its front end:
configuration (:mod:`rollerdyn.config`), the force laws on numpy arrays
(:mod:`rollerdyn.tribology`), the model's derived parameters (:mod:`rollerdyn.model`),
the validation cases (:mod:`rollerdyn.validation`), runs of the dynamic model
(:mod:`rollerdyn.simulation`), figures (:mod:`rollerdyn.plots`) and the command line
(:mod:`rollerdyn.cli`).
"""

from .config import BearingConfig, ConfigError, load_config, parse_config
from .report import report  # the function; its module: from rollerdyn.report import ...
from .sweep import sweep  # the function; its module: from rollerdyn.sweep import ...


def simulate(
    config, t_end=None, detector=None, progress=None, resume=None, threads=None, force=False
):
    """Run the dynamic model of ``config`` (a BearingConfig or the path of a TOML file);
    see :func:`rollerdyn.simulation.simulate`."""
    from .simulation import simulate as _simulate

    return _simulate(
        config,
        t_end=t_end,
        detector=detector,
        progress=progress,
        resume=resume,
        threads=threads,
        force=force,
    )


__all__ = [
    "BearingConfig",
    "ConfigError",
    "load_config",
    "parse_config",
    "report",
    "simulate",
    "sweep",
    "__version__",
]
__version__ = "0.1.0"
