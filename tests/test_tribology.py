"""The numpy front of the force laws: broadcasting, shapes, and clean errors."""

import numpy as np
import pytest

from rollerdyn import _core
from rollerdyn import tribology as tri

#: A traction model with valid arguments (the values of the error test below).
TRACTION = dict(eta0=0.01, z=0.6, tau0=5e6, n=0.5, chi=0.08, p_star=1e9, tau_l0=8e7)
# B1's roller end and inner flange (examples/b1.toml), one trajectory step.
CONTACT_BENCHMARK = dict(
    roller_diameter=4.495e-3,
    roller_length=5e-3,
    edge_radius=0.5e-3,
    end_face_radius=5.0,
    opening_angle=1.92e-3,
    flange_height=1.1e-3,
    root_radius=0.2e-3,
    rim_radius=0.3e-3,
    raceway_radius=10e-3,
    pitch_radius=12.25e-3,
    axial_play=20e-6,
    steps=1,
    mesh_every=1,
)


def test_broadcasting_and_scalars():
    out = tri.hertz_point(
        1e-3, np.array([[2e-3], [5e-3]]), 2.3e11, np.array([10.0, 100.0, 1000.0]), "exact"
    )
    assert out["semi_major"].shape == (2, 3)
    assert isinstance(tri.hertz_point_force(1e-3, 2e-3, 2.3e11, 1e-6, "exact"), float)
    # force and penetration invert each other elementwise
    f = tri.hertz_point_force(1e-3, 2e-3, 2.3e11, out["penetration"][0], "exact")
    np.testing.assert_allclose(f, [10.0, 100.0, 1000.0], rtol=1e-10)


def test_line_hertz_matches_closed_form():
    # Johnson (1985) eq. 4.45: a = sqrt(8 q R / (pi E')), p0 = 2 q / (pi a).
    a, p0 = tri.hertz_line(1000.0, 1e-3, 2e-3, 2.3e11)
    q = 1000.0 / 1e-3
    assert a == pytest.approx(np.sqrt(8 * q * 2e-3 / (np.pi * 2.3e11)), rel=1e-14)
    assert p0 == pytest.approx(2 * q / (np.pi * a), rel=1e-14)


def test_core_errors_are_value_errors_not_panics():
    with pytest.raises(ValueError, match='must be "brewe_hamrock" or "exact"'):
        tri.ellipticity(2.0, "fit")
    with pytest.raises(ValueError, match="roller radius"):
        _core.roller_mass_properties(-1.0, 5e-3, 5e-4, 5.0, 7850.0)
    with pytest.raises(ValueError, match="edge radius"):
        _core.roller_mass_properties(4e-3, 5e-3, 3e-3, 5.0, 7850.0)
    with pytest.raises(ValueError, match="length"):
        _core.hertz_line(np.ones(3), np.ones(2), np.ones(3), np.ones(3))
    with pytest.raises(ValueError, match="nodes"):
        _core.EhlTraction(
            eta0=0.01, z=0.6, tau0=5e6, n=0.5, chi=0.08, p_star=1e9, tau_l0=8e7, nodes=0
        )
    with pytest.raises(ValueError, match="load_max"):
        _core.fit_line_power_law(2e-3, "convex", 1e-2, 2e-3, 2e11, 0.3, 2e11, 0.3, 1e5, 1e4, 64)


@pytest.mark.parametrize(
    ("call", "named"),
    [
        (lambda t: _core.EhlTraction(**TRACTION, nodes=-1), "nodes = -1: must be a whole"),
        (lambda t: t.ellipse_force_tensor(1e9, 3e-4, 1e-4, 0.05, 2e-7, -3, 8), "across = -3"),
        (lambda t: t.ellipse_force_tensor(1e9, 3e-4, 1e-4, 0.05, 2e-7, 8, 0), "along = 0"),
        (lambda t: t.time_per_evaluation(-5), "repetitions = -5"),
        (
            lambda t: _core.fit_line_power_law(
                2e-3, "convex", 1e-2, 2e-3, 2e11, 0.3, 2e11, 0.3, 1e4, 1e5, -64
            ),
            r"samples = -64: must be a whole number in 2\.\.=10000",
        ),
        (
            lambda t: _core.contact_benchmark(**CONTACT_BENCHMARK, mesh_resolutions=[(32, -8)]),
            r"mesh_resolutions\[0\]\.along = -8: must be a whole number in 1\.\.=4096",
        ),
        (
            lambda t: _core.contact_benchmark(
                **CONTACT_BENCHMARK, mesh_resolutions=[(8, 2), (10**6, 2)]
            ),
            r"mesh_resolutions\[1\]\.around = 1000000",
        ),
    ],
)
def test_negative_counts_are_refused_by_name(call, named):
    """A negative count names its argument and range, not PyO3's "can't convert negative int
    to unsigned" (found by an adversarial pass over the Python API)."""
    traction = _core.EhlTraction(**TRACTION)
    with pytest.raises(ValueError, match=named):
        call(traction)


@pytest.mark.parametrize(
    ("call", "named"),
    [
        (lambda: tri.line_films(np.nan, 1.0, 1.0, 1e5, 2.3e11, 2e-8, 0.02), "r_eff = nan"),
        (lambda: tri.hertz_line(1000.0, 0.0, 2e-3, 2.3e11), "length = 0.0"),
        (lambda: tri.hertz_line([1.0, -5.0], 1e-3, 2e-3, 2.3e11), "force = -5.0"),
        (lambda: tri.hertz_point(-1e-3, 2e-3, 2.3e11, 10.0, "exact"), "r1 = -0.001"),
        (lambda: tri.vogel_viscosity(350.0, -6e-5, 1021.7, 101.6), "k = -6e-05"),
        (lambda: tri.roelands_viscosity(1e8, 0.0, 6.3e-5, -1.96e8, 0.6), "eta0 = 0.0"),
        (
            lambda: tri.tripp_deflection(1e5, 2e-3, "convex", 1e-2, 0, 2e11, 0.3, 2e11, 0.7),
            "nu2 = 0.7",
        ),
        (lambda: tri.elliptic_integrals(1.5), "m1 = 1.5"),
        (lambda: tri.boundary_share(np.inf, 2.3, 0.97), "film_ratio = inf"),
        # an adversarial pass of the Python API (2026-11-28): these gave NaN, inf, negative
        # forces or shares above one
        (lambda: tri.hertz_point(None, 2e-3, 2.3e11, 100.0, "exact"), "r1 = None"),
        (lambda: tri.effective_modulus(-2e11, 0.3, 2.1e11, 0.3), "e1 = -2"),
        (lambda: tri.effective_modulus(2e11, 0.3, 2.1e11, 1.0), "nu2 = 1.0"),
        (lambda: tri.roelands_viscosity(1e8, 0.01, 6.31e-5, 1.96e8, 0.6), "p_p = 196"),
        (lambda: tri.roelands_viscosity(-3e8, 0.01, 6.31e-5, -1.96e8, 0.6), "pressure = -3"),
        (lambda: tri.vogel_viscosity(100.0, 5e-5, 1000.0, 150.0), "temperature = 100.0"),
        (lambda: tri.boundary_share(0.5, -1.0, 1.0), "b = -1.0"),
        (lambda: tri.line_power_law_force(1e-6, 0.01, -1e9, 1.1), "k1 = -1"),
        (
            lambda: _core.EhlTraction(
                eta0=0.0165, z=0.62, tau0=5e6, n=0.5, chi=np.nan, p_star=1.5e9, tau_l0=1.2e8
            ),
            "chi = NaN",
        ),
        (
            lambda: _core.EhlTraction(
                eta0=0.0165, z=0.62, tau0=5e6, n=0.5, chi=0.08, p_star=1.5e9, tau_l0=1.2e8, p_p=0
            ),
            "p_p = 0",
        ),
        (
            lambda: _core.fit_line_power_law(
                2e-3, "convex", 1e-2, 2e-3, 2e11, 0.3, 2e11, 0.3, 1e4, 1e6, 10**12
            ),
            "samples",
        ),
    ],
)
def test_bad_arguments_are_refused_naming_the_argument(call, named):
    # NaN, negative radii, zero lengths and negative viscosity constants never reach the
    # core (issue 16): a ValueError names the argument, its value and the rule.
    with pytest.raises(ValueError, match="must") as err:
        call()
    assert named in str(err.value)


def test_functions_show_their_signatures_and_docstrings():
    import inspect

    assert list(inspect.signature(tri.hertz_line).parameters) == [
        "force",
        "length",
        "r_eff",
        "e_prime",
    ]
    assert "eq. 18" in tri.hertz_line.__doc__
    with pytest.raises(TypeError, match="e_prime"):
        tri.hertz_line(1.0, 2.0, 3.0)


def test_traction_is_odd_and_saturates():
    t = _core.EhlTraction(
        eta0=0.0165, z=0.62, tau0=5e6, n=0.5, chi=0.08, p_star=1.5e9, tau_l0=0.12e9
    )
    p0, a, length = 1.5e9, 1e-4, 2e-4
    args = [np.array([x]) for x in (p0, a, length)]

    def force(sliding_speed: float) -> float:
        return t.line_force(*args, np.array([sliding_speed]), np.array([1e-7]))[0]

    f, g = force(0.5), force(-0.5)
    assert f == pytest.approx(-g, rel=1e-14)
    # The shear stress never exceeds the limiting shear stress τ_L(p) of eq. 50, so the
    # force never exceeds l·∫ τ_L(p₀√(1 − x²)) a dx over the Hertz strip (x in [−1, 1]),
    # and at large sliding (shear rate 1e9 1/s) every node reaches it: the force
    # saturates at that bound. The bound by the trapezoidal rule on 200 001 points (its
    # error below 1e-9 of it); the traction's own Gauss quadrature comes within 3e-7 of it
    # (measured), so 1e-5 holds it.
    x = np.linspace(-1.0, 1.0, 200_001)
    bound = length * a * np.trapezoid(t.limiting_shear_stress(p0 * np.sqrt(1.0 - x**2)), x)
    assert 0.0 < f <= bound * (1.0 + 1e-5)
    assert force(100.0) == pytest.approx(bound, rel=1e-5)
    assert force(0.5) < 0.99 * bound  # not saturated at a shear rate of 5e6 1/s


def test_circle_distance_kinds_and_bad_input():
    # Eberly's special cases: coaxial equal circles have a continuum of closest pairs.
    d2, kind, _, _ = _core.circle_circle_distance(
        (0, 0, 0), (0, 0, 1), 1.0, (0, 0, 2), (0, 0, 1), 1.0
    )
    assert kind == "infinite" and d2 == pytest.approx(4.0, rel=1e-12)
    with pytest.raises(ValueError, match="radii"):
        _core.circle_circle_distance((0, 0, 0), (0, 0, 1), -1.0, (1, 0, 0), (0, 0, 1), 1.0)
    with pytest.raises(ValueError, match="finite"):
        _core.circle_circle_distance((np.nan, 0, 0), (0, 0, 1), 1.0, (1, 0, 0), (0, 0, 1), 1.0)


def test_core_helpers_refuse_what_they_cannot_use():
    """An adversarial pass (2026-11-28): a zero circle normal and a NaN temperature went
    through as answers."""
    with pytest.raises(ValueError, match=r"normal1 = \[0.0, 0.0, 0.0\]: must be a direction"):
        _core.circle_circle_distance((0, 0, 0), (0, 0, 0), 1.0, (0, 0, 2), (0, 0, 1), 1.0)
    with pytest.raises(ValueError, match="temperature = NaN: must be finite and positive"):
        _core.fit_roelands_z(
            0.0165, np.nan, 6.31e-5, -1.96e8, 3.3e7, 2.99e5, 4.4e-3, 3e-4, "initial_slope", 1e9
        )
    assert tri.elliptic_integrals(0.0) == (np.inf, 1.0)  # K(m = 1) diverges, E(m = 1) = 1
    with pytest.raises(ValueError, match="beyond the range of Tripp's solution"):
        tri.tripp_deflection(3e10, 2.2475e-3, "convex", 1e-2, 0, 2.1e11, 0.3, 2.1e11, 0.3)
