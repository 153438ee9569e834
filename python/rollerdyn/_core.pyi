"""Type stubs of ``rollerdyn._core``, the Rust core's bindings (internal API).

Checked against the built extension by ``python -m mypy.stubtest rollerdyn._core``
(scripts/test.sh): every name, argument and default here must match the module.
All quantities are SI. _Array arguments are contiguous 1-D float64 arrays of equal length
(``rollerdyn.tribology`` broadcasts and checks them).
"""

from collections.abc import Callable, Sequence
from typing import Any, final

import numpy as np
import numpy.typing as npt

_Array = npt.NDArray[np.float64]
#: The model's parameters: ``rollerdyn.simulation.model_parameters(config)``, a dict of
#: sections (SI), read into the typed structs of ``crates/rollerdyn-py/src/params/schema.rs``
#: (their one description: a missing, unknown or mistyped key is a ValueError naming its path).
_Params = dict[str, Any]
#: A run's options: ``rollerdyn.simulation.run_options(config, t_end)`` (SI, one section).
_Options = dict[str, Any]

__all__ = [
    "__version__",
    "PAIRINGS",
    "FLANGES",
    "DETECTORS",
    "ARRAY_ARGUMENTS",
    "EhlTraction",
    "Model",
    "simulate",
    "initial_state",
    "equilibrium_state",
    "statics",
    "model_rhs",
    "model_timing",
    "model_energy",
    "ramp_factor",
    "time_slack",
    "roller_mass_properties",
    "contact_benchmark",
    "circle_circle_distance",
    "effective_modulus",
    "elliptic_integrals",
    "ellipticity",
    "hertz_point",
    "hertz_point_force",
    "hertz_line",
    "tripp_deflection",
    "fit_line_power_law",
    "line_power_law_force",
    "vogel_viscosity",
    "roelands_viscosity",
    "dicke_viscosity",
    "fit_roelands_z",
    "carreau_shear_stress",
    "alpha_star_roelands",
    "alpha_star_barus",
    "fit_alpha_star",
    "line_films",
    "chittenden_film",
    "thermal_correction",
    "boundary_friction_coefficient",
    "boundary_share",
    "hysteresis_moment",
    "ehl_rolling_force",
]

__version__: str
PAIRINGS: tuple[str, ...]
FLANGES: tuple[str, ...]
DETECTORS: tuple[str, ...]
#: The elementwise functions below: how many of their leading arguments are arrays.
ARRAY_ARGUMENTS: dict[str, int]

@final
class EhlTraction:
    def __new__(
        cls,
        *,
        eta0: float,
        z: float,
        tau0: float,
        n: float,
        chi: float,
        p_star: float,
        tau_l0: float,
        lss_smoothing: float = 20e6,
        eta_p: float = 0.0631e-3,
        p_p: float = ...,
        nodes: int = 12,
        tabulated: bool = False,
    ) -> EhlTraction: ...
    def ellipse_force(
        self,
        max_pressure: _Array,
        semi_major: _Array,
        semi_minor: _Array,
        sliding_speed: _Array,
        film: _Array,
    ) -> _Array: ...
    def ellipse_force_tensor(
        self,
        max_pressure: float,
        semi_major: float,
        semi_minor: float,
        sliding_speed: float,
        film: float,
        across: int,
        along: int,
    ) -> float: ...
    def limiting_shear_stress(self, pressure: _Array) -> _Array: ...
    def line_force(
        self,
        max_pressure: _Array,
        half_width: _Array,
        length: _Array,
        sliding_speed: _Array,
        film: _Array,
    ) -> _Array: ...
    def shear_stress(self, pressure: _Array, shear_rate: _Array) -> _Array: ...
    def time_per_evaluation(self, repetitions: int) -> Any: ...
    def viscosity(self, pressure: _Array) -> _Array: ...

# --- tribology (paper sect. 3.1.2 - 3.3)
def alpha_star_barus(alpha: _Array) -> _Array: ...
def alpha_star_roelands(eta0: _Array, eta_p: float, p_p: float, z: float) -> _Array: ...
def boundary_friction_coefficient(
    sliding_speed: _Array, rolling_speed: _Array, mu_b0: float, s0: float, smoothing_speed: float
) -> _Array: ...
def boundary_share(film_ratio: _Array, b: float, c: float) -> _Array: ...
def carreau_shear_stress(
    viscosity: _Array, shear_rate: _Array, tau0: float, n: float
) -> _Array: ...
def chittenden_film(
    rx: _Array,
    ry: _Array,
    xi: _Array,
    u0: _Array,
    force: _Array,
    e_prime: float,
    alpha_star: float,
    eta0: float,
) -> _Array: ...
def dicke_viscosity(
    pressure: _Array, temperature: _Array, eta0: _Array, a1: float, a2: float, b1: float, b2: float
) -> _Array: ...
def effective_modulus(e1: float, nu1: float, e2: float, nu2: float) -> float: ...
def ehl_rolling_force(
    r_eff: _Array, length: _Array, u0: _Array, normal_force: _Array, e_prime: float, eta0: float
) -> _Array: ...
def elliptic_integrals(m1: _Array) -> tuple[_Array, _Array]: ...
def ellipticity(radius_ratio: _Array, method_name: str) -> tuple[_Array, _Array, _Array]: ...
def fit_alpha_star(
    k: float, b: float, c: float, eta_p: float, p_p: float, z: float, t_min: float, t_max: float
) -> dict[str, Any]: ...
def fit_line_power_law(
    roller_radius: float,
    counterface: str,
    counter_radius: float,
    wall_thickness: float,
    e1: float,
    nu1: float,
    e2: float,
    nu2: float,
    load_min: float,
    load_max: float,
    samples: int,
) -> dict[str, Any]: ...
def fit_roelands_z(
    eta0: float,
    temperature: float,
    eta_p: float,
    p_p: float,
    a1: float,
    a2: float,
    b1: float,
    b2: float,
    method_name: str,
    p_max: float,
) -> float: ...
def hertz_line(
    force: _Array, length: _Array, r_eff: _Array, e_prime: _Array
) -> tuple[_Array, _Array]: ...
def hertz_point(
    r1: _Array, r2: _Array, e_prime: _Array, force: _Array, method_name: str
) -> dict[str, _Array]: ...
def hertz_point_force(
    r1: _Array, r2: _Array, e_prime: _Array, penetration: _Array, method_name: str
) -> _Array: ...
def hysteresis_moment(normal_force: _Array, half_width: _Array, alpha_v: float) -> _Array: ...
def line_films(
    r_eff: _Array,
    u1: _Array,
    u2: _Array,
    load_per_length: _Array,
    e_prime: float,
    alpha_star: float,
    eta0: float,
) -> dict[str, _Array]: ...
def line_power_law_force(deflection: _Array, length: _Array, k1: float, k2: float) -> _Array: ...
def roelands_viscosity(
    pressure: _Array, eta0: _Array, eta_p: float, p_p: float, z: float
) -> _Array: ...
def thermal_correction(
    u0: _Array, sliding_speed: _Array, viscosity_slope: float, thermal_conductivity: float
) -> _Array: ...
def tripp_deflection(
    load_per_length: _Array,
    roller_radius: float,
    counterface: str,
    counter_radius: float,
    wall_thickness: float,
    e1: float,
    nu1: float,
    e2: float,
    nu2: float,
) -> _Array: ...
def vogel_viscosity(temperature: _Array, k: float, b: float, c: float) -> tuple[_Array, _Array]: ...

# --- time: the core's ramp and the slack within which two times are equal
def ramp_factor(shape: str, x: float) -> float: ...
def time_slack(t: float) -> float: ...

# --- geometry and contact detection (paper sect. 2)
def roller_mass_properties(
    diameter: float, length: float, edge_radius: float, end_face_radius: float, density: float
) -> dict[str, float]: ...
def circle_circle_distance(
    center1: Sequence[float],
    normal1: Sequence[float],
    radius1: float,
    center2: Sequence[float],
    normal2: Sequence[float],
    radius2: float,
) -> tuple[float, str, list[Any], list[Any]]: ...
def contact_benchmark(
    *,
    roller_diameter: float,
    roller_length: float,
    edge_radius: float,
    end_face_radius: float,
    opening_angle: float,
    flange_height: float,
    root_radius: float,
    rim_radius: float,
    raceway_radius: float,
    pitch_radius: float,
    axial_play: float,
    steps: int = 6283,
    step: float = 1e-3,
    push: float = 22e-6,
    wobble: float = 1e-3,
    reference_every: int = 100,
    mesh_every: int = 0,
    mesh_resolutions: Sequence[tuple[int, int]] = ...,
) -> dict[str, Any]: ...

# --- the bearing model (paper sect. 3, 4)
@final
class Model:
    def __new__(cls, params: _Params, traction: EhlTraction, threads: int = 1) -> Model: ...
    @property
    def states(self) -> int: ...
    @property
    def rollers(self) -> int: ...
    def initial_state(self) -> list[float]: ...
    def equilibrium_state(self, t: float) -> list[float]: ...
    def check_point_law(self, t: float) -> None: ...
    def rhs(self, t: float, y: Sequence[float]) -> list[float]: ...
    def jacobian(self, t: float, y: Sequence[float]) -> list[float]: ...
    def energy(self, t: float, y: Sequence[float]) -> float: ...
    def timing(
        self, t: float, y: Sequence[float], rhs_repetitions: int, jacobian_repetitions: int
    ) -> dict[str, Any]: ...
    def run(
        self,
        options: _Options,
        progress: Callable[[float, float, int, int, int, float, bool], object] | None = None,
        start: tuple[float, Sequence[float], float | None] | None = None,
        checkpoint: Callable[[dict[str, Any]], object] | None = None,
    ) -> dict[str, Any]: ...

def initial_state(params: _Params, traction: EhlTraction) -> list[float]: ...
def equilibrium_state(params: _Params, traction: EhlTraction, t: float) -> list[float]: ...

#: A quasi-static load case: (radial load [N], axial load [N], moment about y [N*m], moment
#: about z [N*m], inner ring speed [rad/s], prescribed tilt (about y, about z) [rad] or None
#: for a free tilt, roller set's phase [rad], outer ring speed [rad/s], planet carrier speed
#: [rad/s]).
_StaticCase = tuple[
    float, float, float, float, float, tuple[float, float] | None, float, float, float
]

def statics(
    model: Model, cases: Sequence[_StaticCase], chain: bool = True, stiffness: bool = False
) -> list[dict[str, Any] | str]:
    """The quasi-static equilibrium of each case: a dict of SI arrays, or the core's
    message where none was found; with chain, each starts from the last solution."""

def model_energy(params: _Params, traction: EhlTraction, t: float, y: Sequence[float]) -> float: ...
def model_rhs(
    params: _Params, traction: EhlTraction, t: float, y: Sequence[float]
) -> tuple[list[float], list[float]]: ...
def model_timing(
    params: _Params,
    traction: EhlTraction,
    t: float,
    y: Sequence[float],
    rhs_repetitions: int,
    jacobian_repetitions: int,
) -> dict[str, Any]: ...
def simulate(
    params: _Params,
    traction: EhlTraction,
    options: _Options,
    progress: Callable[[float, float, int, int, int, float, bool], object] | None = None,
    start: tuple[float, Sequence[float], float | None] | None = None,
    checkpoint: Callable[[dict[str, Any]], object] | None = None,
) -> dict[str, Any]: ...
