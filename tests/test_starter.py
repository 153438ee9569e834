"""``rollerdyn new``: a starting configuration for another bearing by B1's proportions
(:mod:`rollerdyn.starter`)."""

from __future__ import annotations

import math

import pytest
from b1 import B1
from hypothesis import given
from hypothesis import strategies as st
from typer.testing import CliRunner

from rollerdyn.cli import app
from rollerdyn.config import load_config
from rollerdyn.starter import LEAST_SPACING, StarterError, most_rollers, starter_geometry
from rollerdyn.statics import statics


def _new(tmp_path, *args: str):
    out = tmp_path / "new.toml"
    result = CliRunner().invoke(app, ["new", str(out), *args])
    return result, out


def test_b1s_raceways_give_b1_back(tmp_path):
    """B1's raceways (20 / 29 mm) and clearance (10 µm) give B1's configuration: every value
    of the loaded file equals examples/b1.toml's but the name and description (the scale
    factor is 1; the values are written to 4 digits, B1's have at most 4), and the roller
    count 17 is the most that fit, as the paper's full complement."""
    result, out = _new(
        tmp_path, "--inner-raceway", "20 mm", "--outer-raceway", "29", "--clearance", "10"
    )
    assert result.exit_code == 0, result.output
    made, b1 = load_config(out).model_dump(), load_config(B1).model_dump()
    for key in ("name", "description"):
        made.pop(key), b1.pop(key)
    assert made == b1
    assert "17 rollers of 4.495 x 5 mm on a pitch diameter of 24.5 mm" in result.output
    assert "L_10r 47.95 1e6 rev" in result.output


def test_a_larger_bearing_is_b1_scaled_and_solves(tmp_path):
    """40 / 52 mm raceways: roller diameter (52 - 40)/2 - c/2 with c B1's 10 µm times the
    pitch diameter over B1's (18.78 µm), 24 rollers (the chord 46 sin(pi/24) = 6.004 mm
    clears 1.001 D = 5.997 mm, 25 would not: 5.765 mm), every scaled length B1's times
    D / 4.495 mm, and its quasi-static equilibrium is found at its loads (B1's scaled by
    Z D L: 12.54 kN radially, a fifth of it axially)."""
    result, out = _new(tmp_path, "--inner-raceway", "40 mm", "--outer-raceway", "52 mm")
    assert result.exit_code == 0, result.output
    cfg = load_config(out)
    g = cfg.geometry
    clearance = 10e-6 * 46.0 / 24.5
    assert g.diametral_clearance == pytest.approx(clearance, rel=5e-4)  # written to 4 digits
    assert g.roller_diameter == pytest.approx(6e-3 - clearance / 2, rel=1e-4)
    assert g.roller_count == 24
    k = g.roller_diameter / 4.495e-3
    for value, b1 in (
        (g.roller.length, 5.0e-3),
        (g.roller.edge_radius, 0.5e-3),
        (g.flange.height, 1.1e-3),
        (g.flange.root_radius, 0.2e-3),
        (g.flange.rim_radius, 0.3e-3),
        (g.outer_ring_wall_thickness, 2.5e-3),
    ):
        assert value == pytest.approx(k * b1, rel=5e-4)
    radial = 5000.0 * 24 * k * g.roller.length / (17 * 5e-3)
    assert cfg.operating.radial_load == pytest.approx(radial, rel=5e-4)
    assert cfg.operating.axial_load == pytest.approx(radial / 5, rel=5e-4)
    ds = statics(cfg)
    assert float(ds.max_roller_load) > 0 and math.isfinite(float(ds.friction_torque))
    # The file's comment on end_time quotes this bearing's end time, not B1's 1.288 s (the
    # speed ramp's end plus two roller-set revolutions; written to 4 digits).
    comment = next(line for line in out.read_text().splitlines() if "end_time is" in line)
    quoted = float(comment.rsplit("about ", 1)[1].removesuffix(" s."))
    assert quoted == pytest.approx(cfg.end_time, rel=5e-4)
    assert quoted != pytest.approx(1.288, rel=1e-2)


@pytest.mark.parametrize(("inner", "outer"), [("65 mm", "90 mm"), ("100 mm", "136 mm")])
def test_larger_bearings_solve_from_the_cold_start_at_their_loads(tmp_path, inner, outer):
    """Bearings of B1's proportions on larger raceways, at the loads `new` writes (B1's
    scaled by Z D L, a fifth axially): each case alone, from the cold start, finds the
    equilibrium that a sweep stepping up the load finds (before, none: the ring's axial
    step over the stiffness floor, scaled with its radial step, shrank that to nothing;
    found by a review, 2026-12-02). Checked against Stribeck's Z Q_max / F_r = 4.08 for
    line contact at zero clearance (Harris & Kotzalas, sect. 7.3), which a small clearance
    and the axial load raise: between 4 and 5."""
    result, out = _new(tmp_path, "--inner-raceway", inner, "--outer-raceway", outer)
    assert result.exit_code == 0, result.output
    assert "quasi-static equilibrium: none" not in result.output, result.output
    cfg = load_config(out)
    ds = statics(cfg)
    stribeck = cfg.geometry.roller_count * float(ds.max_roller_load) / cfg.operating.radial_load
    assert 4.0 < stribeck < 5.0, stribeck


@given(
    pitch=st.floats(5e-3, 2.0),
    ratio=st.floats(0.01, 0.5),
)
def test_the_roller_count_is_the_most_that_fit(pitch, ratio):
    """For any pitch and roller diameter (rollers of 1 … 50 % of the pitch diameter): the
    chord between neighbours' centres, d_m sin(pi/Z), clears LEAST_SPACING roller
    diameters at the count returned and would not at one roller more (or the count is 3,
    the least)."""
    diameter = ratio * pitch
    z = most_rollers(pitch, diameter)
    assert z >= 3
    if z > 3 or pitch * math.sin(math.pi / 3) >= LEAST_SPACING * diameter:
        assert pitch * math.sin(math.pi / z) >= LEAST_SPACING * diameter
    assert pitch * math.sin(math.pi / (z + 1)) < LEAST_SPACING * diameter


#: The raceways of README's example bearing, 40 and 52 mm, as `rollerdyn new` takes them.
RACEWAYS_40_52 = ["--inner-raceway", "40", "--outer-raceway", "52"]


def test_bad_options_are_named(tmp_path):
    """Raceways that make no roller, too many rollers, a clearance larger than the gap, a
    length in kilograms, a speed of 0 or one too slow for an end time, and an existing file
    each exit with status 2 and one line naming the option and the rule; nothing is
    written."""
    cases = [
        (["--inner-raceway", "30", "--outer-raceway", "29"], "--outer-raceway"),
        (
            ["--inner-raceway", "20", "--outer-raceway", "29", "--rollers", "18"],
            "--rollers 18: must be 3 ... 17",
        ),
        (["--inner-raceway", "20", "--outer-raceway", "29", "--clearance", "9 mm"], "--clearance"),
        (["--inner-raceway", "20 kg", "--outer-raceway", "29"], "--inner-raceway"),
        (
            ["--inner-raceway", "20", "--outer-raceway", "29", "--roller-length", "-1"],
            "--roller-length",
        ),
        # options not given are not named: raceways too far apart (rollers of 98 % of the
        # pitch diameter) or too close (0.13 %) for ISO 281's D/d_m of 0.01 ... 0.3, whose
        # ratings the statics need (1000/1003 mm wrote a file that crashed the statics),
        # too close for the default clearance
        (["--inner-raceway", "1", "--outer-raceway", "100"], "D/d_m = 0.98, outside 0.01"),
        (["--inner-raceway", "1000", "--outer-raceway", "1003"], "D/d_m = 0.00129, outside"),
        (["--inner-raceway", "40", "--outer-raceway", "40.01"], "give --clearance"),
        # a clearance far past ISO 5753-1's groups (5 mm in a 6 mm gap: 3.5 mm rollers that
        # carried no load), a roller 167 or 0.017 times its diameter long (a review)
        (
            [*RACEWAYS_40_52, "--clearance", "5 mm"],
            "--clearance 0.005 m: must be at most 1% of the pitch diameter (0.00046 m here)",
        ),
        (
            [*RACEWAYS_40_52, "--roller-length", "1 m"],
            "must be 0.5 ... 10 times the roller diameter (0.005991 m here, L/D = 166.9)",
        ),
        (
            [*RACEWAYS_40_52, "--roller-length", "0.1 mm"],
            "--roller-length 0.0001 m: must be 0.5 ... 10 times",
        ),
        # a value the configuration refuses is led by the option behind it, also where no
        # option sets it (a tiny bearing's inner ring of 0.13 g)
        (
            ["--inner-raceway", "1", "--outer-raceway", "1.5"],
            "--inner-raceway, --outer-raceway (B1's value scaled by their size): inner_ring.mass",
        ),
        (
            [*RACEWAYS_40_52, "--radial-load", "1e9"],
            "--radial-load: operating.radial_load:",
        ),
        # the axial load not given is the radial load's share (not "--axial-load")
        (
            [*RACEWAYS_40_52, "--radial-load", "1e9"],
            "--radial-load (the axial load's default is a fifth of it): operating.axial_load",
        ),
        # a ratio just past the bound is not shown as the bound (60 mm was "L/D = 10")
        (
            [*RACEWAYS_40_52, "--roller-length", "60 mm"],
            "L/D = 10.02",
        ),
        # a speed of 0 has no end time to derive (was a ZeroDivisionError)
        (["--inner-raceway", "20", "--outer-raceway", "29", "--speed", "0"], "--speed 0 rpm"),
        # so slow that two roller-set revolutions pass the longest end time
        (
            ["--inner-raceway", "20", "--outer-raceway", "29", "--speed", "1e-300"],
            "operating.end_time",
        ),
    ]
    for args, named in cases:
        result, out = _new(tmp_path, *args)
        assert result.exit_code == 2, (args, result.output)
        assert named in result.output, (args, result.output)
        assert "Traceback" not in result.output and not out.exists()
    out.write_text("keep")
    result, out = _new(tmp_path, "--inner-raceway", "20", "--outer-raceway", "29")
    assert result.exit_code == 2 and "exists; pass --overwrite to replace it" in result.output
    assert out.read_text() == "keep"
    with pytest.raises(StarterError, match="--rollers 2"):
        starter_geometry(20e-3, 29e-3, rollers=2)


def test_the_python_function_writes_what_the_command_writes(tmp_path):
    """``new_bearing`` (SI arguments) gives the text ``rollerdyn new`` writes."""
    import tomllib

    from rollerdyn.config import parse_config
    from rollerdyn.starter import new_bearing

    result, out = _new(tmp_path, "--inner-raceway", "40 mm", "--outer-raceway", "52 mm")
    assert result.exit_code == 0, result.output
    text = new_bearing(40e-3, 52e-3, "new")
    assert text == out.read_text(encoding="utf-8")
    assert parse_config(tomllib.loads(text)).geometry.roller_count == 24


def test_a_bearing_type_writes_its_flanges(tmp_path):
    """``--type``: the flanges of ISO 15's types as docs/configuration.md maps them (NU the
    outer ring's two, N the inner ring's, NJ and NF one more that carries +x), the
    non-locating NU and N at no axial load by default (they carry none: a load given
    anyway is refused naming operating.axial_load), NUP as B1 (no flanges line, all
    four); an unknown type is named."""
    from rollerdyn.starter import BEARING_TYPES

    for kind, flanges in BEARING_TYPES.items():
        out = tmp_path / f"{kind}.toml"
        result = CliRunner().invoke(
            app, ["new", str(out), "--inner-raceway", "40", "--outer-raceway", "52", "--type", kind]
        )
        assert result.exit_code == 0, (kind, result.output)
        cfg = load_config(out)
        assert list(cfg.geometry.flanges) == (
            flanges or ["inner-x", "inner+x", "outer-x", "outer+x"]
        ), kind
        assert (cfg.operating.axial_load == 0.0) == (kind in ("NU", "N")), kind
    result, out = _new(
        tmp_path,
        "--inner-raceway",
        "40",
        "--outer-raceway",
        "52",
        "--type",
        "NU",
        "--axial-load",
        "100",
    )
    assert result.exit_code == 2 and "operating.axial_load" in result.output
    result, out = _new(tmp_path, "--inner-raceway", "40", "--outer-raceway", "52", "--type", "NQ")
    assert result.exit_code == 2 and "--type NQ: must be one of NUP, NU, N, NJ, NF" in result.output
