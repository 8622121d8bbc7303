"""The Python programs in examples/, run as a user runs them (a subprocess, the module found on PYTHONPATH as
the test run finds it), their output checked against scipy; and mypy in strict mode on them."""

import glob
import importlib.util
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial import ConvexHull as ScipyHull

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
ASSETS = os.path.join(EXAMPLES, "..", "assets")


def run_example(name, *arguments):
    """The example's stdout; it must exit 0."""
    result = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *arguments], capture_output=True,
                            text=True, timeout=600, env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
    assert result.returncode == 0, f"{name} exited {result.returncode}\n{result.stdout}\n{result.stderr}"
    return result.stdout


def example_module(name):
    """An example imported as a module (its main() not run), for the data it made."""
    spec = importlib.util.spec_from_file_location(f"example_{name}", os.path.join(EXAMPLES, f"{name}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_batch_volumes_agrees_with_scipy():
    output = run_example("batch_volumes.py")
    example = example_module("batch_volumes")
    points, lengths = example.random_clouds()
    expected = [ScipyHull(points[c, :lengths[c]]).volume for c in range(len(lengths))]

    assert re.search(r"^numpy: 10000 clouds of 6 to 40 points, their volumes in one call: ", output, re.M), output
    shown = re.findall(r"^cloud (\d+): (\d+) points, (\d+) hull vertices, volume (\S+)$", output, re.M)
    assert len(shown) == 5, output
    for cloud, count, vertices, volume in shown:
        c = int(cloud)
        scipy_hull = ScipyHull(points[c, :lengths[c]])
        assert int(count) == lengths[c]
        assert int(vertices) == len(scipy_hull.vertices)
        assert float(volume) == pytest.approx(scipy_hull.volume, rel=1e-12)
    total = float(re.search(r"^total volume (\S+)$", output, re.M).group(1))
    assert total == pytest.approx(np.sum(expected), rel=1e-12)
    assert re.search(r"^scipy: clouds 0 to 19 checked, largest relative difference ", output, re.M), output
    assert re.search(r"^torch: not installed, skipped$|^torch \((cpu|cuda)\): 10000 volumes, the same as NumPy's: "
                     r"True$", output, re.M), output


def test_trimesh_hull_agrees_with_scipy():
    trimesh = pytest.importorskip("trimesh")  # python/requirements-test.txt pins it
    output = run_example("trimesh_hull.py")
    points = np.asarray(trimesh.load_mesh(os.path.join(ASSETS, "bun_zipper.ply")).vertices, dtype=np.float64)
    # What stock trimesh asks scipy for (trimesh.convex.convex_hull's options), whose vertex set the merged
    # hull has; its measures (trimesh computes them from the hull's triangles) are the hull's in the input's
    # coordinates, where scipy's under QbB are those of the scaled points: against scipy without QbB.
    merged = ScipyHull(points, qhull_options="QbB Pp Qt")
    unscaled = ScipyHull(points, qhull_options="Qt")
    exact = ScipyHull(points)

    hull = re.search(r"^convex hull: (\d+) vertices, (\d+) faces, watertight True, convex True$", output, re.M)
    assert hull, output
    # Merged as Qhull merges: the same vertices, or one fewer where Qhull's roundoff in the unit box keeps a
    # point proud of a face (python/tests/test_trimesh.py).
    assert len(merged.vertices) - 1 <= int(hull.group(1)) <= len(merged.vertices)
    measures = re.search(r"^hull volume (\S+), area (\S+)$", output, re.M)
    assert float(measures.group(1)) == pytest.approx(unscaled.volume, rel=1e-9)
    assert float(measures.group(2)) == pytest.approx(unscaled.area, rel=1e-9)
    direct = re.search(r"^cudahull.ConvexHull directly \(exact\): (\d+) vertices, volume (\S+)$", output, re.M)
    # The exact hull keeps every strictly extreme point: at least the vertices Qhull's merging keeps.
    assert int(direct.group(1)) >= len(exact.vertices)
    assert float(direct.group(2)) == pytest.approx(exact.volume, rel=1e-9)


def test_examples_pass_mypy_strict(tmp_path):
    pytest.importorskip("mypy")  # python/requirements-test.txt pins it
    examples = sorted(glob.glob(os.path.join(EXAMPLES, "*.py")))
    assert examples
    # The module as the examples' runs find it: on PYTHONPATH (the build tree), an installed package to mypy.
    result = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-color-output", "--cache-dir",
                             str(tmp_path / "mypy-cache"), *examples], capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, f"mypy --strict on examples/:\n{result.stdout}\n{result.stderr}"
