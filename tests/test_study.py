"""Studies (issue 19): ``rollerdyn study paper`` and ``rollerdyn study map``.

The paper study runs B1 to t = 2 ms (loads barely applied, nothing rolls yet), so its
runs take about a second each on a shared two-worker cluster; the checks that need
rolling or flange contact are tested on copies of those runs with the values they judge
set by hand, and must then PASS or FAIL as their definitions say. The map runs one point
at 3000 rpm from equilibrium for about 20 ms.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import os
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from b1 import B1, b1_file_with, load_b1, variant
from typer.testing import CliRunner

from rollerdyn.cli import app
from rollerdyn.names import GRADIENT, PAIRINGS, SEMI_ANALYTICAL
from rollerdyn.simulation import simulate, write
from rollerdyn.study import FAIL, NOT_RUN, PASS, StudyError, operating_map, paper, parse_range
from rollerdyn.study.findings import _Context, check_findings
from rollerdyn.study.folder import prepare_folder
from rollerdyn.study.plan import build_plan
from rollerdyn.study.report_page import build_page
from rollerdyn.study.runs import (
    NOT_FINISHED,
    PARTIAL,
    RunSpec,
    execute,
    inspect_run,
    lock_folder,
    lost_record,
    read_attrs,
)
from rollerdyn.study.steady import SteadyRule, window_outputs

RUNNER = CliRunner()
T_END = 0.002  # s: the paper study's short version in these tests


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster

    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        Client(cluster) as c,
    ):
        yield c


@pytest.fixture(scope="module")
def study(tmp_path_factory, client):
    out = tmp_path_factory.mktemp("study") / "paper"
    events: list[dict] = []
    result = _short_paper(out, events, scheduler=client, max_wall=120.0)
    return out, result, events


def _short_paper(out: Path, events: list, **options):
    """The tests' short paper study in ``out``: B1 to :data:`T_END`, axial loads 0 N and
    B1's own, fig. 14 at two Δt_max, no figure files (matplotlib's: the command line's
    test writes them); its progress events go to ``events``."""
    return paper(
        B1,
        out,
        t_end=T_END,
        loads=(0.0,),
        dt_max=(5e-4, 1e-3),
        progress=events.append,
        figures=False,
        **options,
    )


def _attrs(out: Path, name: str) -> dict:
    attrs = read_attrs(out / "runs" / f"{name}.nc")
    assert attrs is not None, name
    return attrs


# --------------------------------------------------------------------------- the plan


def test_studies_record_the_outputs_their_figures_read_whatever_the_configuration_says():
    """``solver.outputs``: the paper study's runs record every group; a map's points at
    least the rollers and flanges its steadiness windows read, plus what the configuration
    asks for; with the default outputs both are the configuration's own (its hash too)."""
    from rollerdyn.config.solver import OUTPUT_GROUPS
    from rollerdyn.provenance import config_hash
    from rollerdyn.study.maps import point_config

    bare = variant(**{"solver.outputs": []})
    for spec in build_plan(bare, 0.01, gradient=False, distributed=False).specs:
        assert tuple(spec.data["solver"]["outputs"]) == OUTPUT_GROUPS, spec.name
    point, _ = point_config(bare, 52.36, 5000.0, 0.0, "equilibrium", 0.02)
    assert point.solver.outputs == ("rollers", "flanges", "lubrication")
    powered = variant(**{"solver.outputs": ["power"]})
    assert point_config(powered, 52.36, 5000.0, 0.0, "equilibrium", 0.02)[0].solver.outputs == (
        "rollers",
        "flanges",
        "power",
        "lubrication",
    )
    plan = build_plan(load_b1(), 0.01, gradient=False, distributed=False)
    reference = plan.spec(plan.reference)
    assert reference.config_sha256 == config_hash(load_b1()) and reference.meta["changes"] == "none"
    default, _ = point_config(load_b1(), 52.36, 5000.0, 0.0, "equilibrium", 0.02)
    assert default.solver.outputs == OUTPUT_GROUPS


def test_plan_holds_each_run_once_with_its_role():
    plan = build_plan(load_b1(), 0.01)
    names = [s.name for s in plan.specs]
    assert len(names) == len(set(names)) == 17
    assert plan.reference == "axial-1000N" and plan.loads[1000.0] == "axial-1000N"
    assert sorted(plan.loads) == [0.0, 500.0, 1000.0, 2000.0]
    assert plan.reference_gradient == "axial-1000N-gradient"
    # the round-off twin: the reference with solver.atol changed in the tenth digit only
    twin = plan.spec(plan.reference_twin)
    assert plan.reference_twin == "axial-1000N-roundoff" and twin.detector == SEMI_ANALYTICAL
    assert twin.data["solver"]["atol"] == pytest.approx(1e-9 * (1 + 1e-10), rel=1e-15)
    assert twin.data["solver"]["atol"] != 1e-9
    assert twin.meta["changes"] == "solver.atol: 1e-09 -> 1.0000000001e-09"
    # the tight pair: both detectors with solver.rtol and solver.atol ten times tighter
    assert plan.tight == {
        SEMI_ANALYTICAL: "axial-1000N-tight",
        GRADIENT: "axial-1000N-gradient-tight",
    }
    for detector, name in plan.tight.items():
        spec = plan.spec(name)
        assert spec.detector == detector
        assert (spec.data["solver"]["rtol"], spec.data["solver"]["atol"]) == (1e-6, 1e-10)
        assert spec.data["operating"] == plan.spec(plan.reference).data["operating"]
    assert build_plan(load_b1(), 0.01, tight=False).tight == {}
    # figs. 8, 9: B1's point law cannot run the free tilt; the pair runs the distributed law
    assert plan.free_tilt == "free-tilt-distributed"
    assert plan.tilt_locked == "axial-1000N-distributed"
    for name, tilt in ((plan.free_tilt, "free"), (plan.tilt_locked, "locked")):
        assert plan.spec(name).data["surfaces"]["flange_law"] == "distributed"
        assert plan.spec(name).data["inner_ring"]["tilt"] == tilt
    assert plan.spec("axial-1000N").data["surfaces"]["flange_law"] == "point"
    own_law = build_plan(variant(**{"surfaces.flange_law": "distributed"}), 0.01)
    assert (own_law.free_tilt, own_law.tilt_locked) == ("free-tilt", "axial-1000N")
    # figs. 10-13 once more with the distributed law, which runs the loads the point law
    # refuses; its own load's run is the locked run of figs. 8, 9
    assert plan.loads_distributed == {
        0.0: "axial-0N-distributed",
        500.0: "axial-500N-distributed",
        1000.0: "axial-1000N-distributed",
        2000.0: "axial-2000N-distributed",
    }
    for fa, name in plan.loads_distributed.items():
        data = plan.spec(name).data
        assert data["surfaces"]["flange_law"] == "distributed"
        assert data["operating"]["axial_load"] == fa and data["inner_ring"]["tilt"] == "locked"
    assert own_law.loads_distributed == {}
    # fig. 14 at B1's own dt_max is the reference pair, run once
    assert sorted(plan.runtime) == pytest.approx([2e-4, 5e-4, 1e-3])
    assert plan.runtime[1e-3] == {SEMI_ANALYTICAL: "axial-1000N", GRADIENT: "axial-1000N-gradient"}
    tilt = plan.spec("free-tilt-distributed").data["inner_ring"]
    assert tilt["tilt"] == "free" and tilt["misalignment"] == 0.0
    assert plan.spec("axial-2000N").data["operating"]["axial_load"] == 2000.0
    assert {s.t_end for s in plan.specs} == {0.01}
    none = build_plan(
        load_b1(), 0.01, loads=(0.0,), free_tilt=False, gradient=False, distributed=False
    )
    assert [s.name for s in none.specs] == ["axial-1000N", "axial-0N"]
    assert none.free_tilt is None and none.runtime == {} and none.reference_twin is None
    assert none.tight == {}
    with pytest.raises(StudyError, match="--loads"):
        build_plan(load_b1(), 0.01, loads=(-5.0,))
    # a load the configuration's rules refuse: the option, the field, the value, the rule
    with pytest.raises(StudyError, match=r"^--loads: operating.axial_load: 1000000000.0 — must"):
        build_plan(load_b1(), 0.01, loads=(1e9,))
    assert list(build_plan(load_b1(), 0.01, loads=()).loads) == [1000.0]  # its own load
    # an end time whose results would not fit (1e12 outputs) started all 17 runs, each of
    # which failed with advice to force it, an option the study does not have (a review)
    with pytest.raises(StudyError, match=r"^--t-end = 1e\+09 s: the run axial-1000N: .* GB"):
        build_plan(load_b1(), 1e9)
    with pytest.raises(StudyError, match=r"or a shorter --t-end$") as refused:
        build_plan(load_b1(), 1e9)
    assert "solver.outputs = []" not in str(refused.value) and "--force" not in str(refused.value)


def test_runs_start_longest_first_and_are_reported_in_plan_order():
    """The gradient runs (4-5 times a semi-analytical run's wall time) start first, the
    tightest tolerance first, then the smallest Δt_max; the rest keep the plan's order
    but for the distributed law's runs and then the tight tolerance's, which go first."""
    from rollerdyn.study.schedule import _longest_first

    plan = build_plan(load_b1(), 0.01)
    order = [s.name for s in _longest_first(plan.specs)]
    assert order[:4] == [
        "axial-1000N-gradient-tight",
        "dt-max-0.0002s-gradient",
        "dt-max-0.0005s-gradient",
        "axial-1000N-gradient",
    ]
    # then the distributed law's runs (about twice the point law's time), then the rest
    law = {s.name: s.data["surfaces"]["flange_law"] for s in plan.specs}
    rtol = {s.name: s.data["solver"]["rtol"] for s in plan.specs}
    rest = [s.name for s in plan.specs if s.detector != GRADIENT]
    assert order[4:] == sorted(rest, key=lambda name: (law[name] != "distributed", rtol[name]))
    assert order[4] == "axial-1000N-distributed" and law[order[9]] == "point"
    assert order[9:11] == ["axial-1000N-tight", "axial-1000N"]
    assert sorted(order) == sorted(s.name for s in plan.specs)


# --------------------------------------------------------------------------- the paper study


def test_every_run_completes_and_equals_the_same_run_in_series(study):
    out, result, events = study
    runs = result.runs
    assert list(runs["name"]) == [s.name for s in result.plan.specs]
    assert len(runs) == 11 and set(runs["status"]) == {"completed"}
    assert set(runs["action"]) == {"ran"}
    assert list(runs["reached [s]"]) == pytest.approx([T_END] * 11)
    plan = events[0]
    assert plan["kind"] == "plan" and plan["reused"] == [] and len(plan["pending"]) == 11
    assert sorted(e["name"] for e in events if e["kind"] == "done") == sorted(runs["name"])
    # two workers: the k-th run of the start order reports only once k - 1 runs have ended
    from rollerdyn.study.schedule import _longest_first

    position = {s.name: k for k, s in enumerate(_longest_first(result.plan.specs))}
    ended = 0
    for e in events:
        ended += e["kind"] == "done"
        if e["kind"] == "update":
            assert position[e["name"]] < ended + 2, (e["name"], ended)
    # the 0 N run is B1 with the axial load changed, bit for bit
    ref = simulate(variant(**{"operating.axial_load": "0 N"}), t_end=T_END, threads=1)
    with xr.open_dataset(out / "runs" / "axial-0N.nc", engine="h5netcdf") as opened:
        got = opened.load()
    for name in ("time", "frictional_torque", "position", "final_state"):
        np.testing.assert_array_equal(got[name].values, ref[name].values, err_msg=name)
    assert _attrs(out, "axial-1000N-gradient")["detector"] == GRADIENT
    assert _attrs(out, "dt-max-0.0005s-gradient")["dt_max_s"] == 5e-4
    assert '"tilt": "free"' in _attrs(out, "free-tilt-distributed")["config_resolved"]
    # every file written, the tables among them
    for name in ("report.html", "runs.csv", "findings.csv", "findings.json", "study.json"):
        assert (out / name).is_file(), name


def test_findings_carry_the_numbers_of_the_runs(study):
    out, result, _ = study
    found = {f.key: f for f in result.findings}
    assert len(found) == 13  # 10 and the 3 load checks on the distributed law's series
    wall = {n: _attrs(out, n)["stats_total_seconds"] for n in result.runs["name"]}
    saving = 1.0 - wall["axial-1000N"] / wall["axial-1000N-gradient"]
    semi = found["semi_faster"]
    assert semi.values["saving"] == pytest.approx(saving, rel=1e-12)
    assert semi.status == (PASS if saving > 0 else FAIL)
    shrink = found["advantage_shrinks"]
    small = 1.0 - wall["dt-max-0.0005s-semi-analytical"] / wall["dt-max-0.0005s-gradient"]
    assert shrink.values["saving"][5e-4] == pytest.approx(small, rel=1e-12)
    assert shrink.values["saving"][1e-3] == pytest.approx(saving, rel=1e-12)
    assert shrink.status == (PASS if small < saving else FAIL)
    # at 2 ms the ring stands still and no roller touches a flange: nothing to judge
    assert found["torque_grows"].status == NOT_RUN
    assert "0 N: not at full speed (reached t = 0.002 s)" in found["torque_grows"].numbers
    for key in ("to_co_dominates", "other_pairings_with_tilt", "same_contacts"):
        assert found[key].status == NOT_RUN, key
        assert "no flange contact" in found[key].numbers
    text = (out / "findings.csv").read_text(encoding="utf-8")
    assert f"{saving * 100:.1f} %" in text


def test_a_second_invocation_runs_nothing(study, monkeypatch):
    out, result, _ = study
    before = {p.name: p.stat().st_mtime_ns for p in (out / "runs").iterdir()}

    def no_cluster(*args, **kwargs):
        raise AssertionError("a cluster was started although every run was done")

    monkeypatch.setattr("rollerdyn.study.schedule._connect", no_cluster)
    events: list[dict] = []
    again = _short_paper(out, events, report=False)
    assert [e["kind"] for e in events] == ["plan"] and events[0]["pending"] == []
    assert set(again.runs["action"]) == {"reused"}
    assert list(again.runs["wall [s]"]) == list(result.runs["wall [s]"])
    assert [f.status for f in again.findings] == [f.status for f in result.findings]
    assert {p.name: p.stat().st_mtime_ns for p in (out / "runs").iterdir()} == before


def test_the_report_shows_findings_runs_and_figures(study):
    out, result, _ = study
    page = (out / "report.html").read_text(encoding="utf-8")
    for f in result.findings:
        assert f.statement.replace("'", "&#x27;") in page
    for name in result.runs["name"]:
        assert f"runs/{name}.nc" in page
    for key in ("fig10", "fig11", "fig12", "fig13", "fig8", "fig9", "fig14_wall"):
        assert f'id="plot-{key}"' in page, key
    for key in ("fig10", "fig11", "fig12", "fig13"):  # the distributed law's load series
        assert f'id="plot-{key}_distributed"' in page, key
    assert "document.body.setAttribute('data-plots'" in page
    assert page.count("<td class='PASS'>") == sum(f.status == PASS for f in result.findings)


def test_the_report_renders_in_headless_chromium_without_errors(study, tmp_path):
    from test_report import rendered_dom

    out, _, _ = study
    # figs. 10, 11, 12, 13 and the roller loads of each load series, 8, 9 and fig. 14's
    # two: fourteen plots drawn
    rendered_dom(out / "report.html", tmp_path, plots=14)


# --------------------------------------------------------------------------- one run


def _spec(t_end: float, **changes) -> RunSpec:
    from rollerdyn.provenance import config_hash

    cfg = variant(**{"solver.checkpoint_interval": "1 ms", **changes})
    return RunSpec("run", "test run", cfg.model_dump(), SEMI_ANALYTICAL, t_end, config_hash(cfg))


def test_a_partial_run_continues_from_its_checkpoint_bit_for_bit(tmp_path):
    spec = _spec(0.003)
    cfg = variant(**{"solver.checkpoint_interval": "1 ms"})
    partial = simulate(cfg, t_end=0.0015, threads=1)  # as if stopped at 1.5 ms
    write(partial, tmp_path / spec.file)
    assert inspect_run(spec, read_attrs(tmp_path / spec.file)) == PARTIAL
    rec = execute(spec, str(tmp_path), max_wall=120.0)
    assert rec["action"] == "continued" and rec["status"] == "completed", rec
    whole = simulate(cfg, t_end=0.003, threads=1)
    with xr.open_dataset(tmp_path / spec.file, engine="h5netcdf") as opened:
        got = opened.load()
    assert got.attrs["resumed_at_s"] == pytest.approx(0.001)
    for name in ("time", "frictional_torque", "position", "final_state"):
        np.testing.assert_array_equal(got[name].values, whole[name].values, err_msg=name)
    assert execute(spec, str(tmp_path), max_wall=120.0)["action"] == "reused"


def test_the_wall_time_cap_stops_a_run_and_says_so(tmp_path):
    spec = _spec(0.003)
    rec = execute(spec, str(tmp_path), max_wall=1e-9)
    assert rec["status"] == NOT_FINISHED and rec["reached [s]"] < 0.003
    assert "not finished (reached t = " in rec["note"] and "wall time" in rec["note"]
    attrs = read_attrs(tmp_path / spec.file)
    assert attrs["study_stopped"] == "stopped after 1e-09 s of wall time"
    assert inspect_run(spec, attrs) == PARTIAL  # the next invocation continues it
    other = _spec(0.003, **{"operating.axial_load": "0 N"})
    with pytest.raises(StudyError, match="another configuration"):
        inspect_run(other, attrs)


def test_a_failed_runs_note_is_the_refusal_itself_or_names_the_fault():
    # a refusal of the input (ValueError: the core's and the configuration's checks name
    # the field, the value and the rule) is shown as its message alone; any other
    # exception keeps its class, which says what kind of fault to report
    from rollerdyn.simulation import failure_note

    refusal = "surfaces.flange_law = point: the most loaded roller end lies on its end face"
    assert failure_note(ValueError(refusal)) == refusal
    assert failure_note(KeyError("roller")) == "KeyError: 'roller'"
    assert failure_note(RuntimeError("worker lost")) == "RuntimeError: worker lost"


def test_a_run_whose_worker_was_lost_keeps_what_its_file_holds(tmp_path):
    spec = _spec(0.003)
    lost = RuntimeError("worker lost")
    rec = lost_record(spec, tmp_path, lost)  # no file: it could not be run at all
    assert (
        rec["status"] == "failed"
        and rec["file"] == ""
        and rec["note"] == "RuntimeError: worker lost"
    )
    # killed after a checkpoint: its file holds a run the next invocation continues
    cfg = variant(**{"solver.checkpoint_interval": "1 ms"})
    partial = simulate(cfg, t_end=0.0015, threads=1)
    partial.attrs["completed"] = 0
    write(partial, tmp_path / spec.file)
    rec = lost_record(spec, tmp_path, lost)
    assert rec["status"] == NOT_FINISHED and rec["file"] == spec.file
    assert rec["reached [s]"] == pytest.approx(0.0015)
    assert "stopped (killed or interrupted)" in rec["note"] and "worker lost" in rec["note"]


def test_no_study_touches_a_folder_another_study_is_running_in(tmp_path):
    import subprocess
    import sys

    out = prepare_folder(tmp_path / "s", "paper", load_b1())
    (out / "runs").mkdir()
    run_file = out / "runs" / "axial-1000N.nc"
    run_file.write_bytes(b"a run being written")
    other = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        (out / ".study.lock").write_text(str(other.pid))
        for overwrite in (True, False):
            with pytest.raises(StudyError, match=f"another study \\(process {other.pid}\\)"):
                prepare_folder(out, "paper", load_b1(), overwrite=overwrite)
        with pytest.raises(StudyError, match="another study"):
            lock_folder(out)
    finally:
        other.kill()
        other.wait()
    assert run_file.read_bytes() == b"a run being written"
    # a lock whose process is gone is taken over, even one beyond the range of process ids
    for stale in (str(other.pid), "99999999999999999999"):
        (out / ".study.lock").write_text(stale)
        lock = lock_folder(out)
        assert lock.read_text() == str(os.getpid())
    lock.unlink()


# --------------------------------------------------------------------------- the checks


@pytest.fixture(scope="module")
def judged(study):
    """The study's plan with copies of its runs in which the ring turns at full speed."""
    out, result, _ = study
    plan = result.plan
    sets = {}
    for name in result.runs["name"]:
        with xr.open_dataset(out / "runs" / f"{name}.nc", engine="h5netcdf") as opened:
            ds = opened.load()
        ds["ring_speed"][:] = plan.config.operating.final_inner_ring_speed
        sets[name] = ds
    return plan, sets, result.records


def _check(judged, key: str, change) -> object:
    plan, sets, records = judged
    copies = {k: v.copy(deep=True) for k, v in sets.items()}
    change(copies)
    return next(f for f in check_findings(plan, copies, records) if f.key == key)


def test_torque_and_flange_friction_checks_pass_and_fail_as_defined(judged):
    def loads(torque: dict, friction: dict):
        def change(sets):
            for name, value in torque.items():
                sets[name]["frictional_torque"][:] = value
                sets[name]["flange_friction_force"][:] = friction[name] / (17 * 4)

        return change

    grows = loads({"axial-0N": 0.01, "axial-1000N": 0.3}, {"axial-0N": 0.0, "axial-1000N": 200.0})
    found = _check(judged, "torque_grows", grows)
    assert found.status == PASS and found.values["torque [N*m]"] == pytest.approx(
        {0.0: 0.01, 1000.0: 0.3}
    )
    found = _check(judged, "flange_friction_explains", grows)
    assert found.status == PASS
    assert found.values["lever arm [m]"]["0-1000 N"] == pytest.approx(0.29 / 200.0)
    falls = loads({"axial-0N": 0.3, "axial-1000N": 0.01}, {"axial-0N": 0.0, "axial-1000N": 0.0})
    assert _check(judged, "torque_grows", falls).status == FAIL
    no_friction = loads(
        {"axial-0N": 0.01, "axial-1000N": 0.3}, {"axial-0N": 5.0, "axial-1000N": 5.0}
    )
    assert _check(judged, "flange_friction_explains", no_friction).status == FAIL
    # the distributed law's series is judged on its own runs, under its own keys
    grows_d = loads(
        {"axial-0N-distributed": 0.01, "axial-1000N-distributed": 0.3},
        {"axial-0N-distributed": 0.0, "axial-1000N-distributed": 200.0},
    )
    found = _check(judged, "torque_grows_distributed", lambda sets: (falls(sets), grows_d(sets)))
    assert found.status == PASS and "distributed flange law" in found.statement
    assert found.values["torque [N*m]"] == pytest.approx({0.0: 0.01, 1000.0: 0.3})
    assert _check(judged, "torque_grows", lambda sets: (falls(sets), grows_d(sets))).status == FAIL
    plan, sets, records = judged
    keys = [f.key for f in check_findings(plan, sets, records)]
    assert keys[:6] == [
        "torque_grows",
        "flange_friction_explains",
        "axial_in_load_zone",
        "torque_grows_distributed",
        "flange_friction_explains_distributed",
        "axial_in_load_zone_distributed",
    ]


def test_pairing_checks_pass_and_fail_as_defined(judged):
    to_co, sp_co = PAIRINGS.index("TO-CO"), PAIRINGS.index("SP-CO")

    def pairings(locked: int, free: int):
        def change(sets):
            sets["axial-1000N"]["flange_pairing"][:] = locked
            sets["axial-1000N-distributed"]["flange_pairing"][:] = locked
            sets["free-tilt-distributed"]["flange_pairing"][:] = free
            sets["free-tilt-distributed"]["flange_pairing"][:, :3] = to_co

        return change

    found = _check(judged, "to_co_dominates", pairings(to_co, sp_co))
    assert found.status == PASS and found.values["inner"]["TO-CO"] == 1.0
    assert _check(judged, "to_co_dominates", pairings(sp_co, sp_co)).status == FAIL
    found = _check(judged, "other_pairings_with_tilt", pairings(to_co, sp_co))
    assert found.status == PASS
    assert found.values["inner"] == pytest.approx({"locked": 0.0, "free": 14 / 17})
    assert _check(judged, "other_pairings_with_tilt", pairings(sp_co, to_co)).status == FAIL


def test_a_configuration_free_to_tilt_is_not_compared_with_itself(judged):
    plan, sets, records = judged
    own = build_plan(variant(**{"inner_ring.tilt": "free"}), 0.01)
    assert own.free_tilt == own.reference  # its own run is the free-tilt run
    free = dataclasses.replace(plan, free_tilt=plan.reference)
    other = PAIRINGS.index("SP-CO")
    sets = {k: v.copy(deep=True) for k, v in sets.items()}
    sets[plan.reference]["flange_pairing"][:] = other  # contact everywhere
    found = next(
        f for f in check_findings(free, sets, records) if f.key == "other_pairings_with_tilt"
    )
    assert found.status == NOT_RUN and "free to tilt" in found.numbers
    page = build_page(free, sets, records, [], {}, "free")
    fig8 = page[page.index('id="plot-fig8"') : page.index('id="plot-fig9"')]
    label = plan.spec(plan.reference).label
    assert fig8.count(f'"name":"{label}"') == 1  # one run, not the same run twice


def test_contact_comparison_passes_for_equal_contacts_and_fails_for_others(judged):
    def contacts(offset: float, force: float = 10.0):
        def change(sets):
            for name in ("axial-1000N", "axial-1000N-gradient"):
                sets[name]["flange_penetration"][:] = 1e-6
                sets[name]["flange_normal_force"][:] = force
            sets["axial-1000N-gradient"]["flange_penetration"][:] += offset

        return change

    same = _check(judged, "same_contacts", contacts(0.0))
    assert same.status == PASS and same.values["max |d penetration| loaded [m]"] == 0.0
    differ = _check(judged, "same_contacts", contacts(2e-8))  # 2 % of the penetration
    assert differ.status == FAIL
    assert differ.values["max |d penetration| loaded [m]"] == pytest.approx(2e-8)
    grazing = _check(judged, "same_contacts", contacts(2e-8, force=0.5))  # below 1 N
    assert grazing.status == NOT_RUN and "no contact carries load" in grazing.numbers
    assert grazing.values["max |d penetration| touching [m]"] == pytest.approx(2e-8)


def test_kinematics_comparison_is_judged_against_the_round_off_twin(judged):
    """The methods' runs pass where they differ no more than 3 times the round-off twin
    differs from the reference, or within the absolute bounds (0.1 µm), else fail."""
    plan, sets, _ = judged
    azimuth = np.mod(sets["axial-1000N"].azimuth.values[0], 2 * np.pi)
    top = int(np.argmax(np.abs(azimuth - np.pi)))  # a roller outside the load zone

    def moved(gradient: float, twin: float):
        def change(sets):
            for name in ("axial-1000N-gradient", "axial-1000N-roundoff"):
                sets[name] = sets["axial-1000N"].copy(deep=True)
            for name, shift in (("axial-1000N-gradient", gradient), ("axial-1000N-roundoff", twin)):
                sets[name]["position"][:, top, 0] += shift  # along the axis

        return change

    same = _check(judged, "same_kinematics", moved(0.0, 0.0))
    assert same.status == PASS
    assert same.values["measures"]["position_outside_full_speed"]["methods"] == 0.0
    within_bound = _check(judged, "same_kinematics", moved(0.09e-6, 0.0))
    assert within_bound.status == PASS  # 0.09 µm: within the absolute 0.1 µm
    apart = _check(judged, "same_kinematics", moved(1e-6, 0.0))
    assert apart.status == FAIL and "position_outside_full_speed" in apart.numbers
    measures = apart.values["measures"]["position_outside_full_speed"]
    assert measures["methods"] == pytest.approx(1e-6) and measures["bound"] == 1e-7
    like_the_twin = _check(judged, "same_kinematics", moved(1e-6, 0.4e-6))
    assert like_the_twin.status == PASS  # 1 µm within 3 x 0.4 µm
    beyond_the_twin = _check(judged, "same_kinematics", moved(1e-6, 0.3e-6))
    assert beyond_the_twin.status == FAIL  # 1 µm beyond 3 x 0.3 µm
    no_twin = _check(judged, "same_kinematics", lambda sets: sets.pop("axial-1000N-roundoff"))
    assert no_twin.status == NOT_RUN and "round-off twin" in no_twin.numbers


def test_the_tight_pair_is_judged_against_absolute_bounds(judged):
    """The two methods at ten times tighter tolerances pass where every roller's position
    is within 0.1 µm (whatever the twin says), and fail beyond it."""
    plan, sets, _ = judged
    azimuth = np.mod(sets["axial-1000N-tight"].azimuth.values[0], 2 * np.pi)
    top = int(np.argmax(np.abs(azimuth - np.pi)))  # a roller outside the load zone

    def moved(gradient: float):
        def change(sets):
            sets["axial-1000N-gradient-tight"] = sets["axial-1000N-tight"].copy(deep=True)
            sets["axial-1000N-gradient-tight"]["position"][:, top, 0] += gradient

        return change

    same = _check(judged, "tight_agreement", moved(0.0))
    assert same.status == PASS and same.values["measures"]["position_outside"] == 0.0
    within = _check(judged, "tight_agreement", moved(0.09e-6))
    assert within.status == PASS
    assert within.values["measures"]["position_outside"] == pytest.approx(0.09e-6)
    apart = _check(judged, "tight_agreement", moved(0.2e-6))
    assert apart.status == FAIL and "over the bound: position_outside" in apart.numbers

    # a round-off twin that drifts by 1 µm does not excuse it (it would the same_kinematics)
    def twin_apart(sets):
        moved(0.2e-6)(sets)
        sets["axial-1000N-roundoff"] = sets["axial-1000N"].copy(deep=True)
        sets["axial-1000N-roundoff"]["position"][:, top, 0] += 1e-6

    assert _check(judged, "tight_agreement", twin_apart).status == FAIL

    # flange forces are judged only where the largest carries load (1 N): here, 2 ms into
    # the load ramp, it is mN of grazing contact, and 50 % of it is no verdict
    def forces(largest: float):
        def change(sets):
            moved(0.0)(sets)
            sets["axial-1000N-tight"]["flange_normal_force"][:] = largest
            sets["axial-1000N-gradient-tight"]["flange_normal_force"][:] = 0.5 * largest

        return change

    grazing = _check(judged, "tight_agreement", forces(2e-3))
    assert grazing.status == PASS and "flange_force" not in grazing.values["measures"]
    assert "largest flange force is below 1 N" in grazing.numbers
    loaded = _check(judged, "tight_agreement", forces(100.0))
    assert loaded.status == FAIL and loaded.values["measures"]["flange_force"] == 0.5
    gone = _check(judged, "tight_agreement", lambda s: s.pop("axial-1000N-gradient-tight"))
    assert gone.status == NOT_RUN and "tighter tolerances" in gone.numbers


def test_run_differences_split_a_shift_into_its_directions(judged):
    """A roller moved along the circumference, the radius or the axis by a known length
    shows that length in its own direction only (the measures of both comparisons)."""
    from rollerdyn.study.agreement import differences

    _, sets, _ = judged
    a = sets["axial-1000N"]
    psi = np.mod(a.azimuth.values, 2 * np.pi)  # from +y towards +z
    for direction, unit in (
        ("circumferential_full_speed", np.stack([0 * psi, -np.sin(psi), np.cos(psi)], axis=-1)),
        ("radial_full_speed", np.stack([0 * psi, np.cos(psi), np.sin(psi)], axis=-1)),
        ("axial_full_speed", np.stack([np.ones_like(psi), 0 * psi, 0 * psi], axis=-1)),
    ):
        b = a.copy(deep=True)
        b["position"][:] = a.position.values + 2e-7 * unit
        d = differences(a, b, full_speed=0.0)
        for name in ("axial_full_speed", "radial_full_speed", "circumferential_full_speed"):
            expected = 2e-7 if name == direction else 0.0
            assert d[name] == pytest.approx(expected, abs=1e-15), (direction, name)
        assert d["position_outside"] == pytest.approx(2e-7, rel=1e-9)
        assert d["flange_force"] == 0.0 or math.isnan(d["flange_force"])
    # where the largest difference lies: one roller moved at one output only
    b = a.copy(deep=True)
    outside = np.abs(psi - np.pi) > np.radians(60.0)
    k, roller = 1, int(np.argmax(outside[1]))
    b["position"][k, roller, 0] += 3e-7
    d = differences(a, b, full_speed=0.0)
    assert d["position_outside"] == pytest.approx(3e-7)
    assert d["where"]["position_outside"] == {
        "time": float(a.time.values[k]),
        "roller": roller,
        "azimuth_deg": pytest.approx(float(np.degrees(psi[k, roller]))),
    }
    assert d["where"]["position_load_zone"]["time"] == float(a.time.values[0])  # all zero


def test_axial_force_check_uses_the_load_zone(judged):
    plan, sets, records = judged
    c = _Context(plan, sets, records)
    assert plan.config.operating.load_ramp.end == 0.5  # B1: at 2 ms the loads are not up
    from rollerdyn.study.findings import axial_force_in_load_zone

    assert axial_force_in_load_zone(c).status == NOT_RUN
    # The same runs moved past the load ramp, three rollers loaded at the inner race and the
    # inner flanges' axial force put on the loaded rollers (PASS, the whole of it in the
    # load zone) or on three unloaded ones (FAIL, none of it).
    fa, name = next((fa, n) for fa, n in plan.loads.items() if fa > 0)

    def judged_with(carriers: list[int]):
        copies = {k: v.copy(deep=True) for k, v in sets.items()}
        ds = copies[name].assign_coords(time=copies[name].time + 1.0)
        ds["inner_normal_force"][:] = 0.0
        ds["inner_normal_force"][:, [0, 1, 16]] = 100.0
        ds["flange_axial_force"][:] = 0.0
        ds["flange_axial_force"].loc[{"flange": "inner-x"}] = 0.0
        axial = ds["flange_axial_force"].sel(flange="inner+x").values
        axial[:, carriers] = fa / 3
        ds["flange_axial_force"].loc[{"flange": "inner+x"}] = axial
        copies[name] = ds
        return axial_force_in_load_zone(_Context(plan, copies, records))

    found = judged_with([0, 1, 16])
    assert found.status == PASS, found.numbers
    assert found.values[fa]["share"] == pytest.approx(1.0)
    assert found.values[fa]["zone fraction"] == pytest.approx(3 / 17)
    found = judged_with([5, 8, 11])
    assert found.status == FAIL, found.numbers
    assert found.values[fa]["share"] == pytest.approx(0.0)


# --------------------------------------------------------------------------- steadiness


def _series(torque) -> xr.Dataset:
    t = np.arange(0, 101) * 1e-3
    n = t.size
    return xr.Dataset(
        {
            "frictional_torque": ("time", np.broadcast_to(torque(t), (n,)).copy()),
            "ring_speed": ("time", np.full(n, 100.0)),
            "orbital_speed": (("time", "roller"), np.full((n, 3), 40.0)),
            "flange_normal_force": (("time", "roller", "flange"), np.full((n, 3, 4), 50.0)),
        },
        coords={"time": t},
    )


def test_steady_rule_needs_three_calm_windows_after_the_ramps():
    rule = SteadyRule(settle=0.02, window=0.01, tol=0.02, factor=0.5)
    calm = _series(lambda t: 0.3 + 0 * t)
    assert rule(calm.sel(time=slice(0, 0.049))) == ""  # only two windows after the ramps
    assert rule(calm.sel(time=slice(0, 0.05))) == "steady at t = 0.05 s"
    out = window_outputs(calm, 0.04, 0.05, 0.5)
    # a result without the lubrication outputs has no Lambda (NaN), which the rule ignores
    assert out == pytest.approx(
        {
            "torque [N*m]": 0.3,
            "speed loss [1]": 0.2,
            "max flange force [N]": 50.0,
            "inner race Lambda [1]": math.nan,
            "flange Lambda [1]": math.nan,
            "ring vibration [m]": math.nan,  # no ring position recorded
        },
        nan_ok=True,
    )
    # the ring's vibration: the peak-to-peak of its y over the window's outputs (a sine of
    # 2 um amplitude sampled at its crests: 4 um), reported, not judged
    y = 2e-6 * np.sin(2 * np.pi * 250.0 * calm.time.values)  # 4 ms period, 1 ms outputs
    shaken = calm.assign(
        ring_position=(("time", "xyz"), np.stack([0 * y, y, 0 * y], axis=1)),
    ).assign_coords(xyz=["x", "y", "z"])
    assert window_outputs(shaken, 0.04, 0.05, 0.5)["ring vibration [m]"] == pytest.approx(4e-6)
    assert rule(shaken.sel(time=slice(0, 0.05))) == "steady at t = 0.05 s"
    # with the power losses recorded, the torque is their mean over the ring speed
    lossy = calm.assign(power_loss=("time", np.full(calm.sizes["time"], 25.0)))
    assert window_outputs(lossy, 0.04, 0.05, 0.5)["torque [N*m]"] == pytest.approx(0.25)
    # a window that reaches back before a resume from a result without them: the torque
    partly = lossy.copy(deep=True)
    partly["power_loss"][:45] = np.nan
    assert window_outputs(partly, 0.04, 0.05, 0.5)["torque [N*m]"] == pytest.approx(0.3)
    assert window_outputs(partly, 0.05, 0.06, 0.5)["torque [N*m]"] == pytest.approx(0.25)
    drifting = _series(lambda t: 0.3 + 1.2 * t)  # 3 % per window at t = 0.1 s
    steady, _, last = rule.verdict(drifting)
    assert not steady and last["torque [N*m]"] == pytest.approx(0.3 + 1.2 * 0.0955)
    assert rule.verdict(_series(lambda t: 0.3 + 0.6 * t))[0]  # 1.5 % per window: steady


def test_ranges_are_read_and_refused_by_option():
    assert parse_range("0:1000:3", "--axial-load", "force", "N") == [0.0, 500.0, 1000.0]
    assert parse_range("1 kN,2 kN", "--radial-load", "force", "N") == [1000.0, 2000.0]
    assert parse_range("100:100:1", "--axial-load", "force", "N") == [100.0]
    speeds = parse_range("500:1500:2", "--speed", "angular velocity", "rpm", positive=True)
    assert speeds == pytest.approx([500 * math.pi / 30, 1500 * math.pi / 30])
    for text, reason in (
        ("500:100:0", "empty range"),
        ("500:100:3", "reversed range"),
        ("100:500:1", "one point needs a = b"),
        ("100,,200", "an empty value"),
        ("0", "every value must be above 0"),
        ("5 mm", "expected an angular velocity"),
    ):
        with pytest.raises(StudyError, match=reason) as err:
            parse_range(text, "--speed", "angular velocity", "rpm", positive=True)
        assert str(err.value).startswith("--speed ")


def _b1_map(tmp_path, client, **options):
    """B1's operating map at 3000 rpm in ``tmp_path / "map"`` on the test cluster, with a
    least window of 1 ms (two roller passing periods, 5.8 ms, decide) and a loose
    criterion (tol 0.5: steady within a few windows)."""
    return operating_map(
        B1, tmp_path / "map", speed="3000", window=0.001, tol=0.5, scheduler=client, **options
    )


def test_map_of_a_turning_outer_ring(tmp_path, client):
    """A planet gear's bearing (inner ring 0 rpm, outer ring turning): --speed sweeps the
    outer ring. The window counts roller passes of the roller set the outer ring drives,
    omega_c = omega_o (1 + D/d_m)/2; the speed loss is taken against that orbit (with the
    inner ring's alone it would divide by 0); the estimate beside the point is the statics'
    of the outer ring at that speed (1e-3: the sweep's warm start, as for B1's map)."""
    from rollerdyn.statics import statics

    cfg = variant(
        **{"operating.inner_ring_speed": "0 rpm", "operating.outer_ring_speed": "500 rpm"}
    )
    result = operating_map(
        cfg,
        tmp_path / "map",
        speed="3000",
        window=0.001,
        tol=0.5,
        max_time=0.03,
        scheduler=client,
    )
    row = result.points.iloc[0]
    gamma = 4.495 / 24.5
    assert row["window [s]"] == pytest.approx(2 * 60 / (17 * 3000 * (1 + gamma) / 2))
    assert abs(row["speed loss [1]"]) < 0.02, row["speed loss [1]"]
    estimate = float(statics(cfg, speed=0.0, outer_speed=3000 * np.pi / 30).friction_torque)
    assert row["steady rolling torque [N*m]"] == pytest.approx(estimate, rel=1e-3)
    assert 0.8 < row["torque over steady rolling [1]"] < 1.5, row["torque over steady rolling [1]"]


def test_map_point_stops_when_steady(tmp_path, client):
    def run_map():
        return _b1_map(tmp_path, client, axial_load="0", start="equilibrium", max_time=0.03)

    result = run_map()
    row = result.points.iloc[0]
    assert row["speed [rpm]"] == pytest.approx(3000.0) and row["axial_load [N]"] == 0.0
    window = row["window [s]"]
    assert window == pytest.approx(2 * 60 / (17 * 3000 * (1 - 4.495 / 24.5) / 2))
    with xr.open_dataset(tmp_path / "map" / "points" / "point_0000.nc", engine="h5netcdf") as f:
        ds = f.load()
    # steady at the first multiple of the window at which the rule says so, not before
    steady_at = row["steady at [s]"]
    k = round(steady_at / window)
    assert row["status"] == "steady" and k >= 3 and steady_at == pytest.approx(k * window)
    assert ds.attrs["study_done"] == f"steady at t = {steady_at:.6g} s"
    rule = SteadyRule(0.0, window, 0.5, (1 - 4.495 / 24.5) / 2)
    for j in range(3, k):  # the run as the rule saw it at each earlier checkpoint
        seen = ds.sel(time=slice(0, j * window + 1e-9)).drop_vars("checkpoint_time")
        assert rule(seen.assign(checkpoint_time=j * window)) == "", j
    assert rule(ds) == ds.attrs["study_done"]
    assert float(ds.time[-1]) < steady_at + 2e-3  # stopped at the next output, not at 0.03 s
    t = ds.time.values
    # each window is sampled by at least OUTPUTS_PER_WINDOW = 100 outputs (B1's 1 ms would
    # give about 6 here): the spacing of the outputs, to round-off
    assert np.diff(t).max() <= window / 100 * (1 + 1e-9)
    last = (t > steady_at - window + 1e-12) & (t <= steady_at + 1e-12)
    # the torque the window's mean power loss means at its mean ring speed
    power = float(ds.power_loss.values[last].mean())
    assert row["torque [N*m]"] == pytest.approx(power / float(ds.ring_speed.values[last].mean()))
    loss = 1 - ds.orbital_speed.values[last].mean() / (
        ds.ring_speed.values[last].mean() * (1 - 4.495 / 24.5) / 2
    )
    assert row["speed loss [1]"] == pytest.approx(loss, rel=1e-9)
    assert row["max flange force [N]"] == pytest.approx(
        float(np.nanmax(ds.flange_normal_force.values[last]))
    )
    # the median Lambda of the contacts in contact over the window (reported, not judged;
    # NaN where none touches: without axial load the roller ends may not)
    for column, prefix in (("inner race Lambda [1]", "inner"), ("flange Lambda [1]", "flange")):
        lam = ds[f"{prefix}_specific_film_thickness"].values[last]
        on = ds[f"{prefix}_max_pressure"].values[last] > 0.0
        assert on.any() or prefix == "flange"
        expected = float(np.median(lam[on])) if on.any() else math.nan
        assert row[column] == pytest.approx(expected, rel=1e-12, nan_ok=True), column
    # the ring's vibration over the window: the peak-to-peak of its y. The statics turned
    # over one roller pitch (docs/dynamics.md, "Vibration and torque ripple ...") give B1
    # without axial load 36.2 nm at Z f_c and 4.1 nm at 2 Z f_c along the load, so a
    # peak-to-peak of about 2 x 36.2 = 72 nm, 64-81 nm with the second harmonic's phase;
    # 25 % for that, the higher harmonics and the window's drift (measured: 82 nm)
    ring_y = ds.ring_position.sel(xyz="y").values[last]
    assert row["ring vibration [m]"] == pytest.approx(float(np.ptp(ring_y)), rel=1e-12)
    assert row["ring vibration [m]"] == pytest.approx(2 * 36.2e-9, rel=0.25)
    # beside it the quasi-static estimate: the friction torque of steady rolling at the
    # point's loads and speed, as `rollerdyn statics` gives it (the same solve: 1e-9), and
    # the dynamic torque over it
    from rollerdyn.statics import statics
    from rollerdyn.study.estimates import STEADY_ROLLING, TORQUE_RATIO

    alone = float(statics(B1, speed=3000 * math.pi / 30, axial_load=0.0).friction_torque)
    assert row[STEADY_ROLLING] == pytest.approx(alone, rel=1e-9)
    assert row[TORQUE_RATIO] == pytest.approx(row["torque [N*m]"] / alone, rel=1e-12)
    assert (tmp_path / "map" / "map.csv").is_file()
    assert {p.name for p in (tmp_path / "map" / "figures").iterdir()} >= {"map_torque.png"}
    # a worker stopped while writing the point's file (Ctrl-C) leaves point_0000.nc.tmp<pid>
    # beside it; the next invocation reuses the point and removes what the dead writer left
    stale = tmp_path / "map" / "points" / "point_0000.nc.tmp999999999"
    stale.write_bytes(b"half a netCDF file")
    again = run_map()
    assert again.points.iloc[0]["steady at [s]"] == steady_at
    assert not stale.exists()
    # the points are numbered in their grid: another grid in the same folder (here one
    # more axial load; point_0001 would be a new point, and a smaller grid rewrote the
    # table without the rest) is refused before any run, naming both grids
    grids = r"axial loads 0 N; now speeds 3000 rpm, radial loads 5000 N, axial loads 0, 500 N"
    with pytest.raises(StudyError, match=f"holds a map of another grid .*{grids}"):
        _b1_map(tmp_path, client, axial_load="0,500", start="equilibrium", max_time=0.03)


def _map_frame(rows):
    import pandas as pd

    keys = ("speed [rpm]", "radial_load [N]", "axial_load [N]", "status", "torque [N*m]")
    frame = pd.DataFrame([dict(zip(keys, r, strict=True)) for r in rows])
    frame["speed loss [1]"] = frame["torque [N*m]"] * 0.01
    frame["max flange force [N]"] = frame["torque [N*m]"] * 500
    frame["inner race Lambda [1]"] = frame["torque [N*m]"] * 2
    frame["flange Lambda [1]"] = frame["torque [N*m]"] * 0.1
    return frame


def _drawn_maps(frame, tmp_path, monkeypatch) -> list:
    """The torque figure's axes that ``write_maps`` draws for ``frame``."""
    import rollerdyn.plots as plots
    from rollerdyn.study.map_figures import write_maps

    figures = []
    monkeypatch.setattr(plots, "save_figure", lambda fig, out, name: figures.append(fig) or [])
    write_maps(frame, tmp_path, "B1")
    return figures[0].axes


def test_map_figures_leave_out_an_output_no_point_has(tmp_path, monkeypatch):
    """A map whose roller ends never touch has no flange Lambda at any point: its figure
    is left out (an all-NaN colour scale has nothing to show), the others are drawn."""
    import rollerdyn.plots as plots
    from rollerdyn.study.map_figures import write_maps

    frame = _map_frame(
        [(500.0, 5000.0, 0.0, "steady", 0.005), (2000.0, 5000.0, 0.0, "steady", 0.012)]
    )
    frame["flange Lambda [1]"] = math.nan
    names = []
    monkeypatch.setattr(plots, "save_figure", lambda fig, out, name: names.append(name) or [])
    write_maps(frame, tmp_path, "B1")
    assert "map_inner_race_Lambda" in names and "map_torque" in names
    assert "map_flange_Lambda" not in names


def test_map_figures_cross_points_not_steady_and_label_points_without_a_value(
    tmp_path, monkeypatch
):
    # a not-steady point has a value and gets a red cross; a failed point has none and
    # is labelled with its status in its blank cell (not crossed as if it were unsteady)
    grid = _map_frame(
        [
            (500.0, 5000.0, 0.0, "steady", 0.005),
            (500.0, 5000.0, 1000.0, "not steady", 0.30),
            (2000.0, 5000.0, 0.0, "steady", math.nan),
            (2000.0, 5000.0, 1000.0, "failed", math.nan),
        ]
    )
    ax = _drawn_maps(grid, tmp_path, monkeypatch)[0]
    crosses = [line for line in ax.lines if line.get_marker() == "x"]
    assert [(float(c.get_xdata()[0]), float(c.get_ydata()[0])) for c in crosses] == [(0, 1)]
    labels = [(t.get_text(), t.get_position()) for t in ax.texts]
    # a steady point without a value (a flange's film without axial load) said "steady"
    assert labels == [("none", (1, 0)), ("failed", (1, 1))]
    # one swept quantity: a line; the failed point is a labelled dotted line at its value
    line = _map_frame(
        [
            (500.0, 5000.0, 0.0, "steady", 0.005),
            (500.0, 5000.0, 1000.0, "not steady", 0.30),
            (500.0, 5000.0, 2000.0, "failed", math.nan),
        ]
    )
    ax = _drawn_maps(line, tmp_path, monkeypatch)[0]
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["map point", "not steady"]
    assert [t.get_text() for t in ax.texts] == ["failed"]


def test_map_torque_figure_draws_the_steady_rolling_estimate_beside_it(tmp_path, monkeypatch):
    from rollerdyn.study.estimates import STEADY_ROLLING

    line = _map_frame(
        [(500.0, 5000.0, 0.0, "steady", 0.005), (500.0, 5000.0, 1000.0, "steady", 0.30)]
    )
    line[STEADY_ROLLING] = [0.006, 0.28]
    ax = _drawn_maps(line, tmp_path, monkeypatch)[0]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend == ["map point", "steady rolling (quasi-static, spins balanced)"]
    assert list(ax.lines[1].get_ydata()) == [0.006, 0.28]


def test_map_steady_rolling_estimates_are_each_points_statics():
    """The estimate of every grid point (speed x radial x axial x temperature, the
    temperature fastest, as the map numbers its points) is that point's own quasi-static
    friction torque of steady rolling: the sweep behind it solves each case from its
    neighbour's equilibrium, so to the equilibrium's tolerance (measured: 2e-4 relative
    at B1's 1000 N after 0 N, the unloaded rollers' positions); 1e-3."""
    from rollerdyn.statics import statics
    from rollerdyn.study.estimates import steady_rolling_torques

    rpm = math.pi / 30
    axes = ([500 * rpm, 3000 * rpm], [5000.0], [0.0, 1000.0], [333.15, 353.15])
    estimates = steady_rolling_torques(load_b1(), axes)
    assert len(estimates) == 8
    for estimate, (w, fr, fa, temp) in zip(estimates, itertools.product(*axes), strict=True):
        cfg = variant(**{"operating.temperature": f"{temp} K"})
        alone = statics(cfg, speed=w, radial_load=fr, axial_load=fa)
        assert estimate == pytest.approx(float(alone.friction_torque), rel=1e-3), (w, fa, temp)
    # the oil's temperature matters: hotter oil, thinner films, less torque at 0 N
    assert estimates[1] < estimates[0]


def test_map_points_are_sampled_a_hundred_times_a_window():
    # 1 ms outputs sample the spiky torque of an unloaded B1 ten times in a 10 ms window,
    # and the window means scatter by 6 % (docs/study.md, "How often a point is sampled");
    # a point's outputs come at most every W / 100, a finer interval of the configuration
    # is kept, and the checkpoints are the windows' ends
    from rollerdyn.study.maps import OUTPUTS_PER_WINDOW, windowed

    b1 = load_b1()
    assert b1.solver.output_interval == pytest.approx(1e-3)
    point = windowed(b1, 0.01)
    assert OUTPUTS_PER_WINDOW == 100
    assert point.solver.output_interval == pytest.approx(1e-4, rel=1e-12)
    assert point.solver.checkpoint_interval == 0.01
    fine = windowed(variant(**{"solver.output_interval": "20 us"}), 0.01)
    assert fine.solver.output_interval == pytest.approx(2e-5, rel=1e-12)
    assert b1.solver.output_interval == pytest.approx(1e-3)  # the configuration unchanged


def test_map_says_it_prepares_its_points_before_they_run():
    # each point is checked with its quasi-static start (about 57 ms): 1000 points were a
    # minute without a word before the first line (a review); progress hears of them first
    from rollerdyn.study.maps import RPM, _map_points

    events = []
    axes = ([1000 * RPM, 2000 * RPM], [5000.0], [0.0, 1000.0], [load_b1().operating.temperature])
    specs, _ = _map_points(load_b1(), axes, "equilibrium", 0.02, 0.01, 0.02, 0.1, events.append)
    assert len(specs) == 4
    assert events[0] == {"kind": "prepare", "done": 0, "total": 4}
    assert events[-1] == {"kind": "prepare", "done": 4, "total": 4}
    assert all(e["kind"] == "prepare" and e["total"] == 4 for e in events)


def test_equilibrium_refusal_names_why_a_point_has_no_equilibrium():
    # B1 with the free inner-ring tilt and the distributed law at 1000 N: the statics tilt
    # the ring until one roller end presses its flange past ISO 76's 4 GPa, so there is no
    # equilibrium to start from (measured: 4.2 GPa at roller 14), though the dynamic run
    # from short ramps reaches a steady state with 155 N flange forces (docs/study.md);
    # the locked ring has one
    from rollerdyn.model import Model
    from rollerdyn.study.maps import RPM, equilibrium_refusal, point_config

    free = variant(**{"inner_ring.tilt": "free", "surfaces.flange_law": "distributed"})
    traction = Model(free).traction_model(tabulated=False)
    point, _ = point_config(free, 1000 * RPM, 5000.0, 1000.0, "equilibrium", 0.02)
    reason = equilibrium_refusal(point, traction)
    assert reason is not None and "cannot carry" in reason and "ISO 76" in reason, reason
    assert not reason.startswith("solver.start")
    locked, _ = point_config(load_b1(), 1000 * RPM, 5000.0, 1000.0, "equilibrium", 0.02)
    assert equilibrium_refusal(locked, traction) is None


def test_map_point_without_equilibrium_starts_from_short_ramps(tmp_path, client, monkeypatch):
    # a point the statics cannot start (here by decree, for speed) runs from the short
    # ramps instead of failing, and its row's start says so and why
    import rollerdyn.study.maps as maps

    monkeypatch.setattr(maps, "equilibrium_refusal", lambda variant, traction: "a reason")
    result = _b1_map(tmp_path, client, axial_load="0", ramp=0.002, max_time=0.04)
    row = result.points.iloc[0]
    assert row["start"] == f"{maps.FALLBACK} (a reason)"
    assert row["status"] in ("steady", "not steady") and row["reached [s]"] > 0.004
    with xr.open_dataset(tmp_path / "map" / "points" / "point_0000.nc", engine="h5netcdf") as f:
        assert float(f.radial_load.values[0]) < 1.0  # loads ramped up from 0, not at once


def test_map_point_the_point_law_refuses_runs_when_forced(tmp_path, client):
    """A grid point the point law's load check refuses (B1 without radial load at 100 N
    axially: its most loaded roller end on its end face, docs/dynamics.md, "The whole B1
    run") is a run that could not be run: failed, no file, the refusal as its note. The
    map invoked again in the same folder with ``force`` runs it (as ``rollerdyn run
    --force``), and its row and file say that it was forced."""

    def run_map(**kw):
        # to three windows of two roller passing periods (5.8 ms)
        return _b1_map(tmp_path, client, radial_load="0", axial_load="100", max_time=0.018, **kw)

    refused = run_map().points.iloc[0]
    assert refused["status"] == "failed" and refused["file"] == ""
    assert "lies on its end face" in refused["note"] and "--force" in refused["note"]
    forced = run_map(force=True).points.iloc[0]
    assert forced["status"] in ("steady", "not steady") and forced["file"] != ""
    assert "run with --force past the point law's load check" in forced["note"]
    with xr.open_dataset(tmp_path / "map" / "points" / forced["file"], engine="h5netcdf") as f:
        assert "lies on its end face" in f.attrs["forced"]
        assert f.attrs["final_time_s"] > 0.017


# --------------------------------------------------------------------------- command line


def _refused(args: list[str], *needles: str) -> str:
    result = RUNNER.invoke(app, args)
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    for needle in needles:
        assert needle in result.output, (needle, result.output)
    return result.output


def test_cli_refuses_bad_input_naming_the_option(tmp_path, study):
    out, _, _ = study
    _refused(
        ["study", "map", str(B1), "--speed", "500:100:0", "-o", str(tmp_path / "m")],
        "--speed '500:100:0': empty range",
    )
    _refused(
        ["study", "map", str(B1), "--speed", "500:100:3", "-o", str(tmp_path / "m")],
        "--speed '500:100:3': reversed range",
    )
    _refused(
        [
            "study",
            "map",
            str(B1),
            "--speed",
            "500",
            "--axial-load",
            "-5",
            "-o",
            str(tmp_path / "m"),
        ],
        "--axial-load",
    )
    _refused(
        ["study", "map", str(B1), "--speed", "500", "--radial-load", "200 kN"]
        + ["-o", str(tmp_path / "m")],
        "operating.radial_load — ",
        "(--radial-load)",
    )
    assert not (tmp_path / "m").exists()
    _refused(["study", "paper", str(B1), "--t-end", "-1", "-o", str(tmp_path / "p")], "--t-end")
    _refused(["study", "paper", str(B1), "--loads", "a,b", "-o", str(tmp_path / "p")], "--loads")
    _refused(
        [
            "study",
            "paper",
            str(B1),
            "--t-end",
            "1 ms",
            "--scheduler",
            "tcp://127.0.0.1:1",
            "-o",
            str(tmp_path / "p"),
        ],
        "--scheduler 'tcp://127.0.0.1:1': cannot connect",
    )
    assert not (tmp_path / "p").exists()
    # the study folder holds runs of B1; another configuration is refused, nothing touched
    other = b1_file_with(tmp_path, 'radial_load = "5000 N"', 'radial_load = "4000 N"')
    before = sorted((p.name, p.stat().st_mtime_ns) for p in out.rglob("*"))
    text = _refused(
        ["study", "paper", str(other), "--t-end", "2 ms", "-o", str(out)],
        f"-o {out}: holds runs of another configuration",
        "operating.radial_load: 5000.0 -> 4000.0",
    )
    assert len(text.strip().splitlines()) == 1
    assert sorted((p.name, p.stat().st_mtime_ns) for p in out.rglob("*")) == before


def test_map_ramp_is_refused_without_short_ramps(tmp_path):
    # --ramp only shapes the short ramps; with the default start (equilibrium) it would be
    # ignored, so it is refused naming the start; with --start short-ramps it is read (a
    # bad one refused as such)
    _refused(
        ["study", "map", str(B1), "--speed", "500", "--ramp", "10 ms"]
        + ["-o", str(tmp_path / "m")],
        "--ramp 10 ms: sets the short ramps of --start short-ramps",
        "--start equilibrium",
    )
    _refused(
        ["study", "map", str(B1), "--speed", "500", "--start", "short-ramps", "--ramp", "-1"]
        + ["-o", str(tmp_path / "m")],
        "--ramp",
    )
    assert not (tmp_path / "m").exists()


def test_map_whose_point_files_would_be_too_large_is_refused_before_any_run(tmp_path):
    # 100 s at 3000 rpm: W = 10 ms, an output every 0.1 ms, 1e6 outputs of about 6.6 kB
    # (B1's result per output) would exceed simulation.MAX_RESULT_BYTES = 2 GB; the map
    # refuses at planning, naming its own options (not solver.output_interval, which the
    # map sets), and creates no folder
    _refused(
        ["study", "map", str(B1), "--speed", "3000", "--axial-load", "1000"]
        + ["--max-time", "100 s", "-o", str(tmp_path / "m")],
        "--max-time = 100 s: too long for point 0",
        "1e+06 outputs",
        "choose a longer --window or a shorter --max-time",
    )
    # the configuration's own finer interval is kept, and then it is what the line names
    fine = b1_file_with(tmp_path, 'output_interval = "1e-3 s"', 'output_interval = "1 us"')
    _refused(
        ["study", "map", str(fine), "--speed", "3000", "--axial-load", "1000"]
        + ["--max-time", "1 s", "-o", str(tmp_path / "m")],
        "1e+06 outputs (one every 1e-06 s: the configuration's solver.output_interval)",
        "choose a solver.output_interval of up to 0.0001 s or a shorter --max-time",
    )
    assert not (tmp_path / "m").exists()


def test_cli_study_paper_short_version_and_its_rerun(tmp_path, client):
    address = client.scheduler_info()["address"]
    args = [
        "study",
        "paper",
        str(B1),
        "-o",
        str(tmp_path / "s"),
        "--t-end",
        "1 ms",
        "--loads",
        "1000",
        "--dt-max",
        "none",
        "--no-free-tilt",
        "--no-gradient",
        "--no-distributed",
        "--scheduler",
        address,
    ]
    first = RUNNER.invoke(app, args)
    assert first.exit_code == 0, first.output
    assert "study paper: 1 run, 0 already done, 1 to run" in first.output
    assert "axial-1000N completed; 1 of 1 done" in first.output
    assert "NOT RUN" in first.output and "report.html" in first.output
    second = RUNNER.invoke(app, args)
    assert second.exit_code == 0, second.output
    assert "nothing to run: every run was already in the folder" in second.output
    # --no-run on a folder without the runs: it says so, and claims no runs it does not hold
    empty = [*args[:4], str(tmp_path / "empty"), *args[5:], "--no-run"]
    none = RUNNER.invoke(app, empty)
    assert none.exit_code == 0, none.output
    assert "no run was run: 0 of the 1 runs are in the folder" in none.output
    assert "every run was already in the folder" not in none.output


def test_cli_help_explains_units_and_defaults():
    paper_help = RUNNER.invoke(app, ["study", "paper", "--help"]).output
    for text in (
        "--t-end",
        "--max-wall",
        "[s]",
        "in N",
        "default: results/study",
        "1.288 s",
        "0,500,1000,2000",
        "--scheduler",
        "Exit status",
    ):
        assert text in paper_help, text
    map_help = RUNNER.invoke(app, ["study", "map", "--help"]).output
    for text in ("rpm", "in N", "--tol", "N*m", "default: results/map", "0.02", "a:b:n"):
        assert text in map_help, text
    # a point starts from equilibrium unless told otherwise, from the command line and from
    # Python alike (docs/study.md: about half the wall time of short ramps when loaded)
    assert "[default: equilibrium]" in " ".join(map_help.split())
    import inspect

    assert inspect.signature(operating_map).parameters["start"].default == "equilibrium"


def test_no_study_file_is_over_700_lines():
    root = Path(__file__).resolve().parents[1] / "python" / "rollerdyn"
    for path in [*(root / "study").glob("*.py"), root / "cli" / "study.py"]:
        assert len(path.read_text(encoding="utf-8").splitlines()) <= 700, path
    assert os.path.basename(B1) == "b1.toml"


def test_a_run_the_study_stopped_is_marked_in_the_figures_legends():
    """plots' legend entry of a run capped by the study says how far it got (docs/study.md:
    runs that did not finish are marked in every legend)."""
    from rollerdyn.plots import _label

    ds = xr.Dataset(
        {
            "axial_load": ("time", np.array([0.0, 2000.0])),
            "ring_tilt": (("time", "axis"), np.zeros((2, 2))),
        },
        attrs={"final_time_s": 0.503},
    )
    assert _label(ds, "axial-2000N") == "axial-2000N (F_a = 2000 N)"
    ds.attrs["study_stopped"] = "stopped after 600 s of wall time"
    assert _label(ds, "axial-2000N").endswith("[not finished, to t = 0.503 s]")


def test_timing_counts_a_run_refused_at_its_start_as_costing_nothing():
    """The study of 2026-11-26 printed "whose own times sum to nan s": B1 at 2000 N with the
    point law is refused before its first step (docs/dynamics.md) and has no wall time. The
    sum is over the runs that have one, and the efficiency is sum / (wall x workers)."""
    from rollerdyn.study.schedule import timing

    records = {
        "a": {"action": "ran", "attempt wall [s]": 30.0},
        "b": {"action": "ran", "attempt wall [s]": math.nan},
        "c": {"action": "continued", "attempt wall [s]": 10.0},
        "d": {"action": "reused", "attempt wall [s]": 99.0},
    }
    t = timing(records, wall=25.0, workers=2)
    assert t["runs run"] == 3
    assert t["sum of run walls [s]"] == 40.0
    assert t["parallel efficiency"] == pytest.approx(40.0 / 50.0)


@pytest.mark.parametrize(
    ("signame", "status", "said"),
    [("SIGTERM", 143, "terminated (SIGTERM)"), ("SIGINT", 130, "interrupted")],
)
def test_sigterm_stops_a_study_as_ctrl_c_does(tmp_path, signame, status, said):
    # SIGTERM to the command alone (`kill`, `timeout`, a batch system) ended it at once
    # with no line, left its lock and lost the runs in flight; now it stops as after
    # Ctrl-C: the workers closed, each run's file as far as it got, exit status 143. Ctrl-C
    # said only "rollerdyn: interrupted"; now the same line as SIGTERM's (a review)
    import signal
    import subprocess
    import sys
    import time

    command = Path(sys.executable).parent / "rollerdyn"
    args = [str(command), "study", "paper", str(B1), "--t-end", "0.3", "-o", str(tmp_path / "st")]
    args += ["--no-distributed", "--loads", "none", "--no-free-tilt", "--dt-max", "none"]
    proc = subprocess.Popen(
        args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True
    )
    lines = []
    for line in proc.stdout:  # until the runs have started and passed a checkpoint
        lines.append(line)
        if "steps" in line and " 0 steps" not in line:
            break
    time.sleep(3.0)
    proc.send_signal(getattr(signal, signame))
    # the stop closes the Dask workers and writes each run's file: a few seconds alone;
    # the bound leaves room for a machine busy with another run, and a hang still fails
    out, _ = proc.communicate(timeout=240)
    out = "".join(lines) + out
    assert proc.returncode == status, out
    last = out.strip().splitlines()[-1]
    assert last.startswith(f"rollerdyn study: {said};") and "keeps the runs" in last, out
    for noise in ("Traceback", "Exception ignored"):
        assert noise not in out, out
    assert list((tmp_path / "st" / "runs").glob("*.nc")), out
    assert not (tmp_path / "st" / ".study.lock").exists()


def test_the_papers_loads_and_steps_take_units_as_the_map_does():
    """``study paper --loads`` and ``--dt-max`` take bare numbers in N and s, or values
    with their own unit ("0.5 kN", "1 ms"), as ``study map`` takes its loads (the
    adversarial review: "500 N" was refused there); a wrong kind of unit is refused naming
    the option."""
    import typer

    from rollerdyn.cli.study import _numbers

    assert _numbers("0, 0.5 kN,1000 N", "--loads", "N") == [0.0, 500.0, 1000.0]
    assert _numbers("1 ms,2e-3", "--dt-max", "s") == [1e-3, 2e-3]
    assert _numbers("none", "--loads", "N") == []
    with pytest.raises(typer.Exit):
        _numbers("5 kg", "--loads", "N")


def test_a_long_failure_is_cut_in_the_printed_table(capfd):
    # a failed map point's reason (about 900 characters) made a status cell 70 lines tall
    # in the printed table (a review); the CSV keeps it whole
    from rollerdyn.cli.study_tables import LONGEST_STATUS, _shortened

    reason = "failed: " + "the point law " * 70
    cut = _shortened(reason)
    assert cut.startswith(reason[:200]) and cut.endswith("… (whole in the folder's CSV table)")
    assert len(cut) < LONGEST_STATUS + 40
    assert _shortened("steady") == "steady"
    # the map's marks follow the cut reason, not cut with it (a review)
    import pandas as pd

    from rollerdyn.cli.study_tables import print_map
    from rollerdyn.simulation import FORCED_MARK
    from rollerdyn.study.maps import FALLBACK, MAP_COLUMNS

    row = {column: 1.0 for column, _, _ in MAP_COLUMNS}
    row |= {"status": "failed", "note": reason + FORCED_MARK, "start": f"{FALLBACK} (x)"}
    capfd.readouterr()
    print_map(pd.DataFrame([row]), "map")
    shown = "".join(capfd.readouterr().out.replace("│", "").split())
    assert "(fromshortramps:noequilibrium)" in shown
    assert "(--force:pastthepointlaw'sloadcheck)" in shown
