"""Files written safely and result files read carefully (the adversarial CLI review, items
2-9 and 11): an output is written through a temporary file and renamed into place, so a
failed write leaves an earlier file as it was and a file another program created meanwhile
is kept; odd inputs and outputs (a name that is not UTF-8, a damaged HDF5 file, a symbolic
link loop, a name part over 255 bytes, an attribute that is no number) get one line and
status 2, never a traceback.

The result files are those of a 2 ms B1 run (about 3 s); the write failures are simulated
by making the writer raise (no disk is filled).
"""

from __future__ import annotations

import errno
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from b1 import B1
from typer.testing import CliRunner

from rollerdyn import paths
from rollerdyn.cli import app
from rollerdyn.report import ReportError, open_result

RUNNER = CliRunner()

#: A file name whose bytes are not UTF-8 (printf 'run\xe9.nc'), as Python keeps it.
NOT_UTF8 = os.fsdecode(b"run\xe9.nc")


def invoke(*args: str):
    return RUNNER.invoke(app, [str(a) for a in args])


def one_line(res) -> str:
    """The output of a refused command, checked to be one line without a traceback."""
    text = res.output.strip()
    assert "Traceback" not in text and "Exception ignored" not in text, text
    assert len(text.splitlines()) == 1, text
    return text


@pytest.fixture(scope="module")
def result(tmp_path_factory) -> Path:
    """A 2 ms B1 run's result."""
    path = tmp_path_factory.mktemp("run") / "r.nc"
    res = invoke("run", B1, "-o", path, "--t-end", "0.002")
    assert res.exit_code == 0, res.output
    return path


@pytest.fixture(scope="module")
def damaged(result, tmp_path_factory) -> Path:
    """``result`` with its root group's HDF5 object header damaged (its version byte): h5py
    opens the file, h5netcdf then fails half-way (what a write on a full disk left)."""
    data = bytearray(result.read_bytes())
    assert data[8] == 0  # superblock version 0: the root's object header address at 64
    header = int.from_bytes(data[64:72], "little")
    assert data[header : header + 4] == b"OHDR"
    data[header + 4] = 7
    path = tmp_path_factory.mktemp("damaged") / "damaged.nc"
    path.write_bytes(bytes(data))
    return path


# --------------------------------------------------------------------------- paths


def test_a_failed_atomic_write_leaves_the_earlier_file_and_no_temporary(tmp_path, monkeypatch):
    target = tmp_path / "out.nc"
    target.write_bytes(b"earlier")

    def full(_fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(paths.os, "fsync", full)
    with pytest.raises(OSError, match="No space"):
        paths.write_atomically(target, b"new result", replace=True)
    assert target.read_bytes() == b"earlier"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc"]


def test_a_file_created_meanwhile_is_kept_and_the_new_one_goes_to_a_free_name(tmp_path):
    target = tmp_path / "s.nc"
    assert paths.write_atomically(target, b"first") == target
    (tmp_path / "s-2.nc").write_bytes(b"someone else's")
    written = paths.write_atomically(target, b"second")
    assert written == tmp_path / "s-3.nc" and written.read_bytes() == b"second"
    assert target.read_bytes() == b"first"
    assert paths.write_atomically(target, b"third", replace=True) == target
    assert target.read_bytes() == b"third"
    # asked at the rename: replaced only if the file there may be
    assert paths.write_atomically(target, b"fourth", replace=lambda p: False) != target
    assert paths.write_atomically(target, b"fifth", replace=lambda p: True) == target
    assert target.read_bytes() == b"fifth"
    assert not [p for p in tmp_path.iterdir() if ".tmp" in p.name]


def test_long_names_symbolic_link_loops_and_the_probe(tmp_path):
    loop = tmp_path / "loop1.nc"
    loop.symlink_to(tmp_path / "loop2.nc")
    (tmp_path / "loop2.nc").symlink_to(loop)
    assert "symbolic link loop" in paths.name_problem(loop)
    assert paths.same_file(loop, loop) and not paths.same_file(loop, tmp_path / "x")
    long = tmp_path / ("b" * 300 + ".nc")
    assert "303 bytes" in paths.name_problem(long)
    assert not paths.same_file(long, tmp_path / "x")
    for check in (paths.check_output_file, paths.check_output_dir):
        with pytest.raises(paths.OutputPathError, match="symbolic link loop"):
            check(loop, "-o")
        with pytest.raises(paths.OutputPathError, match="at most 255 bytes"):
            check(long, "-o")
    # a valid name of 250 bytes: the probe's own name is short
    valid = tmp_path / ("c" * 247 + ".nc")
    assert paths.check_output_file(valid, "-o", reserve=0) == valid
    # ... but no room for run's NAME.tmp<pid>: refused before the work, saying why
    with pytest.raises(paths.OutputPathError, match="it may be at most"):
        paths.check_output_file(valid, "-o")
    assert paths.write_atomically(valid, b"x") == valid and valid.read_bytes() == b"x"
    assert not [p for p in tmp_path.iterdir() if "tmp" in p.name or "probe" in p.name]


# --------------------------------------------------------------------------- statics -o


def test_statics_keeps_the_earlier_file_and_the_new_result_when_the_write_fails(
    tmp_path, monkeypatch
):
    """Defect 2: the write failed (a full disk, a reader's lock): one line, status 1, the
    earlier file unchanged and the computed result kept in the temporary folder."""
    out = tmp_path / "s.nc"
    assert invoke("statics", B1, "-o", out).exit_code == 0
    earlier = out.read_bytes()
    keep = tmp_path / "keep"
    keep.mkdir()
    monkeypatch.setattr("tempfile.tempdir", str(keep))

    def full(*_args, **_kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(paths, "write_atomically", full)
    res = invoke("statics", B1, "-o", out, "--overwrite", "--set", "operating.radial_load=2000")
    assert res.exit_code == 1, res.output
    line = res.output.strip().splitlines()[-1]
    assert line.startswith(f"-o {out}: could not write the result (No space left on device")
    assert "the earlier file is unchanged" in line and str(keep) in line
    assert out.read_bytes() == earlier
    (kept,) = keep.glob("rollerdyn-statics-*.nc")
    kept_ds = xr.open_dataset(kept, engine="h5netcdf").load()
    assert float(kept_ds.radial_load_applied) == pytest.approx(2000.0)


def test_statics_survives_an_hdf5_runtime_error(tmp_path, monkeypatch):
    out = tmp_path / "s.nc"
    out.write_bytes(b"\x89HDF\r\n\x1a\n earlier")

    def broken(*_args, **_kwargs):
        raise RuntimeError("Can't decrement id ref count (file write failed)")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", broken)
    res = invoke("statics", B1, "-o", out, "--overwrite")
    assert res.exit_code == 1, res.output
    assert "Traceback" not in res.output
    assert "could not write the result (it cannot be encoded as netCDF" in res.output
    assert out.read_bytes() == b"\x89HDF\r\n\x1a\n earlier"


def test_statics_keeps_a_file_another_program_created_meanwhile(tmp_path, monkeypatch):
    """Defect 3: the output did not exist at the start and appeared during the work (a
    second command writing it): kept, the result written beside it, said in one line."""
    import rollerdyn.cli.statics as cli_statics

    out = tmp_path / "st.nc"
    original = cli_statics._print_case

    def meanwhile(ds):
        out.write_text("another program's")
        original(ds)

    monkeypatch.setattr(cli_statics, "_print_case", meanwhile)
    res = invoke("statics", B1, "-o", out)
    assert res.exit_code == 0, res.output
    assert f"wrote {tmp_path / 'st-2.nc'}: {out} was created by another program" in res.output
    assert out.read_text() == "another program's"
    assert "inner_race_load" in xr.open_dataset(tmp_path / "st-2.nc", engine="h5netcdf")


@pytest.mark.parametrize(
    ("when", "name"),
    [
        ("before the first checkpoint", "r"),
        ("after a checkpoint", "r"),
        ("after a checkpoint", "e" * 251),  # 254 bytes: NAME-2.nc shortens the stem
    ],
)
def test_run_keeps_a_file_another_program_wrote_during_the_run(tmp_path, monkeypatch, when, name):
    """``rollerdyn run -o``: the output did not exist when the command checked it, and
    another program wrote it during the run, before the run's first checkpoint or over
    one of them: its file is kept, the run's checkpoints and result go to ``NAME-2.nc``
    (said in one line as it happens), which holds the whole run; for a name of 254 bytes
    the stem is shortened so that the new name fits in 255."""
    from rollerdyn import simulation

    out = tmp_path / f"{name}.nc"
    original = simulation.simulate

    def meanwhile(*args, checkpoint=None, **kwargs):
        if when == "before the first checkpoint":
            out.write_text("another program's")
            return original(*args, checkpoint=checkpoint, **kwargs)

        def foreign_after_first(partial):
            checkpoint(partial)
            if not out.read_bytes().startswith(b"another"):
                out.write_text("another program's")

        return original(*args, checkpoint=foreign_after_first, **kwargs)

    monkeypatch.setattr(simulation, "simulate", meanwhile)
    res = invoke("run", B1, "-o", out, "--t-end", "0.002", "--checkpoint-interval", "0.5 ms")
    assert res.exit_code == 0, res.output
    moved = tmp_path / f"{name[: 255 - len('-2.nc')]}-2.nc"
    said = (
        f"-o {out}: another program put a file there during the run; it is kept, and this "
        f"run's checkpoints and result go to {moved}"
    )
    assert said in " ".join(res.output.split()), res.output
    assert out.read_text() == "another program's"
    with xr.open_dataset(moved, engine="h5netcdf") as ds:
        assert float(ds.attrs["final_time_s"]) == pytest.approx(0.002)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([moved.name, out.name])


def test_run_replaces_its_own_checkpoints_and_an_allowed_file(tmp_path):
    """The run's checkpoints (every 0.5 ms, each written: --save-interval 0) replace each
    other, and --overwrite replaces a file that was there at the start: one file, the
    whole run, nothing beside it."""
    out = tmp_path / "r.nc"
    out.write_text("an earlier file")
    res = invoke(
        "run", B1, "-o", out, "--t-end", "0.002", "--checkpoint-interval", "0.5 ms",
        "--save-interval", "0", "--overwrite",
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    assert "another program" not in res.output
    assert [p.name for p in tmp_path.iterdir()] == ["r.nc"]
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert float(ds.attrs["final_time_s"]) == pytest.approx(0.002)


# --------------------------------------------------------------------------- report, plot


def test_report_keeps_the_earlier_page_when_the_write_fails(result, tmp_path, monkeypatch):
    """Defect 4: the page is written through a temporary file."""
    page = tmp_path / "rep.html"
    assert invoke("report", result, "-o", page).exit_code == 0
    earlier = page.read_bytes()

    def full(_fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(paths.os, "fsync", full)
    res = invoke("report", result, "-o", page)
    assert res.exit_code == 1, res.output
    assert one_line(res) == (
        f"-o {page}: could not write the report (No space left on device); an earlier "
        "report there is unchanged"
    )
    assert page.read_bytes() == earlier
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rep.html"]


def test_report_and_plot_take_a_file_name_that_is_not_utf8(result, tmp_path):
    """Defect 5: the legends and the page show the byte as \\xe9."""
    odd = tmp_path / NOT_UTF8
    shutil.copyfile(result, odd)
    page = tmp_path / "u.html"
    res = invoke("report", result, odd, "-o", page)
    assert res.exit_code == 0, res.output
    assert "run\\xe9 (F_a = 1000 N)" in page.read_text(encoding="utf-8")
    res = invoke("plot", odd, "-o", tmp_path / "figures")
    assert res.exit_code == 0, res.output
    assert (tmp_path / "figures" / "fig10_frictional_torque.svg").is_file()


def test_plot_refuses_an_image_name_and_an_empty_folder(result, tmp_path, monkeypatch):
    """Defect 11: -o torque.png made a folder torque.png; -o "" wrote into the current
    folder (an unset variable)."""
    monkeypatch.chdir(tmp_path)
    res = invoke("plot", result, "-o", "torque.png")
    assert res.exit_code == 2 and "names an image file" in one_line(res)
    res = invoke("plot", result, "-o", "")
    assert res.exit_code == 2 and one_line(res).startswith("-o '': empty")
    res = invoke("bench", "mbs", "--sweep-dt-max", "1e-4", "-o", "")
    assert res.exit_code == 2 and one_line(res).startswith("-o '': empty")
    assert list(tmp_path.iterdir()) == []


def test_a_failed_figure_leaves_the_earlier_one(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rollerdyn.plots import save_figure

    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    first = save_figure(fig, tmp_path, "f")
    assert [p.name for p in first] == ["f.png", "f.svg"]
    earlier = (tmp_path / "f.png").read_bytes()

    def full(_fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(paths.os, "fsync", full)
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    with pytest.raises(OSError):
        save_figure(fig, tmp_path, "f")
    assert (tmp_path / "f.png").read_bytes() == earlier
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.png", "f.svg"]


# --------------------------------------------------------------------------- odd inputs


def test_a_damaged_hdf5_file_gives_one_line_without_the_destructors_traceback(damaged):
    """Defect 6, in a process of its own: the half-made h5netcdf file's destructor printed
    "Exception ignored in: File.close ... AttributeError" after the refusal."""
    for args in (["modes", damaged], ["report", damaged, "-o", damaged.with_suffix(".html")]):
        done = subprocess.run(
            [sys.executable, "-m", "rollerdyn.cli", *map(str, args)],
            capture_output=True,
            text=True,
            timeout=120,
        )
        text = (done.stdout + done.stderr).strip()
        assert done.returncode == 2, text
        assert text.splitlines() == [
            f"{damaged}: not a rollerdyn result (cannot be read as netCDF: 'Unable to "
            "synchronously open object (bad object header version number)')"
        ]


def test_symbolic_link_loops_are_refused_in_one_line_before_the_work(result, tmp_path):
    """Defect 7."""
    loop = tmp_path / "loop1.nc"
    loop.symlink_to(tmp_path / "loop2.nc")
    (tmp_path / "loop2.nc").symlink_to(loop)
    image = tmp_path / "loop1.png"
    image.symlink_to(tmp_path / "loop2.png")
    (tmp_path / "loop2.png").symlink_to(image)
    for args, shown in (
        (["report", loop, "-o", tmp_path / "m.html"], f"{loop}: cannot be read"),
        (["report", result, "-o", loop], f"-o {loop}: is a symbolic link loop"),
        (["plot", result, "-o", loop], f"-o {loop}: is a symbolic link loop"),
        (["modes", loop], f"{loop}: cannot be read"),
        (["statics", B1, "-o", loop], f"-o {loop}: is a symbolic link loop"),
        (["statics", B1, "--plot", image], f"--plot {image}: is a symbolic link loop"),
        (["run", B1, "--t-end", "1ms", "-o", loop], f"-o {loop}: is a symbolic link loop"),
    ):
        res = invoke(*args)
        assert res.exit_code == 2, (args, res.output)
        line = one_line(res)
        assert line.startswith(shown) and "symbolic link loop" in line, line
    assert not (tmp_path / "m.html").exists()


def test_name_parts_over_255_bytes_and_valid_long_names(result, tmp_path):
    """Defect 8: refused in one line as input and as output; a valid name of 250 bytes
    is written (the probe no longer lengthens it)."""
    long = tmp_path / ("b" * 300 + ".nc")
    for args in (
        ["modes", long],
        ["plot", long, "-o", tmp_path / "p"],
        ["compare", result, long],
        ["report", long, "-o", tmp_path / "m.html"],
        ["report", result, "-o", long.with_suffix(".html")],
        ["plot", result, "-o", long.with_suffix("")],
        ["statics", B1, "-o", long],
        ["statics", B1, "--plot", long.with_suffix(".png")],
    ):
        res = invoke(*args)
        assert res.exit_code == 2, (args, res.output)
        assert "a file system takes at most 255 bytes" in one_line(res)
    page = tmp_path / ("c" * 245 + ".html")
    res = invoke("report", result, "-o", page)
    assert res.exit_code == 0, res.output
    assert page.is_file()
    statics = tmp_path / ("d" * 247 + ".nc")
    res = invoke("statics", B1, "-o", statics)
    assert res.exit_code == 0, res.output
    assert statics.is_file()
    run = tmp_path / ("e" * 250 + ".nc")  # no room for NAME.tmp<pid>: a short one is taken
    res = invoke("run", B1, "-o", run, "--t-end", "0.0005")
    assert res.exit_code == 0, res.output
    assert run.is_file() and not list(tmp_path.glob(".rollerdyn.tmp*"))


@pytest.mark.parametrize(
    ("name", "value", "said"),
    [
        ("completed", "abc", "attribute completed = 'abc' is not a number"),
        ("final_time_s", "abc", "attribute final_time_s = 'abc' is not a number"),
        ("stats_steps", "abc", "attribute stats_steps = 'abc' is not a number"),
        ("stats_total_seconds", "abc", "attribute stats_total_seconds = 'abc' is not a number"),
        ("stats_error_test_failures", "x", "stats_error_test_failures = 'x' is not a number"),
        ("final_time_s", np.nan, "attribute final_time_s = nan is not a finite number"),
        ("stats_steps", np.array([1, 2]), "attribute stats_steps = [1, 2] is not a number"),
    ],
)
def test_attributes_that_are_no_numbers_are_refused(result, tmp_path, name, value, said):
    """Defect 9: report, bench model --state and run --resume crashed on them."""
    ds = xr.open_dataset(result, engine="h5netcdf").load()
    ds.attrs[name] = value
    bad = tmp_path / f"{name}.nc"
    ds.to_netcdf(bad, engine="h5netcdf")
    with pytest.raises(ReportError, match="not a rollerdyn result"):
        open_result(bad)
    for args, prefix in (
        (["report", bad, "-o", tmp_path / "m.html"], ""),
        (["bench", "model", "--state", bad], "--state "),
        (["run", B1, "-o", tmp_path / "z.nc", "--resume", bad, "--t-end", "5ms"], "--resume "),
    ):
        res = invoke(*args)
        assert res.exit_code == 2, (args, res.output)
        line = one_line(res)
        assert line.startswith(f"{prefix}{bad}: not a rollerdyn result") and said in line, line


def test_a_damaged_chunk_of_a_compressed_array_is_refused(tmp_path):
    """The arrays a result compresses (64 kB or more) carry HDF5's Fletcher-32 checksum per
    chunk: bytes changed inside the data (a flipped byte read as 6.3e268 N*m before) make
    reading the file fail, which `report` and the rest refuse in one line naming it; the
    file as written reads back bit for bit."""
    import h5py

    from rollerdyn.simulation import COMPRESS_FROM, write

    n = COMPRESS_FROM // 8 * 4
    torque = np.linspace(0.0, 0.3, n)
    ds = xr.Dataset({"frictional_torque": ("time", torque)}, coords={"time": np.arange(n) * 1e-6})
    path = tmp_path / "big.nc"
    write(ds, path)
    with h5py.File(path, "r") as f:
        assert f["frictional_torque"].fletcher32
        offset = f["frictional_torque"].id.get_chunk_info(1).byte_offset
    with xr.open_dataset(path, engine="h5netcdf") as back:
        np.testing.assert_array_equal(back["frictional_torque"].values, torque)
    data = bytearray(path.read_bytes())
    data[offset + 100] ^= 0xFF
    damaged = tmp_path / "damaged.nc"
    damaged.write_bytes(bytes(data))
    with pytest.raises(ReportError, match=r"damaged.nc: not a rollerdyn result \(cannot be read"):
        open_result(damaged)
    out = invoke("report", damaged, "-o", tmp_path / "r.html")
    assert out.exit_code == 2 and "filter returned failure" in one_line(out)
