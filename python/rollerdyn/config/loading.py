"""Reading a configuration: :func:`load_config` (a TOML file) and :func:`parse_config` (a
mapping), both returning a validated :class:`~rollerdyn.config.BearingConfig` or raising a
:class:`~rollerdyn.config.ConfigError` that lists every problem.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from ..units import SI_NUMBERS
from .errors import ConfigError, problems_from
from .schema import BearingConfig


def load_config(path: str | Path) -> BearingConfig:
    """Read and validate a TOML configuration file; raise :class:`ConfigError` if invalid."""
    p = Path(path)
    if not p.exists():
        raise ConfigError(f"{p}: configuration file not found", source=str(p))
    if not p.is_file():
        raise ConfigError(f"{p}: not a file", source=str(p))
    try:
        text = p.read_bytes().decode("utf-8-sig")  # a byte-order mark is not TOML
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"{p}: not UTF-8 text ({exc.reason} at byte {exc.start})", source=str(p)
        ) from None
    except OSError as exc:
        raise ConfigError(f"{p}: cannot read ({exc.strerror})", source=str(p)) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        where = f"{p}:{m.group(1)}:{m.group(2)}" if m else f"{p}"
        reason = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", msg)
        raise ConfigError(f"{where}: malformed TOML — {reason}", source=str(p)) from None
    config = parse_config(data, source=str(p))
    config._toml = text
    return config


def parse_config(
    data: Mapping[str, Any], *, source: str | None = None, si_numbers: bool = False
) -> BearingConfig:
    """Validate a configuration mapping (as read from TOML).

    ``si_numbers=True`` accepts bare numbers for dimensional fields and takes them as SI
    (for re-validating ``BearingConfig.model_dump()``); files never use it.
    """
    if not isinstance(data, Mapping):
        raise ConfigError(
            f"{source or 'configuration'}: expected a table of sections, got {type(data).__name__}",
            source=source,
        )
    try:
        return BearingConfig.model_validate(dict(data), context={SI_NUMBERS: si_numbers})
    except ValidationError as exc:
        problems = problems_from(exc, data)
        head = f"invalid configuration{f' {source}' if source else ''}"
        n = len(problems)
        lines = [f"{head} ({n} problem{'s' if n != 1 else ''}):", *map(str, problems)]
        raise ConfigError("\n".join(lines), problems, source) from None
