"""Bearing configuration: the TOML schema, its validation and the derived quantities.

A configuration file (see ``examples/b1.toml`` and ``docs/configuration.md``) is read with
:func:`load_config`, a dict with :func:`parse_config`. Both return a frozen
:class:`BearingConfig` whose numeric fields are plain SI floats; dimensional values are
converted at the boundary by :mod:`rollerdyn.units`. Every problem found is reported at
once in a :class:`ConfigError`, one line per problem::

    geometry.roller.edge_radius: "3 mm" — must be < roller diameter/2 = 2.2475 mm

Derived quantities (roller diameter, pitch diameter, effective Vogel factor, end time,
roller mass properties, ...) are properties, never typed into the file.

The package's modules:

- :mod:`.schema`: one pydantic model per section, with the rules of its fields and the
  cross-field checks, up to :class:`BearingConfig`;
- :mod:`.solver`: the ``[solver]`` section, the numerical settings;
- :mod:`.derived`: the derived quantities (mixins of the section models) and
  :func:`fit_roelands_z`;
- :mod:`.errors`: :class:`Problem`, :class:`ConfigError` and :func:`problems_from`, the
  rendering of validation errors as one line per problem;
- :mod:`.loading`: :func:`load_config` and :func:`parse_config`;
- :mod:`.base`: the limits, the sections' base class, time tables and field hints.

Every name is importable from ``rollerdyn.config`` itself.
"""

from __future__ import annotations

from .base import (
    MAX_HERTZ_PRESSURE,
    MAX_PITCH_SPEED,
    MAX_SLICES,
    T0_CELSIUS,
    T_DENSITY_REF,
    ForceHistory,
    Hint,
    QuantityOrTable,
    RadialHistory,
    SpeedHistory,
    TimeTable,
)
from .derived import fit_roelands_z
from .errors import (
    ConfigError,
    Problem,
    _field_at,  # noqa: F401  (the field at a dotted path; rollerdyn.sweep)
    problems_from,
)
from .loading import load_config, parse_config
from .schema import (
    AlphaStarFitConfig,
    BearingConfig,
    BoundaryFrictionConfig,
    CarreauConfig,
    CavityConfig,
    DickeConfig,
    FlangeConfig,
    GeometryConfig,
    InnerRingConfig,
    LimitingShearStressConfig,
    LubricantConfig,
    LubricantDensityConfig,
    MaterialConfig,
    MaterialsConfig,
    OperatingConfig,
    RaceFilmConfig,
    RampConfig,
    ReferenceViscosityConfig,
    RoelandsConfig,
    RollerConfig,
    SqueezeFilmConfig,
    SurfacePairConfig,
    SurfacesConfig,
    VogelConfig,
)
from .solver import LineFitConfig, SolverConfig

__all__ = [
    # reading and errors
    "BearingConfig",
    "ConfigError",
    "Problem",
    "load_config",
    "parse_config",
    "problems_from",
    # derived values
    "fit_roelands_z",
    # the sections
    "AlphaStarFitConfig",
    "BoundaryFrictionConfig",
    "CarreauConfig",
    "CavityConfig",
    "DickeConfig",
    "FlangeConfig",
    "GeometryConfig",
    "InnerRingConfig",
    "LimitingShearStressConfig",
    "LineFitConfig",
    "LubricantConfig",
    "LubricantDensityConfig",
    "MaterialConfig",
    "MaterialsConfig",
    "OperatingConfig",
    "RaceFilmConfig",
    "RampConfig",
    "ReferenceViscosityConfig",
    "RoelandsConfig",
    "RollerConfig",
    "SolverConfig",
    "SqueezeFilmConfig",
    "SurfacePairConfig",
    "SurfacesConfig",
    "VogelConfig",
    # field types, hints and limits
    "ForceHistory",
    "Hint",
    "QuantityOrTable",
    "RadialHistory",
    "SpeedHistory",
    "TimeTable",
    "MAX_HERTZ_PRESSURE",
    "MAX_PITCH_SPEED",
    "MAX_SLICES",
    "T0_CELSIUS",
    "T_DENSITY_REF",
]
