"""The command line: exit codes, clean errors, and the commands' output."""

import numpy as np
import pytest
from b1 import B1, b1_file_with
from typer.testing import CliRunner

from rollerdyn.cli import app

RUNNER = CliRunner()


def test_validate_passes_and_prints_the_table():
    result = RUNNER.invoke(app, ["validate"])
    assert result.exit_code == 0, result.output
    assert "Tripp" in result.output and "Moes" in result.output
    assert " 0 failed" in result.output


def test_validate_another_bearing_leaves_b1s_own_cases_out(tmp_path):
    """`rollerdyn validate -c` of another bearing (from `rollerdyn new`) failed B1's own
    cases (its roller's mass, eq. 11 at B1's races), whose expected values are B1's: they
    are left out with a line saying why, and every general case still passes."""
    other = tmp_path / "other.toml"
    made = RUNNER.invoke(app, ["new", str(other), "--inner-raceway", "40", "--outer-raceway", "52"])
    assert made.exit_code == 0, made.output
    result = RUNNER.invoke(app, ["validate", "-c", str(other)])
    assert result.exit_code == 0, result.output
    assert "0 failed" in result.output and "B1 roller mass" not in result.output
    assert "B1's own cases" in result.output and "geometry differs" in result.output
    assert "B1's own cases" not in RUNNER.invoke(app, ["validate", "-c", str(B1)]).output


def test_check_prints_derived_quantities():
    result = RUNNER.invoke(app, ["check", str(B1)])
    assert result.exit_code == 0, result.output
    assert "roller diameter" in result.output and "0.004495" in result.output
    # the result's size: 1 289 outputs of 1 615 numbers (rollerdyn.simulation's count,
    # tests/test_report.py), and of 17 with only the bearing's own outputs
    assert "1289" in result.output and "16.6539" in result.output
    bare = RUNNER.invoke(app, ["check", str(B1), "--set", "solver.outputs=[]"])
    assert bare.exit_code == 0 and "0.175304" in bare.output, bare.output


def test_bad_config_is_a_clean_error(tmp_path):
    bad = b1_file_with(tmp_path, 'radial_load = "5000 N"', 'radial_load = "5000 mm"', "bad.toml")
    result = RUNNER.invoke(app, ["check", str(bad)])
    assert result.exit_code == 2
    assert "operating.radial_load" in result.output and "expected a force" in result.output
    assert "Traceback" not in result.output


def test_missing_config_is_a_clean_error(tmp_path):
    result = RUNNER.invoke(app, ["check", str(tmp_path / "nope.toml")])
    assert result.exit_code == 2
    assert "Traceback" not in result.output


def test_bench_reports_both_contacts():
    result = RUNNER.invoke(app, ["bench", "--repetitions", "2000"])
    assert result.exit_code == 0, result.output
    assert "line slice" in result.output and "ellipse" in result.output


def test_help_explains_units():
    result = RUNNER.invoke(app, ["validate", "--help"])
    assert result.exit_code == 0
    assert "SI" in result.output


def test_version_names_the_release_and_the_commit():
    import re

    import rollerdyn
    from rollerdyn.provenance import git_commit

    result = RUNNER.invoke(app, ["--version"])
    assert result.exit_code == 0, result.output
    line = result.output.strip()
    assert line.startswith(f"rollerdyn {rollerdyn.__version__}") and "\n" not in line
    # the commit a result file records (attribute git_commit), when run from a checkout
    if git_commit():
        assert line.endswith(f"(git {git_commit()})")
        assert re.fullmatch(r"[0-9a-f]{40}(\+dirty)?", git_commit())


def _row(output: str, label: str, cell: int = 2) -> str:
    """Cell ``cell`` (2: the value) of the table row that begins with ``label``."""
    line = next(line for line in output.splitlines() if label in line)
    return line.split("│")[cell].strip()


def test_compare_prints_the_largest_differences(tmp_path):
    """Two runs differing by known amounts (a copy of one run with roller 3 moved 1 µm
    along the axis, roller 5 tilted by a further 0.2 mrad and the torque 1 % higher) show
    exactly those as the largest differences; a run against itself shows zeros, and with
    no output at full speed the full-speed rows are n/a."""
    from b1 import variant

    from rollerdyn.simulation import simulate, write

    ds = simulate(variant(), t_end=0.002, threads=1)  # B1's first 2 ms: 3 outputs
    write(ds, tmp_path / "a.nc")
    moved = ds.copy(deep=True)
    moved["position"][:, 3, 0] += 1e-6
    moved["tilt"][:, 5] += 2e-4
    moved["frictional_torque"] *= 1.01
    write(moved, tmp_path / "b.nc")
    a, b = str(tmp_path / "a.nc"), str(tmp_path / "b.nc")
    result = RUNNER.invoke(app, ["compare", a, b, "--full-speed", "0 s"])
    assert result.exit_code == 0, result.output
    out = result.output
    assert "3 common outputs" in out
    assert _row(out, "position along the axis, full speed") == "1 µm"
    assert _row(out, "position along the radius, full speed") == "0 µm"
    assert _row(out, "roller tilt, full speed") == "0.2 mrad"
    assert _row(out, "roller skew, full speed") == "0 mrad"
    assert _row(out, "mean frictional torque at full speed, relative") == "1 %"
    assert _row(out, "end-flange normal force, of the largest") == "n/a"  # none yet at 2 ms
    whole = (
        _row(out, "in the load zone (±60°), whole run"),
        _row(out, "outside the load zone, whole run"),
    )
    assert sorted(whole) == ["0 µm", "1 µm"]  # roller 3 is in one of the two
    # where: the first output at which roller 3's 1 µm (and roller 5's tilt) is largest
    azimuth = np.degrees(np.mod(ds.azimuth.values[0], 2 * np.pi))
    assert _row(out, "position along the axis, full speed", 3) == (
        f"t = {ds.time.values[0]:.4g} s, roller 3 at {azimuth[3]:.1f}°"
    )
    assert _row(out, "roller tilt, full speed", 3).startswith(
        f"t = {ds.time.values[0]:.4g} s, roller 5"
    )
    assert _row(out, "mean frictional torque at full speed, relative", 3) == ""
    same = RUNNER.invoke(app, ["compare", a, a])
    assert (
        same.exit_code == 0
        and _row(same.output, "roller position outside the load zone, whole run") == "0 µm"
    )
    assert _row(same.output, "roller tilt, full speed") == "n/a"  # 2 ms: never at 0.75 s
    missing = RUNNER.invoke(app, ["compare", a, str(tmp_path / "none.nc")])
    assert missing.exit_code == 2 and "none.nc: result file not found" in missing.output
    assert "Traceback" not in missing.output
    # outputs every 0.7 ms against every 1 ms shared only t = 0: "1 common outputs" and
    # 0 in every row, exit status 0 (a review); refused now, as runs sharing no output are
    sparse = ds.assign_coords(time=ds.time * 0.7)
    write(sparse, tmp_path / "c.nc")
    other = RUNNER.invoke(app, ["compare", a, str(tmp_path / "c.nc")])
    assert other.exit_code == 2, other.output
    assert "share only their output at t = 0 s (outputs every 0.001 s and every 0.0007 s)" in (
        " ".join(other.output.split())
    )


def test_runs_of_two_output_intervals_are_compared_where_both_have_outputs():
    """The times both runs' outputs hit (every 7 ms for 0.7 and 1 ms), within 1e-12 s of
    round-off; runs of one interval share their leading outputs."""
    import xarray as xr

    from rollerdyn.study.agreement import shared_outputs

    def run(times):
        return xr.Dataset(coords={"time": np.asarray(times, float)})

    a = run(np.arange(22) * 1e-3)
    b = run(np.arange(31) * 0.7e-3)
    ia, ib = shared_outputs(a, b)
    assert list(a.time.values[ia]) == pytest.approx([0.0, 0.007, 0.014, 0.021], abs=1e-15)
    assert list(ib) == [0, 10, 20, 30]
    ia, ib = shared_outputs(a, run(np.arange(5) * 1e-3 + 1e-13))
    assert list(ia) == list(ib) == [0, 1, 2, 3, 4]
    assert [len(x) for x in shared_outputs(a, run([]))] == [0, 0]


def test_bench_contact_compares_the_methods():
    result = RUNNER.invoke(app, ["bench", "contact", "--steps", "64"])
    assert result.exit_code == 0, result.output
    for row in ("semi-analytical (6 pairings)", "gradient (Koch)", "pruned", "Mesh baseline"):
        assert row in result.output


def test_bench_model_times_rhs_and_jacobian(tmp_path):
    """bench model: one right-hand side and one Jacobian at a state (here the initial
    one), with the right-hand side's split; a file that is no result is refused cleanly."""
    result = RUNNER.invoke(app, ["bench", "model"])
    assert result.exit_code == 0, result.output
    for row in ("right-hand side", "line contacts", "Jacobian", "193 states"):
        assert row in result.output
    # every timed right-hand side evaluates the contacts (B1's 68 roller ends), none is
    # taken from the one before at the same state
    import re

    assert re.search(r"\b68 detections per right-hand side", result.output), result.output
    junk = tmp_path / "junk.nc"
    junk.write_text("not netCDF")
    bad = RUNNER.invoke(app, ["bench", "model", "--state", str(junk)])
    assert bad.exit_code == 2 and "--state" in bad.output and "Traceback" not in bad.output


def test_bench_model_times_a_state_with_the_configuration_its_run_records(tmp_path):
    """bench model --state: the run's own configuration (here the distributed end-flange
    law, given to `run` with --set), not the default file's point law, unless --config
    names one; the title says which law was timed."""
    out = tmp_path / "distributed.nc"
    args = ["run", str(B1), "-o", str(out), "--t-end", "0.0004"]
    made = RUNNER.invoke(app, [*args, "--set", "surfaces.flange_law=distributed"])
    assert made.exit_code == 0, made.output
    own = RUNNER.invoke(app, ["bench", "model", "--state", str(out)])
    assert own.exit_code == 0, own.output
    assert "B1 (distributed end-flange law)" in " ".join(own.output.split())
    other = RUNNER.invoke(app, ["bench", "model", "--state", str(out), "-c", str(B1)])
    assert other.exit_code == 0, other.output
    assert "B1 (point end-flange law)" in " ".join(other.output.split())


def test_compare_and_modes_note_runs_of_another_bearing(tmp_path):
    """Two runs of different bearings (here 5 and 6 mm rollers, the same roller count) are
    compared, and a state evaluated with another bearing's --config, with a note naming
    what differs: the differences are then not a method's or round-off's."""
    runs = {}
    law = ["--set", "surfaces.flange_law=distributed"]
    for name, sets in (
        ("b1", []),
        ("long", ["--set", 'geometry.roller.length="6 mm"']),
        ("law", law),
    ):
        runs[name] = tmp_path / f"{name}.nc"
        args = ["run", str(B1), "-o", str(runs[name]), "--t-end", "0.0004", *sets]
        made = RUNNER.invoke(app, args)
        assert made.exit_code == 0, made.output
    other = RUNNER.invoke(app, ["compare", str(runs["b1"]), str(runs["long"])])
    assert other.exit_code == 0, other.output
    assert "runs of different bearings (geometry.roller.length: 0.005 -> 0.006)" in " ".join(
        other.output.split()
    )
    same = RUNNER.invoke(app, ["compare", str(runs["b1"]), str(runs["b1"])])
    assert same.exit_code == 0 and "different bearings" not in same.output
    assert "differ in their case" not in same.output
    # another flange law (or load, or oil) is the case's difference: named too (a review)
    other = RUNNER.invoke(app, ["compare", str(runs["b1"]), str(runs["law"])])
    assert other.exit_code == 0 and "different bearings" not in other.output
    assert "differ in their case (surfaces.flange_law: 'point' -> 'distributed')" in " ".join(
        other.output.split()
    )
    modes = RUNNER.invoke(app, ["modes", str(runs["long"]), "-c", str(B1), "-n", "1"])
    assert modes.exit_code == 0, modes.output
    assert "--config describes another bearing" in modes.output


def test_bench_thread_counts_are_capped_at_the_cores_and_not_repeated(monkeypatch, capsys):
    # On a machine whose process may use 2 cores, "--threads 1,4,all,2" runs each case on
    # 1 and 2 threads once each (a run never uses more threads than cores), and says that
    # the 4 was capped; bad counts are refused by name.
    import rollerdyn.simulation
    from rollerdyn.cli.bench import _thread_counts

    monkeypatch.setattr(rollerdyn.simulation, "default_threads", lambda: 2)
    assert _thread_counts("1,4,all,2") == [1, 2]
    assert "--threads 4: this process may use 2 core(s); runs on 2" in capsys.readouterr().err
    assert _thread_counts("2,1") == [2, 1]
    assert capsys.readouterr().err == ""
    import typer

    with pytest.raises(typer.Exit) as refused:
        _thread_counts("1,0")
    assert refused.value.exit_code == 2


def test_bench_refuses_unknown_target():
    result = RUNNER.invoke(app, ["bench", "everything"])
    assert result.exit_code == 2


@pytest.mark.parametrize(
    "args",
    [["validate"], ["bench", "traction"], ["study", "paper", "--t-end", "0.001", "-o"]],
)
def test_commands_without_b1_next_to_the_package_say_so_in_one_line(monkeypatch, tmp_path, args):
    # A copy of the package installed without the source tree has no examples/b1.toml:
    # the commands that default to it name the missing file and --config (status 2), never
    # a traceback.
    import rollerdyn.validation

    def missing():
        raise FileNotFoundError(
            "B1's configuration (examples/b1.toml of the source tree) is not found next to "
            "the installed package (site-packages/rollerdyn); pass --config PATH"
        )

    monkeypatch.setattr(rollerdyn.validation, "default_config_path", missing)
    if args[-1] == "-o":
        args = [*args, str(tmp_path / "study")]
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 2, result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "examples/b1.toml" in result.output and "--config" in result.output
    assert "Traceback" not in result.output


def test_runtime_study_writes_table_csv_and_plot(tmp_path):
    """bench mbs --sweep-dt-max (the paper's fig. 14): both detectors at each dt_max, each
    on one thread as the table says (the semi-analytical runs once took all cores while
    the gradient runs took one), a CSV with one row per run and the plot; a bad list is
    refused with the rule named."""
    import pandas as pd

    out = tmp_path / "rt"
    args = ["bench", "mbs", "--t-end", "0.0005", "--sweep-dt-max", "1e-5,1e-4", "-o", str(out)]
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 0, result.output
    frame = pd.read_csv(out / "runtime_study.csv")
    assert len(frame) == 4
    assert set(frame.detector) == {"semi-analytical", "gradient"}
    assert set(frame.dt_max_s) == {1e-5, 1e-4}
    assert (frame.t_reached_s == 0.0005).all() and (frame.wall_s > 0).all()
    assert (frame.threads == 1).all(), frame.threads
    assert (out / "fig14_runtime_over_dt_max.png").is_file()
    bad = RUNNER.invoke(app, ["bench", "mbs", "--sweep-dt-max", "1e-5,fast"])
    assert bad.exit_code == 2 and "comma-separated positive" in bad.output


def test_bench_mbs_judges_the_detectors_agreement_and_takes_set():
    """bench mbs prints, after the runtime table, how far the two detectors' runs agree
    against issue 15's bounds (every roller's position 0.1 µm, flange forces 1 % of the
    largest, mean torque 0.1 %), n/a where a measure has no output (no full speed in 2 ms);
    --set changes the configuration it runs (a tolerance ten times tighter takes more
    steps), and is refused with --state unless --config names the configuration."""

    def semi_steps(output: str) -> int:
        row = next(line for line in output.splitlines() if line.startswith("│ semi-analytical"))
        return int(row.split("│")[3])

    base = RUNNER.invoke(app, ["bench", "mbs", "--t-end", "2 ms"])
    assert base.exit_code == 0, base.output
    flat = " ".join(base.output.split())
    assert "agreement of the two runs over 0 … 0.002 s (full speed not reached)" in flat
    for row in ("roller position in the load zone (±60°), whole run │", "│ 0.1 µm │"):
        assert row in base.output, base.output
    assert "mean frictional torque at full speed, relative │ n/a │ 0.1 % │ n/a" in flat
    tight = RUNNER.invoke(app, ["bench", "mbs", "--t-end", "2 ms", "--set", "solver.rtol=1e-6"])
    assert tight.exit_code == 0, tight.output
    assert semi_steps(tight.output) > semi_steps(base.output)
    state = RUNNER.invoke(app, ["bench", "model", "--state", "x.nc", "--set", "solver.rtol=1e-6"])
    assert state.exit_code == 2 and "give --config as well" in state.output


def test_run_notes_the_slow_free_tilt_with_the_point_law(tmp_path):
    """B1 with `inner_ring.tilt = "free"` and the point end-flange law stalls in the load
    ramp, at t = 0.0226 s (docs/dynamics.md, "Free inner ring tilt"), and with a prescribed
    tilt it creeps: `run` says so in one line and names the law that runs it, and says
    nothing for B1 as it is or for either tilt with the distributed law."""
    from rollerdyn import load_config
    from rollerdyn.notes import slow_configuration_note

    free = b1_file_with(tmp_path, 'tilt = "locked"', 'tilt = "free"', "free.toml")
    note = slow_configuration_note(load_config(free))
    assert note is not None and "flange_law" in note and "distributed" in note
    assert slow_configuration_note(load_config(B1)) is None
    distributed = tmp_path / "d.toml"
    distributed.write_text(
        free.read_text().replace('flange_law = "point"', 'flange_law = "distributed"')
    )
    assert slow_configuration_note(load_config(distributed)) is None
    # A prescribed tilt creeps with the point law (B1 at 0.05 deg: t = 0.55 s after 63 s on
    # two cores, docs/dynamics.md, "Prescribed tilt instead"), not with the distributed one.
    tilted = b1_file_with(
        tmp_path, 'tilt = "locked"', 'tilt = "locked"\nmisalignment = "0.05 deg"', "tilt.toml"
    )
    note = slow_configuration_note(load_config(tilted))
    assert note is not None and "misalignment" in note and "distributed" in note
    tilted_distributed = tmp_path / "td.toml"
    tilted_distributed.write_text(
        tilted.read_text().replace('flange_law = "point"', 'flange_law = "distributed"')
    )
    assert slow_configuration_note(load_config(tilted_distributed)) is None
    out = tmp_path / "free.nc"
    result = RUNNER.invoke(app, ["run", str(free), "-o", str(out), "--t-end", "0.0002"])
    assert result.exit_code == 0, result.output
    assert "stalls in the load ramp" in result.output and "Traceback" not in result.output


def test_an_equilibrium_start_before_the_loads_is_noted(tmp_path):
    """`solver.start = "equilibrium"` solves the equilibrium of the loads at t = 0: with B1's
    ramps, which start from nothing, that is an unloaded bearing, and `check` says so in one
    line with the remedy (removing the ramps), however short the ramp; it says nothing with
    the ramps removed or for B1's start from rest."""
    from b1 import variant

    from rollerdyn.notes import unloaded_start_note

    equilibrium = {"solver.start": "equilibrium"}
    note = unloaded_start_note(variant(**equilibrium))
    assert note is not None and "operating.load_ramp" in note and "t = 0" in note
    no_ramps = {**equilibrium, "operating.load_ramp": None, "operating.speed_ramp": None}
    assert unloaded_start_note(variant(**no_ramps)) is None
    assert unloaded_start_note(variant()) is None
    short_ramp = {
        **equilibrium,
        "operating.load_ramp.start": "0 s",
        "operating.load_ramp.end": "1 ms",
    }
    assert unloaded_start_note(variant(**short_ramp)) is not None  # 1 ms: still zero at 0
    path = b1_file_with(tmp_path, "[solver]\n", '[solver]\nstart = "equilibrium"\n', "eq.toml")
    result = RUNNER.invoke(app, ["check", str(path)])
    assert result.exit_code == 0, result.output
    assert 'solver.start = "equilibrium"' in result.output and "Traceback" not in result.output
    plain = RUNNER.invoke(app, ["check", str(B1)])
    assert "solver.start" not in plain.output


def test_check_says_when_run_would_refuse_the_point_law(tmp_path):
    """`check` tells what `run` would refuse before its first step: the point law's load
    check (B1 without radial load at 100 N axially puts its most loaded roller end on its
    end face: docs/dynamics.md, "The whole B1 run"), with the refusal's own words, --force
    and the remedy as a --set; nothing for B1 itself or for the same loads with the
    distributed law (in a file or by --set)."""
    from b1 import variant

    from rollerdyn.notes import refusal_note

    axial = {"operating.radial_load": "0 N", "operating.axial_load": "100 N"}
    note = refusal_note(variant(**axial))
    assert note is not None and "lies on its end face" in note and "--force" in note
    assert refusal_note(variant()) is None
    assert refusal_note(variant(**axial, **{"surfaces.flange_law": "distributed"})) is None
    path = b1_file_with(tmp_path, 'radial_load = "5000 N"', 'radial_load = "0 N"', "axial.toml")
    text = path.read_text(encoding="utf-8")
    path.write_text(text.replace('axial_load = "1000 N"', 'axial_load = "100 N"'), "utf-8")
    result = RUNNER.invoke(app, ["check", str(path)])
    assert result.exit_code == 0, result.output
    flat = " ".join(result.output.split())
    assert "run refuses this configuration" in flat
    assert "--set surfaces.flange_law=distributed" in flat  # the remedy as a command line
    assert "refuses" not in RUNNER.invoke(app, ["check", str(B1)]).output
    # the same with --set: the refusal, and none with the remedy it names
    changed = ["check", str(B1), "--set", "operating.radial_load=0 N"]
    changed += ["--set", "operating.axial_load=100 N"]
    assert "run refuses" in " ".join(RUNNER.invoke(app, changed).output.split())
    remedied = RUNNER.invoke(app, [*changed, "--set", "surfaces.flange_law=distributed"])
    assert remedied.exit_code == 0 and "refuses" not in remedied.output


def test_run_notes_a_load_past_the_flanges_static_limit(tmp_path):
    """A run whose loads at its end time, or at a load table's row before it, the flanges
    cannot carry by ISO 76's static limit (4 GPa; B1's quasi-static equilibrium at 10 kN
    axially presses a flange rim at 15.6 GPa with the point law and 7.9 GPa with the
    distributed one, `rollerdyn statics`) gets one line saying so, and goes on; B1 as it
    is, and B1 at 10 kN at a time when its load ramp has brought less than a newton, get
    none."""
    from rollerdyn import load_config
    from rollerdyn.notes import capacity_note, configuration_notes

    b1 = load_config(B1)
    assert capacity_note(b1, b1.end_time) is None
    heavy = b1_file_with(tmp_path, 'axial_load = "1000 N"', 'axial_load = "10000 N"')
    point = load_config(heavy)
    note = capacity_note(point, point.end_time)
    assert note is not None and "axial 10000 N" in note and "ISO 76" in note, note
    assert "15.6 GPa" in note and "a run goes on" in note, note
    assert capacity_note(point, 0.002) is None  # the cosine ramp has brought 0.004 % of the loads
    # A load table that peaks within the run is judged at its rows: 10 kN at 0.6 s, back
    # to 1000 N by the end (the distributed law: 7.9 GPa at the peak).
    peak = b1_file_with(
        tmp_path,
        'axial_load = "1000 N"',
        'axial_load = {table = [["0 s", "0 N"], ["0.6 s", "10000 N"], ["0.8 s", "1000 N"]]}',
        "peak.toml",
    )
    peak.write_text(peak.read_text().replace('flange_law = "point"', 'flange_law = "distributed"'))
    peaked = capacity_note(load_config(peak), 1.0)
    assert peaked is not None and "t = 0.6 s" in peaked and "7.9 GPa" in peaked, peaked
    assert capacity_note(load_config(peak), 0.1) is None  # the table has reached 1667 N
    # The races: B1 at 15 kN radially presses its inner race at 4.5 GPa in equilibrium,
    # at 10 kN at 3.8 GPa (`rollerdyn statics`).
    for radial, pressure in (("15000 N", "4.5 GPa"), ("10000 N", None)):
        radial_file = b1_file_with(
            tmp_path, 'radial_load = "5000 N"', f'radial_load = "{radial}"', "radial.toml"
        )
        radial_cfg = load_config(radial_file)
        race = capacity_note(radial_cfg, radial_cfg.end_time)
        if pressure is None:
            assert race is None, race
        else:
            assert race is not None and f"inner race at {pressure}" in race, race
    # From Python, the notes run prints: the capacity note only, for this configuration.
    assert configuration_notes(heavy) == [note]
    assert configuration_notes(B1) == [] and configuration_notes(heavy, t_end=0.002) == []
    # The loads ramped up within 0.1 ms, the distributed law: the note, then the run.
    fast = tmp_path / "fast.toml"
    fast.write_text(
        heavy.read_text()
        .replace('end = "0.5 s"', 'end = "0.1 ms"', 1)
        .replace('flange_law = "point"', 'flange_law = "distributed"')
    )
    out = tmp_path / "heavy.nc"
    result = RUNNER.invoke(
        app, ["run", str(fast), "-o", str(out), "--t-end", "0.0002", "--threads", "1"]
    )
    assert result.exit_code == 0, result.output
    assert "7.9 GPa, above the 4 GPa of ISO 76" in result.output, result.output
    assert "Traceback" not in result.output and out.is_file()
    # `check` prints the same note after its table, and none for B1.
    checked = RUNNER.invoke(app, ["check", str(heavy)])
    assert checked.exit_code == 0 and "15.6 GPa, above the 4 GPa" in checked.output
    assert "cannot carry" not in RUNNER.invoke(app, ["check", str(B1)]).output


def test_ctrl_c_while_the_result_is_written_loses_nothing(tmp_path, monkeypatch):
    """Ctrl-C (or SIGTERM) that arrives after the run has ended, while its result is being
    written (about 1.5 s for B1, compressing), lets the write finish: the file holds the
    whole run, one line says what happened, and the exit status is Ctrl-C's 130. Without
    the deferral the KeyboardInterrupt cut the write, and the file left was the last
    checkpoint's (seen by hand: B1 to 0.2 s interrupted at 8 s kept t = 0.1 s)."""
    import os
    import signal

    import xarray as xr

    import rollerdyn.simulation

    real_write = rollerdyn.simulation.write

    def interrupted_write(ds, path, compress=True, replace=True):
        if compress:  # the final result, not a checkpoint
            os.kill(os.getpid(), signal.SIGINT)
        return real_write(ds, path, compress, replace)

    monkeypatch.setattr(rollerdyn.simulation, "write", interrupted_write)
    out = tmp_path / "late.nc"
    result = RUNNER.invoke(app, ["run", str(B1), "-o", str(out), "--t-end", "0.0004"])
    assert result.exit_code == 130, result.output
    assert "interrupted while its result was written; the result is whole" in result.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert float(ds.time[-1]) == pytest.approx(4e-4, abs=1e-15)


@pytest.mark.parametrize(("signame", "status"), [("SIGINT", 130), ("SIGTERM", 143)])
def test_a_signal_after_the_last_progress_report_loses_nothing(
    tmp_path, monkeypatch, signame, status
):
    """Ctrl-C or SIGTERM that comes after the run's last progress report, before its
    result is written (the adversarial review: Ctrl-C there lost the whole run, SIGTERM
    was ignored and the command exited 0): the result is written whole, one line says
    what happened, and the exit status is the signal's."""
    import os
    import signal

    import xarray as xr

    import rollerdyn.simulation

    real_simulate = rollerdyn.simulation.simulate

    def signalled_at_the_end(*args, **kwargs):
        ds = real_simulate(*args, **kwargs)
        os.kill(os.getpid(), getattr(signal, signame))
        return ds

    monkeypatch.setattr(rollerdyn.simulation, "simulate", signalled_at_the_end)
    out = tmp_path / "end.nc"
    result = RUNNER.invoke(app, ["run", str(B1), "-o", str(out), "--t-end", "0.0004"])
    assert result.exit_code == status, result.output
    assert "run ended, then interrupted; the result is whole" in result.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert float(ds.time[-1]) == pytest.approx(4e-4, abs=1e-15)


def test_a_result_that_cannot_be_written_is_kept_elsewhere(tmp_path, monkeypatch):
    """The final write fails (a full disk, a folder gone): the result is kept in the
    system's temporary folder, one line names both files, exit status 1."""
    import os
    import re

    import xarray as xr

    import rollerdyn.paths

    real = rollerdyn.paths.write_atomically

    def failing(path, data, replace=False):
        if os.path.basename(path) == "full.nc":  # B1's 10 ms checkpoints: none in 0.4 ms
            raise OSError(28, "No space left on device")
        return real(path, data, replace)

    monkeypatch.setattr(rollerdyn.paths, "write_atomically", failing)
    out = tmp_path / "full.nc"
    result = RUNNER.invoke(app, ["run", str(B1), "-o", str(out), "--t-end", "0.0004"])
    assert result.exit_code == 1, result.output
    text = " ".join(result.output.split())
    assert f"-o {out}: could not write the result (No space left on device)" in text, text
    kept = re.search(r"the result was kept in (\S+\.nc)", text)
    assert kept, text
    with xr.open_dataset(kept.group(1), engine="h5netcdf") as ds:
        assert float(ds.time[-1]) == pytest.approx(4e-4, abs=1e-15)
    os.remove(kept.group(1))


def test_a_checkpoint_that_cannot_be_written_stops_the_run_and_keeps_it(tmp_path, monkeypatch):
    """A checkpoint's write fails (here: every uncompressed write): the run stops there,
    its result is written whole all the same, one line says what happened, status 1."""
    import xarray as xr

    import rollerdyn.simulation

    real_write = rollerdyn.simulation.write

    def checkpoints_fail(ds, path, compress=True, replace=True):
        if not compress:
            raise OSError(5, "Input/output error")
        return real_write(ds, path, compress, replace)

    monkeypatch.setattr(rollerdyn.simulation, "write", checkpoints_fail)
    out = tmp_path / "cp.nc"
    args = ["run", str(B1), "-o", str(out), "--t-end", "0.002", "--checkpoint-interval", "1e-4"]
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 1, result.output
    said = f"-o {out}: could not write the checkpoint ([Errno 5] Input/output error); run stopped"
    assert said in " ".join(result.output.split()), result.output
    assert "the result is written whole" in result.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        # stopped before its end, at its last output before the next progress report: the
        # output at 1 ms, or t = 0 where a report between outputs (every 0.2 s of wall time,
        # a machine under load) came first
        assert ds.sizes["time"] >= 1 and float(ds.time[-1]) < 0.002


def test_run_checkpoint_interval_option(tmp_path):
    """`run --checkpoint-interval SECONDS` overrides solver.checkpoint_interval (10 ms in
    B1, so a 0.4 ms run would have no checkpoint); --resume keeps the earlier run's
    interval unless told otherwise; a bad value is refused with the option and the rule
    named, before any work."""
    import tomllib

    import xarray as xr

    from rollerdyn.config import parse_config

    out = tmp_path / "cp.nc"
    args = ["run", str(B1), "-o", str(out), "--t-end", "0.0004"]
    result = RUNNER.invoke(app, [*args, "--checkpoint-interval", "1e-4"])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.attrs["checkpoint_interval_s"] == 1e-4
        assert float(ds.checkpoint_time) == pytest.approx(4e-4, abs=1e-15)
        # recorded as the file's table with the changed interval (as --set records it)
        text = ds.attrs["config_toml"]
        assert 'changed: solver.checkpoint_interval = "0.0001 s"' in text.splitlines()[0]
        assert parse_config(tomllib.loads(text)).solver.checkpoint_interval == 1e-4
    resumed = tmp_path / "resumed.nc"
    again = RUNNER.invoke(
        app, ["run", str(B1), "-o", str(resumed), "--t-end", "0.0005", "--resume", str(out)]
    )
    assert again.exit_code == 0, again.output
    with xr.open_dataset(resumed, engine="h5netcdf") as ds:
        assert ds.attrs["checkpoint_interval_s"] == 1e-4
        assert float(ds.checkpoint_time) == pytest.approx(5e-4, abs=1e-15)
    for bad in ("0", "-1e-3", "nan", "inf", "1e-30"):
        refused = RUNNER.invoke(app, [*args, "--checkpoint-interval", bad])
        assert refused.exit_code == 2, (bad, refused.output)
        assert "--checkpoint-interval" in refused.output and "at least 1 ns" in refused.output
        assert "Traceback" not in refused.output
    not_a_number = RUNNER.invoke(app, [*args, "--checkpoint-interval", "often"])
    assert not_a_number.exit_code == 2 and "Traceback" not in not_a_number.output
    help_text = RUNNER.invoke(app, ["run", "--help"]).output
    assert "--checkpoint-interval" in help_text and "seconds" in help_text
    # --save-interval: wall time between checkpoint writes, 0 allowed, nothing below. The
    # four checkpoints of a run to 0.4 ms every 0.1 ms are each written with 0, only the
    # first with an hour; the final, compressed write comes on top.
    assert "--save-interval" in help_text
    from rollerdyn import simulation

    real_write = simulation.write
    for every, expected in (("0", 4), ("1 h", 1)):
        writes: list[bool] = []

        def counting_write(ds, path, compress=True, replace=True, writes=writes):
            writes.append(compress)
            return real_write(ds, path, compress, replace)

        simulation.write = counting_write
        try:
            saved = RUNNER.invoke(
                app,
                [*args, "--overwrite", "--checkpoint-interval", "1e-4", "--save-interval", every],
            )
        finally:
            simulation.write = real_write
        assert saved.exit_code == 0, saved.output
        assert writes.count(False) == expected and writes[-1], (every, writes)
    for bad in ("-1", "nan", "inf", "often"):
        refused = RUNNER.invoke(app, [*args, "--overwrite", "--save-interval", bad])
        assert refused.exit_code == 2, (bad, refused.output)
        assert "--save-interval" in refused.output and "Traceback" not in refused.output
        assert bad == "often" or "at least 0 s" in refused.output


def test_the_run_line_gives_a_short_runs_wall_time_in_significant_digits():
    """`rollerdyn run`'s closing line gave a 12 ms integration as "0.0 s wall", beside a
    progress line of 0.7 s (the model's construction included): three significant digits
    below 10 s, tenths above."""
    from rollerdyn.cli.run import _seconds

    assert _seconds(0.0118) == "0.0118 s"
    assert _seconds(3.14159) == "3.14 s"
    assert _seconds(46.43) == "46.4 s"


def test_ctrl_c_stops_the_whole_benchmark(monkeypatch):
    """Ctrl-C in one of `bench mbs`' runs (the detector comparison or a case) stops the
    benchmark: the interruption is not taken for a run that ended early, after which the
    next run would start and a table compare an interrupted run with a finished one."""
    import xarray as xr

    import rollerdyn.bench_cases
    import rollerdyn.simulation
    from rollerdyn import load_config
    from rollerdyn.cli.bench_targets import _mbs_runs
    from rollerdyn.simulation import SimulationInterrupted

    calls = []

    def interrupted(*args, **kwargs):
        calls.append(kwargs.get("detector"))
        raise SimulationInterrupted("KeyboardInterrupt", xr.Dataset())

    monkeypatch.setattr(rollerdyn.simulation, "simulate", interrupted)
    monkeypatch.setattr(rollerdyn.bench_cases, "simulate", interrupted)
    cfg = load_config(B1)
    with pytest.raises(KeyboardInterrupt):
        _mbs_runs(cfg, 1e-3)
    assert calls == ["semi-analytical"]
    with pytest.raises(KeyboardInterrupt):
        rollerdyn.bench_cases.run_case(cfg, "axial-0N", 10.0)


def test_run_set_changes_the_configuration_and_resume_needs_the_same(tmp_path):
    """`run --set PATH=VALUE` runs the file with values changed (here the distributed
    end-flange law, the remedy the point law's refusals name, and the axial load): the
    result records the changed configuration, its TOML text headed by the file and the
    changes, which `rollerdyn modes` reads back; --resume continues only with the same
    --set and names the field that differs; a bad --set exits 2 in one line before any
    work."""
    import tomllib

    import xarray as xr

    from rollerdyn.config import load_config, parse_config

    out = tmp_path / "set.nc"
    sets = ["--set", "surfaces.flange_law=distributed", "--set", "operating.axial_load=500 N"]
    args = ["run", str(B1), "-o", str(out), "--t-end", "0.0004", *sets]
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 0, result.output
    expected = load_config(
        B1, {"surfaces.flange_law": "distributed", "operating.axial_load": "500 N"}
    )
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        text = ds.attrs["config_toml"]
        recorded = parse_config(tomllib.loads(text))
        assert recorded.model_dump() == expected.model_dump()
        assert 'changed: surfaces.flange_law = "distributed", ' in text.splitlines()[0]
        assert float(ds.axial_load.isel(time=-1)) == pytest.approx(
            expected.operating.axial_load_at(4e-4), rel=1e-12
        )
    modes = RUNNER.invoke(app, ["modes", str(out), "-n", "1"])
    assert modes.exit_code == 0, modes.output
    resume = ["run", str(B1), "-o", str(out), "--t-end", "0.0005", "--resume", str(out)]
    without = RUNNER.invoke(app, resume)
    assert without.exit_code == 2
    assert "surfaces.flange_law: 'distributed' -> 'point'" in without.output
    assert "the same file and --set options" in " ".join(without.output.split())
    assert "Traceback" not in without.output
    same = RUNNER.invoke(app, [*resume, *sets])
    assert same.exit_code == 0, same.output
    for bad, rule in (
        ("surfaces.flange_law=nope", 'must be one of "point" or "distributed"'),
        ("surfaces.flange_lw=distributed", "did you mean 'flange_law'"),
        ("operating.axial_load=500", "no unit"),
        ("operating.axial_load", "expected PATH=VALUE"),
        ("operating.axial_load=1 N,2 N", "one value per path"),
        ("name.first=x", "not a table"),
    ):
        refused = RUNNER.invoke(app, ["run", str(B1), "-o", str(tmp_path / "x.nc"), "--set", bad])
        assert refused.exit_code == 2, (bad, refused.output)
        assert rule in refused.output and "Traceback" not in refused.output, bad
        assert not (tmp_path / "x.nc").exists()
    twice = RUNNER.invoke(app, [*args, "--overwrite", "--set", "operating.axial_load=600 N"])
    assert twice.exit_code == 2 and "operating.axial_load is set twice" in twice.output
    table = 'operating.load_ramp={start = "0 s", end = "20 ms", shape = "cosine"}'
    inside = RUNNER.invoke(
        app, [*args, "--overwrite", "--set", table, "--set", "operating.load_ramp.end=30 ms"]
    )
    assert inside.exit_code == 2
    assert "overlaps --set operating.load_ramp (one sets a table" in " ".join(inside.output.split())
    # bytes that are not UTF-8 (kept by Python as surrogates): in a --set value refused in
    # one line; in the file's name escaped in the recorded header (a result holds UTF-8 only)
    odd = RUNNER.invoke(
        app, ["run", str(B1), "-o", str(tmp_path / "x.nc"), "--set", "name=B\udcff"]
    )
    assert odd.exit_code == 2 and "not UTF-8 text" in odd.output
    odd_name = tmp_path / "b\udcff1.toml"
    odd_name.write_bytes(B1.read_bytes())
    named = RUNNER.invoke(
        app, ["run", str(odd_name), "-o", str(out), "--overwrite", "--t-end", "0.0002", *sets]
    )
    assert named.exit_code == 0, named.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert "b\\xff1.toml, changed:" in ds.attrs["config_toml"].splitlines()[0]


def test_resume_refuses_a_checkpoint_interval_changed_by_hand(tmp_path):
    # a result whose checkpoint_interval_s had been edited to 'abc' ended --resume with
    # a traceback (could not convert string to float)
    import xarray as xr

    out = tmp_path / "a.nc"
    made = RUNNER.invoke(app, ["run", str(B1), "-o", str(out), "--t-end", "0.0004"])
    assert made.exit_code == 0, made.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        edited = ds.load()
    edited.attrs["checkpoint_interval_s"] = "abc"
    changed = tmp_path / "edited.nc"
    edited.to_netcdf(changed, engine="h5netcdf")
    args = ["run", str(B1), "-o", str(changed), "--resume", str(changed), "--t-end", "0.0006"]
    res = RUNNER.invoke(app, args)
    assert res.exit_code == 2, res.output
    assert "checkpoint_interval_s = 'abc' is no positive number" in " ".join(res.output.split())


def test_set_none_removes_an_optional_value(tmp_path):
    """`--set PATH=none` (bare) removes the value, leaving its default: B1 without its load
    ramp has its loads from t = 0, and the result's TOML record says what was removed; a
    required value removed is refused as missing, naming it; a quoted "none" stays a
    string (refused here, where a table is expected)."""
    import tomllib

    import xarray as xr

    out = tmp_path / "no_ramp.nc"
    sets = ["--set", "operating.load_ramp=none", "--set", "operating.speed_ramp=none"]
    result = RUNNER.invoke(app, ["run", str(B1), "-o", str(out), "--t-end", "0.0004", *sets])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        text = ds.attrs["config_toml"]
        assert "operating.load_ramp = none (removed)" in text.splitlines()[0]
        assert "load_ramp" not in tomllib.loads(text)["operating"]
        assert float(ds.radial_load.isel(time=0)) == pytest.approx(5000.0)
    for bad, rule in (
        ("operating.radial_load=none", "operating.radial_load: (missing) — required"),
        ('operating.load_ramp="none"', "expected a table"),
    ):
        refused = RUNNER.invoke(app, ["check", str(B1), "--set", bad])
        assert refused.exit_code == 2, (bad, refused.output)
        assert rule in refused.output and "Traceback" not in refused.output, bad


def test_check_says_when_run_would_refuse_a_run_too_large(monkeypatch):
    """`check` tells that `run` would refuse a run far beyond a normal one, with run's own
    words: outputs every nanosecond to B1's end time would hold 1.66e4 GB (it printed
    only the size in its table); and a model the core cannot build is no point-law
    refusal (it claimed "--force runs it" for flanges too tall together, which --force
    never ran; the configuration refuses those now)."""
    from b1 import variant

    from rollerdyn.notes import refusal_note

    result = RUNNER.invoke(app, ["check", str(B1), "--set", "solver.output_interval=1e-9 s"])
    assert result.exit_code == 0, result.output
    flat = " ".join(result.output.split())
    assert "run refuses this configuration: solver.output_interval = 1e-09 s" in flat
    assert "GB of results" in flat

    def no_model(cfg):
        raise ValueError("inner_flange.height + outer_flange.height = 0.0046: must be < ...")

    monkeypatch.setattr("rollerdyn.statics._core_model", no_model)
    assert refusal_note(variant()) is None


def test_a_run_with_the_mesh_detector_is_noted_as_slow():
    """`rollerdyn run --detector mesh` (or solver.detector) notes at its start that the
    mesh detector is the slow baseline (its first step on B1: 16 s on one thread, with no
    progress line meanwhile); the other detectors get no note."""
    from rollerdyn.notes import detector_note

    note = detector_note("mesh")
    assert note is not None and "9 ms a roller end" in note and "between its long steps" in note
    assert detector_note("semi-analytical") is None and detector_note("gradient") is None
