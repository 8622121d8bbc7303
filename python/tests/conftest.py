"""The cpu suite's skip policy: nothing vanishes.

Every skip is reported (as -rs would), and a skip whose reason is not allowed here fails the test: a test that
cannot run where it should is a failure, not a quiet pass.  Allowed are:

- the reasons in ALLOWED_SKIPS, each for a machine where the test has nothing to check;
- "could not import 'NAME'" (pytest.importorskip) where NAME is listed in the environment variable
  CUDAHULL_TESTS_WITHOUT (comma-separated): a machine that does not install all of
  python/requirements-test.txt (python/gpu_tests/run_on_gpu_machine.sh) says which it lacks.

The run ends with one line counting the tests that ran, by outcome.
"""

from __future__ import annotations

import os
import re

import pytest

ALLOWED_SKIPS = {
    # test_device_input.py: the error for points in GPU memory on a machine without a usable GPU.
    "a usable GPU is here; the error is for machines without one",
}

_IMPORT_SKIP = re.compile(r"^could not import '([\w.]+)'")


def _without() -> set[str]:
    return {name.strip() for name in os.environ.get("CUDAHULL_TESTS_WITHOUT", "").split(",") if name.strip()}


def skip_reason(report: pytest.TestReport | pytest.CollectReport) -> str:
    """The reason of a skipped report, without pytest's "Skipped: " prefix."""
    longrepr = report.longrepr
    text = longrepr[2] if isinstance(longrepr, tuple) and len(longrepr) == 3 else str(longrepr)
    return text.removeprefix("Skipped: ")


def allowed(reason: str) -> bool:
    if reason in ALLOWED_SKIPS:
        return True
    missing = _IMPORT_SKIP.match(reason)
    return missing is not None and missing.group(1).partition(".")[0] in _without()


def _refuse(report: pytest.TestReport | pytest.CollectReport, where: str) -> None:
    reason = skip_reason(report)
    report.outcome = "failed"
    report.longrepr = (f"{where} was skipped ({reason!r}), and python/tests/conftest.py allows no such skip: "
                       f"install what python/requirements-test.txt lists, or add the reason to ALLOWED_SKIPS "
                       f"(or the module to CUDAHULL_TESTS_WITHOUT) if the test truly has nothing to check here")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]):  # type: ignore[no-untyped-def]
    outcome = yield
    report: pytest.TestReport = outcome.get_result()
    if report.skipped and not hasattr(report, "wasxfail") and not allowed(skip_reason(report)):
        _refuse(report, item.nodeid)


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector: pytest.Collector):  # type: ignore[no-untyped-def]
    outcome = yield
    report: pytest.CollectReport = outcome.get_result()
    if report.skipped and not allowed(skip_reason(report)):
        _refuse(report, f"{collector.nodeid} (the whole module)")


def pytest_configure(config: pytest.Config) -> None:
    # Report every skip, with its reason, as -rs does, whatever the command line asked for.
    chars = config.option.reportchars or ""
    if "s" not in chars and "a" not in chars and "A" not in chars:
        config.option.reportchars = chars + "s"


def pytest_terminal_summary(terminalreporter) -> None:  # type: ignore[no-untyped-def]
    stats = terminalreporter.stats
    counts = {outcome: len([r for r in stats.get(outcome, []) if getattr(r, "when", "call") in ("call", "setup")])
              for outcome in ("passed", "failed", "skipped", "xfailed", "xpassed", "error")}
    ran = counts["passed"] + counts["failed"] + counts["xfailed"] + counts["xpassed"]
    parts = ", ".join(f"{n} {outcome}" for outcome, n in counts.items() if n)
    terminalreporter.write_line(f"python/tests: {ran} tests ran ({parts}); skips allowed: "
                                f"{sorted(ALLOWED_SKIPS)} and missing modules {sorted(_without()) or 'none'}")
