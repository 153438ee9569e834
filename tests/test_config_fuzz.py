"""Property-based fuzzing of the configuration loader (issue 6, point 1: the config loader's
fuzz target; docs/robustness.md).

examples/b1.toml is mutated at random: values replaced (NaN, ±inf, negative, zero, huge and
tiny numbers, integers beyond 64 bits, booleans, quantity strings with wrong or odd units,
arbitrary text, arrays, tables), keys deleted, unknown keys and sections added, tables and
values swapped, and the TOML bytes themselves corrupted (bytes replaced, inserted, deleted,
the file cut short, invalid UTF-8). For every input ``load_config`` either returns a
configuration or raises :class:`ConfigError` whose message names the field of every problem
(a file-level error, malformed TOML or not UTF-8, names the file and, for TOML, the line);
any other exception is a finding.

Short mode (CI): ``CONFIG_FUZZ_EXAMPLES`` examples per test, 300 by default. Long mode:
``CONFIG_FUZZ_EXAMPLES=100000 pytest -q tests/test_config_fuzz.py`` (docs/robustness.md).
"""

from __future__ import annotations

import copy
import io
import math
import os
import subprocess
import sys
import tomllib
from pathlib import Path
from typing import Any

import pytest
from b1 import B1_BYTES, b1_data, dump_toml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from rich.console import Console
from rich.text import Text

from rollerdyn.config import BearingConfig, ConfigError, load_config
from rollerdyn.simulation import check_cost, estimated_cost

B1 = b1_data()
EXAMPLES = int(os.environ.get("CONFIG_FUZZ_EXAMPLES", "300"))
FUZZ = settings(
    max_examples=EXAMPLES,
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


def _paths(data: Any, prefix: tuple = ()) -> list[tuple]:
    """Every key path of the nested tables (tables themselves included)."""
    out = []
    if isinstance(data, dict):
        for key, value in data.items():
            path = (*prefix, key)
            out.append(path)
            out.extend(_paths(value, path))
    return out


PATHS = _paths(B1)


def _at(data: dict, path: tuple) -> Any:
    for key in path:
        data = data[key]
    return data


TABLE_PATHS = [()] + [p for p in PATHS if isinstance(_at(B1, p), dict)]

# ------------------------------------------------------------------ values

UNITS = [
    "mm",
    "m",
    "um",
    "nm",
    "km",
    "in",
    "deg",
    "rad",
    "N",
    "kN",
    "N/m",
    "Pa",
    "MPa",
    "GPa",
    "s",
    "ms",
    "us",
    "min",
    "rpm",
    "rad/s",
    "1/s",
    "kg",
    "g",
    "kg/m^3",
    "Pa*s",
    "mPa*s",
    "degC",
    "K",
    "W/(m*K)",
    "1/Pa",
    "1/K",
    "m/s^2",
    "%",
    "",
    "furlong",
    "mm^2",
    "N*m",
    "m/s",
    "1/GPa",
    "Hz",
    "1/min",
    "degF",
    "cSt",
    "mm2/s",
    "kg*m^2",
    "m**2",
    "1/0",
    "A/0",
    "m**-0",
    "m**9**9**9",
    "m^(1/2)",
    "m^^2",
]

SPECIAL = [
    math.nan,
    math.inf,
    -math.inf,
    0.0,
    -0.0,
    -1.0,
    1e-308,
    5e-324,
    1e308,
    -1e308,
    1.7976931348623157e308,
    1e-30,
    1e30,
    0.5,
    1.0,
    2.0,
    3.0,
    1e3,
    1e6,
    1e9,
]


def numbers() -> st.SearchStrategy:
    return st.one_of(
        st.sampled_from(SPECIAL),
        st.floats(allow_nan=True, allow_infinity=True),
        st.integers(min_value=-(2**63), max_value=2**63 - 1),
        st.sampled_from([0, 1, -1, 2, 3, 4, 17, 1000, 2**31, 2**53 + 1]),
    )


def _number_text(x: float | int) -> str:
    return repr(x) if isinstance(x, float) else str(x)


def quantities() -> st.SearchStrategy:
    return st.builds(
        lambda x, u, space: f"{_number_text(x)}{' ' if space else ''}{u}",
        numbers(),
        st.sampled_from(UNITS),
        st.booleans(),
    )


def scalars() -> st.SearchStrategy:
    return st.one_of(
        numbers(),
        quantities(),
        st.booleans(),
        st.text(max_size=20),
        st.sampled_from(
            [
                "",
                " ",
                "nan mm",
                "inf N",
                "-inf s",
                "1e999 mm",
                "mm",
                "5 mm mm",
                "5..0 mm",
                "0x10 mm",
                "1_000 N",
                "tr-bdf2",
                "mesh",
                "gradient",
                "straight",
                "crowned",
                "logarithmic",
                "semi-analytical",
                "cosine",
                "linear",
                "exact",
                "tabulated",
                "direct",
                # rich markup in text: printed as text, never interpreted (issue 16)
                "5000 [/x] N",
                "B1 [/x]",
                "[red]",
                "[bold]5 mm[/bold]",
                "[mass]",
                "[/]",
                # values that drive cost or lie beyond any bearing (issue 16)
                "1e-12 s",
                "1e-30 s",
                "1e300 N",
                "1e300 rpm",
                "1e12 rpm",
                "1e-300 mm",
                100000000,
                10**18,
            ]
        ),
    )


def values() -> st.SearchStrategy:
    return st.recursive(
        scalars(),
        lambda inner: st.one_of(
            st.lists(inner, max_size=4),
            st.dictionaries(st.text(max_size=8), inner, max_size=3),
        ),
        max_leaves=8,
    )


# ------------------------------------------------------------------ mutations


def _replace(data: dict, path: tuple, value: Any) -> None:
    cur = data
    for key in path[:-1]:
        if not isinstance(cur.get(key), dict):
            return
        cur = cur[key]
    cur[path[-1]] = value


def _delete(data: dict, path: tuple) -> None:
    cur = data
    for key in path[:-1]:
        if not isinstance(cur.get(key), dict):
            return
        cur = cur[key]
    cur.pop(path[-1], None)


@st.composite
def mutation(draw) -> tuple[str, tuple, Any]:
    kind = draw(st.sampled_from(["replace", "replace", "replace", "delete", "add", "table"]))
    if kind == "add":
        table = draw(st.sampled_from(TABLE_PATHS))
        key = draw(
            st.one_of(
                st.text(min_size=1, max_size=12),
                st.sampled_from(
                    [
                        "extra",
                        "roller",
                        "flange",
                        "inner",
                        "outer",
                        "name",
                        "units",
                        "ramp",
                        "table",
                    ]
                ),
            )
        )
        return kind, (*table, key), draw(values())
    path = draw(st.sampled_from(PATHS))
    if kind == "delete":
        return kind, path, None
    if kind == "table":  # a value turned into a table or a table into a value
        return "replace", path, draw(st.one_of(st.just({}), values()))
    return kind, path, draw(values())


def mutated(mutations: list[tuple[str, tuple, Any]]) -> dict:
    data = copy.deepcopy(B1)
    for kind, path, value in mutations:
        if kind == "delete":
            _delete(data, path)
        else:
            _replace(data, path, value)
    return data


# ------------------------------------------------------------------ the property


def check_load(path: Path) -> BearingConfig | None:
    """load_config(path) returns a configuration or raises ConfigError naming the field of
    every problem; anything else fails the test. An accepted configuration has a cost
    estimate, and a run far beyond a normal one is refused by :func:`check_cost` with a
    ValueError before any work; every message prints as plain text through rich."""
    try:
        config = load_config(path)
    except ConfigError as err:
        _prints_as_text(str(err))
        message = str(err)
        assert message.strip(), "empty message"
        if err.problems:
            for problem in err.problems:
                assert problem.path and problem.path != "()", f"no field named: {message}"
                assert problem.path in message, message
                assert problem.rule.strip(), message
        else:
            assert str(path) in message, message
            assert any(
                reason in message for reason in ("malformed TOML", "not UTF-8", "expected a table")
            ), message
        return None
    cost = estimated_cost(config, config.end_time)
    assert cost["outputs"] >= 1 and cost["min_steps"] > 0, cost
    try:
        check_cost(config, config.end_time)
    except ValueError as err:
        _prints_as_text(str(err))
        assert str(err).startswith("solver."), err
    return config


def _prints_as_text(message: str) -> None:
    """The CLI prints messages as rich Text: any brackets in them must survive."""
    out = io.StringIO()
    Console(file=out, width=300).print(Text(message, style="red"))
    shown, expected = (
        "".join(c for c in t if c.isprintable() and not c.isspace())
        for t in (out.getvalue(), message)
    )
    assert shown == expected  # layout and control characters aside, nothing is lost


def test_the_writer_round_trips_b1(tmp_path: Path) -> None:
    path = tmp_path / "b1.toml"
    path.write_text(dump_toml(B1), encoding="utf-8")
    assert tomllib.loads(path.read_text(encoding="utf-8")) == B1
    assert isinstance(check_load(path), BearingConfig)


@FUZZ
@given(st.lists(mutation(), min_size=1, max_size=4))
def test_mutated_b1_loads_or_names_the_field(tmp_path_factory, mutations) -> None:
    data = mutated(mutations)
    path = tmp_path_factory.mktemp("fuzz") / "mutated.toml"
    path.write_text(dump_toml(data), encoding="utf-8")
    assert tomllib.loads(path.read_text(encoding="utf-8")) is not None  # the writer's TOML
    check_load(path)


@st.composite
def corrupted(draw) -> bytes:
    data = bytearray(B1_BYTES)
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.sampled_from(["set", "insert", "delete", "cut", "splice"]))
        at = draw(st.integers(0, max(len(data) - 1, 0)))
        if kind == "set" and data:
            data[at] = draw(st.integers(0, 255))
        elif kind == "insert":
            chunk = draw(
                st.one_of(
                    st.binary(min_size=1, max_size=8),
                    st.sampled_from(
                        [
                            b"=",
                            b"[",
                            b"]",
                            b'"',
                            b"\n",
                            b"[[",
                            b"{",
                            b"}",
                            b"#",
                            b"\xff",
                            b"\xc3",
                            b"nan",
                            b"inf",
                            b"\x00",
                            b"'''",
                            b'"""',
                        ]
                    ),
                )
            )
            data[at:at] = chunk
        elif kind == "delete":
            del data[at : at + draw(st.integers(1, 16))]
        elif kind == "cut":
            del data[at:]
        else:  # a line moved elsewhere
            lines = bytes(data).split(b"\n")
            if len(lines) > 1:
                i = draw(st.integers(0, len(lines) - 1))
                j = draw(st.integers(0, len(lines) - 1))
                lines.insert(j, lines.pop(i))
                data = bytearray(b"\n".join(lines))
    return bytes(data)


@FUZZ
@given(corrupted())
def test_corrupted_b1_bytes_load_or_give_a_clean_error(tmp_path_factory, raw: bytes) -> None:
    path = tmp_path_factory.mktemp("fuzz") / "corrupted.toml"
    path.write_bytes(raw)
    check_load(path)


@pytest.mark.parametrize(
    "mutations",
    [
        # pint tokenizes a unit as Python source: an unterminated string or bracket raised
        # tokenize.TokenError through load_config (found by the byte corruption).
        [("replace", ("lubricant", "carreau", "tau0"), "5''' MPa")],
        [("replace", ("lubricant", "carreau", "tau0"), "5] MPa")],
        [("replace", ("geometry", "roller", "length"), '5 mm"""')],
        # pint evaluates numbers in a unit: ZeroDivisionError (found by the long mode, as
        # shrunk: a NaN name beside it), KeyError after a zero exponent.
        [
            ("replace", ("name",), math.nan),
            ("replace", ("geometry", "inner_raceway_diameter"), "NAN0/0"),
        ],
        [("replace", ("geometry", "inner_raceway_diameter"), "20 A/0")],
        [("replace", ("geometry", "inner_raceway_diameter"), "20 mm**-0")],
    ],
)
def test_fuzz_findings(tmp_path: Path, mutations) -> None:
    """Inputs the fuzzer found (kept as regressions): each gives a ConfigError naming the
    field."""
    path = tmp_path / "finding.toml"
    path.write_text(dump_toml(mutated(mutations)), encoding="utf-8")
    assert check_load(path) is None


def test_a_tower_of_powers_in_a_unit_is_refused_quickly(tmp_path: Path) -> None:
    """pint evaluates a unit with Python integers, so "mm**9**9**9" never returned (found
    beside the fuzzer's ZeroDivisionError). Run in a subprocess: the power holds the GIL,
    so only a process can be timed out."""
    for unit in ("mm**9**9**9", "mm^99999999"):
        data = mutated([("replace", ("geometry", "inner_raceway_diameter"), f"20 {unit}")])
        path = tmp_path / "tower.toml"
        path.write_text(dump_toml(data), encoding="utf-8")
        code = (
            "import sys; from rollerdyn.config import ConfigError, load_config\n"
            "try:\n    load_config(sys.argv[1])\nexcept ConfigError as e:\n    print(e)"
        )
        done = subprocess.run(
            [sys.executable, "-c", code, str(path)], capture_output=True, text=True, timeout=60
        )
        assert done.returncode == 0, done.stderr
        assert "geometry.inner_raceway_diameter" in done.stdout and "exponent" in done.stdout
