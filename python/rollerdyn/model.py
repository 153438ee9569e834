"""The model's derived parameters: what the Rust core computes from a configuration before a
run (lubricant state at the run temperature, alpha* fit, line-contact power laws, the EHL
traction model). All values SI.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from functools import cached_property, lru_cache

from . import _core
from .config import BearingConfig, ConfigError, load_config


@dataclass(frozen=True)
class LineContactLaw:
    """The power law of eq. 11 fitted to Tripp (eqs. 9, 10) for one kind of line contact."""

    name: str
    k1: float
    k2: float
    load_min: float
    load_max: float
    max_force_error: float
    max_deflection_error: float


class Model:
    """Derived parameters of a configuration (immutable; computed on first use)."""

    def __init__(self, config: BearingConfig | str | os.PathLike) -> None:
        """``config``: a configuration, or the path of its TOML file (read with
        :func:`~rollerdyn.config.load_config`); :class:`~rollerdyn.config.ConfigError`
        naming ``config`` for anything else."""
        if isinstance(config, str | os.PathLike):
            config = load_config(config)
        if not isinstance(config, BearingConfig):
            raise ConfigError(
                f"config = {_shown(config)}: expected a BearingConfig (rollerdyn.load_config) "
                f"or the path of a TOML file, got {type(config).__name__}"
            )
        self.config = config

    @property
    def temperature(self) -> float:
        return self.config.operating.temperature

    @cached_property
    def _vogel(self) -> tuple[float, float]:
        lub = self.config.lubricant
        eta, slope = _core.vogel_viscosity(
            _array(self.temperature), lub.vogel_k, lub.vogel.b, lub.vogel.c
        )
        return float(eta[0]), float(slope[0])

    @property
    def eta0(self) -> float:
        """Ambient-pressure viscosity at the run temperature (Vogel, eq. 20), Pa*s."""
        return self._vogel[0]

    @property
    def viscosity_slope(self) -> float:
        """d eta0 / dT at the run temperature, Pa*s/K (for eq. 48)."""
        return self._vogel[1]

    @cached_property
    def roelands_z(self) -> float:
        return self.config.roelands_z

    @cached_property
    def alpha_star_fit(self) -> dict[str, float]:
        """Coefficients of eq. 32 fitted to Blok's alpha* (eq. 31), with the fit's error."""
        lub = self.config.lubricant
        return dict(
            _core.fit_alpha_star(
                lub.vogel_k,
                lub.vogel.b,
                lub.vogel.c,
                lub.roelands.eta_p,
                lub.roelands.p_p,
                self.roelands_z,
                lub.alpha_star_fit.t_min,
                lub.alpha_star_fit.t_max,
            )
        )

    @cached_property
    def alpha_star(self) -> float:
        """alpha* at the run temperature from the fit of eq. 32, 1/Pa."""
        import math

        c = self.alpha_star_fit
        t = self.temperature
        return c["c1"] * math.exp(c["c2"] * t) + c["c3"] * math.exp(c["c4"] * t)

    @cached_property
    def reference_line_load(self) -> float:
        """q_ref = 4.08 F_r / (Z l), N/m: the Stribeck/Harris estimate of the heaviest
        roller's load (zero clearance, line contact) per unit straight roller length."""
        cfg = self.config
        props = _core.roller_mass_properties(
            cfg.geometry.roller_diameter,
            cfg.geometry.roller.length,
            cfg.geometry.roller.edge_radius,
            cfg.geometry.roller.end_face_radius,
            cfg.materials.roller.density,
        )
        radial = abs(cfg.operating.radial_load_at(cfg.end_time))
        return 4.08 * radial / (cfg.geometry.roller_count * props["straight_length"])

    def line_fit_range(self, kind: str) -> tuple[float, float]:
        """Load range (N/m) over which eq. 11 is fitted for ``kind`` (inner/outer/roller)."""
        fit = self.config.solver.line_fit
        if fit.load_min is not None and fit.load_max is not None:
            return fit.load_min, fit.load_max
        q = max(self.reference_line_load, 1e3)
        return (0.01 * q, 0.2 * q) if kind == "roller" else (0.1 * q, 2.0 * q)

    @cached_property
    def line_contacts(self) -> dict[str, LineContactLaw]:
        """Eq. 11 fitted to Tripp for roller-inner race, roller-outer race, roller-roller."""
        cfg = self.config
        g, m = cfg.geometry, cfg.materials
        fit = cfg.solver.line_fit
        r = g.roller_diameter / 2.0
        roller = (m.roller.youngs_modulus, m.roller.poisson_ratio)
        pairs = {
            "inner": ("convex", g.inner_raceway_diameter / 2.0, m.inner_ring),
            "outer": ("outer_ring", g.outer_raceway_diameter / 2.0, m.outer_ring),
            "roller": ("convex", r, m.roller),
        }
        laws = {}
        for name, (face, radius, mat) in pairs.items():
            d = _core.fit_line_power_law(
                r,
                face,
                radius,
                g.outer_ring_wall_thickness,
                *roller,
                mat.youngs_modulus,
                mat.poisson_ratio,
                *self.line_fit_range(name),
                fit.samples,
            )
            laws[name] = LineContactLaw(name=name, **d)
        return laws

    @cached_property
    def traction(self) -> _core.EhlTraction:
        """The EHL traction model at the run temperature (sect. 3.2.1)."""
        return self.traction_model(self.config.solver.traction == "tabulated")

    def traction_model(self, tabulated: bool) -> _core.EhlTraction:
        """:attr:`traction`, its table built (``tabulated``; about 1.5 s, once per
        process) or not (the direct quadrature, built at once: for models whose traction
        is never evaluated, such as the quasi-static one)."""
        lub = self.config.lubricant
        lss = lub.limiting_shear_stress
        return _ehl_traction(
            eta0=self.eta0,
            z=self.roelands_z,
            tau0=lub.carreau.tau0,
            n=lub.carreau.n,
            chi=lss.chi,
            p_star=lss.p_star,
            tau_l0=lss.tau_l0,
            eta_p=lub.roelands.eta_p,
            p_p=lub.roelands.p_p,
            nodes=int(self.config.solver.traction_nodes),
            tabulated=tabulated,
        )


@lru_cache(maxsize=8)
def _ehl_traction(**parameters) -> _core.EhlTraction:
    """The traction model for these parameters, built once per process: its table takes
    about 2 s, and runs of one configuration (resumed runs, tests, the runtime study) share
    it. The model is immutable and depends on nothing else, so sharing changes no result."""
    return _core.EhlTraction(**parameters)


def _array(x: float):
    import numpy as np

    return np.array([x], dtype=float)


def _shown(value: object) -> str:
    """``value``'s repr, shortened to 60 characters."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."
