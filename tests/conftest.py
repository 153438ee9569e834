"""Fixtures shared by the tests: B1 (``tests/b1.py`` holds it and its variants)."""

from __future__ import annotations

import pytest
from b1 import b1_data, load_b1

from rollerdyn.config import BearingConfig


@pytest.fixture(scope="module")
def b1() -> BearingConfig:
    """B1 read from ``examples/b1.toml``, one object per test module."""
    return load_b1()


@pytest.fixture()
def raw() -> dict:
    """B1's TOML data as read, a fresh copy for each test to change."""
    return b1_data()
