"""The GPU tests' session: the `lib` fixture, and when nothing passed because everything was skipped (no GPU, no CuPy, no PyTorch),
the run exits with 77, which ctest's SKIP_RETURN_CODE reports as skipped rather than passed."""

import pytest

SKIPPED_EXIT = 77


@pytest.fixture(params=["cupy", "torch"])
def lib(request):
    """The array library a GPU test reads from: CuPy, or PyTorch with a CUDA device (skipped without)."""
    module = pytest.importorskip(request.param)
    if request.param == "torch" and not module.cuda.is_available():
        pytest.skip("PyTorch sees no CUDA device")
    return module


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    if not reporter.stats.get("passed") and reporter.stats.get("skipped"):
        session.exitstatus = SKIPPED_EXIT
