"""A pytest plugin that puts cudahull.ConvexHull in scipy's place for scipy's own test_qhull.py.

scipy's tests call ``scipy.spatial._qhull.ConvexHull`` through the module (``qhull.ConvexHull(...)``), so
replacing that attribute before they run is enough; scipy's Delaunay, which some of them compare against,
stays scipy's.  The tests that cannot pass are marked strict xfail here, each with its reason: one that
starts passing fails the run, so this list stays true.
"""

import pytest
import scipy.spatial._qhull as qhull

import cudahull

# The ConvexHull tests of test_qhull.py (TestConvexHull and TestUtilities' volume and area tests).
SELECTION = ("TestConvexHull or test_volume_area or test_random_volume_area or "
             "test_incremental_volume_area_random_input")

FACET_ORDER_REASON = ("asserts the order in which Qhull lists its facets (good[k] of the k-th simplex), an artefact "
                "of Qhull's construction; cudahull's good marks the same facets, listed counter-clockwise")


# Each test that asserts Qhull's facet order, by name: its expected `good` has a True at a place fixed by the
# order in which Qhull lists its facets.  (The other `good` tests expect no facet good, which any order gives,
# and test_good3d's order happens to agree.)  Every other selected test passes, 4-D to 8-D ones included.
FACET_ORDER_TESTS = (
    "TestConvexHull::test_good2d[False]",
    "TestConvexHull::test_good2d[True]",
    "TestConvexHull::test_good2d_incremental_changes[new_gen1-expected1-QG4]",
    "TestConvexHull::test_good2d_incremental_changes[new_gen1-expected1-QG-4]",
    "TestConvexHull::test_good2d_incremental_changes[new_gen2-expected2-QG4]",
    "TestConvexHull::test_good2d_incremental_changes[new_gen2-expected2-QG-4]",
    "TestConvexHull::test_good2d_incremental_changes[new_gen3-expected3-QG4]",
    "TestConvexHull::test_good2d_incremental_changes[new_gen3-expected3-QG-4]",
)


def expected_failure(nodeid):
    """The reason a test is expected to fail with cudahull in scipy's place, or None."""
    if nodeid.split("::", 1)[-1] in FACET_ORDER_TESTS:
        return FACET_ORDER_REASON, AssertionError
    return None


# Which backends each test's hulls ran on (hull.backend: "qhull" for 4-D and up), by test id, so that the run
# reports how many passed through Qhull and how many through cudahull's engines (test_scipy_suite.py checks).
_backends: dict[str, set[str]] = {}
_current = [""]
_passed: dict[str, int] = {}


class _RecordingConvexHull(cudahull.ConvexHull):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        _backends.setdefault(_current[0], set()).add("qhull" if self.backend == "qhull" else "engines")


def pytest_configure(config):
    qhull.ConvexHull = _RecordingConvexHull


def pytest_runtest_setup(item):
    _current[0] = item.nodeid


def pytest_runtest_logreport(report):
    if report.when == "call" and report.passed and not hasattr(report, "wasxfail"):
        ran = _backends.get(report.nodeid, set())
        kind = "through Qhull" if ran == {"qhull"} else "through cudahull" if "engines" in ran else "with no hull"
        _passed[kind] = _passed.get(kind, 0) + 1


def pytest_terminal_summary(terminalreporter):
    counts = ", ".join(f"{_passed.get(kind, 0)} {kind}" for kind in ("through cudahull", "through Qhull",
                                                                         "with no hull"))
    terminalreporter.write_line(f"cudahull_in_scipys_place: passed {counts}")


def pytest_collection_modifyitems(config, items):
    for item in items:
        expected = expected_failure(item.nodeid)
        if expected is not None:
            reason, raises = expected
            item.add_marker(pytest.mark.xfail(reason=reason, raises=raises, strict=True))
