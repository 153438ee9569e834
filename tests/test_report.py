"""The HTML report (issue 5, item 2): `rollerdyn report` on a short real run, opened in a
real headless Chromium (Debian's `chromium`).

The run is a short rolling B1 variant (loads ramped over 5 ms, the speed over the next
3 ms, 10 ms simulated; about 15 s). Chromium must be installed when CI=true (scripts/test.sh
installs it); elsewhere the browser tests are skipped without it.
"""

from __future__ import annotations

import html
import json
import math
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from b1 import variant
from typer.testing import CliRunner

import rollerdyn
from rollerdyn.cli import app
from rollerdyn.report import (
    MAX_FRAMES,
    POWER_COLUMNS,
    animation_figure,
    pairing_shares,
    power_by_contact,
    summary,
)
from rollerdyn.simulation import numbers_per_output, simulate, write

RUNNER = CliRunner()

ROLLING = {
    "operating.gravity": "0 m/s^2",
    "operating.load_ramp.end": "5 ms",
    "operating.speed_ramp.start": "5 ms",
    "operating.speed_ramp.end": "8 ms",
    "operating.end_time": "10 ms",
    "solver.output_interval": "0.25 ms",
}

# Records every console.error, uncaught exception and unhandled promise rejection of the
# page in an attribute of <html>, so that --dump-dom shows them (Chromium's own log prints
# every console message at level INFO, whatever its kind).
ERROR_HOOK = """<script>
(function () {
  var errors = [];
  function note(text) {
    errors.push(String(text));
    document.documentElement.setAttribute('data-errors', JSON.stringify(errors));
  }
  document.documentElement.setAttribute('data-errors', '[]');
  window.addEventListener('error', function (e) { note('error: ' + e.message); });
  window.addEventListener('unhandledrejection', function (e) { note('rejection: ' + e.reason); });
  var original = console.error;
  console.error = function () {
    note('console.error: ' + Array.prototype.join.call(arguments, ' '));
    return original.apply(console, arguments);
  };
})();
</script>"""


@pytest.fixture(scope="module")
def result(tmp_path_factory) -> Path:
    ds = simulate(variant(**ROLLING))
    path = tmp_path_factory.mktemp("run") / "rolling.nc"
    write(ds, path)
    return path


@pytest.fixture(scope="module")
def page(result, tmp_path_factory) -> Path:
    """The report of the run and of a copy of it (two results in one page), via the CLI."""
    second = result.with_name("rolling_copy.nc")
    shutil.copyfile(result, second)
    out = tmp_path_factory.mktemp("report") / "report.html"
    res = RUNNER.invoke(app, ["report", str(result), str(second), "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert "wrote" in res.output and out.is_file()
    return out


def chromium() -> str:
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        message = "chromium is not installed (scripts/test.sh installs Debian's chromium)"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(message)
        pytest.skip(message)
    return exe


def run_chromium(args: list[str], profile: Path) -> subprocess.CompletedProcess:
    cmd = [
        chromium(),
        "--headless=new",
        "--disable-gpu",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--no-first-run",
        "--hide-scrollbars",
        f"--user-data-dir={profile}",
        "--enable-logging=stderr",
        "--v=0",
        "--virtual-time-budget=5000",
        *args,
    ]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120)


def console_lines(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if "CONSOLE" in line or "Uncaught" in line]


def rendered_dom(page: Path, tmp_path: Path, plots: int) -> str:
    """The DOM of ``page`` after headless Chromium ran its scripts, checked: ``plots``
    plot containers built and counted by the page's last script, no error, no uncaught
    exception, no console error (also used by the study's report test)."""
    checked = tmp_path / "checked.html"
    text = page.read_text(encoding="utf-8")
    checked.write_text(text.replace("<head>", "<head>" + ERROR_HOOK, 1), encoding="utf-8")
    done = run_chromium(["--dump-dom", checked.as_uri()], tmp_path / "profile")
    assert done.returncode == 0, done.stderr[-3000:]
    dom = done.stdout
    assert len(re.findall(r'class="plot-container', dom)) == plots
    assert f'data-plots="{plots}"' in dom
    errors = re.search(r'data-errors="([^"]*)"', dom)
    assert errors is not None, "the error hook did not run"
    assert json.loads(errors.group(1).replace("&quot;", '"')) == []
    bad = [line for line in console_lines(done.stderr) if "rror" in line or "Uncaught" in line]
    assert bad == []
    return dom


def test_page_is_self_contained_and_holds_every_part(page, result):
    text = page.read_text(encoding="utf-8")
    # No external script, style or image: everything inline.
    assert not re.search(r"<script[^>]*\ssrc=", text)
    assert not re.search(r"<link[^>]*\shref=", text)
    assert not re.search(r"<img[^>]*\ssrc=[\"']?(https?:)?//", text)
    assert text.count("<script") >= 10
    # plotly.js inline exactly once.
    assert text.count("plotly.js v") == 1
    assert len(text) > 3_000_000
    # plotly writes its labels in JSON with \uXXXX escapes (also for '/' and '<').
    plain = re.sub(r"\\u([0-9a-fA-F]{4})", lambda m: chr(int(m.group(1), 16)), text)
    for heading in ("Summary", "Inputs", "Figures of the paper", "Roller set over time"):
        assert heading in text
    for words in (
        "mean bearing frictional torque, last 20 % of the run",
        "max. roller-race load",
        "max. roller end / flange normal force",
        "max. |slide-to-roll ratio| at the inner race",
        "fig. 10",
        "fig. 11",
        "fig. 12",
        "fig. 13",
        "fig. 8",
        "fig. 9",
        "bearing frictional torque [N·m]",
        "roller azimuth ψ [deg]",
        "ring speed [rad/s]",
        "tr-bdf2",
        "semi-analytical",
        # built in Python (no TOML text): the resolved configuration the result records
        "configuration (resolved to SI; built in Python, no TOML text)",
        '"radial_load": 5000.0',
    ):
        assert words in plain, words
    assert "rolling (F_a = 1000 N)" in text and "rolling_copy (F_a = 1000 N)" in text


def test_page_renders_in_headless_chromium_without_errors(page, tmp_path):
    # The scripts ran: plotly built a plot container in each of the 12 figures (inputs,
    # figs. 10, 11, 8, 9, 12, 13, loads over azimuth, Lambda over azimuth at the inner race
    # and at the flanges, one animation per result) and the page's last script counted them.
    dom = rendered_dom(page, tmp_path, plots=12)
    assert len(re.findall(r"class=\"slider-container", dom)) == 2  # one per animation
    assert "updatemenu-button" in dom  # play / pause


def test_screenshot_of_the_page_is_not_blank(page, tmp_path):
    import matplotlib.image as mpimg

    shot = tmp_path / "shot.png"
    done = run_chromium(
        [f"--screenshot={shot}", "--window-size=1280,2400", page.as_uri()], tmp_path / "p"
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert shot.is_file() and shot.stat().st_size > 10_000
    img = mpimg.imread(shot)
    assert img.shape[:2] == (2400, 1280)
    rgb = (img[..., :3] * 255).round().astype(np.uint32)
    packed = (rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2]
    colours, counts = np.unique(packed, return_counts=True)
    assert colours.size > 200, colours.size  # text, tables, lines of the plots
    assert counts.max() / packed.size < 0.9  # not one flat background
    bad = [line for line in console_lines(done.stderr) if "rror" in line or "Uncaught" in line]
    assert bad == []


def test_summary_matches_the_data(result):
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds = ds.load()
    s = summary(ds)
    t = ds.time.values
    last = t >= 0.8 * t[-1]
    assert s["mean_torque"] == pytest.approx(float(ds.frictional_torque[last].mean()))
    assert s["mean_torque"] > 0.0  # rolling at full speed: friction resists the rotation
    race = max(float(ds.inner_normal_force.max()), float(ds.outer_normal_force.max()))
    assert s["max_race_load"] == pytest.approx(race)
    # The radial load of 5000 N is carried by a few rollers: the largest load is between
    # the mean over the rollers in the load zone and the whole load.
    assert 5000 / 17 < s["max_race_load"] < 5000
    assert s["max_flange_force"] == pytest.approx(float(ds.flange_normal_force.max()))
    assert s["max_flange_force"] > 0.0  # the axial load of 1000 N goes through flanges
    assert s["final_time"] == pytest.approx(0.01)
    assert s["steps"][0] == ds.attrs["stats_steps"] > 0
    assert s["status"] == "completed"
    # the wall time's threads (the page said "on one core" for a run on two)
    assert s["threads"] == ds.attrs["threads"] >= 1
    for ring in ("inner", "outer"):
        shares = pairing_shares(ds, ring)
        assert sum(shares.values()) == pytest.approx(1.0)
        assert shares["none"] < 1.0  # some roller end touched a flange
    power = float(ds.power_loss[last].mean())
    assert s["mean_power_loss"] == pytest.approx(power)
    assert s["torque_from_power"] == pytest.approx(power / float(ds.ring_speed[last].mean()))
    # four shares in per cent, flanges first, that add up to the whole loss
    for key in ("power_shares", "power_mechanisms"):
        shares = [float(x) for x in s[key].split(" / ")]
        assert len(shares) == 4 and sum(shares) == pytest.approx(100.0, abs=0.3), key
    # a result written before power losses were recorded: n/a, no error
    old = summary(ds.drop_vars([v for v in ds.data_vars if "power_loss" in v]))
    assert math.isnan(old["mean_power_loss"]) and old["power_shares"] == "n/a"
    assert old["power_mechanisms"] == "n/a"


def test_the_power_by_contact_adds_up_and_says_when_it_is_not_recorded(result, tmp_path):
    """The report's table of where the power goes: per contact kind its sliding, normal
    forces' and rolling resistance's parts add up to its total (with the drag's, for all
    of them), the rows to the bearing's mean loss (round-off: 1e-9 relative), with the
    flanges' rolling resistance nil; a file written before the parts were recorded gets
    None and a note on the page, no error."""
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds = ds.load()
    last = ds.time.values >= 0.8 * ds.time.values[-1]
    rows = dict(power_by_contact(ds, last))
    assert list(rows) == ["inner race", "outer race", "roller pairs", "flanges", "drag", "all"]
    for name, values in rows.items():
        assert len(values) == len(POWER_COLUMNS)
        parts = sum(values[:3]) + (rows["drag"][3] if name == "all" else 0.0)
        if name != "drag":
            assert parts == pytest.approx(values[3], rel=1e-9, abs=1e-15), name
    assert rows["flanges"][2] == 0.0
    loss = float(ds.power_loss[last].mean())
    assert rows["all"][3] == pytest.approx(loss, rel=1e-9)
    assert rows["all"][0] == pytest.approx(float(ds.sliding_power_loss[last].mean()), rel=1e-9)
    old = ds.drop_vars([v for v in ds.data_vars if "sliding_power_loss" in v])
    assert power_by_contact(old, last) is None
    write(old, tmp_path / "old.nc")
    page = rollerdyn.report([result, tmp_path / "old.nc"], tmp_path / "p.html", max_frames=2)
    text = page.read_text(encoding="utf-8")
    assert "Where the power goes" in text and "not recorded (an older file" in text
    assert "<th>rolling resistance</th>" in text


def test_the_lubrication_table_is_on_the_page_and_says_when_it_is_not_recorded(result, tmp_path):
    """The report's table of the lubrication at the contacts (rollerdyn.lubrication,
    tested in tests/test_lubrication.py): its rows and columns for a result that records
    it, a note for one that does not."""
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds = ds.load()
    bare = ds.drop_vars([v for v in ds.data_vars if v.endswith("_max_pressure")])
    write(bare, tmp_path / "bare.nc")
    page = rollerdyn.report([result, tmp_path / "bare.nc"], tmp_path / "p.html", max_frames=2)
    text = page.read_text(encoding="utf-8")
    assert "Lubrication at the contacts" in text
    for words in ("<th>largest maximum pressure p0 [GPa]</th>", "<td>flanges</td>"):
        assert words in text, words
    assert 'not recorded (an older file, or solver.outputs without "lubrication")' in text


def test_the_cost_estimate_counts_every_number_a_result_holds_per_output(result):
    """``estimated_cost``'s result size (a run is refused far beyond a normal one) counts
    what a result holds per output time: every time-dependent number, exactly."""
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        nt, z = ds.sizes["time"], ds.sizes["roller"]
        held = sum(v.size for v in ds.variables.values() if "time" in v.dims)
    assert held == nt * numbers_per_output(z)


def test_animation_is_subsampled_to_at_most_max_frames(result):
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds = ds.load()
    fig, n = animation_figure(ds, max_frames=7)
    assert n == len(fig.frames) == 7
    assert len(fig.layout.sliders[0].steps) == 7
    # Every output when there are fewer than the default limit.
    fig, n = animation_figure(ds)
    assert n == ds.sizes["time"] <= MAX_FRAMES


def test_python_api_writes_the_page(result, tmp_path):
    out = rollerdyn.report([result], tmp_path / "sub" / "one.html", max_frames=5)
    assert out == tmp_path / "sub" / "one.html" and out.is_file()
    text = out.read_text(encoding="utf-8")
    assert "(5 frames of" in text and text.count("plotly.js v") == 1


def test_a_forced_run_says_so_on_the_page(result, tmp_path):
    # a run forced past the point law's load check keeps the refusal in its file
    # (tests/test_oil_and_threads.py); the page says it above the run's inputs
    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds = ds.load()
    ds.attrs["forced"] = "run with --force past the point law's load check: the <end> face"
    write(ds, tmp_path / "forced.nc")
    text = rollerdyn.report([tmp_path / "forced.nc"], tmp_path / "f.html", max_frames=2)
    page = text.read_text(encoding="utf-8")
    said = html.escape("Run with --force past the point law's load check: the <end> face")
    assert f'<p class="warn">{said}</p>' in page


def test_missing_or_foreign_files_exit_with_status_2_and_a_clear_message(tmp_path):
    missing = RUNNER.invoke(app, ["report", str(tmp_path / "none.nc"), "-o", "x.html"])
    assert missing.exit_code == 2 and "result file not found" in missing.output
    assert isinstance(missing.exception, SystemExit)  # no traceback
    # a device exists but holds no result: said so, not "not found" (and never read)
    device = RUNNER.invoke(app, ["report", "/dev/null", "-o", str(tmp_path / "x.html")])
    assert device.exit_code == 2 and "/dev/null: not a regular file" in device.output
    garbage = tmp_path / "garbage.nc"
    garbage.write_text("not a netCDF file")
    res = RUNNER.invoke(app, ["report", str(garbage), "-o", str(tmp_path / "x.html")])
    assert res.exit_code == 2 and "not a rollerdyn result" in res.output
    assert isinstance(res.exception, SystemExit)
    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"a": ("x", [1.0, 2.0])}).to_netcdf(foreign, engine="h5netcdf")
    res = RUNNER.invoke(app, ["report", str(foreign), "-o", str(tmp_path / "x.html")])
    assert res.exit_code == 2 and "not a rollerdyn result" in res.output
    assert "frictional_torque" in res.output
    assert not (tmp_path / "x.html").exists()
    # a result whose torque holds text (made by hand): refused, not a TypeError traceback
    from rollerdyn.report import REQUIRED

    texts = tmp_path / "texts.nc"
    fake = {v: ("time", ["a", "b"]) for v in REQUIRED}
    xr.Dataset(fake, coords={"time": [0.0, 1.0]}, attrs={"final_time_s": 1.0}).to_netcdf(
        texts, engine="h5netcdf"
    )
    res = RUNNER.invoke(app, ["report", str(texts), "-o", str(tmp_path / "x.html")])
    assert res.exit_code == 2 and "not numeric" in res.output, res.output
    assert isinstance(res.exception, SystemExit)
    helped = RUNNER.invoke(app, ["report", "--help"])
    assert helped.exit_code == 0 and "N*m" in helped.output and "report.html" in helped.output


def test_only_an_earlier_report_is_replaced(page, result, tmp_path):
    # -o names an existing page: one rollerdyn wrote is replaced, anyone else's (notes
    # saved as .html) is refused with status 2 and left as it was.
    earlier = tmp_path / "earlier.html"
    shutil.copyfile(page, earlier)
    res = RUNNER.invoke(app, ["report", str(result), "-o", str(earlier), "--max-frames", "2"])
    assert res.exit_code == 0, res.output
    assert "(2 frames of" in earlier.read_text(encoding="utf-8")
    notes = tmp_path / "notes.html"
    notes.write_text("<html><body>my notes</body></html>", encoding="utf-8")
    res = RUNNER.invoke(app, ["report", str(result), "-o", str(notes)])
    assert res.exit_code == 2 and "only an earlier report of rollerdyn" in res.output
    assert notes.read_text(encoding="utf-8") == "<html><body>my notes</body></html>"
    # a report written under another extension is still the report (it was refused the
    # second time as "only an earlier report of rollerdyn is replaced")
    odd = tmp_path / "report.txt"
    shutil.copyfile(page, odd)
    res = RUNNER.invoke(app, ["report", str(result), "-o", str(odd), "--max-frames", "2"])
    assert res.exit_code == 0, res.output
    # the Python function keeps the same rule: the notes and a configuration are refused
    # by ReportError and left as they were, an earlier report is replaced
    from rollerdyn.report import ReportError, report

    config = tmp_path / "my.toml"
    config.write_text('name = "mine"\n', encoding="utf-8")
    for theirs in (notes, config):
        before = theirs.read_bytes()
        with pytest.raises(ReportError, match="only an earlier report of rollerdyn"):
            report([result], theirs, max_frames=2)
        assert theirs.read_bytes() == before
    assert report([result], earlier, max_frames=2) == earlier


def test_legends_name_the_load_case_and_tell_runs_of_the_same_name_apart():
    """A run stopped in its load ramp (0 N reached of 1000 N) is labelled with its load
    case's axial load, not the load it reached; two sweeps' run_0000 are told apart by
    their paths (they were both "run_0000")."""
    import json

    import numpy as np
    import xarray as xr

    from rollerdyn.report import configured_axial_load, run_names

    ramping = xr.Dataset(
        {"axial_load": ("time", np.array([0.0, 0.0]))},
        attrs={"config_resolved": json.dumps({"operating": {"axial_load": 1000.0}})},
    )
    assert configured_axial_load(ramping) == 1000.0
    unrecorded = xr.Dataset({"axial_load": ("time", np.array([0.0, 250.0]))})
    assert configured_axial_load(unrecorded) == 250.0  # no record: the load reached
    same = [Path("sweep/run_0000.nc"), Path("sweep3/run_0000.nc")]
    assert run_names(same) == ["sweep/run_0000.nc", "sweep3/run_0000.nc"]
    assert run_names([Path("a/b1.nc"), Path("a/tilt.nc")]) == ["b1", "tilt"]


def test_the_report_function_checks_its_arguments_before_the_work(result, tmp_path):
    # a Dataset was taken as a list of files ("ring_speed: result file not found"), a
    # folder as out failed with IsADirectoryError after the work, and max_frames of 0 or
    # NaN were taken without a word
    import xarray as xr

    from rollerdyn.report import ReportError, report

    with xr.open_dataset(result, engine="h5netcdf") as ds:
        with pytest.raises(ReportError, match="paths = <xarray.Dataset> .*: must be result"):
            report(ds, tmp_path / "r.html")
    for kwargs, match in (
        ({"out": None}, "out = None: must be the report's file path"),
        ({"out": tmp_path}, "is a folder; name the report's file in it"),
        ({"out": tmp_path / "r.html", "max_frames": 0}, "max_frames = 0: must be a whole"),
        ({"out": tmp_path / "r.html", "max_frames": float("nan")}, "max_frames = nan"),
        ({"out": tmp_path / "r.html", "max_frames": 1.5}, "max_frames = 1.5"),
    ):
        with pytest.raises(ReportError, match=match):
            report([result], **kwargs)
    assert not (tmp_path / "r.html").exists()
    # None raised a bare TypeError; a generator's files were used up by the check, and the
    # page said "no result files given"
    with pytest.raises(ReportError, match="paths = None: must be result files' paths"):
        report(None, tmp_path / "r.html")
    assert report((p for p in [result]), tmp_path / "g.html") == tmp_path / "g.html"


def test_a_result_given_twice_is_refused_by_report_and_plot(result, tmp_path):
    """The same file twice (here once by a relative name through a link) gave two
    identical columns and legend entries under one label."""
    link = tmp_path / "again.nc"
    link.symlink_to(result)
    for command in (["report", "-o", str(tmp_path / "r.html")], ["plot", "-o", str(tmp_path)]):
        out = RUNNER.invoke(app, [*command, str(result), str(link)])
        assert out.exit_code == 2, out.output
        assert f"given twice (also as {link}); give each result once" in out.output
    assert not (tmp_path / "r.html").exists() and not list(tmp_path.glob("*.png"))


def test_a_run_beside_its_quasi_static_estimate(tmp_path):
    """The report's "Beside the quasi-static estimate" (rollerdyn.crosscheck): B1 started
    from equilibrium at full load and speed, 20 ms (its last 20 %, 16-20 ms, steady): the
    heaviest roller's load within 3 % of the equilibrium's (measured 0.995; B1's whole
    run 1 293 against 1 311 N), the largest flange force within 5 % (1.018; the whole run
    143.7 against 141.1 N), the torque within 3 % of the estimate, whose rollers' spins and
    skews are balanced (measured 0.994, the whole run 0.995; at zero skew the estimate was
    10 % low) and the loaded rollers' slip within 15 % (0.95; the whole run 0.95: the run's
    ends press the flanges higher); a result without a configuration says so instead; the
    page holds the table."""
    from rollerdyn.crosscheck import beside_statics
    from rollerdyn.report import build_html, last_outputs

    cfg = variant(
        **{
            "operating.load_ramp": None,
            "operating.speed_ramp": None,
            "operating.end_time": "20 ms",
            "solver.start": "equilibrium",
            "solver.output_interval": "0.1 ms",
        }
    )
    ds = simulate(cfg, t_end=0.02)
    rows = {r.label.split(" (")[0]: r for r in beside_statics(ds, last_outputs(ds))}
    ratio = {k: r.run / r.estimate for k, r in rows.items()}
    assert abs(ratio["heaviest roller's load at the inner race"] - 1.0) < 0.03, ratio
    assert abs(ratio["largest roller end / flange force"] - 1.0) < 0.05, ratio
    assert abs(ratio["friction torque"] - 1.0) < 0.03, ratio
    slip = next(r for k, r in rows.items() if k.startswith("slip"))
    assert slip.run < 0 and abs(slip.run / slip.estimate - 1.0) < 0.15, slip
    bare = ds.copy()
    bare.attrs = {k: v for k, v in ds.attrs.items() if not k.startswith("config")}
    assert str(beside_statics(bare, last_outputs(bare))).startswith("no estimate")
    path = tmp_path / "r.nc"
    write(ds, path)
    page = build_html([path])
    assert 'id="statics"' in page and "run / quasi-static" in page


def test_results_with_nan_or_inf_values_plot_and_one_without_rollers_is_refused(result, tmp_path):
    """A result whose azimuths are all NaN and whose last outputs are infinite (a damaged
    or hand-made file) failed `plot` with matplotlib's "Data cannot be log-scaled"
    traceback, and `report` printed NumPy's RuntimeWarnings; one without rollers gave an
    IndexError. Now the figures are drawn from what can be drawn, the page is written
    quietly, and a result without rollers is refused in one line (found by a review,
    2026-12-02)."""
    from rollerdyn.simulation import write

    with xr.open_dataset(result, engine="h5netcdf") as ds:
        ds = ds.load()
    odd = ds.copy(deep=True)
    odd["azimuth"][:] = np.nan
    odd["frictional_torque"][-3:] = np.inf
    write(odd, tmp_path / "odd.nc")
    for command in (
        ["plot", "-o", str(tmp_path / "figs")],
        ["report", "-o", str(tmp_path / "r.html")],
    ):
        out = RUNNER.invoke(app, [*command, str(tmp_path / "odd.nc")])
        assert out.exit_code == 0, out.output
        assert "Warning" not in out.output and "Traceback" not in out.output, out.output
    write(ds.isel(roller=slice(0, 0)), tmp_path / "none.nc")
    for command in (
        ["plot", "-o", str(tmp_path / "figs2")],
        ["report", "-o", str(tmp_path / "n.html")],
    ):
        out = RUNNER.invoke(app, [*command, str(tmp_path / "none.nc")])
        assert out.exit_code == 2, out.output
        assert "none.nc: not a rollerdyn result (it holds no rollers)" in out.output
