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
from cudahull_in_scipys_place import FACET_ORDER_REASON, FACET_ORDER_TESTS, SELECTION  # noqa: E402


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
    counts = {word: int(number)
              for number, word in re.findall(r"(\d+) (passed|xfailed|xpassed|failed|error)", summary)}
    assert "failed" not in counts and "error" not in counts and "xpassed" not in counts, summary
    # Every expected failure, counted by its reason (-rx lists "XFAIL id - reason"): with scipy 1.17.1
    # (python/requirements-test.txt) the 8 tests that assert Qhull's facet order, and no other.
    reasons: dict[str, list[str]] = {}
    for nodeid, reason in re.findall(r"^XFAIL \S*?::(\S+) - (.*)$", report, re.MULTILINE):
        reasons.setdefault(reason, []).append(nodeid)
    assert {reason: sorted(ids) for reason, ids in reasons.items()} == {FACET_ORDER_REASON: sorted(FACET_ORDER_TESTS)}
    assert counts.get("xfailed") == 8, summary
    # The passes, by what hulled their points (the plugin's count): 4-D to 8-D points go to scipy's Qhull.
    passes = re.search(r"^cudahull_in_scipys_place: passed (\d+) through cudahull, (\d+) through Qhull, "
                       r"(\d+) with no hull$", report, re.MULTILINE)
    assert passes is not None, report[-3000:]
    assert tuple(map(int, passes.groups())) == (37, 20, 2), passes.group(0)
    assert counts.get("passed") == 59, summary
