"""Points of 4 to 8 dimensions: ConvexHull and convex_hull() give scipy's answer through Qhull (backend
"qhull"), attribute for attribute, with incremental hulls and add_points, against scipy.spatial.ConvexHull
called directly."""

import numpy as np
import pytest
import scipy.spatial

import cudahull

DIMENSIONS = [4, 5, 6, 7, 8]
ATTRIBUTES = ("points", "vertices", "simplices", "neighbors", "equations", "coplanar", "min_bound", "max_bound")


def cloud(dimension, n=None, seed=0):
    rng = np.random.default_rng(seed + dimension)
    return rng.normal(size=(n or 3 * dimension + 20, dimension))


def assert_same_as_scipy(ours, theirs):
    assert ours.backend == "qhull" and ours.precision == "double" and ours.stats is None
    for name in ATTRIBUTES:
        np.testing.assert_array_equal(getattr(ours, name), getattr(theirs, name), err_msg=name)
    assert (ours.volume, ours.area) == (theirs.volume, theirs.area)
    assert (ours.npoints, ours.ndim, ours.nsimplex) == (theirs.npoints, theirs.ndim, theirs.nsimplex)
    if theirs.good is None:
        assert ours.good is None
    else:
        np.testing.assert_array_equal(ours.good, theirs.good)


@pytest.mark.parametrize("dimension", DIMENSIONS)
def test_convex_hull_is_scipys(dimension):
    points = cloud(dimension)
    hull = cudahull.ConvexHull(points)
    assert_same_as_scipy(hull, scipy.spatial.ConvexHull(points))
    assert hull.dimension == dimension and len(hull.vertices) > dimension
    # The measures are right, not only equal: a cube's, scaled.
    cube = np.array(np.meshgrid(*[[0.0, 2.0]] * dimension)).reshape(dimension, -1).T
    boxed = cudahull.ConvexHull(np.vstack([cube, np.ones((1, dimension))]))
    assert boxed.volume == pytest.approx(2.0**dimension) and boxed.area == pytest.approx(2 * dimension * 2.0**(dimension - 1))
    assert sorted(boxed.vertices.tolist()) == list(range(2**dimension))


@pytest.mark.parametrize("options", ["QG0", "QG-3", "Qc", "QJ", "Qx Qt", "QbB"])
def test_qhull_options_go_to_qhull(options):
    points = cloud(5, 60)
    assert_same_as_scipy(cudahull.ConvexHull(points, qhull_options=options),
                         scipy.spatial.ConvexHull(points, qhull_options=options))


@pytest.mark.parametrize("dimension", [4, 6])
def test_incremental_add_points_is_scipys(dimension):
    first, more, last = cloud(dimension, 30, 1), cloud(dimension, 25, 2) * 1.5, cloud(dimension, 10, 3) * 3
    ours = cudahull.ConvexHull(first, incremental=True)
    theirs = scipy.spatial.ConvexHull(first, incremental=True)
    for batch, restart in ((more, False), (last, True)):
        ours.add_points(batch, restart=restart)
        theirs.add_points(batch, restart=restart)
        assert_same_as_scipy(ours, theirs)
    ours.close()
    with pytest.raises(RuntimeError, match="closed"):
        ours.add_points(last)


def test_add_points_without_incremental_is_the_hull_of_all_the_points():
    first, more = cloud(4, 30, 4), cloud(4, 30, 5) * 2
    hull = cudahull.ConvexHull(first)
    hull.add_points(more)
    assert_same_as_scipy(hull, scipy.spatial.ConvexHull(np.vstack([first, more])))
    with pytest.raises(ValueError, match=r"add_points takes \(m, 4\) points"):
        hull.add_points(np.zeros((3, 3)))


@pytest.mark.parametrize("dimension", DIMENSIONS)
def test_convex_hull_dict_is_scipys(dimension):
    points = cloud(dimension).astype(np.float32)  # Qhull computes in double, as scipy
    result = cudahull.convex_hull(points)
    theirs = scipy.spatial.ConvexHull(points)
    assert result["backend"] == "qhull" and result["dimension"] == result["input_dimension"] == dimension
    assert result["vertices"].tolist() == theirs.vertices.tolist()
    assert result["simplices"].tolist() == theirs.simplices.tolist()
    np.testing.assert_array_equal(result["equations"], theirs.equations)
    assert (result["volume"], result["area"]) == (theirs.volume, theirs.area)
    assert result["polygon"].size == 0


def test_errors_are_qhulls_and_catchable_as_either():
    flat = np.column_stack([cloud(4, 20)[:, :3], np.zeros(20)])
    with pytest.raises(scipy.spatial.QhullError) as theirs:
        scipy.spatial.ConvexHull(flat)
    for compute in (cudahull.ConvexHull, cudahull.convex_hull):
        with pytest.raises(cudahull.QhullError) as ours:
            compute(flat)
        assert isinstance(ours.value, scipy.spatial.QhullError)
        assert str(ours.value).split("\n")[0] == str(theirs.value).split("\n")[0]
    with pytest.raises(cudahull.QhullError, match="^QH6214 qhull input error: not enough points"):
        cudahull.ConvexHull(cloud(5, 4))
    with pytest.raises(ValueError, match="No points given"):  # scipy's
        cudahull.ConvexHull(np.zeros((0, 5)))


def test_what_only_the_exact_engines_do_is_refused():
    points = cloud(4)
    for arguments, words in [(dict(backend="cuda"), "backend must be 'auto' or 'cpu'"),
                             (dict(precision="float"), "precision must be 'auto' or 'double'"),
                             (dict(engine="resident"), "engine must be 'auto'"),
                             (dict(tolerance=0.01), "tolerance must be None or 'qhull'")]:
        with pytest.raises(ValueError, match="4-D points are hulled by scipy's Qhull.*" + words):
            cudahull.ConvexHull(points, **arguments)
        with pytest.raises(ValueError, match=words):
            cudahull.convex_hull(points, **arguments)
    # The engines' own dimensions are unchanged.
    assert cudahull.ConvexHull(cloud(4)[:, :3]).backend != "qhull"
    with pytest.raises(ValueError, match=r"must be an \(n, 3\) array"):
        cudahull.convex_hull_batch([cloud(4)])


def test_4d_with_cudahull_in_scipys_place(monkeypatch):
    """A client that swaps scipy.spatial.ConvexHull for cudahull's (trimesh's own tests do) still gets
    Qhull's 4-D hull, not cudahull calling itself until RecursionError."""
    points = np.random.default_rng(0).random((100, 4))
    expected = scipy.spatial.ConvexHull(points)
    monkeypatch.setattr(scipy.spatial, "ConvexHull", cudahull.ConvexHull)
    monkeypatch.setattr(scipy.spatial._qhull, "ConvexHull", cudahull.ConvexHull)
    hull = scipy.spatial.ConvexHull(points)
    assert hull.backend == "qhull"
    assert np.array_equal(np.sort(hull.vertices), np.sort(expected.vertices))
    assert hull.volume == pytest.approx(expected.volume, rel=1e-12)
