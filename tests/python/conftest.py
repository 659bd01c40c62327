"""With IGAPARAM_NO_SKIP=1 (scripts/test.sh sets it) a skipped test fails instead, and so does
a test module skipped as a whole (``pytest.importorskip`` at its top): the full suite has
meshio, pygismo and the C++ example, so every comparison with them must run."""

import os

import pytest


def _fail_if_skipped(report):
    if report.skipped and os.environ.get("IGAPARAM_NO_SKIP") == "1":
        report.outcome = "failed"
        report.longrepr = f"skipped under IGAPARAM_NO_SKIP=1: {report.longrepr}"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    _fail_if_skipped(outcome.get_result())


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector):
    outcome = yield
    _fail_if_skipped(outcome.get_result())
