"""Issue 16 in the library: results record what made them, resume refuses another
configuration, limits on what drives cost are checked before any work, the Python API
validates as the CLI does, the core checks its own inputs, and Ctrl-C inside
``simulate`` is a KeyboardInterrupt that keeps what was computed."""

import hashlib
import json
import math
import os
import signal
import threading
import time
from pathlib import Path

import pytest
from b1 import B1, B1_TEXT, b1_file_with

import rollerdyn
from rollerdyn import _core
from rollerdyn.config import ConfigError, load_config
from rollerdyn.model import Model
from rollerdyn.provenance import NOT_HASHED, check_same_configuration, config_hash, flatten
from rollerdyn.simulation import (
    MAX_RESULT_BYTES,
    SimulationInterrupted,
    _resume_point,
    check_cost,
    estimated_cost,
    model_parameters,
    simulate,
)


@pytest.fixture(scope="module")
def short_run(b1):
    return simulate(b1, t_end=0.003, threads=1)


def _changed(cfg, section: str, **values):
    return cfg.model_copy(update={section: getattr(cfg, section).model_copy(update=values)})


# --------------------------------------------------------------------------- provenance


def test_a_result_records_its_configuration_version_and_commit(short_run, b1):
    a = short_run.attrs
    assert a["config_toml"] == B1_TEXT
    resolved = json.loads(a["config_resolved"])
    assert resolved["operating"]["radial_load"] == 5000.0  # SI, as resolved
    assert a["config_sha256"] == config_hash(b1) and len(a["config_sha256"]) == 64
    assert a["rollerdyn_version"] == rollerdyn.__version__
    assert "git_commit" in a


def test_a_changed_configuration_records_no_stale_text(b1):
    # the TOML text is recorded only while it still gives the configuration's values
    changed = _changed(b1, "operating", radial_load=100.0)
    ds = simulate(changed, t_end=0.001, threads=1)
    assert ds.attrs["config_toml"] == ""
    assert json.loads(ds.attrs["config_resolved"])["operating"]["radial_load"] == 100.0


def test_the_hash_ignores_only_what_a_resumed_run_may_change(b1):
    assert config_hash(_changed(b1, "solver", checkpoint_interval=0.05)) == config_hash(b1)
    assert config_hash(_changed(b1, "operating", end_time=2.0)) == config_hash(b1)
    assert config_hash(_changed(b1, "operating", radial_load=5001.0)) != config_hash(b1)
    assert config_hash(_changed(b1, "solver", rtol=2e-5)) != config_hash(b1)


def test_resume_refuses_another_configuration_naming_the_field(short_run, b1):
    # a B1 run resumed with radial_load = 100 N was spliced onto the 5000 N run before
    other = _changed(b1, "operating", radial_load=100.0)
    with pytest.raises(ValueError, match="another configuration") as err:
        simulate(other, t_end=0.006, resume=short_run, threads=1)
    assert "operating.radial_load: 5000.0 -> 100.0" in str(err.value)


def test_resume_makes_the_point_laws_load_check_at_its_new_end_time(b1):
    # B1 at 2000 N run for 1 ms (the loads then are light: not refused) and resumed to
    # 0.6 s: the resumed run reaches the loads a fresh run to 0.6 s is refused at, and
    # was let through (its steps then stalled at 0.503 s)
    heavy = _changed(b1, "operating", axial_load=2000.0)
    first = simulate(heavy, t_end=0.001, threads=1)
    with pytest.raises(ValueError, match=r"surfaces.flange_law = point: at the loads of t = 0"):
        simulate(heavy, t_end=0.6, threads=1)
    with pytest.raises(ValueError, match=r"surfaces.flange_law = point: at the loads of t = 0"):
        simulate(heavy, t_end=0.6, resume=first, threads=1)


def test_resume_refuses_a_result_changed_after_its_run(short_run, b1):
    # each was a traceback (KeyError), a silent loss of outputs, or a start from the wrong
    # state, found by editing result files by hand
    import numpy as np

    no_time = short_run.drop_vars("checkpoint_time")
    with pytest.raises(ValueError, match="has checkpoint_state, checkpoint_step but no "):
        simulate(b1, t_end=0.006, resume=no_time, threads=1)
    times = short_run.time.values.copy()
    times[1] = np.nan
    with pytest.raises(ValueError, match="output times are not finite and increasing"):
        simulate(b1, t_end=0.006, resume=short_run.assign_coords(time=times), threads=1)
    fresh = short_run.copy()
    fresh["checkpoint_step"] = np.nan  # the fresh start's mark, at a later time
    fresh["checkpoint_time"] = 0.0015
    with pytest.raises(ValueError, match="has no step"):
        simulate(b1, t_end=0.006, resume=fresh, threads=1)


def test_resume_refuses_a_result_without_a_configuration_record(short_run, b1):
    stripped = short_run.copy()
    del stripped.attrs["config_sha256"]
    with pytest.raises(ValueError, match="records no configuration"):
        simulate(b1, t_end=0.006, resume=stripped, threads=1)


def _recorded_before_the_move(ds):
    """``ds`` with its configuration record as written before border_band_roller,
    border_band_flange and friction moved from [surfaces] to [solver] (same values)."""
    values = json.loads(ds.attrs["config_resolved"])
    for key in ("border_band_roller", "border_band_flange", "friction"):
        values["surfaces"][key] = values["solver"].pop(key)
    del values["solver"]["outputs"]  # added later still (provenance.ADDED_FIELDS)
    hashed = {k: v for k, v in flatten(values).items() if k not in NOT_HASHED}
    old = ds.copy()
    old.attrs["config_resolved"] = json.dumps(values, sort_keys=True)
    old.attrs["config_sha256"] = hashlib.sha256(
        json.dumps(hashed, sort_keys=True).encode("utf-8")
    ).hexdigest()
    return old


def test_a_result_recorded_before_settings_moved_resumes_with_them_in_solver(b1):
    # before the move results recorded the groups of solver.outputs of that time
    three = _changed(b1, "solver", outputs=("rollers", "flanges", "power"))
    run = simulate(three, t_end=0.003, threads=1)
    old = _recorded_before_the_move(run)
    assert old.attrs["config_sha256"] != run.attrs["config_sha256"]
    check_same_configuration(old.attrs, three)  # the same values, at their new places
    t0, y, _ = _resume_point(old, three, "semi-analytical", 0.006)
    assert (t0, y) == _resume_point(run, three, "semi-analytical", 0.006)[:2]
    # a real difference is named as now, with no noise from the moved fields
    other = _changed(three, "solver", friction=False)
    with pytest.raises(ValueError, match="another configuration") as err:
        simulate(other, t_end=0.006, resume=old, threads=1)
    assert "solver.friction: True -> False" in str(err.value)
    assert "surfaces." not in str(err.value)


def test_a_field_added_later_leaves_the_hash_of_its_default_as_it_was(b1):
    """``solver.outputs`` came after results began to record their configuration's hash:
    at what every earlier run recorded (the groups "rollers", "flanges" and "power") a
    configuration hashes as it did without the field, so such results resume and such
    studies go on; another value is a difference like any other, and so is today's
    default, which adds "lubrication": a result without it is not continued as one with
    it."""
    earlier = _changed(b1, "solver", outputs=("rollers", "flanges", "power"))
    values = earlier.model_dump(mode="json")
    del values["solver"]["outputs"]
    hashed = {k: v for k, v in flatten(values).items() if k not in NOT_HASHED}
    before = hashlib.sha256(json.dumps(hashed, sort_keys=True).encode("utf-8")).hexdigest()
    assert config_hash(earlier) == before
    assert config_hash(b1) != before
    bare = _changed(b1, "solver", outputs=())
    assert config_hash(bare) != before


# --------------------------------------------------------------------------- limits


@pytest.mark.parametrize(
    ("old", "new", "field"),
    [
        ("slices = 20 ", "slices = 100000000 ", "geometry.roller.slices"),
        ('output_interval = "1e-3 s"', 'output_interval = "1e-12 s"', "solver.output_interval"),
        ('dt_max = "1e-3 s"', 'dt_max = "1e-15 s"', "solver.dt_max"),
        ("rtol = 1e-5 ", "rtol = 1e-30 ", "solver.rtol"),
        ('radial_load = "5000 N"', 'radial_load = "1e300 N"', "operating.radial_load"),
        ('axial_load = "1000 N"', 'axial_load = "1e7 N"', "operating.axial_load"),
        ('inner_ring_speed = "500 rpm"', 'inner_ring_speed = "1e300 rpm"', "inner_ring_speed"),
        ("samples = 64 ", "samples = 100000000 ", "solver.line_fit.samples"),
    ],
)
def test_what_drives_cost_or_lies_beyond_any_bearing_is_refused(tmp_path, old, new, field):
    # slices = 1e8 hung at 1.7 GB and output_interval = 1e-12 s aborted in Rust before
    start = time.monotonic()
    with pytest.raises(ConfigError) as err:
        load_config(b1_file_with(tmp_path, old, new))
    assert field in str(err.value) and "must" in str(err.value)
    assert time.monotonic() - start < 5.0  # refused before any work, not after a hang


def test_the_load_limit_is_a_hertz_pressure_of_10_gpa(b1):
    # Independent check: Stribeck's heaviest roller Q = 4.08 F/Z at the limit load gives
    # p0 = sqrt(Q E' / (2 pi R' l)) = 10 GPa on B1's inner race (Harris & Kotzalas, eq. 6.39).
    q = 4.08 * b1.load_limit / 17
    r_eff = 1 / (1 / 2.2475e-3 + 1 / 10e-3)
    e_prime = 2 / (2 * (1 - 0.3**2) / 210e9)
    p0 = math.sqrt(q * e_prime / (2 * math.pi * r_eff * 4e-3))
    assert p0 == pytest.approx(10e9, rel=1e-9)
    assert 5000.0 < b1.load_limit < 1e6  # B1's own loads pass


def test_a_run_far_beyond_a_normal_one_is_refused_with_its_estimate(b1):
    fine = _changed(b1, "solver", output_interval=1e-8)  # allowed by the schema (>= 1 ns)
    cost = estimated_cost(fine, 1.288)
    assert cost["outputs"] == pytest.approx(1.288e8, rel=1e-6)
    with pytest.raises(ValueError, match=r"solver.output_interval = 1e-08 s.*GB.*--force"):
        simulate(fine, threads=1)
    # with any group selected the core records every group until the result is built, so
    # one group costs the run's memory of all four; with none (solver.outputs = []) it
    # records the bearing's own outputs only: the memory is the file's, 17 of 1 615
    # numbers per output (B1: 1 + 13 scalars + 3 + 2, against 17 rollers' records)
    one = _changed(fine, "solver", outputs=("flanges",))
    assert estimated_cost(one, 1.288)["memory_bytes"] == cost["memory_bytes"]
    with pytest.raises(ValueError, match=r"solver.output_interval = 1e-08 s.*outputs = \[\]"):
        simulate(one, threads=1)
    bare = _changed(fine, "solver", outputs=())
    cost = estimated_cost(bare, 1.288)
    assert cost["memory_bytes"] == cost["bytes"] == cost["outputs"] * 8 * 17
    with pytest.raises(ValueError, match=r"solver.output_interval = 1e-08 s.*GB.*--force"):
        simulate(bare, threads=1)  # 1.288e8 outputs of 136 bytes: 17.5 GB all the same
    every_us = _changed(bare, "solver", output_interval=1e-6)
    check_cost(every_us, 1.288)  # 1.3e6 outputs: 0.18 GB bare (16.6 GB with the rollers)
    assert (
        estimated_cost(_changed(every_us, "solver", outputs=("rollers",)), 1.288)["memory_bytes"]
        > MAX_RESULT_BYTES
    )
    slow = _changed(b1, "solver", dt_max=1e-9)
    with pytest.raises(ValueError, match=r"solver.dt_max = 1e-09 s.*steps"):
        check_cost(slow, 1.288)
    check_cost(b1, b1.end_time)  # B1 itself is a normal run


# --------------------------------------------------------------------------- Python API


def test_simulate_takes_a_path(tmp_path):
    ds = rollerdyn.simulate(B1, t_end="2 ms", threads=1)
    assert float(ds.attrs["final_time_s"]) == pytest.approx(0.002)
    # the package's simulate takes every argument of rollerdyn.simulation.simulate, whose
    # documentation it points to (checkpoint and notice were refused as unknown)
    saved = []
    every_ms = load_config(B1, {"solver.checkpoint_interval": "1 ms"})
    rollerdyn.simulate(every_ms, t_end="2 ms", threads=1, checkpoint=saved.append, notice=print)
    assert [float(s.attrs["final_time_s"]) for s in saved] == pytest.approx([0.001, 0.002])
    with pytest.raises(ConfigError, match="not found"):
        rollerdyn.simulate(tmp_path / "nope.toml", t_end=0.001)


@pytest.mark.parametrize(
    ("section", "values", "field"),
    [
        ("solver", {"rtol": -1.0}, "solver.rtol"),
        ("solver", {"dt_max": float("nan")}, "solver.dt_max"),
        ("solver", {"output_interval": -1.0}, "solver.output_interval"),
        ("operating", {"radial_load": float("inf")}, "operating.radial_load"),
    ],
)
def test_a_config_changed_in_python_is_validated_again(b1, section, values, field):
    # rtol = -1 and dt_max = nan ran to "completed", output_interval = -1 hung before
    with pytest.raises(ConfigError) as err:
        simulate(_changed(b1, section, **values), t_end=0.001, threads=1)
    assert field in str(err.value)


@pytest.mark.parametrize("t_end", ["5 N", -1.0, float("nan"), "soon"])
def test_a_bad_end_time_is_refused(b1, t_end):
    with pytest.raises(ValueError, match="t_end"):
        simulate(b1, t_end=t_end, threads=1)


def test_an_end_time_of_any_real_number_type_is_taken(b1):
    # numpy's scalars and 0-d arrays, Fraction and Decimal are numbers of seconds like a
    # float (they were refused as "must be a finite time"); booleans and arrays are not
    from decimal import Decimal
    from fractions import Fraction

    import numpy as np

    from rollerdyn.units import parse_time

    for value in (np.float32(0.5), np.int64(1), Fraction(1, 500), Decimal("0.002")):
        assert parse_time(value, "t_end") == pytest.approx(float(value), rel=1e-7)
    assert parse_time(np.array(0.002), "t_end") == 0.002
    for value in (np.True_, np.array([0.002]), Decimal("NaN")):
        with pytest.raises(ValueError, match="t_end"):
            parse_time(value, "t_end")
    # a control character inside ("2 ms\x00" passed; a review), not the whitespace round it
    with pytest.raises(ValueError, match="a control character in it"):
        parse_time("2 ms\x00", "t_end")
    assert parse_time("2 ms\n", "t_end") == pytest.approx(0.002)
    with pytest.raises(ValueError, match="a control character in it"):
        parse_time("2 ms\x1f", "t_end")  # which str.strip() removes
    ds = simulate(b1, t_end=np.float64(0.001), threads=1)
    assert float(ds.attrs["final_time_s"]) == pytest.approx(0.001)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"progress": 5}, "progress = 5: must be a function"),
        ({"checkpoint": "file.nc"}, "checkpoint = 'file.nc': must be a function"),
        ({"notice": print, "force": "no"}, "force = 'no': must be True or False"),
    ],
)
def test_bad_callbacks_and_flags_are_refused_before_the_run(b1, kwargs, match):
    # a progress of 5 failed only at the first report, as "interrupted ... TypeError",
    # and force="no" counted as true
    with pytest.raises(ValueError, match=match):
        simulate(b1, t_end=0.001, threads=1, **kwargs)


@pytest.mark.parametrize(
    ("path", "match"),
    [
        (None, "path = None: expected the configuration file's path"),
        (5, "got int"),
        ({"name": "B1"}, "got dict"),
        ("", "no configuration file named"),
    ],
)
def test_load_config_names_a_path_of_the_wrong_type(path, match):
    with pytest.raises(ConfigError, match=match):
        load_config(path)


@pytest.mark.parametrize(
    ("option", "value"),
    [
        ("rtol", float("nan")),
        ("dt_max", -1e-4),
        ("output_interval", 0.0),
        ("atol", math.inf),
        ("min_mean_step", -1e-9),
    ],
)
def test_the_core_checks_its_own_run_options(b1, option, value):
    # the core never runs on a NaN tolerance, even when called past the front end
    options = {
        "t_end": 0.001,
        "rtol": 1e-5,
        "atol": 1e-9,
        "atol_time_scale": 1e-5,
        "dt_max": 1e-4,
        "output_interval": 1e-3,
        "method": "tr-bdf2",
        "max_step_growth": 1.3,
        "step_gain": 0.3,
        "jacobian_after_newton_failure": True,
        "jacobian_at_latest_iterate": True,
        "partial_jacobians": 2,
        "checkpoint_interval": 0.1,
        "threads": 1,
        "start": "rest",
        "min_mean_step": 2e-8,
        "check_flange_law": True,
        "roller_records": True,
        option: value,
    }
    with pytest.raises(ValueError, match=option):
        _core.simulate(model_parameters(b1), Model(b1).traction, options)


# --------------------------------------------------------------------------- signals


def test_ctrl_c_inside_simulate_is_a_keyboard_interrupt_within_a_second(b1):
    # The interrupt is read between outputs too (every 0.2 s of wall time), so a run with
    # one output per 0.5 s of simulated time still stops within a second of Ctrl-C.
    sparse = _changed(b1, "solver", output_interval=0.5, checkpoint_interval=1.0)
    sent: list[float] = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(2.0, interrupt)
    # Python's own handler, which turns SIGINT into KeyboardInterrupt: a process that a
    # non-interactive shell starts in the background has SIGINT ignored, and Python leaves
    # it so (measured: the whole suite started that way ran this test's whole second of B1
    # and failed here, twice; started in the foreground it passed).
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as err:
            simulate(sparse, t_end=1.0, threads=1)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, handler)
    latency = time.monotonic() - sent[0]
    assert latency < 1.0, latency
    assert isinstance(err.value, SimulationInterrupted)
    assert err.value.dataset.sizes["time"] >= 1  # what was computed is kept


def test_progress_is_reported_between_outputs(b1):
    # 15 ms of B1 take about 1.5 s of wall time: several reports fall between its outputs
    sparse = _changed(b1, "solver", output_interval=0.015)
    seen = []
    simulate(sparse, t_end=0.015, threads=1, progress=seen.append)
    between = [p for p in seen if 0.0 < p.time < 0.015 - 1e-12]
    assert between, [p.time for p in seen]  # a slow run's bar moves between outputs


def _time_to_reach_the_entry_point() -> float:
    """Wall time of a Python that imports ``rollerdyn._entry`` and exits, the longest of
    three: before the entry point runs, a Ctrl-C is Python's own (its start takes 20-50 ms
    here, more on a loaded machine; a fixed 50 ms delay once landed in it)."""
    import subprocess
    import sys

    times = []
    for _ in range(3):
        start = time.monotonic()
        subprocess.run([sys.executable, "-c", "import rollerdyn._entry"], check=True)
        times.append(time.monotonic() - start)
    return max(times)


@pytest.mark.parametrize("delay", ["imports", 0.4, 1.2])
def test_ctrl_c_while_the_command_starts_is_one_line(tmp_path, delay):
    # Ctrl-C while Python imports the libraries or builds the model (before the run's own
    # handler): one line and status 130, never a traceback (typer alone exits silently).
    # "imports": as soon as the entry point surely runs (twice the time a Python needs to
    # reach it), well inside the second of the heavy imports that follow.
    import subprocess
    import sys

    if delay == "imports":
        delay = max(0.05, 2.0 * _time_to_reach_the_entry_point())
    command = Path(sys.executable).parent / "rollerdyn"
    args = [str(command), "run", str(B1), "-o", str(tmp_path / "r.nc"), "--t-end", "0.05"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    assert proc.returncode == 130, out
    assert "Traceback" not in out
    assert "interrupted" in out, out


def test_the_package_imports_light_and_keeps_its_functions():
    # `import rollerdyn` loads no heavy library (the command can be interrupted while it
    # starts); rollerdyn.report and rollerdyn.sweep stay the functions after their
    # modules are imported.
    import subprocess
    import sys

    code = (
        "import sys, rollerdyn; light = 'xarray' not in sys.modules; "
        "import rollerdyn.report, rollerdyn.sweep; "
        "print(light, callable(rollerdyn.report), rollerdyn.sweep.__name__)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.stdout.split() == ["True", "True", "sweep"], out.stderr


def test_the_core_model_is_built_once_and_answers_as_the_functions_do(b1):
    # _core.Model (issue 17's typed boundary): one model for every call, the same numbers
    # as the one-shot functions, bit for bit; a wrong state length is a ValueError.
    import numpy as np

    params, traction = model_parameters(b1), Model(b1).traction
    model = _core.Model(params, traction, 2)
    y = model.initial_state()
    assert y == _core.initial_state(params, traction) and model.states == len(y)
    assert model.rollers == 17
    f, jac = _core.model_rhs(params, traction, 0.0, y)
    assert np.array_equal(model.rhs(0.0, y), f)
    assert np.array_equal(model.jacobian(0.0, y), jac)
    assert model.energy(0.0, y) == _core.model_energy(params, traction, 0.0, y)
    with pytest.raises(ValueError, match="states"):
        model.rhs(0.0, y[:-1])
    # counts are checked by name (PyO3 alone said "can't convert negative int to unsigned")
    with pytest.raises(ValueError, match="threads = -1: must be a whole number in 1"):
        _core.Model(params, traction, -1)
    with pytest.raises(ValueError, match="rhs_repetitions = 0"):
        model.timing(0.0, y, 0, 1)
    with pytest.raises(ValueError, match="jacobian_repetitions = -2"):
        model.timing(0.0, y, 1, -2)


def test_a_full_disk_is_refused_before_hdf5_writes(tmp_path, monkeypatch):
    # HDF5 that runs out of space mid-write printed tracebacks it could not raise and
    # crashed the process (a full tmpfs); the room is checked first: OSError (ENOSPC), no
    # temporary file, and the earlier file untouched.
    import errno
    import shutil
    from collections import namedtuple

    import numpy as np
    import xarray as xr

    from rollerdyn.simulation import write

    ds = xr.Dataset({"x": ("time", np.arange(1000.0))})
    path = tmp_path / "r.nc"
    write(ds, path)
    before = path.read_bytes()
    usage = namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda _: usage(10**6, 10**6 - 4096, 4096))
    with pytest.raises(OSError) as err:
        write(ds, path)
    assert err.value.errno == errno.ENOSPC and "4096 bytes free" in str(err.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc"]
    assert path.read_bytes() == before
