"""Study and sweep folders replace or remove only what rollerdyn wrote there.

Found by two adversarial reviews: ``study paper``/``study map -o DIR`` wrote over a user's
``report.html`` and ``runs.csv`` in a folder without ``study.json``, and with
``--overwrite`` first deleted the user's report, runs and figures and then refused anyway;
a ``study.json`` holding ``[1,2,3]`` gave a traceback; ``rollerdyn.sweep`` deleted any
``run_NNNN.nc`` and ``summary.*`` in its folder; ``rollerdyn.study.paper`` became a module
after a call of ``operating_map``; some arguments of the studies and the sweep were
accepted as true or failed with bare exceptions. Every test checks that the user's files
survive and that the refusal names what it refuses. Nothing here runs a simulation: the
studies run with ``run=False`` (``--no-run``), and the sweeps are refused before their
cluster starts.
"""

from __future__ import annotations

import json
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from b1 import B1, changed_b1
from typer.testing import CliRunner

import rollerdyn
from rollerdyn.cli import app
from rollerdyn.study import StudyError, operating_map
from rollerdyn.sweep import SweepError

RUNNER = CliRunner()

#: The smallest paper study: one run planned (B1 to 1 ms), none run.
PAPER = {
    "t_end": "1 ms",
    "loads": (),
    "dt_max": (),
    "free_tilt": False,
    "gradient": False,
    "distributed": False,
    "tight": False,
    "workers": 1,
    "run": False,
}
PAPER_CLI = [
    *("study", "paper", str(B1), "--t-end", "1 ms", "--loads", "none", "--dt-max", "none"),
    *("--no-gradient", "--no-tight", "--no-distributed", "--no-free-tilt", "--workers", "1"),
    "--no-run",
]
SWEEP_CLI = ["sweep", str(B1), "--set", "operating.axial_load=0 N", "--t-end", "1 ms"]
SHORT_DATA = changed_b1({})  # B1 as data; no run starts here


def _files(folder: Path) -> dict[str, bytes]:
    """Every file under ``folder`` and its bytes."""
    return {
        p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*") if p.is_file()
    }


def _refused(args: list, *needles: str) -> str:
    """The command's one line of refusal (exit status 2, no traceback), holding ``needles``."""
    result = RUNNER.invoke(app, [str(a) for a in args])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output, result.output
    assert len(result.output.strip().splitlines()) == 1, result.output
    for needle in needles:
        assert needle in " ".join(result.output.split()), (needle, result.output)
    return result.output


def _user_folder(folder: Path) -> dict[str, bytes]:
    """A folder of another program's files of the names a study writes (no study.json)."""
    (folder / "figures").mkdir(parents=True)
    (folder / "runs").mkdir()
    (folder / "report.html").write_text("<html>my report</html>")
    (folder / "runs.csv").write_text("my,data\n")
    (folder / "figures" / "my_fig.png").write_bytes(b"my figure")
    (folder / "runs" / "my_other_run.nc").write_bytes(b"my run")
    return _files(folder)


# --------------------------------------------------------------------------- study folders


@pytest.mark.parametrize("overwrite", [False, True])
def test_study_refuses_a_folder_of_other_files_and_removes_nothing(tmp_path, overwrite):
    # without --overwrite the study wrote over report.html and runs.csv; with it, it first
    # deleted them (and the runs and figures) and then refused, suggesting --overwrite
    folder = tmp_path / "mine"
    before = _user_folder(folder)
    text = _refused(
        [*PAPER_CLI, "-o", folder, *(["--overwrite"] if overwrite else [])],
        f"-o {folder}: holds report.html",
        "but no study.json",
    )
    assert "or --overwrite" not in text
    assert _files(folder) == before
    with pytest.raises(StudyError, match="holds report.html, runs.csv, runs/my_other_run.nc, ..."):
        rollerdyn.study.paper(B1, folder, overwrite=overwrite, **PAPER)
    with pytest.raises(StudyError, match="but no study.json"):
        operating_map(B1, folder, speed="3000", overwrite=overwrite)
    assert _files(folder) == before


@pytest.mark.parametrize(
    ("manifest", "said"),
    [
        ("[1,2,3]", "it holds a JSON list"),
        ("null", "it holds a JSON NoneType"),
        ('"paper"', "it holds a JSON str"),
        ('{"study": 5}', "study = 5"),
        ('{"study": "paper", "files": "report.html"}', "'files' is not a JSON list"),
        ('{"study": "paper", "settings": []}', "'settings' is not a JSON dict"),
        ("{broken", "Expecting property name"),
    ],
)
def test_a_manifest_that_is_not_a_studys_is_refused_in_one_line(tmp_path, manifest, said):
    # [1,2,3] gave "AttributeError: 'list' object has no attribute 'get'"
    folder = tmp_path / "s"
    _user_folder(folder)
    (folder / "study.json").write_text(manifest)
    before = _files(folder)
    for overwrite in ([], ["--overwrite"]):
        _refused([*PAPER_CLI, "-o", folder, *overwrite], "study.json cannot be read", said)
    with pytest.raises(StudyError, match="its study.json cannot be read"):
        rollerdyn.study.paper(B1, folder, overwrite=True, **PAPER)
    assert _files(folder) == before


def test_overwrite_removes_only_what_the_manifest_lists(tmp_path):
    folder = tmp_path / "s"
    rollerdyn.study.paper(B1, folder, **PAPER)
    manifest = json.loads((folder / "study.json").read_text())
    assert {"report.html", "runs.csv", "findings.csv", "runs/axial-1000N.nc"} <= set(
        manifest["files"]
    )
    # the user's files beside the study's, and a manifest edited to list some of them
    (folder / "figures").mkdir()
    mine = {
        "my_notes.txt": b"notes",
        "my_run.nc": b"a run",
        "runs/my_other_run.nc": b"another run",
        "figures/my_fig.png": b"a figure",
    }
    for name, data in mine.items():
        (folder / name).write_bytes(data)
    (tmp_path / "outside.txt").write_text("outside")
    manifest["files"] += ["../outside.txt", "my_notes.txt", str(tmp_path / "outside.txt")]
    (folder / "study.json").write_text(json.dumps(manifest))
    (folder / "runs" / "axial-1000N.nc").write_bytes(b"the study's run")  # listed
    rollerdyn.study.paper(B1, folder, overwrite=True, **PAPER)
    assert not (folder / "runs" / "axial-1000N.nc").exists()  # listed: removed
    assert (folder / "report.html").is_file()  # written again
    assert {n: (folder / n).read_bytes() for n in mine} == mine
    assert (tmp_path / "outside.txt").read_text() == "outside"
    # a file this study writes that the manifest does not list: refused, nothing removed
    manifest = json.loads((folder / "study.json").read_text())
    manifest["files"].remove("runs.csv")
    (folder / "study.json").write_text(json.dumps(manifest))
    before = _files(folder)
    _refused(
        [*PAPER_CLI, "-o", folder, "--overwrite"],
        "holds runs.csv, which its study.json does not list",
        "--overwrite removes only the files listed there",
    )
    assert _files(folder) == before
    # a manifest of an earlier version (no list): the files of the kinds a study writes
    del manifest["files"]
    (folder / "study.json").write_text(json.dumps(manifest))
    rollerdyn.study.paper(B1, folder, overwrite=True, **PAPER)
    assert (folder / "my_notes.txt").read_bytes() == b"notes"
    assert (folder / "my_run.nc").read_bytes() == b"a run"


def test_study_functions_stay_functions_after_their_modules_are_imported():
    # operating_map imports .paper in its body, which bound the module rollerdyn.study.paper
    # over the function: "TypeError: 'module' object is not callable"
    code = (
        "import types, rollerdyn\n"
        "try:\n"
        "    rollerdyn.study.operating_map('examples/b1.toml', 'm', speed=float('nan'))\n"
        "except rollerdyn.study.StudyError:\n"
        "    pass\n"
        "import rollerdyn.study.paper, rollerdyn.study.maps\n"
        "from rollerdyn.study import paper\n"
        "s = rollerdyn.study\n"
        "print(all(isinstance(f, types.FunctionType) for f in "
        "(s.paper, s.operating_map, s.parse_range, paper)))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=B1.parents[1], capture_output=True, text=True
    )
    assert done.stdout.strip() == "True", done.stdout + done.stderr
    assert isinstance(rollerdyn.study.paper, types.FunctionType)
    assert isinstance(sys.modules["rollerdyn.study.paper"], types.ModuleType)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"loads": ["a"]}, r"--loads = \['a'\]: 'a' is not a number"),
        ({"loads": None}, "--loads = None: expected a list of axial loads in N"),
        ({"dt_max": ["x"]}, r"--dt-max = \['x'\]: 'x' is not a number"),
        ({"free_tilt": "no"}, "free_tilt = 'no': must be True or False"),
        ({"overwrite": "yes"}, "overwrite = 'yes': must be True or False"),
        ({"run": 1}, "run = 1: must be True or False"),
        ({"progress": 3}, "progress = 3: must be a function"),
    ],
)
def test_paper_arguments_are_refused_by_name_before_any_work(tmp_path, kwargs, match):
    folder = tmp_path / "s"
    rollerdyn.study.paper(B1, folder, **PAPER)
    (folder / "my_notes.txt").write_text("notes")
    before = _files(folder)
    with pytest.raises(StudyError, match=match):
        rollerdyn.study.paper(B1, folder, **{**PAPER, **kwargs})
    assert _files(folder) == before


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"speed": None}, "--speed None: give a:b:n"),
        ({"speed": b"3000"}, "--speed b'3000': give a:b:n"),
        ({"progress": 3}, "progress = 3: must be a function"),  # failed after the cluster
        ({"overwrite": "yes"}, "overwrite = 'yes': must be True or False"),
        ({"force": "yes"}, "force = 'yes': must be True or False"),
    ],
)
def test_map_arguments_are_refused_by_name_before_any_work(tmp_path, kwargs, match):
    folder = tmp_path / "m"
    _user_folder(folder)
    before = _files(folder)
    with pytest.raises(StudyError, match=match):
        operating_map(B1, folder, **{"speed": "3000", **kwargs})
    assert _files(folder) == before
    with pytest.raises(StudyError, match=match):
        operating_map(B1, tmp_path / "new", **{"speed": "3000", **kwargs})
    assert not (tmp_path / "new").exists()


# --------------------------------------------------------------------------- sweep folders


def _sweep_files(folder: Path) -> None:
    """An earlier sweep's files, as rollerdyn writes them (a result's attributes, the
    summary's columns), without running it."""
    import h5py

    folder.mkdir(parents=True, exist_ok=True)
    for name in ("run_0000.nc", "run_0001.nc"):
        with h5py.File(folder / name, "w") as f:
            f.attrs["final_time_s"] = 0.001
            f.attrs["rollerdyn_version"] = rollerdyn.__version__
    summary = {"run": [0, 1], "status": ["completed"] * 2, "error": [""] * 2}
    pd.DataFrame({**summary, "file": ["run_0000.nc", "run_0001.nc"]}).to_parquet(
        folder / "summary.parquet"
    )
    (folder / "summary.png").write_bytes(b"\x89PNG\r\n\x1a\n tEXtSoftware Matplotlib version")


@pytest.mark.parametrize(
    "foreign",
    [
        {"run_0042.nc": b"my own run_0042"},
        {"summary.png": b"my figure"},
        {"summary.parquet": b"my table"},
    ],
)
def test_sweep_replaces_only_an_earlier_sweeps_files(tmp_path, foreign):
    # rollerdyn.sweep() deleted every run_NNNN.nc and summary.* in outdir by name
    alone = tmp_path / "alone"  # the user's file only
    alone.mkdir()
    beside = tmp_path / "beside"  # beside an earlier sweep's own files
    _sweep_files(beside)
    name = next(iter(foreign))
    for folder in (alone, beside):
        for n, data in foreign.items():
            (folder / n).write_bytes(data)
        before = _files(folder)
        with pytest.raises(SweepError, match=r"holds earlier results .*pass overwrite=True"):
            rollerdyn.sweep(SHORT_DATA, {"operating.axial_load": ["0 N"]}, folder, workers=1)
        with pytest.raises(SweepError, match=f"{name} is not a file an earlier sweep wrote"):
            rollerdyn.sweep(
                SHORT_DATA, {"operating.axial_load": ["0 N"]}, folder, workers=1, overwrite=True
            )
        _refused(
            [*SWEEP_CLI, "-o", folder, "--overwrite"],
            f"-o {folder}: {name} is not a file an earlier sweep wrote",
            "--overwrite replaces only a sweep's own files",
        )
        assert _files(folder) == before


def test_sweep_arguments_are_refused_or_read_as_simulate_reads_them(tmp_path):
    folder = tmp_path / "s"
    _sweep_files(folder)
    before = _files(folder)
    grid = {"operating.axial_load": ["0 N"]}
    for config in (None, 5):  # a bare TypeError from pathlib
        with pytest.raises(SweepError, match=f"config = {config}: expected a TOML file's path"):
            rollerdyn.sweep(config, grid, folder, overwrite=True)
    with pytest.raises(SweepError, match="overwrite = 'yes': must be True or False"):
        rollerdyn.sweep(SHORT_DATA, grid, folder, overwrite="yes")
    with pytest.raises(SweepError, match="t_end = '5 kg': must be a time .*got a mass"):
        rollerdyn.sweep(SHORT_DATA, grid, folder, t_end="5 kg", overwrite=True)
    # "1 ms" and numpy's numbers are times, as in rollerdyn.simulate: the sweep goes as far
    # as its (unreachable) scheduler, which is refused before the folder is touched
    for t_end in ("1 ms", np.float32(1e-3)):
        with pytest.raises(SweepError, match="scheduler = 'tcp://127.0.0.1:1'"):
            rollerdyn.sweep(
                SHORT_DATA,
                grid,
                folder,
                t_end=t_end,
                scheduler="tcp://127.0.0.1:1",
                connect_timeout=2.0,
                overwrite=True,
            )
    assert _files(folder) == before


def test_a_rerun_removes_the_figures_of_its_earlier_plan_it_did_not_draw(tmp_path):
    """A paper study rerun with fewer runs left the earlier plan's figures (fig. 14, the
    tilt's, the distributed law's: 62 files, 20 of them written again) beside a report
    without them (a review). The figures the manifest lists and this study did not draw
    again are removed, with the figure folders left empty; nothing it does not list."""
    import json

    from rollerdyn.study.folder import replace_figures

    listed = ["figures/tilt/fig8.png", "figures/tilt/fig8.svg", "figures/fig9.png"]
    listed += ["figures/old/fig14.png", "runs/axial-0N.nc", "notes.txt"]
    for rel in [*listed, "figures/old/mine.png"]:
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("x")
    (tmp_path / "study.json").write_text(json.dumps({"kind": "paper", "files": listed}))
    replace_figures(tmp_path, [tmp_path / "figures" / "fig9.png"])
    left = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file())
    assert left == [
        "figures/fig9.png",
        "figures/old/mine.png",  # not the study's: kept, and so its folder
        "notes.txt",
        "runs/axial-0N.nc",
        "study.json",
    ]
    assert not (tmp_path / "figures" / "tilt").exists()
    files = json.loads((tmp_path / "study.json").read_text())["files"]
    assert files == ["figures/fig9.png", "notes.txt", "runs/axial-0N.nc"]


def test_another_grid_is_shown_with_the_digits_that_differ():
    """A map of 150 rad/s refused a rerun at 1432.39448783 rpm as "speeds 1432.39 rpm ...
    now speeds 1432.39 rpm" (a review): where six digits show no difference, all are."""
    import math

    from rollerdyn.study.folder import _grid_texts

    earlier = [[150.0], [5000.0], [0.0]]
    now = [[1432.39448783 * math.pi / 30], [5000.0], [0.0]]
    was, is_ = _grid_texts(earlier, now)
    assert was != is_ and was.startswith("speeds 1432.394487827") and "5000 N" in was
    was, is_ = _grid_texts([[100.0], [5000.0], [0.0]], now)
    assert (was, is_[:20]) == ("speeds 954.93 rpm, radial loads 5000 N, axial loads 0 N", is_[:20])
    assert is_.startswith("speeds 1432.39 rpm,")
