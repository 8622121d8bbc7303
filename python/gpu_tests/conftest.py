"""The GPU tests' session: the `lib` fixture, and what a run that could not test means.

On a machine without a GPU, when nothing passed because everything was skipped, the run exits with 77, which
ctest's SKIP_RETURN_CODE reports as skipped rather than passed.  On a machine with a GPU (nvidia-smi lists
one, or the module reports a usable device) the run FAILS instead where it could not test: where neither
CuPy nor PyTorch with a CUDA device is importable, or where the module sees no usable device although
nvidia-smi lists one.  Nothing vanishes as a skip on the machine these tests are for."""

from __future__ import annotations

import importlib
import shutil
import subprocess

import pytest

import cudahull

SKIPPED_EXIT = 77


@pytest.fixture(params=["cupy", "torch"])
def lib(request):
    """The array library a GPU test reads from: CuPy, or PyTorch with a CUDA device (skipped without)."""
    module = pytest.importorskip(request.param)
    if request.param == "torch" and not module.cuda.is_available():
        pytest.skip("PyTorch sees no CUDA device")
    return module


def nvidia_smi_gpus() -> list[str]:
    """The GPUs nvidia-smi lists ("GPU 0: ..."), none where it is missing or fails."""
    command = shutil.which("nvidia-smi")
    if command is None:
        return []
    try:
        listed = subprocess.run([command, "-L"], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return []
    if listed.returncode != 0:
        return []
    return [line for line in listed.stdout.splitlines() if line.startswith("GPU ")]


def array_libraries() -> list[str]:
    """The GPU array libraries these tests can read from here: CuPy, PyTorch with a CUDA device."""
    found = []
    for name in ("cupy", "torch"):
        try:
            module = importlib.import_module(name)
        except Exception:  # ImportError, or a CUDA library that fails to load
            continue
        if name == "torch" and not module.cuda.is_available():
            continue
        found.append(name)
    return found


def untestable_gpu() -> str | None:
    """Why this machine has a GPU but the suite cannot test it, or None (no GPU, or a testable one)."""
    usable, why = cudahull._cudahull.cuda_device()
    listed = nvidia_smi_gpus()
    if not usable and not listed:
        return None  # no GPU here: skipping is right
    if not usable:
        return f"nvidia-smi lists {listed[0]!r}, but the module reports no usable CUDA device: {why}"
    if not array_libraries():
        return ("a GPU is here, but neither CuPy nor PyTorch with a CUDA device is importable: install one (the "
                "tests read points in GPU memory from them)")
    return None


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    why = untestable_gpu()
    if why is not None:
        if reporter is not None:
            reporter.write_line(f"python/gpu_tests: FAILED: {why}", red=True)
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
        return
    if reporter is None or exitstatus != 0:
        return
    if not reporter.stats.get("passed") and reporter.stats.get("skipped"):
        session.exitstatus = SKIPPED_EXIT
