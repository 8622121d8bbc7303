"""The package as a user and a type checker meet it: its public names and their docstrings, an import that
leaves scipy.spatial alone until a QhullError is needed, that error as scipy's, the package without scipy,
the extension's generated stub (stale fails), and mypy --strict on code that uses the package."""

import inspect
import os
import pickle
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import scipy.spatial

import cudahull

PUBLIC = ["BatchHulls", "ConvexHull", "DeviceError", "Engine", "InputError", "QhullError", "SWAP_KINDS",
          "convex_hull", "convex_hull_batch", "release_device_memory"]


def run_python(code, **env_changes):
    env = dict(os.environ, **env_changes)
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, env=env,
                          timeout=300)


def test_the_face_shows_only_the_public_names():
    assert sorted(cudahull.__all__) == sorted(PUBLIC)
    # The public names and the public submodules (cudahull.dask is there once someone imported it).
    shown = {name for name in dir(cudahull) if not name.startswith("_")} - {"dask"}
    assert shown == set(PUBLIC) | {"qhull_options"}
    # Each name is the package's own object: a class or function of cudahull, or the swap kinds' names.
    for name in PUBLIC:
        value = getattr(cudahull, name)
        if name == "SWAP_KINDS":
            assert isinstance(value, tuple) and value and all(isinstance(kind, str) for kind in value), value
        else:
            assert callable(value) and value.__module__.partition(".")[0] == "cudahull", (name, value)
    with pytest.raises(AttributeError, match="no attribute 'np'"):
        cudahull.np


def test_every_public_name_has_a_numpydoc_docstring():
    sections = {"function": ("Parameters", "Returns"), "class": ("Parameters", "Attributes")}
    for name in PUBLIC:
        if name == "SWAP_KINDS":  # a tuple of names: documented in the package's docstring
            assert "SWAP_KINDS" in cudahull.__doc__
            continue
        thing = getattr(cudahull, name)
        doc = inspect.getdoc(thing)
        assert doc and doc.splitlines()[0].strip(), name
        if inspect.isclass(thing) and issubclass(thing, BaseException):
            continue  # an error: a summary and what it subclasses
        kind = "class" if inspect.isclass(thing) else "function"
        wanted = sections[kind] if name not in ("BatchHulls", "release_device_memory") else ()
        for section in wanted:
            assert f"{section}\n{'-' * len(section)}" in doc, (name, section)
        if kind == "class":  # and its public methods
            for method_name, method in inspect.getmembers(thing, inspect.isfunction):
                if not method_name.startswith("_"):
                    assert inspect.getdoc(method), f"{name}.{method_name}"
    # No user-facing text cites an issue number.
    for module in ("__init__", "_arrays", "_batch", "_engine", "_errors", "_hull", "_hull_call", "_option_results",
                   "_qhull", "dask", "qhull_options"):
        with open(os.path.join(os.path.dirname(cudahull.__file__), module + ".py")) as source:
            assert "issue " not in source.read().lower(), module


def test_import_leaves_scipy_spatial_alone_until_a_qhull_error_is_needed():
    run = run_python("""
        import sys
        import cudahull
        assert 'scipy.spatial' not in sys.modules, 'imported by cudahull'
        import numpy as np
        cudahull.ConvexHull(np.random.default_rng(0).normal(size=(50, 3)))
        cudahull.convex_hull_batch([np.eye(3), np.ones((4, 3))], backend='cpu')
        assert 'scipy.spatial' not in sys.modules, 'imported by a hull'
        try:
            cudahull.ConvexHull(np.zeros((5, 3)))
        except Exception as error:
            import scipy.spatial
            assert isinstance(error, scipy.spatial.QhullError), type(error).__mro__
        else:
            raise AssertionError('no error for flat input')
        print('ok')
    """)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stderr
    asked = run_python("""
        import sys
        import cudahull
        error = cudahull.QhullError
        assert 'scipy.spatial' in sys.modules
        import scipy.spatial
        assert issubclass(error, scipy.spatial.QhullError)
        print('ok')
    """)
    assert asked.returncode == 0 and asked.stdout.strip() == "ok", asked.stderr


def test_qhull_error_is_scipys_and_one_class():
    with pytest.raises(scipy.spatial.QhullError) as raised:
        cudahull.ConvexHull(np.zeros((5, 3)))
    assert isinstance(raised.value, cudahull.QhullError)
    assert type(raised.value) is cudahull.QhullError  # built once, the same class every time
    assert issubclass(cudahull.QhullError, RuntimeError)
    copy = pickle.loads(pickle.dumps(raised.value))
    assert type(copy) is cudahull.QhullError and str(copy) == str(raised.value)
    try:
        cudahull.ConvexHull(np.zeros((5, 3)))
    except scipy.spatial.QhullError:  # code written for scipy catches it
        pass


def test_without_scipy():
    # scipy made unimportable: the exact engines work, QhullError is a RuntimeError, 4-D says what is missing.
    run = run_python("""
        import sys
        sys.modules['scipy'] = None
        import numpy as np
        import cudahull
        hull = cudahull.ConvexHull(np.random.default_rng(0).normal(size=(50, 3)))
        assert hull.backend.split()[0] in ('cpu', 'cuda') and len(hull.vertices) > 4
        assert cudahull.QhullError.__bases__ == (RuntimeError,)
        try:
            cudahull.ConvexHull([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 3, 0]])
        except cudahull.QhullError as error:
            assert str(error).startswith('QH6154 Qhull precision error: Initial simplex is flat'), error
        else:
            raise AssertionError('no error for flat input')
        try:
            cudahull.ConvexHull(np.random.default_rng(0).normal(size=(50, 4)))
        except ValueError as error:
            print(error)
        else:
            raise AssertionError('no error for 4-D points without scipy')
    """)
    assert run.returncode == 0, run.stderr
    assert "4-dimensional" in run.stdout and "scipy's Qhull, which is not installed (pip install scipy)" in run.stdout


def test_the_extensions_stub_is_shipped_and_current(tmp_path):
    """_cudahull.pyi, generated by nanobind's stubgen at build time, beside the extension; generated again
    here from the imported extension it must be the same text."""
    pytest.importorskip("nanobind.stubgen")  # python/requirements-test.txt pins nanobind
    folder = os.path.dirname(cudahull._cudahull.__file__)
    shipped = os.path.join(folder, "_cudahull.pyi")
    assert os.path.exists(shipped), "no _cudahull.pyi beside the extension"
    fresh = tmp_path / "_cudahull.pyi"
    # As python/CMakeLists.txt runs it: the extension imported as the top-level module _cudahull.
    run = subprocess.run([sys.executable, "-m", "nanobind.stubgen", "-q", "-i", folder, "-m", "_cudahull", "-o",
                          str(fresh)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    with open(shipped) as old:
        assert fresh.read_text() == old.read(), "the shipped _cudahull.pyi is stale: rebuild the target _cudahull"
    text = fresh.read_text()
    for name in ("def convex_hull(", "def convex_hull_batch(", "class Engine", "class InputError",
                 "class DeviceError", "SWAP_KINDS"):
        assert name in text, name


USER_CODE = '''
from __future__ import annotations

import numpy as np
import numpy.typing as npt

import cudahull


def volumes(clouds: list[npt.NDArray[np.float64]]) -> npt.NDArray[np.float64]:
    hulls: cudahull.BatchHulls = cudahull.convex_hull_batch(clouds, backend="cpu")
    return np.asarray(hulls.volumes, dtype=np.float64)


def hull_volume(points: npt.NDArray[np.float64]) -> float:
    try:
        hull = cudahull.ConvexHull(points, qhull_options="QbB Pp Qt")
    except cudahull.QhullError as error:
        raise ValueError(str(error)) from error
    vertices: npt.NDArray[np.intc] = hull.vertices
    assert vertices.ndim == 1 and hull.backend != ""
    hull.add_points(points[:2])
    return hull.volume


def corners(points: npt.NDArray[np.float64]) -> list[int]:
    result = cudahull.convex_hull(points, backend="cpu", tolerance="qhull")
    return [int(i) for i in result["polygon"]]


engine = cudahull.Engine(np.zeros((4, 3)))
records: list[dict[str, object]] = engine.run()
kinds: tuple[str, ...] = cudahull.SWAP_KINDS
'''

BAD_USER_CODE = '''
import cudahull

hull = cudahull.ConvexHull([[0.0, 0, 0]], qhull_options=3)
volume: str = hull.volume
'''


def run_mypy(tmp_path, code):
    pytest.importorskip("mypy")  # python/requirements-test.txt pins it
    path = tmp_path / "user_code.py"
    path.write_text(code)
    # mypy finds the package on the interpreter's sys.path, as an installed typed package: the folder of the
    # package imported here goes first on PYTHONPATH (absolute: mypy runs in tmp_path).
    parent = os.path.dirname(os.path.dirname(os.path.abspath(cudahull.__file__)))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([parent] + [os.path.abspath(p) for p in os.environ.get(
        "PYTHONPATH", "").split(os.pathsep) if p]))
    return subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "--cache-dir", os.devnull,
                           str(path)], capture_output=True, text=True, timeout=600, cwd=tmp_path, env=env)


def test_mypy_strict_checks_code_using_the_package(tmp_path):
    run = run_mypy(tmp_path, USER_CODE)
    assert run.returncode == 0, run.stdout + run.stderr
    # And it sees the types: wrong code fails.
    bad = run_mypy(tmp_path, BAD_USER_CODE)
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert 'Argument "qhull_options" to "ConvexHull" has incompatible type "int"' in bad.stdout, bad.stdout
    assert 'Incompatible types in assignment (expression has type "float", variable has type "str")' in bad.stdout


def test_the_package_itself_passes_mypy_strict(tmp_path):
    """The package's own modules, checked as user code is (the generated stub's bare dict and tuple types are
    nanobind's: only its generics check is relaxed)."""
    pytest.importorskip("mypy")  # python/requirements-test.txt pins it
    config = tmp_path / "mypy.ini"
    config.write_text("[mypy]\nstrict = True\n\n[mypy-cudahull._cudahull]\ndisallow_any_generics = False\n")
    parent = os.path.dirname(os.path.dirname(os.path.abspath(cudahull.__file__)))
    # A build tree is named through MYPYPATH; an installed package (the wheel's test) is found as installed,
    # and mypy refuses site-packages on MYPYPATH.
    env = dict(os.environ)
    if os.path.basename(parent) != "site-packages":
        env["MYPYPATH"] = parent
    run = subprocess.run([sys.executable, "-m", "mypy", "--config-file", str(config), "--no-incremental",
                          "--cache-dir", os.devnull, "-p", "cudahull"], capture_output=True, text=True, timeout=600,
                         cwd=tmp_path, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
