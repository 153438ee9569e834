"""The parameter dicts of the front end and the core's structs cannot disagree silently.

``rollerdyn.simulation.model_parameters`` builds a dict of sections (``geometry``,
``materials``, ..., ``solver``), each a dict of SI values or of nested sections, and
``run_options`` one flat dict; the bindings read them into typed structs of the same
shape (``crates/rollerdyn-py/src/params/schema.rs``) and then into the core's
``BearingParams`` and ``RunOptions``. Every key is read at every depth (the time histories
included), and a key no struct has is refused as a missing key is, naming its path. B1's
dicts are read whole; each key, at every depth, removed or given a value of the wrong type
is refused by its path; one key more, at the top or in a section, is refused by its path.
"""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest
from b1 import changed_b1

from rollerdyn import _core
from rollerdyn.config import BearingConfig
from rollerdyn.model import Model
from rollerdyn.simulation import model_parameters, run_options

HISTORIES = ("radial_load", "axial_load", "inner_ring_speed", "outer_ring_speed", "carrier_speed")
SECTIONS = (
    "geometry",
    "materials",
    "inner_ring",
    "lubricant",
    "surfaces",
    "operating",
    "cavity",
    "solver",
)
#: The values that are names, and the names each may be (in the core's messages).
CHOICES = {
    "solver.detector": "semi-analytical, gradient or mesh",
    "surfaces.flange_law": "point or distributed",
    "surfaces.rolling_resistance": "paper or balanced",
    "method": "tr-bdf2 or esdirk34",
    "start": "rest or equilibrium",
    **{f"operating.{h}.kind": "ramp or table" for h in HISTORIES},
    **{f"operating.{h}.shape": "linear or cosine" for h in HISTORIES},
}


@pytest.fixture(scope="module")
def traction(b1: BearingConfig) -> _core.EhlTraction:
    return Model(b1).traction


@pytest.fixture(scope="module")
def params(b1: BearingConfig) -> dict:
    return model_parameters(b1)


@pytest.fixture(scope="module")
def options(b1: BearingConfig) -> dict:
    return run_options(b1, b1.end_time)


def _paths(d: dict, prefix: str = "") -> Iterator[str]:
    """The dotted path of every key of ``d`` at every depth, a section before its keys."""
    for key, value in d.items():
        yield prefix + key
        if isinstance(value, dict):
            yield from _paths(value, f"{prefix}{key}.")


def _leaves(d: dict) -> list[str]:
    """The paths of the values that are not sections."""
    return [p for p in _paths(d) if not isinstance(_at(d, p), dict)]


def _at(d: dict, path: str):
    for key in path.split("."):
        d = d[key]
    return d


def _stop(*_progress: object) -> bool:
    return True  # stops the run at its first report: the options were read whole by then


def _refused(build, bad: dict, message: str) -> None:
    with pytest.raises(ValueError) as err:
        build(bad)
    assert str(err.value) == message


def _wrong(noun: str, path: str) -> str:
    """The core's message for the value "x" under ``path``."""
    rule = f"must be {CHOICES[path]}" if path in CHOICES else "wrong type"
    return f"{noun} {path} = x: {rule}"


# --------------------------------------------------------------------------- model parameters


def test_b1_parameters_build_a_model_reading_every_key(params, traction):
    started = time.perf_counter()
    model = _core.Model(params, traction)
    assert time.perf_counter() - started < 0.5  # milliseconds: the loops below are cheap
    assert model.rollers == 17
    # the sections of the configuration, physical and numerical apart
    assert tuple(params) == SECTIONS
    assert all(isinstance(params[s], dict) for s in SECTIONS)
    # the three histories are nested dicts, each read key by key too
    assert all(isinstance(params["operating"][h], dict) for h in HISTORIES)


@pytest.mark.parametrize(
    "extra",
    [
        "bogus",
        "border_band",
        "roller_radius",  # a key of the old flat dict
        "surfaces.friction",  # a numerical setting among the physical ones
        "solver.eta0",
        "geometry.roller.bogus",
        "geometry.inner_flange.bogus",
        "operating.radial_load.bogus",
    ],
)
def test_a_parameter_the_core_does_not_read_is_refused_naming_it(params, traction, extra):
    _refused(
        lambda d: _core.Model(d, traction),
        changed_b1({extra: 1.0}, params),
        f"model parameter {extra} is not a parameter of the core",
    )


def test_every_parameter_removed_is_refused_naming_it(params, traction):
    assert len(_leaves(params)) > 60
    paths = list(_paths(params))
    assert {"geometry", "geometry.roller", "geometry.roller.radius"} <= set(paths)
    for path in paths:
        rest = changed_b1({path: None}, params)
        _refused(lambda d: _core.Model(d, traction), rest, f"model parameter {path} is missing")


def test_every_parameter_of_the_wrong_type_is_refused_naming_it(params, traction):
    # a string where a number, a flag, a list or a section belongs; a name not among the
    # choices where a name belongs
    for path in _paths(params):
        _refused(
            lambda d: _core.Model(d, traction),
            changed_b1({path: "x"}, params),
            _wrong("model parameter", path),
        )


@pytest.mark.parametrize("history", HISTORIES)
def test_every_key_of_a_history_is_read_and_required(params, traction, history):
    path = f"operating.{history}"
    ramp = _at(params, path)
    assert ramp["kind"] == "ramp"
    build = lambda d: _core.Model(d, traction)  # noqa: E731
    _refused(
        build,
        changed_b1({f"{path}.bogus": 0.0}, params),
        f"model parameter {path}.bogus is not a parameter of the core",
    )
    for key in ramp:
        rest = changed_b1({f"{path}.{key}": None}, params)
        _refused(build, rest, f"model parameter {path}.{key} is missing")
    table = {"kind": "table", "times": [0.0, 1.0], "values": [0.0, 1.0]}
    _core.Model(changed_b1({path: table}, params), traction)
    _refused(
        build,
        changed_b1({path: {**table, "value": 1.0}}, params),  # a ramp's key in a table
        f"model parameter {path}.value is not a parameter of the core",
    )


# --------------------------------------------------------------------------- run options


def test_b1_run_options_are_read_whole(params, traction, options):
    model = _core.Model(params, traction)
    raw = model.run(options, _stop)
    assert raw["final_time"] < options["t_end"]  # stopped at once, after reading them


def test_a_run_option_the_core_does_not_read_is_refused_naming_it(params, traction, options):
    model = _core.Model(params, traction)
    _refused(
        lambda d: model.run(d, _stop),
        {**options, "bogus": 1.0},
        "run option bogus is not an option of the core",
    )


def test_every_run_option_removed_is_refused_naming_it(params, traction, options):
    model = _core.Model(params, traction)
    for key in options:
        rest = {k: v for k, v in options.items() if k != key}
        _refused(lambda d: model.run(d, _stop), rest, f"run option {key} is missing")


def test_every_run_option_of_the_wrong_type_is_refused_naming_it(params, traction, options):
    model = _core.Model(params, traction)
    for key in [*options, "threads"]:
        _refused(lambda d: model.run(d, _stop), {**options, key: "x"}, _wrong("run option", key))


def test_threads_is_an_option_of_simulate_only_as_a_whole_number(params, traction, options):
    # _core.simulate builds its model on options["threads"] (Model.run: the model's own)
    model = _core.Model(params, traction)
    _refused(
        lambda d: model.run(d, _stop),
        {**options, "threads": "two"},
        "run option threads = two: wrong type",
    )
    _refused(
        lambda d: _core.simulate(params, traction, d, _stop),
        {**options, "threads": "two"},
        "run option threads = two: wrong type",
    )
    raw = _core.simulate(params, traction, {**options, "threads": 1}, _stop)
    assert raw["final_time"] < options["t_end"]
