"""cudahull.ConvexHull against scipy.spatial.ConvexHull (Qhull) and against geometry known by construction."""

import subprocess

import numpy as np
import pytest
import scipy.spatial

import cudahull

CUBE = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])


def random_sets():
    rng = np.random.default_rng(16)
    sphere = rng.normal(size=(500, 3))
    sphere /= np.linalg.norm(sphere, axis=1, keepdims=True)
    return {
        "gauss": rng.normal(size=(3000, 3)),
        "cube": rng.uniform(-1, 1, size=(3000, 3)),
        "sphere": sphere,  # every point a vertex
        "ball_shifted": rng.uniform(-1, 1, size=(2000, 3)) * [1e3, 1, 1e-3] + [1e6, -5, 7],
        "few": rng.normal(size=(12, 3)),
    }


RANDOM_SETS = random_sets()


def oriented_triangles(simplices):
    """Each triangle as its rotation starting at its smallest index (orientation kept), as a set."""
    out = set()
    for t in simplices.tolist():
        k = t.index(min(t))
        out.add(tuple(t[k:] + t[:k]))
    return out


def unordered_triangles(simplices):
    return {tuple(sorted(t)) for t in simplices.tolist()}


def assert_consistent(hull):
    """Closed, consistently oriented, outward triangles; neighbours opposite their vertex; every point below
    or on every plane; vertices exactly the corners used."""
    s, n, eq = hull.simplices, hull.neighbors, hull.equations
    assert s.dtype == np.int32 and n.dtype == np.int32 and s.shape == n.shape == (hull.nsimplex, 3)
    assert eq.shape == (hull.nsimplex, 4)
    assert np.array_equal(np.unique(s), hull.vertices)
    directed = {}
    for f, (a, b, c) in enumerate(s.tolist()):
        for edge in ((a, b), (b, c), (c, a)):
            assert edge not in directed, f"directed edge {edge} twice: not a consistently oriented 2-manifold"
            directed[edge] = f
    assert all((b, a) in directed for a, b in directed), "an edge with one face: not closed"
    v, e, f = len(hull.vertices), len(directed) // 2, hull.nsimplex
    assert v - e + f == 2
    for f, tri in enumerate(s.tolist()):
        for k in range(3):
            g = n[f, k]
            opposite_edge = {tri[(k + 1) % 3], tri[(k + 2) % 3]}
            assert opposite_edge <= set(s[g].tolist()), f"neighbour {k} of face {f} does not share its edge"
            assert tri[k] not in s[g]
            # ... and g's neighbour opposite its third vertex is f.
            third = [x for x in s[g].tolist() if x not in opposite_edge][0]
            assert n[g, s[g].tolist().index(third)] == f
    pts = hull.points.astype(np.float64)
    a, b, c = pts[s[:, 0]], pts[s[:, 1]], pts[s[:, 2]]
    # Counter-clockwise from outside: the corners' cross product points along the outward normal.
    assert np.all(np.einsum("ij,ij->i", np.cross(b - a, c - a), eq[:, :3]) > 0)
    assert np.allclose(np.linalg.norm(eq[:, :3], axis=1), 1, atol=1e-14)
    scale = np.abs(pts).max()
    heights = pts @ eq[:, :3].T + eq[:, 3]
    assert heights.max() <= 1e-12 * scale, "a point above a face's plane"
    centroid = pts[hull.vertices].mean(axis=0)
    assert np.all(centroid @ eq[:, :3].T + eq[:, 3] < 0), "a plane facing inward"


def test_unit_cube():
    for dtype in (np.float64, np.float32):
        hull = cudahull.ConvexHull(CUBE.astype(dtype), backend="cpu")
        assert hull.volume == 1.0 and hull.area == 6.0
        assert hull.vertices.tolist() == list(range(8)) and hull.vertices.dtype == np.int32
        assert hull.nsimplex == 12 and hull.npoints == 8 and hull.ndim == 3 and hull.dimension == 3
        assert hull.min_bound.tolist() == [0, 0, 0] and hull.max_bound.tolist() == [1, 1, 1]
        assert hull.coplanar.shape == (0, 3) and hull.coplanar.dtype.kind == "i"
        assert hull.good is None
        assert_consistent(hull)


def test_the_hull_says_how_it_ran():
    # The plan's line (engine, backend, precision, each with its reason), as the command line's --stats says.
    hull = cudahull.ConvexHull(CUBE.astype(np.float32), backend="cpu", engine="resident")
    assert hull.plan.startswith("resident engine (as requested); backend cpu (as requested); precision float")
    assert hull.stats is not None and hull.stats["plan"] == hull.plan
    flat = cudahull.convex_hull(CUBE[:, :2], backend="cpu", precision="double")
    assert flat["plan"].startswith("2-D input: the planar hull") and "precision double (as requested)" in flat["plan"]
    assert cudahull.ConvexHull(np.random.default_rng(1).normal(size=(30, 4))).plan.startswith("scipy's Qhull")


@pytest.mark.parametrize("name", sorted(RANDOM_SETS))
def test_random_sets_match_scipy(name):
    points = RANDOM_SETS[name]
    ours = cudahull.ConvexHull(points, backend="cpu")
    theirs = scipy.spatial.ConvexHull(points)
    assert ours.precision == "double"
    assert np.array_equal(ours.vertices, theirs.vertices)
    assert ours.volume == pytest.approx(theirs.volume, rel=1e-12)
    assert ours.area == pytest.approx(theirs.area, rel=1e-12)
    # General position: the same triangles (scipy's are not oriented, so compared as vertex sets).
    assert unordered_triangles(ours.simplices) == unordered_triangles(theirs.simplices)
    assert_consistent(ours)


def test_float32_stays_float():
    points = RANDOM_SETS["gauss"].astype(np.float32)
    ours = cudahull.ConvexHull(points, backend="cpu")
    assert ours.precision == "float" and ours.points.dtype == np.float32
    # Qhull computes in double on the same values, widened exactly.
    theirs = scipy.spatial.ConvexHull(points.astype(np.float64))
    assert np.array_equal(ours.vertices, theirs.vertices)
    assert ours.volume == pytest.approx(theirs.volume, rel=1e-12)
    assert_consistent(ours)


def test_double_is_exact_where_float_is_not():
    # A point 1e-12 above the cube's top face is a vertex in double; rounded to float it lies on the face.
    points = np.vstack([CUBE, [[0.5, 0.5, 1 + 1e-12]]])
    in_double = cudahull.ConvexHull(points, backend="cpu")
    in_float = cudahull.ConvexHull(points, backend="cpu", precision="float")
    assert in_double.precision == "double" and 8 in in_double.vertices and len(in_double.vertices) == 9
    assert in_float.precision == "float" and in_float.vertices.tolist() == list(range(8))
    assert_consistent(in_double)


def test_add_points_equals_one_run():
    points = RANDOM_SETS["gauss"]
    whole = cudahull.ConvexHull(points, backend="cpu")
    for restart in (False, True):
        growing = cudahull.ConvexHull(points[:1000], backend="cpu", incremental=True)
        growing.add_points(points[1000:2000], restart=restart)
        growing.add_points(points[2000:], restart=restart)
        assert growing.npoints == whole.npoints and np.array_equal(growing.points, points)
        assert np.array_equal(growing.vertices, whole.vertices)
        assert oriented_triangles(growing.simplices) == oriented_triangles(whole.simplices)
        assert growing.volume == pytest.approx(whole.volume, rel=1e-14)
        assert_consistent(growing)
    growing.close()
    with pytest.raises(RuntimeError, match="closed"):
        growing.add_points(points[:10])


def test_flat_input_is_a_qhull_error_as_in_scipy():
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]], dtype=float)
    with pytest.raises(scipy.spatial.QhullError):
        scipy.spatial.ConvexHull(square, incremental=True)
    with pytest.raises(scipy.spatial.QhullError, match="QH6154.*cudahull.convex_hull"):
        cudahull.ConvexHull(square, True, backend="cpu")  # incremental, positionally, as scipy's
    assert issubclass(cudahull.QhullError, scipy.spatial.QhullError)
    # The lower-dimensional answer stays in convex_hull().
    flat = cudahull.convex_hull(square, backend="cpu")
    assert flat["dimension"] == 2 and sorted(flat["polygon"].tolist()) == [0, 1, 2, 3]


def test_flat_input_gives_a_polygon():
    rng = np.random.default_rng(3)
    uv = rng.uniform(-1, 1, size=(400, 2))
    # The plane z = 2x - 3y + 1: exact for these dyadic values.
    uv = np.round(uv * 1024) / 1024
    points = np.column_stack([uv, 2 * uv[:, 0] - 3 * uv[:, 1] + 1])
    with pytest.raises(scipy.spatial.QhullError):
        scipy.spatial.ConvexHull(points)  # QH6154: what cudahull answers instead
    with pytest.raises(cudahull.QhullError):
        cudahull.ConvexHull(points, backend="cpu")
    hull = cudahull.convex_hull(points, backend="cpu")
    flat = scipy.spatial.ConvexHull(uv)  # the oracle: the 2-D hull of the projection onto x, y
    assert hull["dimension"] == 2
    assert np.array_equal(hull["vertices"], np.sort(flat.vertices))
    assert sorted(hull["polygon"].tolist()) == hull["vertices"].tolist()
    # The polygon goes round in order: the same cycle as Qhull's (either direction).
    ring = hull["polygon"].tolist()
    start = ring.index(flat.vertices[0])
    ring = ring[start:] + ring[:start]
    assert ring == flat.vertices.tolist() or ring[:1] + ring[1:][::-1] == flat.vertices.tolist()
    # Both sides of the polygon; its area in the plane is the projected area times |n| / |n_z|.
    assert hull["area"] == pytest.approx(2 * flat.volume * np.sqrt(1 + 4 + 9), rel=1e-12)
    assert hull["volume"] == 0 and hull["simplices"].shape == (0, 3)
    assert hull["equations"].shape == (0, 4)


def test_collinear_input_gives_a_segment():
    t = np.random.default_rng(5).permutation(np.arange(-50, 50)) / 8.0
    points = np.column_stack([t, 2 * t + 1, -t])
    hull = cudahull.convex_hull(points, backend="cpu")
    assert hull["dimension"] == 1
    assert hull["vertices"].tolist() == sorted([int(np.argmin(t)), int(np.argmax(t))])
    assert hull["volume"] == 0 and hull["area"] == 0 and len(hull["simplices"]) == 0


def test_duplicates_keep_the_lowest_index():
    rng = np.random.default_rng(9)
    inside = rng.uniform(0.1, 0.9, size=(200, 3))
    points = np.vstack([inside, CUBE, CUBE[::-1], inside[:10]])  # every corner twice
    hull = cudahull.ConvexHull(points, backend="cpu")
    assert hull.vertices.tolist() == list(range(200, 208))
    assert hull.volume == 1.0 and hull.area == 6.0
    assert_consistent(hull)
    same = cudahull.convex_hull(np.repeat([[1.5, -2.0, 3.0]], 5, axis=0), backend="cpu")
    assert same["dimension"] == 0 and same["vertices"].tolist() == [0]


@pytest.mark.parametrize("count", [0, 1, 2, 3, 4])
def test_fewer_than_four_points(count):
    points = np.array([[0, 0, 0], [2, 0, 0], [0, 3, 0], [0, 0, 4]], dtype=float)[:count]
    hull = cudahull.convex_hull(points, backend="cpu")
    assert hull["dimension"] == count - 1
    assert hull["vertices"].tolist() == list(range(count))
    if count == 4:
        assert hull["volume"] == 4.0 and len(hull["simplices"]) == 4  # 2 * 3 * 4 / 6
        assert_consistent(cudahull.ConvexHull(points, backend="cpu"))
    else:
        assert hull["volume"] == 0 and len(hull["simplices"]) == 0
        # scipy raises ValueError for no points and QhullError for too few (QH6214); so does ConvexHull.
        expected = ValueError if count == 0 else scipy.spatial.QhullError
        with pytest.raises(expected):
            scipy.spatial.ConvexHull(points)
        with pytest.raises(expected, match="No points given" if count == 0 else "QH6214|QH6154"):
            cudahull.ConvexHull(points, backend="cpu")
    if count == 3:
        assert hull["area"] == 2 * 3.0  # both sides of the triangle of area 3


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_input_is_a_value_error(bad):
    points = np.array(RANDOM_SETS["few"])
    points[3, 1] = bad
    with pytest.raises(ValueError, match=r"^point 3: y coordinate .* is not finite$"):
        cudahull.ConvexHull(points)
    with pytest.raises(ValueError, match="point 3"):
        cudahull.ConvexHull(points.astype(np.float32))


def test_other_bad_input():
    # 4-D and higher go to Qhull, which asks for what only the exact engines give.
    with pytest.raises(ValueError, match="4-D points are hulled by scipy's Qhull.*backend must be 'auto' or 'cpu'"):
        cudahull.ConvexHull(np.eye(5, 4), backend="cuda")
    with pytest.raises(ValueError, match=r"^points must be an \(n, 2\) or \(n, 3\) array, not one of shape \(5, 1\)"):
        cudahull.ConvexHull(np.zeros((5, 1)))
    with pytest.raises(ValueError, match="masked arrays"):
        cudahull.ConvexHull(np.ma.masked_all((5, 3)))
    with pytest.raises(ValueError, match="does not fit in float"):
        cudahull.ConvexHull(np.vstack([CUBE, [[1e39, 0, 0]]]), precision="float")
    with pytest.raises(ValueError, match="precision must be auto, float or double, not 'half'"):
        cudahull.ConvexHull(CUBE, precision="half")
    with pytest.raises(ValueError, match="backend must be auto, cpu or cuda"):
        cudahull.ConvexHull(CUBE, backend="gpu")


def test_every_finite_double_is_taken_exactly():
    # A point at x = 1e300: the cube's far corners stay vertices by 1e-300 (a rounding would lose them),
    # except (1, 0, 0), which lies on the edge from (0, 0, 0) to it.
    far = cudahull.ConvexHull(np.vstack([CUBE, [[1e300, 0, 0]]]))
    assert far.backend == "cpu-wide"
    assert far.vertices.tolist() == [0, 1, 2, 3, 5, 6, 7, 8]
    # Subnormal coordinates: one just below the bottom face is a vertex, one just above it is not.
    tiny = np.nextafter(0.0, 1.0)
    hull = cudahull.ConvexHull(np.vstack([CUBE, [[0.5, 0.5, -tiny], [0.25, 0.5, tiny]]]))
    assert hull.vertices.tolist() == list(range(9))
    flat = cudahull.convex_hull(np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, -tiny]]))
    assert flat["polygon"].tolist() == [0, 4, 1, 2, 3]


def gpu_present():
    try:
        return subprocess.run(["nvidia-smi", "-L"], capture_output=True).returncode == 0
    except FileNotFoundError:
        return False


def test_cuda_backend_request():
    points = RANDOM_SETS["gauss"]
    if gpu_present():
        on_gpu = cudahull.ConvexHull(points, backend="cuda")
        assert on_gpu.backend.startswith("cuda")
        assert np.array_equal(on_gpu.vertices, cudahull.ConvexHull(points, backend="cpu").vertices)
    else:
        with pytest.raises(cudahull.DeviceError, match="^backend cuda: no usable CUDA device: "):
            cudahull.ConvexHull(points, backend="cuda")
        assert issubclass(cudahull.DeviceError, RuntimeError)
        assert cudahull.ConvexHull(points).backend.startswith("cpu")  # auto falls back


def test_resident_engine_gives_the_same_hull():
    points = RANDOM_SETS["gauss"]
    resident = cudahull.convex_hull(points, backend="cpu", engine="resident")
    stepping = cudahull.convex_hull(points, backend="cpu")
    assert resident["backend"] == "cpu-resident"
    assert np.array_equal(resident["vertices"], stepping["vertices"])
    assert resident["volume"] == pytest.approx(stepping["volume"], rel=1e-14)


# --- one number format in every error ------------------------------------------------------------------------

# std::to_chars's shortest text (libstdc++), which the module's C++ messages use, for values that exercise each
# rule: fixed or scientific, whichever is shorter, fixed on a tie, a whole number's exact digits.
TO_CHARS = [(0.0, "0"), (-0.0, "-0"), (1.0, "1"), (-3.0, "-3"), (0.25, "0.25"), (0.1, "0.1"), (1e-05, "1e-05"),
            (0.001, "0.001"), (0.0001, "1e-04"), (0.0001234, "0.0001234"), (1e5, "1e+05"), (123456.0, "123456"),
            (1e16, "1e+16"), (1e39, "1e+39"), (-3.5e38, "-3.5e+38"), (1.2345678901234568e18, "1234567890123456768"),
            (2.2250738585072014e-308, "2.2250738585072014e-308"), (5e-324, "5e-324"), (12345.678, "12345.678"),
            (float("nan"), "nan"), (float("inf"), "inf"), (float("-inf"), "-inf")]


def test_number_text_is_the_modules_to_chars():
    from cudahull._errors import number_text

    for value, text in TO_CHARS:
        assert number_text(value) == text, value
        assert number_text(np.float64(value)) == text, value


@pytest.mark.parametrize("value", [1e39, -3.5e38, np.float64(4e38)])
def test_a_value_is_written_alike_by_the_constructor_and_add_points(value):
    points = np.random.default_rng(40).normal(size=(50, 3)).astype(np.float32)
    bad = np.array([[0.0, float(value), 0.0]])
    with pytest.raises(ValueError) as built:
        cudahull.ConvexHull(np.vstack([points, bad]), precision="float")
    hull = cudahull.ConvexHull(points, incremental=True)
    with pytest.raises(ValueError) as added:
        hull.add_points(bad)
    text = str(built.value).split(": ", 1)[1]  # "y coordinate 1e+39 does not fit in float"
    assert str(built.value) == f"point 50: {text}"
    assert str(added.value) == f"add_points: point 0: {text} (a row of the new points; nothing was added)"
    assert "np." not in text


def test_numpy_scalar_arguments_are_written_as_numbers():
    points = np.random.default_rng(41).normal(size=(20, 3))
    for tolerance, text in ((np.float64(-1.0), "-1"), (np.float32(-0.5), "-0.5"), (-2.5, "-2.5"),
                            (np.float64("nan"), "nan")):
        with pytest.raises(ValueError, match=f"finite number >= 0, not {text}$"):
            cudahull.ConvexHull(points, tolerance=tolerance)
    with pytest.raises(ValueError, match="0 for every core, not 1.5$"):
        cudahull.convex_hull_batch([points], threads=np.float64(1.5))
    with pytest.raises(ValueError, match="tolerance must be None or 'qhull', not 0.25$"):
        cudahull.ConvexHull(np.random.default_rng(42).normal(size=(20, 4)), tolerance=np.float64(0.25))
