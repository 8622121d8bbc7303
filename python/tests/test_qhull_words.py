"""Degenerate input gets Qhull's code and words, as scipy raises them for the same points (clients match
them: scikit-image matches "Qhull precision error: Initial simplex is flat"); and under QbB / Qbb / Qbk:n /
QBk:n the volume and area are scipy's, those of the points as Qhull scales them."""

import numpy as np
import pytest
import scipy.spatial

import cudahull

rng = np.random.default_rng(42)


def with_axes(points, **fixed):
    points = points.copy()
    for axis, value in fixed.items():
        points[:, "xyz".index(axis)] = value
    return points


DEGENERATE = {
    "flat on z=0": with_axes(rng.random((10, 3)), z=0.0),
    "flat on y=5": with_axes(rng.random((10, 3)), y=5.0),
    "flat, tilted": rng.integers(-9, 9, size=(10, 2)) @ np.array([[1, 0, 1.0], [0, 1, 2.0]]),  # exactly
    "flat on x=5": with_axes(rng.random((10, 3)), x=5.0),
    "flat on x=-3": with_axes(rng.random((10, 3)), x=-3.0),
    "flat on x=0": with_axes(rng.random((10, 3)), x=0.0),
    "collinear": np.outer(rng.random(10), [1, 2, 3.0]),
    "collinear along x": with_axes(rng.random((10, 3)), y=0.0, z=0.0),
    "collinear, x and y fixed": with_axes(rng.random((10, 3)), x=5.0, y=7.0),
    "coincident": np.ones((10, 3)),
    "coincident at 0": np.zeros((10, 3)),
    "four coplanar": np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]]),
    "one point": rng.random((1, 3)),
    "two points": rng.random((2, 3)),
    "three points": rng.random((3, 3)),
    "2-D collinear": np.outer(rng.random(10), [1, 2.0]),
    "2-D on y=0": np.column_stack([rng.random(10), np.zeros(10)]),
    "2-D on x=5": np.column_stack([np.full(10, 5.0), rng.random(10)]),
    "2-D coincident": np.ones((10, 2)),
    "2-D two points": rng.random((2, 2)),
}


def scipys_error(points, options=None):
    with pytest.raises(scipy.spatial.QhullError) as raised:
        scipy.spatial.ConvexHull(points, qhull_options=options)
    return str(raised.value)


def ours(points, options=None):
    with pytest.raises(cudahull.QhullError) as raised:
        cudahull.ConvexHull(points, qhull_options=options)
    assert isinstance(raised.value, scipy.spatial.QhullError)
    return str(raised.value)


def expected_head(message):
    """What of Qhull's message we reproduce: its first line, but for QH6154 the words before Qhull's
    parenthesis (it names Qhull's own facet), and for QH6022 its first two lines."""
    lines = message.split("\n")
    if lines[0].startswith("QH6154"):
        return lines[0].split(" (")[0]
    if lines[0].startswith("QH6022"):
        return "\n".join(lines[:2])
    return lines[0]


@pytest.mark.parametrize("options", [None, "Qt", "Qc", "QbB Pp Qt"])
@pytest.mark.parametrize("case", list(DEGENERATE))
def test_degenerate_input_gets_scipys_code_and_words(case, options):
    points = DEGENERATE[case]
    theirs = scipys_error(points, options)
    mine = ours(points, options)
    assert mine.split()[0] == theirs.split()[0], (mine, theirs)  # Qhull's code
    assert mine.startswith(expected_head(theirs)), (mine, theirs)


def test_scikit_images_match_is_met():
    # scikit-image's convex_hull_image warns with the error's text, and its tests match this, case-sensitively.
    flat_image_points = np.array([[r, c, 3.0] for r in range(1, 5) for c in range(1, 5)])
    assert "Qhull precision error: Initial simplex is flat" in ours(flat_image_points)
    assert "Qhull precision error: Initial simplex is flat" in scipys_error(flat_image_points)


def test_the_lower_dimensional_answer_stays_convex_hulls():
    for case, points in DEGENERATE.items():
        if len(points) > points.shape[1]:
            hull = cudahull.convex_hull(points, backend="cpu")
            assert hull["dimension"] < points.shape[1], case


# --- QbB's measures ----------------------------------------------------------------------------------------

SCALINGS = ["QbB", "Qbb", "QbB Pp Qt", "Qt QbB", "Qb0:-2 QB0:3", "QB1:7", "Qb1", "Qbb Qc"]


@pytest.mark.parametrize("options", SCALINGS)
@pytest.mark.parametrize("dimension", [2, 3])
def test_measures_under_qhulls_scaling_are_scipys(options, dimension):
    points = np.random.default_rng(dimension).normal(size=(300, dimension)) * [2, 30, 0.5][:dimension] + 7
    # A copy for scipy: under Qbb, Qhull scales the last coordinate of scipy's input in place.
    theirs = scipy.spatial.ConvexHull(points.copy(), qhull_options=options)
    mine = cudahull.ConvexHull(points, qhull_options=options, backend="cpu")
    assert mine.volume == pytest.approx(theirs.volume, rel=1e-9)
    assert mine.area == pytest.approx(theirs.area, rel=1e-9)
    assert sorted(mine.vertices.tolist()) == sorted(theirs.vertices.tolist())
    # The true measures without the options, and the equations stay in the input's coordinates.
    true = scipy.spatial.ConvexHull(points)
    exact = cudahull.ConvexHull(points, backend="cpu")
    assert exact.volume == pytest.approx(true.volume, rel=1e-12) and exact.volume != pytest.approx(mine.volume)
    heights = points @ mine.equations[:, :-1].T + mine.equations[:, -1]
    assert heights.max() <= 1e-9 * np.abs(points).max()


def test_a_bound_for_an_axis_beyond_the_points_is_qhulls_error():
    points = np.random.default_rng(0).normal(size=(20, 2))
    assert ours(points, "QB2:7").split("\n")[0] == scipys_error(points, "QB2:7").split("\n")[0]


def test_qhulls_projection_has_no_defined_behaviour():
    with pytest.raises(cudahull.QhullError, match="has no defined behaviour"):
        cudahull.ConvexHull(np.random.default_rng(0).normal(size=(20, 3)), qhull_options="Qb1:0B1:0")


def test_qj_on_flat_points_gives_qhulls_thin_hull():
    """QJ asks Qhull to joggle: flat points then get a thin full-dimensional hull, not an error (trimesh
    retries a flat mesh's hull with QJ).  Each corner of the flat polygon stays a vertex."""
    points = np.random.default_rng(0).random((200, 3)) * 1000 + 5
    points[:, 2] = 7.0
    theirs = scipy.spatial.ConvexHull(points, qhull_options="QJ")
    ours = cudahull.ConvexHull(points, qhull_options="QJ")
    corners = scipy.spatial.ConvexHull(points[:, :2]).vertices
    assert set(corners) <= set(ours.vertices.tolist())
    for hull in (ours, theirs):  # thin: a joggle's thickness under the polygon's two sides
        assert 0 < hull.volume < 1e-6 * hull.area ** 1.5
    assert ours.area == pytest.approx(theirs.area, rel=1e-6)  # both sides of the flat polygon
    assert np.array_equal(ours.points, points)
    with pytest.raises(cudahull.QhullError, match="QH6154"):
        cudahull.ConvexHull(points)  # without QJ: the flat input's error, as Qhull's
