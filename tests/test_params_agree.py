"""The parameter dicts of the front end and the core's structs cannot disagree silently.

``rollerdyn.simulation.model_parameters`` and ``run_options`` build untyped SI dicts that the
bindings (``crates/rollerdyn-py/src/params.rs``) read into the core's ``BearingParams`` and
``RunOptions``. The bindings record every key they read, the nested time histories
included, and refuse a key they did not read as they refuse a missing one, naming it. B1's
dicts are read whole; each key, removed, is refused by name; one key more is refused by name.
"""

from __future__ import annotations

import time

import pytest

from rollerdyn import _core
from rollerdyn.config import BearingConfig
from rollerdyn.model import Model
from rollerdyn.simulation import model_parameters, run_options

HISTORIES = ("radial_load", "axial_load", "inner_ring_speed")


@pytest.fixture(scope="module")
def traction(b1: BearingConfig) -> _core.EhlTraction:
    return Model(b1).traction


@pytest.fixture(scope="module")
def params(b1: BearingConfig) -> dict:
    return model_parameters(b1)


@pytest.fixture(scope="module")
def options(b1: BearingConfig) -> dict:
    return run_options(b1, b1.end_time)


def _stop(*_progress: object) -> bool:
    return True  # stops the run at its first report: the options were read whole by then


def _refused(build, bad: dict, message: str) -> None:
    with pytest.raises(ValueError) as err:
        build(bad)
    assert str(err.value) == message


# --------------------------------------------------------------------------- model parameters


def test_b1_parameters_build_a_model_reading_every_key(params, traction):
    started = time.perf_counter()
    model = _core.Model(params, traction)
    assert time.perf_counter() - started < 0.5  # milliseconds: the loops below are cheap
    assert model.rollers == 17
    # the three histories are nested dicts, each read key by key too
    assert all(isinstance(params[h], dict) for h in HISTORIES)


@pytest.mark.parametrize("extra", ["bogus", "border_band", "surfaces.friction"])
def test_a_parameter_the_core_does_not_read_is_refused_naming_it(params, traction, extra):
    _refused(
        lambda d: _core.Model(d, traction),
        {**params, extra: 1.0},
        f"model parameter {extra} is not a parameter of the core",
    )


def test_every_parameter_removed_is_refused_naming_it(params, traction):
    assert len(params) > 60
    for key in params:
        rest = {k: v for k, v in params.items() if k != key}
        _refused(lambda d: _core.Model(d, traction), rest, f"model parameter {key} is missing")


@pytest.mark.parametrize("history", HISTORIES)
def test_every_key_of_a_history_is_read_and_required(params, traction, history):
    ramp = params[history]
    assert ramp["kind"] == "ramp"
    build = lambda d: _core.Model(d, traction)  # noqa: E731
    _refused(
        build,
        {**params, history: {**ramp, "bogus": 0.0}},
        f"model parameter {history}.bogus is not a parameter of the core",
    )
    for key in ramp:
        rest = {k: v for k, v in ramp.items() if k != key}
        _refused(build, {**params, history: rest}, f"model parameter {history}.{key} is missing")
    table = {"kind": "table", "times": [0.0, 1.0], "values": [0.0, 1.0]}
    _core.Model({**params, history: table}, traction)
    _refused(
        build,
        {**params, history: {**table, "value": 1.0}},  # a ramp's key in a table
        f"model parameter {history}.value is not a parameter of the core",
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


def test_threads_is_an_option_of_simulate_only_as_a_whole_number(params, traction, options):
    # _core.simulate builds its model on options["threads"] (Model.run: the model's own)
    model = _core.Model(params, traction)
    _refused(
        lambda d: model.run(d, _stop),
        {**options, "threads": "two"},
        "run option threads = two: wrong type",
    )
    raw = _core.simulate(params, traction, {**options, "threads": 1}, _stop)
    assert raw["final_time"] < options["t_end"]
