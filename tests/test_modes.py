"""``rollerdyn modes``: the modes of the equations of motion at a run's final state
(python/rollerdyn/modes.py, cli/modes.py)."""

from __future__ import annotations

import numpy as np
import pytest
from b1 import B1, b1_file_with, variant
from typer.testing import CliRunner

from rollerdyn import _core
from rollerdyn.cli import app
from rollerdyn.model import Model
from rollerdyn.modes import FORCES_OFF, growth_by_force, modes_at, state_names
from rollerdyn.simulation import model_parameters, simulate, write

RUNNER = CliRunner()


@pytest.fixture(scope="module")
def short_run(tmp_path_factory):
    """B1's first 2 ms (loads rising, rollers settling) and its file."""
    cfg = variant()
    ds = simulate(cfg, t_end=0.002, threads=1)
    path = tmp_path_factory.mktemp("modes") / "b1_2ms.nc"
    write(ds, path)
    return cfg, ds, path


def _jacobian(cfg, t, y):
    core = _core.Model(model_parameters(cfg, cfg.solver.detector), Model(cfg).traction)
    n = core.states
    return np.asarray(core.jacobian(t, list(y)), dtype=float).reshape(n, n)


def test_state_names_follow_the_cores_layout():
    """The names follow crates/rollerdyn-core/src/bearing/state.rs: the ring's 6 states
    (11 with the tilt free), then 11 per roller; roller i's spin rate wx at 6 + 11 i + 8."""
    names = state_names(17, tilt_free=False)
    assert len(names) == 193 == 6 + 17 * 11
    assert names[6 + 11 * 4 + 8] == ("roller 4", "wx")
    assert names[6 + 11 * 16 + 3] == ("roller 16", "theta_y")
    tilted = state_names(17, tilt_free=True)
    assert len(tilted) == 198 and tilted[6] == ("inner ring", "theta_y")
    assert tilted[11 + 11 * 2 + 5] == ("roller 2", "vx")


def test_modes_are_the_jacobians_eigenvalues(short_run):
    """The modes at the final state are the eigenvalues of the core's Jacobian there
    (numpy's eig of the matrix taken independently, compared as sorted sets, relative
    1e-9: the same matrix, so only the eigen solver's round-off), fastest growing first,
    and each mode's first state is its eigenvector's largest component, named by the
    layout (6 + 11 i + j for roller i's state j)."""
    cfg, ds, _ = short_run
    t, y = float(ds.attrs["final_time_s"]), ds["final_state"].values
    modes = modes_at(cfg, t, y)
    values, vectors = np.linalg.eig(_jacobian(cfg, t, y))
    assert len(modes) == len(values) == 193
    got = np.sort_complex(np.array([m.eigenvalue for m in modes]))
    want = np.sort_complex(values)
    scale = np.abs(values).max()
    assert np.abs(got - want).max() <= 1e-9 * scale
    rates = [m.growth_rate for m in modes]
    assert rates == sorted(rates, reverse=True)
    k = int(np.argmax(values.real))
    j = int(np.argmax(np.abs(vectors[:, k])))
    body = "inner ring" if j < 6 else f"roller {(j - 6) // 11}"
    state = (
        ("x", "y", "z", "vx", "vy", "vz")[j]
        if j < 6
        else ("x", "y", "z", "theta_y", "theta_z", "vx", "vy", "vz", "wx", "wy", "wz")[(j - 6) % 11]
    )
    assert modes[0].states[0] == (body, state, 1.0)
    broken = np.array(y, dtype=float)
    broken[10] = np.nan
    with pytest.raises(ValueError, match="not finite numbers"):
        modes_at(cfg, t, broken)
    with pytest.raises(ValueError, match="the state has 192 values; this model has 193"):
        modes_at(cfg, t, y[:-1])


def test_a_changed_setting_changes_the_model_at_the_same_state(short_run):
    """--set evaluates the same state with the changed configuration: without friction
    the spectrum differs (the traction's slope is a large part of the spins' rates)."""
    cfg, ds, _ = short_run
    t, y = float(ds.attrs["final_time_s"]), ds["final_state"].values
    with_friction = np.array([m.eigenvalue for m in modes_at(cfg, t, y)])
    without = np.array([m.eigenvalue for m in modes_at(cfg, t, y, {"solver.friction": False})])
    assert np.abs(np.sort_complex(with_friction) - np.sort_complex(without)).max() > 1.0


def test_growth_by_force_switches_each_force_off_then_all(short_run):
    """--by-force: the model as configured, each force of FORCES_OFF off in turn, then all
    of them off; each row is the fastest mode of modes_at with those changes."""
    cfg, ds, _ = short_run
    t, y = float(ds.attrs["final_time_s"]), ds["final_state"].values
    rows = growth_by_force(cfg, t, y)
    assert [label for label, _ in rows][1:-1] == list(FORCES_OFF)
    assert len(rows) == len(FORCES_OFF) + 2
    everything = {k: v for changes in FORCES_OFF.values() for k, v in changes.items()}
    assert rows[0][1] == modes_at(cfg, t, y)[0]
    assert rows[-1][1] == modes_at(cfg, t, y, everything)[0]
    assert rows[1][1] == modes_at(cfg, t, y, {"solver.friction": False})[0]


def test_modes_prints_the_table_and_refuses_bad_input(short_run, tmp_path):
    """The command prints the fastest growing modes with the rollers that carry them, with
    the configuration the run records (here its SI values: the run was built in Python)
    or one given with --config; a missing file, a run that records no configuration, a
    --config of another bearing, and a bad or doubled --set exit with status 2 and one
    line, never a traceback."""
    _, ds, run = short_run
    b1 = str(b1_file_with(tmp_path, "roller_count = 17", "roller_count = 17"))
    args = ["-n", "3", "--set", "solver.friction=false"]
    ok = RUNNER.invoke(app, ["modes", str(run), *args, "--by-force"])
    assert ok.exit_code == 0, ok.output
    assert "fastest growing modes at t = 0.002 s" in ok.output
    assert "solver.friction = false" in ok.output.replace("\n", " ")
    assert "193 modes" in ok.output
    assert "with forces switched off" in ok.output and "all of these" in ok.output
    given = RUNNER.invoke(app, ["modes", str(run), "--config", b1, *args])
    assert given.exit_code == 0, given.output
    first_row = next(line for line in ok.output.splitlines() if line.startswith("│ "))
    assert first_row in given.output  # the same model from the file as from the record
    bare = ds.copy()
    bare.attrs = {k: v for k, v in ds.attrs.items() if not k.startswith("config")}
    write(bare, tmp_path / "bare.nc")
    other = str(b1_file_with(tmp_path, "roller_count = 17", "roller_count = 16", "z16.toml"))
    cases = [
        ([str(tmp_path / "none.nc")], "none.nc: result file not found"),
        ([str(tmp_path / "bare.nc")], "records no configuration; give it with --config"),
        ([str(run), "--config", other], "the state has 193 values; this model has 182 states"),
        ([str(run), "--set", "solver.friction"], "expected PATH=VALUE"),
        ([str(run), "--set", "solver.rtol=1e-5,1e-6"], "one value per path"),
        ([str(run), "--set", "operating.temperature=hot"], "--set: invalid configuration"),
        # read as `run --set` reads it: a bare number of a dimensional field has no unit
        # (it was taken as SI: 90 for a temperature as 90 K)
        ([str(run), "--set", "operating.temperature=90"], "a bare number is ambiguous"),
        ([str(run), "--config", b1, "--set", "operating.radial_load=50"], "bare number"),
    ]
    for case, message in cases:
        result = RUNNER.invoke(app, ["modes", *case])
        assert result.exit_code == 2, (case, result.output)
        assert message in " ".join(result.output.split()), result.output
        assert "Traceback" not in result.output


def test_the_recorded_toml_and_si_values_give_the_same_model(short_run):
    """A run read from a file records its TOML text, one built in Python its values in
    SI; both give the same model, eigenvalue for eigenvalue (the SI values are the TOML's
    after the unit conversion, so the same numbers)."""
    from b1 import B1_TEXT

    from rollerdyn.modes import run_config

    _, ds, _ = short_run
    assert not ds.attrs["config_toml"]  # built in Python: only config_resolved
    with_text = ds.copy()
    with_text.attrs = {**ds.attrs, "config_toml": B1_TEXT}
    t, y = float(ds.attrs["final_time_s"]), ds["final_state"].values
    from_si = [m.eigenvalue for m in modes_at(run_config(ds), t, y)]
    from_text = [m.eigenvalue for m in modes_at(run_config(with_text), t, y)]
    assert from_si == from_text
    # changes read as in the file from either record: with its unit, or refused without
    for run in (ds, with_text):
        assert run_config(run, {"operating.axial_load": "0.5 kN"}).operating.axial_load == 500
        with pytest.raises(ValueError, match="bare number is ambiguous"):
            run_config(run, {"operating.axial_load": 500})


def test_a_crawling_run_says_so_once():
    """A run notes once when its steps average less than 1 µs over 10 s of wall time, 30 s
    in (rollerdyn.simulation.CrawlWatch): the pace, `rollerdyn modes` and, with the point
    law, the distributed law as a --set. B1's pace (69 µs a step) says nothing."""
    from rollerdyn.simulation import CrawlWatch, Progress

    def feed(point_law, step) -> list[str]:
        # one report a second of wall time for 60 s, `step` seconds simulated per step,
        # 1000 steps a second
        clock = [0.0]
        watch = CrawlWatch(point_law, clock=lambda: clock[0])
        notes = []
        for second in range(61):
            clock[0] = float(second)
            n = 1000 * second
            note = watch(Progress(n * step, 1.0, n, 0, 0, step))
            if note is not None:
                notes.append(note)
        assert watch.note == (notes[0] if notes else None)
        return notes

    assert feed(True, 69e-6) == []
    (note,) = feed(True, 0.44e-6)
    assert note.startswith("the run crawled: from t = 0.0088 s its 10000 steps averaged 4.4e-07 s")
    assert "rollerdyn modes" in note and "--set surfaces.flange_law=distributed" in note
    (note,) = feed(False, 0.44e-6)
    assert "crawled" in note and "distributed" not in note
    # a checkpoint interval below the pace ends every step: named as the cause (a run with
    # --checkpoint-interval 0.0005ms was told to look at its roller ends and flange law)
    note = _note_of_capped_steps("solver.checkpoint_interval", 5e-7)
    assert "held below solver.checkpoint_interval = 5e-07 s" in note
    assert "distributed" not in note
    # a dt_max of 1 ns was blamed on the point law (a review): named as the largest step
    note = _note_of_capped_steps("solver.dt_max", 1e-9)
    assert "held below solver.dt_max = 1e-09 s, the largest step the solver takes" in note
    assert "distributed" not in note


def _note_of_capped_steps(name: str, cap: float) -> str:
    """The one note of a watch over a minute of steps of ``cap`` each, held by ``name``."""
    from rollerdyn.simulation import CrawlWatch, Progress

    clock = [0.0]
    watch = CrawlWatch(True, clock=lambda: clock[0], step_caps={name: cap})
    found = []
    for second in range(61):
        clock[0] = float(second)
        n = 1000 * second
        found.append(watch(Progress(n * cap, 1.0, n, 0, 0, cap)))
    (note,) = [n for n in found if n]
    return note


def test_a_crawling_run_is_noted_in_its_result_and_by_run(tmp_path, monkeypatch):
    """`simulate` calls `notice` once with the note and records it in the result,
    `rollerdyn run` prints it with the command for its file, and a sweep's
    summary row carries it (`summarize`). A watch that takes every pace for a crawl stands
    in for a run that crawls for 30 s."""
    import xarray as xr
    from typer.testing import CliRunner

    from rollerdyn import simulation
    from rollerdyn.cli import app
    from rollerdyn.sweep import summarize

    class Eager(simulation.CrawlWatch):
        def __init__(self, point_law, **_):
            super().__init__(point_law, after=0.0, window=0.0, mean_step=1.0)

    real = simulation.CrawlWatch
    monkeypatch.setattr(simulation, "CrawlWatch", Eager)
    notes: list[str] = []
    ds = simulation.simulate(B1, t_end=2e-3, notice=notes.append)
    assert len(notes) == 1 and notes[0].startswith("the run crawled")
    assert ds.attrs["crawl_note"] == notes[0]
    assert summarize(ds)["note"] == notes[0]
    out = tmp_path / "crawl.nc"
    result = CliRunner().invoke(app, ["run", str(B1), "-o", str(out), "--t-end", "2e-3"])
    assert result.exit_code == 0, result.output
    flat = " ".join(result.output.split())
    assert flat.count("note: the run crawled") == 1
    assert f"For this run: rollerdyn modes {out}" in flat
    with xr.open_dataset(out, engine="h5netcdf") as written:
        assert written.attrs["crawl_note"].startswith("the run crawled")
    monkeypatch.setattr(simulation, "CrawlWatch", real)
    assert "crawl_note" not in simulation.simulate(B1, t_end=2e-3).attrs


def test_a_rollers_note_names_its_flange_pairings():
    """The table's roller note: azimuth, race and flange loads, and the pairings of its
    flange contacts by name (rollerdyn.names.PAIRINGS; -1, no contact, left out)."""
    import xarray as xr

    from rollerdyn.cli.modes import _roller_note
    from rollerdyn.names import PAIRINGS

    last = xr.Dataset(
        {
            "azimuth": ("roller", [np.radians(115.0)]),
            "inner_normal_force": ("roller", [298.0]),
            "outer_normal_force": ("roller", [302.0]),
            "flange_normal_force": (("roller", "flange"), [[275.0, 0.0, 0.0, 50.8]]),
            "flange_pairing": (("roller", "flange"), np.array([[0, -1, -1, 5]], dtype=np.int8)),
        }
    )
    note = _roller_note(last, 0)
    assert note == (
        f"roller 0: 115°, races 298/302 N, flanges up to 275 N ({PAIRINGS[0]}, {PAIRINGS[5]})"
    )
    assert _roller_note(last, 3) == "roller 3"  # not in the file
