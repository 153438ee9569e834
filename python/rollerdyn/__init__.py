"""rollerdyn: dynamic simulation of full-complement cylindrical roller bearings.

The physics runs in a Rust core (``rollerdyn._core``); this package is its front end:
configuration (:mod:`rollerdyn.config`), the force laws on numpy arrays
(:mod:`rollerdyn.tribology`), the model's derived parameters (:mod:`rollerdyn.model`),
the validation cases (:mod:`rollerdyn.validation`) and the command line
(:mod:`rollerdyn.cli`).
"""

from .config import BearingConfig, ConfigError, load_config, parse_config

__all__ = ["BearingConfig", "ConfigError", "load_config", "parse_config", "__version__"]
__version__ = "0.1.0"
