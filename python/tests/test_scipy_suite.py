"""scipy's own ConvexHull tests, from the installed scipy (scipy/spatial/tests/test_qhull.py, not copied),
run with cudahull.ConvexHull in scipy's place (scipy_suite/cudahull_in_scipys_place.py says how, and lists
the tests that cannot pass, each with its reason, as strict xfails)."""

import os
import re
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "scipy_suite"))
from cudahull_in_scipys_place import SELECTION  # noqa: E402


def test_scipys_convex_hull_tests_pass_with_cudahull_in_its_place():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [os.path.join(HERE, "scipy_suite"), env.get("PYTHONPATH")]))
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "cudahull_in_scipys_place",
         "-rxX", "--pyargs", "scipy.spatial.tests.test_qhull", "-k", SELECTION],
        capture_output=True, text=True, env=env, timeout=600)
    report = run.stdout + run.stderr
    assert run.returncode == 0, report[-6000:]
    summary = report.strip().splitlines()[-1]
    passed = int(re.search(r"(\d+) passed", summary).group(1))
    # TestConvexHull's 2-D and 3-D tests, incremental ones included: well over a hundred run and pass.
    assert passed >= 100, summary
    assert "failed" not in summary and "error" not in summary, summary
