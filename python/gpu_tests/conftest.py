"""The GPU tests' session: when nothing passed because everything was skipped (no GPU, no CuPy, no PyTorch),
the run exits with 77, which ctest's SKIP_RETURN_CODE reports as skipped rather than passed."""

SKIPPED_EXIT = 77


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    if not reporter.stats.get("passed") and reporter.stats.get("skipped"):
        session.exitstatus = SKIPPED_EXIT
