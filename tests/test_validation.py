"""The validation cases of ``rollerdyn validate``, one test each (sources in the cases)."""

import math

import pytest

from rollerdyn.validation import cases, run


def _ids():
    return [f"{c.group}: {c.name}" for c in cases()]


@pytest.mark.parametrize("index", range(len(cases())), ids=_ids())
def test_case(index):
    case = cases()[index]
    value = float(case.compute())
    assert math.isfinite(value), case.name
    if case.report_only:
        return
    if case.expected == 0.0:
        assert abs(value) <= case.rtol, f"{case.name}: {value} ({case.source}; {case.why})"
    else:
        error = abs(value / case.expected - 1.0)
        assert error <= case.rtol, f"{case.name}: {value} vs {case.expected} ({case.why})"


def test_run_reports_every_case():
    results = list(run())
    assert len(results) == len(cases()) >= 40
    assert all(r.passed for r in results)
