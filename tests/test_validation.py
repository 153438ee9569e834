"""The validation cases of ``rollerdyn validate``, one test each (sources in the cases)."""

import math

import pytest

from rollerdyn.validation import cases, run

CASES = cases()


@pytest.mark.parametrize("case", CASES, ids=[f"{c.group}: {c.name}" for c in CASES])
def test_case(case):
    value = float(case.compute())
    assert math.isfinite(value), case.name
    if case.expected == 0.0:
        assert abs(value) <= case.rtol, f"{case.name}: {value} ({case.source}; {case.why})"
    else:
        error = abs(value / case.expected - 1.0)
        assert error <= case.rtol, f"{case.name}: {value} vs {case.expected} ({case.why})"


def test_run_reports_every_case():
    results = list(run())
    assert len(results) == len(CASES) >= 40
    assert all(r.passed for r in results)
