"""conftest.py's skip policy, on small suites run in a subprocess with a copy of it: a skip it does not allow
fails the run, an allowed one passes, and the run counts the tests that ran."""

import os
import shutil
import subprocess
import sys
import textwrap

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))


def run_suite(tmp_path, body, **env_changes):
    shutil.copy(os.path.join(HERE, "conftest.py"), tmp_path / "conftest.py")
    (tmp_path / "test_it.py").write_text(textwrap.dedent(body))
    env = {key: value for key, value in os.environ.items() if key != "CUDAHULL_TESTS_WITHOUT"}
    env.update(env_changes)
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(tmp_path)],
                         capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    return run.returncode, run.stdout + run.stderr


@pytest.mark.parametrize("body", [
    "import pytest\ndef test_a():\n    pytest.skip('no reason given here')\n",
    "import pytest\n@pytest.mark.skipif(True, reason='the machine is odd')\ndef test_a():\n    pass\n",
    "import pytest\ndef test_a():\n    pytest.importorskip('cudahull_no_such_module')\n",
    "import pytest\npytest.importorskip('cudahull_no_such_module')\ndef test_a():\n    pass\n",
])
def test_an_unexpected_skip_fails_the_run(tmp_path, body):
    code, output = run_suite(tmp_path, body + "def test_b():\n    pass\n")
    assert code != 0, output
    assert "allows no such skip" in output, output


def test_an_allowed_skip_passes_and_is_reported(tmp_path):
    code, output = run_suite(tmp_path, """\
        import pytest
        @pytest.mark.skipif(True, reason="a usable GPU is here; the error is for machines without one")
        def test_a():
            pass
        def test_b():
            pytest.importorskip("cudahull_no_such_module")
        def test_c():
            pass
        """, CUDAHULL_TESTS_WITHOUT="cudahull_no_such_module")
    assert code == 0, output
    assert "SKIPPED" in output and "a usable GPU is here" in output, output  # reported, as -rs does
    assert "python/tests: 1 tests ran (1 passed, 2 skipped)" in output, output


# --- python/gpu_tests: on a machine with a GPU, a run that cannot test fails; without one it exits 77 -----------

GPU_TESTS = os.path.join(os.path.dirname(HERE), "gpu_tests")


def gpu_conftest():
    import importlib.util

    spec = importlib.util.spec_from_file_location("cudahull_gpu_conftest", os.path.join(GPU_TESTS, "conftest.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("usable, listed, libraries, fails", [
    (False, [], [], False),                         # no GPU: skipping (exit 77) is right
    (False, ["GPU 0: H100"], ["cupy"], True),       # nvidia-smi sees one, the module none
    (True, ["GPU 0: H100"], [], True),              # neither CuPy nor PyTorch
    (True, [], [], True),                           # the module's device alone counts as a GPU
    (True, ["GPU 0: H100"], ["torch"], False),      # one library is enough
])
def test_gpu_suite_fails_where_a_gpu_cannot_be_tested(monkeypatch, usable, listed, libraries, fails):
    conftest = gpu_conftest()
    monkeypatch.setattr(conftest, "nvidia_smi_gpus", lambda: listed)
    monkeypatch.setattr(conftest, "array_libraries", lambda: libraries)

    class Module:
        @staticmethod
        def cuda_device():
            return usable, "H100" if usable else "no driver"

    monkeypatch.setattr(conftest.cudahull, "_cudahull", Module)
    assert (conftest.untestable_gpu() is not None) == fails


def test_gpu_suite_run_exits_77_without_a_gpu_and_fails_with_one_it_cannot_test(tmp_path):
    """End to end, where this machine has no GPU (else the unit test above stands for it): the suite as it
    is exits 77; with an nvidia-smi that lists a GPU on PATH it fails."""
    import cudahull

    conftest = gpu_conftest()
    usable = cudahull._cudahull.cuda_device()[0]
    if usable or conftest.nvidia_smi_gpus():
        assert (conftest.untestable_gpu() is None) == (usable and bool(conftest.array_libraries()))
        return
    fake = tmp_path / "bin"
    fake.mkdir()
    (fake / "nvidia-smi").write_text("#!/bin/sh\necho 'GPU 0: NVIDIA H100 80GB HBM3 (UUID: GPU-0)'\n")
    (fake / "nvidia-smi").chmod(0o755)
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", GPU_TESTS]
    plain = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert plain.returncode == 77, plain.stdout[-3000:]
    env = dict(os.environ, PATH=f"{fake}{os.pathsep}{os.environ.get('PATH', '')}")
    listed = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)
    assert listed.returncode == 1, listed.stdout[-3000:]
    assert "python/gpu_tests: FAILED: nvidia-smi lists 'GPU 0: NVIDIA H100" in listed.stdout, listed.stdout[-3000:]
