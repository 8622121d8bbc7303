"""cudahull.ConvexHull as scipy's drop-in (issue 25): 2-D hulls against an exact brute force, qhull_options,
Qhull-like merging with its certificate against Qhull's own output, planes on slivers, scipy's errors."""

from fractions import Fraction

import numpy as np
import pytest
import scipy.spatial

import cudahull


# --- oracles -----------------------------------------------------------------------------------------------


def exact_corners_2d(points):
    """The strict corners of the 2-D hull, counter-clockwise from the lowest (x, y), by Andrew's monotone
    chain in exact rational arithmetic (every double is a Fraction exactly); lowest index among duplicates."""
    exact = [(Fraction(float(x)), Fraction(float(y)), i) for i, (x, y) in enumerate(points)]
    exact.sort()
    unique = []
    for p in exact:
        if not unique or unique[-1][:2] != p[:2]:
            unique.append(p)
    if len(unique) < 3:
        return [p[2] for p in unique]

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in unique:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(unique):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return [p[2] for p in lower[:-1] + upper[:-1]]


def random_planar_sets(seed, count):
    rng = np.random.default_rng(seed)
    for case in range(count):
        n = int(rng.integers(3, 300))
        kind = case % 5
        if kind == 0:
            points = rng.uniform(-1, 1, size=(n, 2))
        elif kind == 1:  # an integer grid: many collinear points on the hull's edges
            points = rng.integers(-4, 5, size=(n, 2)).astype(float)
        elif kind == 2:  # a circle: every point a corner, some nearly collinear
            angle = rng.uniform(0, 2 * np.pi, size=n)
            points = np.column_stack([np.cos(angle), np.sin(angle)]) * 1e3 + [1e6, -7]
        elif kind == 3:  # duplicates
            points = rng.uniform(-1, 1, size=(n, 2))
            points = np.vstack([points, points[rng.integers(0, n, size=n // 2)]])
        else:  # near-collinear doubles along a line, a few units in the last place off it
            t = rng.uniform(0, 1, size=n)
            points = np.column_stack([t, 0.5 + t * np.float64(1 / 3)])
            points[:, 1] += rng.integers(-2, 3, size=n) * np.spacing(points[:, 1])
        yield case, points


# --- 2-D -----------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [1, 2])
def test_2d_hull_is_exact_against_a_rational_brute_force(seed):
    for case, points in random_planar_sets(seed, 150):
        expected = exact_corners_2d(points)
        hull = cudahull.convex_hull(points, backend="cpu")
        assert hull["input_dimension"] == 2
        if len(expected) >= 3:
            assert hull["dimension"] == 2, case
            assert hull["polygon"].tolist() == expected, case
        else:
            assert hull["dimension"] == len(expected) - 1, case
            assert sorted(hull["vertices"].tolist()) == sorted(expected), case
            with pytest.raises(cudahull.QhullError):
                cudahull.ConvexHull(points)


def test_2d_hull_has_scipys_attributes():
    rng = np.random.default_rng(7)
    points = rng.uniform(-1, 1, size=(500, 2))
    hull = cudahull.ConvexHull(points)
    reference = scipy.spatial.ConvexHull(points)
    # Uniform doubles in general position: Qhull is exact here, so the vertex sets agree.
    assert sorted(hull.vertices.tolist()) == sorted(reference.vertices.tolist())
    # scipy's 2-D vertices run counter-clockwise: the same cycle as Qhull's.
    ring = hull.vertices.tolist()
    start = ring.index(reference.vertices[0])
    assert ring[start:] + ring[:start] == reference.vertices.tolist()
    assert hull.simplices.shape == (len(ring), 2) and hull.neighbors.shape == (len(ring), 2)
    assert hull.equations.shape == (len(ring), 3) and hull.ndim == 2 and hull.dimension == 2
    assert hull.volume == pytest.approx(reference.volume, rel=1e-13)  # the area
    assert hull.area == pytest.approx(reference.area, rel=1e-13)  # the perimeter
    assert {tuple(sorted(e)) for e in hull.simplices.tolist()} == {tuple(sorted(e)) for e in
                                                                  reference.simplices.tolist()}
    for e, (a, b) in enumerate(hull.simplices.tolist()):
        # neighbors[e][k] is the edge opposite vertex k: it shares the other end.
        assert b in hull.simplices[hull.neighbors[e, 0]] and a not in hull.simplices[hull.neighbors[e, 0]]
        assert a in hull.simplices[hull.neighbors[e, 1]] and b not in hull.simplices[hull.neighbors[e, 1]]
    heights = points @ hull.equations[:, :2].T + hull.equations[:, 2]
    assert heights.max() <= 1e-15
    np.testing.assert_allclose(np.linalg.norm(hull.equations[:, :2], axis=1), 1, atol=1e-15)
    # add_points, as scipy's.
    more = rng.uniform(-1.5, 1.5, size=(100, 2))
    hull.add_points(more)
    whole = np.vstack([points, more])
    assert hull.vertices.tolist() == exact_corners_2d(whole)


def test_2d_float32_stays_exact_in_float():
    rng = np.random.default_rng(3)
    points = rng.uniform(-1, 1, size=(2000, 2)).astype(np.float32)
    hull = cudahull.ConvexHull(points)
    assert hull.precision == "float"
    assert hull.vertices.tolist() == exact_corners_2d(points.astype(np.float64))


# --- qhull_options ----------------------------------------------------------------------------------------


def test_qhull_options_that_scipy_callers_pass_are_accepted():
    rng = np.random.default_rng(11)
    points = rng.normal(size=(400, 3))
    exact = cudahull.ConvexHull(points)
    for options in ("Qt QbB Pp", "QbB", "QbB Pp", "QJ", "Qbb Qc Qx Q12", "Qt", "Qx Qi", "C-0", "Qbb Qc"):
        hull = cudahull.ConvexHull(points, qhull_options=options)
        reference = scipy.spatial.ConvexHull(points, qhull_options=options)
        # A random Gaussian cloud has no near-coplanar facets: merging changes nothing, and Qhull agrees.
        assert hull.vertices.tolist() == exact.vertices.tolist(), options
        assert sorted(hull.vertices.tolist()) == sorted(reference.vertices.tolist()), options
    qi = cudahull.ConvexHull(points, qhull_options="Qi")
    # Qi: every point that is not a vertex is listed, with a facet and a vertex.
    assert sorted(qi.coplanar[:, 0].tolist() + qi.vertices.tolist()) == list(range(len(points)))


def test_unknown_qhull_options_raise_qhull_error_naming_them():
    points = np.random.default_rng(1).normal(size=(20, 3))
    for options, name in (("Qt Fv", "Fv"), ("Q3", "Q3"), ("d", "d"), ("QbB Tz", "Tz")):
        with pytest.raises(cudahull.QhullError, match=f"'{name}'"):
            cudahull.ConvexHull(points, qhull_options=options)
        with pytest.raises(scipy.spatial.QhullError):  # code that catches scipy's error catches ours
            cudahull.ConvexHull(points, qhull_options=options)


@pytest.mark.parametrize("visible", [True, False])
def test_good_is_the_facets_point_n_sees(visible):
    rng = np.random.default_rng(5)
    for points in (rng.uniform(0, 1, size=(40, 2)), rng.uniform(0, 1, size=(60, 3))):
        points = np.vstack([points, np.full(points.shape[1], 1.2)])  # point n, outside
        n = len(points) - 1
        option = f"QG{n}" if visible else f"QG-{n}"
        hull = cudahull.ConvexHull(points, qhull_options=option)
        reference = scipy.spatial.ConvexHull(points, qhull_options=option)
        assert n not in hull.vertices  # point n is left out of the hull, as in Qhull
        ours = {tuple(sorted(s)) for s, g in zip(hull.simplices.tolist(), hull.good) if g}
        theirs = {tuple(sorted(s)) for s, g in zip(reference.simplices.tolist(), reference.good) if g}
        assert ours == theirs and len(ours) > 0


# --- errors --------------------------------------------------------------------------------------------------


def test_add_points_is_atomic_and_names_the_row_in_the_batch():
    rng = np.random.default_rng(2)
    points = rng.normal(size=(100, 3))
    hull = cudahull.ConvexHull(points, incremental=True)
    before = (hull.points.copy(), hull.vertices.copy(), hull.simplices.copy(), hull.npoints)
    batch = rng.normal(size=(10, 3)) * 5
    batch[6, 2] = np.nan
    with pytest.raises(ValueError, match=r"^add_points: point 6: z coordinate nan is not finite"):
        hull.add_points(batch)
    assert np.array_equal(hull.points, before[0]) and hull.npoints == before[3]
    assert np.array_equal(hull.vertices, before[1]) and np.array_equal(hull.simplices, before[2])
    batch[6, 2] = 0.0
    hull.add_points(batch)  # the batch's valid points all count afterwards
    assert hull.vertices.tolist() == cudahull.ConvexHull(np.vstack([points, batch])).vertices.tolist()


def test_positional_arguments_follow_scipy():
    points = np.random.default_rng(4).normal(size=(50, 3))
    hull = cudahull.ConvexHull(points, True, "Qt")
    assert hull.vertices.tolist() == cudahull.ConvexHull(points).vertices.tolist()


# --- merging ----------------------------------------------------------------------------------------------


def rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.diag(r))


def chamfered_box(rng, size=(2.0, 1.0, 0.5), chamfer=0.1, per_face=200):
    """A box with chamfered edges and corners (a truncated box, convex), densely sampled on its faces and
    edges, rotated arbitrarily in double: its planar faces' points are no longer exactly coplanar."""
    a = np.array(size) / 2
    corners = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                s = np.array([sx, sy, sz])
                for axis in range(3):
                    p = s * a
                    p[axis] -= s[axis] * chamfer
                    corners.append(p)
    corners = np.array(corners)
    hull = scipy.spatial.ConvexHull(corners)  # on the unrotated corners, Qhull is exact: 24 of them
    samples = [corners]
    for tri in hull.simplices:
        w = rng.dirichlet(np.ones(3), size=per_face // 4)
        samples.append(w @ corners[tri])
        t = rng.uniform(0, 1, size=(per_face // 8, 1))
        samples.append(corners[tri[0]] + t * (corners[tri[1]] - corners[tri[0]]))
    points = np.vstack(samples)
    return points @ rotation(rng).T + rng.normal(size=3) * 10


def vertex_points(points, vertices):
    """A hull's vertex set, as points: of duplicate points Qhull may keep any one (part 4's chamfer collapses
    four pairs of corners), the same point whichever."""
    return {tuple(p) for p in points[np.asarray(vertices)].tolist()}


def rotated_cube(rng, per_edge=50, per_face=100):
    """The unit cube sampled on its 12 edges and 6 faces, its 8 corners first, rotated arbitrarily in double."""
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    samples = [corners]
    for i in range(8):
        for j in range(i + 1, 8):
            if np.sum(corners[i] != corners[j]) == 1:
                samples.append(corners[i] + rng.uniform(0, 1, size=(per_edge, 1)) * (corners[j] - corners[i]))
    for axis in range(3):
        for side in (0.0, 1.0):
            face = rng.uniform(0, 1, size=(per_face, 3))
            face[:, axis] = side
            samples.append(face)
    return np.vstack(samples) @ rotation(rng).T + rng.normal(size=3) * 10


def cylinder_part(rng, sides=24, rings=5, per_cap=100):
    """A 24-sided prism (a turned part's facets), its two end rings (the corners) first, then rings between
    them on its sides and points inside its two caps, rotated arbitrarily in double."""
    angle = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    ring = np.c_[np.cos(angle), np.sin(angle)]
    samples = [np.c_[ring, np.full(sides, z)] for z in np.r_[0.0, 2.0, np.linspace(0, 2, rings)[1:-1]]]
    for z in (0.0, 2.0):
        r, t = 0.99 * np.sqrt(rng.uniform(0, 1, per_cap)), rng.uniform(0, 2 * np.pi, per_cap)
        samples.append(np.c_[r * np.cos(t), r * np.sin(t), np.full(per_cap, z)])
    return np.vstack(samples) @ rotation(rng).T + rng.normal(size=3) * 10


def test_merged_hull_matches_qhull_on_rotated_chamfered_boxes():
    rng = np.random.default_rng(25)
    for part in range(6):
        points = chamfered_box(rng, chamfer=0.05 + 0.05 * part)
        exact = cudahull.ConvexHull(points)
        merged = cudahull.ConvexHull(points, tolerance="qhull")
        reference = scipy.spatial.ConvexHull(points)  # Qhull's default merging
        assert vertex_points(points, merged.vertices) == vertex_points(points, reference.vertices), part
        assert set(merged.vertices.tolist()) < set(exact.vertices.tolist())  # merging dropped the slivers' corners
        # The certificate, checked independently: every input point within max_outside of every plane.
        heights = points @ merged.equations[:, :3].T + merged.equations[:, 3]
        assert heights.max() <= merged.max_outside
        assert merged.max_outside < 1e3 * merged.tolerance + 1e-12
        # No triangle thinner than the tolerance: each altitude at least it.
        corners = points[merged.simplices]
        edges = np.linalg.norm(corners[:, [1, 2, 0]] - corners, axis=2)
        twice_area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
        assert (twice_area / edges.max(axis=1)).min() >= merged.tolerance
        # The exact hull's vertices that merging left out are listed in coplanar.
        dropped = sorted(set(exact.vertices.tolist()) - set(merged.vertices.tolist()))
        assert sorted(merged.coplanar[:, 0].tolist()) == dropped


# Qhull's Cn on CAD-like parts: Qhull's vertices are exactly the part's corners (its answer is well defined:
# every input point lies within roundoff of the hull of the corners), as (shape, seed, option).
_PARTS = {"chamfered box": chamfered_box, "rotated cube": rotated_cube, "cylinder": cylinder_part}
_CORNERS = {"chamfered box": 24, "rotated cube": 8, "cylinder": 48}
# Where no input point lies within n of a corner along its edges, cudahull's Cn keeps Qhull's vertex set.
_CN_AS_QHULL = [(shape, seed, option) for seed in (0, 1, 2) for shape, options in (
    ("chamfered box", ("C0", "C-0", "C0.0001", "C-0.0001", "C1e-06")),
    ("rotated cube", ("C0", "C-0", "C0.001", "C-0.001", "C0.0001")),
    ("cylinder", ("C0", "C0.01", "C-0.01", "C0.001", "C-0.001"))) for option in options]
# Where edge points lie within about n of a corner, cudahull's Cn can keep one of them in the corner's place
# (docs/python.md's options table): these cases differ from Qhull today.
_CN_CORNER_REPLACED = [("chamfered box", 0, "C0.01"), ("chamfered box", 1, "C0.01"), ("chamfered box", 5, "C0.01"),
                       ("chamfered box", 0, "C0.001"), ("chamfered box", 0, "C-0.001"),
                       ("rotated cube", 0, "C0.01"), ("rotated cube", 5, "C0.001")]
_CN_REASON = ("cudahull's Cn drops a vertex that stands within n of the hull of its neighbours, so a corner with "
              "edge points within about n of it can be replaced by one of them (left outside by up to about n); "
              "Qhull merges facets and keeps every vertex where three merged facets meet")


def _part(shape, seed):
    points = _PARTS[shape](np.random.default_rng(seed))
    reference = scipy.spatial.ConvexHull(points)  # Qhull's default merging: exactly the corners
    assert sorted(reference.vertices.tolist()) == list(range(_CORNERS[shape])), (shape, seed)
    return points


def _check_cn(shape, seed, option):
    points = _part(shape, seed)
    merged = cudahull.ConvexHull(points, qhull_options=option)
    reference = scipy.spatial.ConvexHull(points, qhull_options=option)
    assert sorted(reference.vertices.tolist()) == list(range(_CORNERS[shape]))  # Qhull's answer: the corners
    assert sorted(merged.vertices.tolist()) == sorted(reference.vertices.tolist())


@pytest.mark.parametrize("shape, seed, option", _CN_AS_QHULL)
def test_cn_keeps_qhulls_vertex_set_on_cad_parts(shape, seed, option):
    _check_cn(shape, seed, option)


@pytest.mark.parametrize("shape, seed, option", [
    pytest.param(*case, marks=pytest.mark.xfail(reason=_CN_REASON, raises=AssertionError, strict=True))
    for case in _CN_CORNER_REPLACED])
def test_cn_keeps_the_corners_where_edge_points_are_near(shape, seed, option):
    _check_cn(shape, seed, option)


@pytest.mark.parametrize("shape, seed, option", _CN_CORNER_REPLACED)
def test_cn_where_a_corner_is_replaced_stays_within_its_certificate(shape, seed, option):
    """What the options table documents where Cn's vertices differ from Qhull's: the vertices are the exact
    hull's, every input point lies within max_outside of every facet's plane, and the corner left out lies
    within about n (1.5 n) of the triangles kept, so that the volume differs from Qhull's by about n x area."""
    points = _part(shape, seed)
    distance = abs(float(option[1:]))
    merged = cudahull.ConvexHull(points, qhull_options=option)
    exact = cudahull.ConvexHull(points)
    assert set(merged.vertices.tolist()) <= set(exact.vertices.tolist())
    heights = points @ merged.equations[:, :3].T + merged.equations[:, 3]
    assert heights.max() <= merged.max_outside <= 1.5 * distance
    dropped = sorted(set(exact.vertices.tolist()) - set(merged.vertices.tolist()))
    assert sorted(merged.coplanar[:, 0].tolist()) == dropped
    # Each triangle's own plane (merging keeps a triangle within n of its facet's plane, not on it).
    a, b, c = (points[merged.simplices[:, k]] for k in range(3))
    normals = np.cross(b - a, c - a)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    outside = np.einsum("ij,kj->ik", points, normals) - np.einsum("kj,kj->k", normals, a)
    corners = list(range(_CORNERS[shape]))
    assert 0 < outside[corners].max() <= 1.5 * distance  # a corner left out, by about n at most
    reference = scipy.spatial.ConvexHull(points, qhull_options=option)
    assert 0 < reference.volume - merged.volume <= 1.5 * distance * merged.area


def test_merged_hull_of_a_sphere_changes_nothing():
    rng = np.random.default_rng(8)
    points = rng.normal(size=(2000, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)
    exact = cudahull.ConvexHull(points)
    merged = cudahull.ConvexHull(points, tolerance="qhull")
    assert merged.vertices.tolist() == exact.vertices.tolist()
    assert len(merged.coplanar) == 0


def test_merged_2d_drops_nearly_collinear_corners():
    rng = np.random.default_rng(6)
    t = rng.uniform(0, 1, size=(300, 1))
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    points = np.vstack([square, square[0] + t * (square[1] - square[0]), square[1] + t * (square[2] - square[1])])
    angle = 0.3
    points = points @ np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]]).T
    merged = cudahull.ConvexHull(points, tolerance="qhull")
    assert sorted(merged.vertices.tolist()) == [0, 1, 2, 3]
    assert len(scipy.spatial.ConvexHull(points).vertices) == 4
    heights = points @ merged.equations[:, :2].T + merged.equations[:, 2]
    assert heights.max() <= merged.max_outside


# --- planes -------------------------------------------------------------------------------------------------


def test_planes_are_accurate_on_slivers():
    rng = np.random.default_rng(9)
    worst = 0.0
    for _ in range(20):
        points = chamfered_box(rng, per_face=100)
        hull = cudahull.ConvexHull(points)  # exact: slivers kept
        scale = np.abs(points).max()
        heights = points @ hull.equations[:, :3].T + hull.equations[:, 3]
        worst = max(worst, heights.max() / scale)
    assert worst <= 1e-13


# --- review cases -------------------------------------------------------------------------------------------


def test_qhull_option_words_follow_qhulls_groups():
    points = np.random.default_rng(12).normal(size=(40, 3))
    for options in ("QbBPp", "QcQi", "A1.5"):
        with pytest.raises(cudahull.QhullError):
            cudahull.ConvexHull(points, qhull_options=options)
        if options != "A1.5":  # scipy refuses the run-together words too (QH7023)
            with pytest.raises(scipy.spatial.QhullError):
                scipy.spatial.ConvexHull(points, qhull_options=options)
    for options in ("Qcx", "-Qt", "Qci Tv", "A-0"):
        assert cudahull.ConvexHull(points, qhull_options=options).vertices.tolist() == \
            sorted(scipy.spatial.ConvexHull(points).vertices.tolist())
    assert cudahull.ConvexHull(points, qhull_options="").tolerance == 0  # "" is None: exact


def test_qc_lists_points_on_facets_as_scipy():
    cube = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
    points = np.vstack([cube, [[0.5, 0.5, 1.0], [0.5, 0.5, 0.0], [0.5, 0.5, 0.5]], cube[:1]])
    hull = cudahull.ConvexHull(points, qhull_options="Qc")
    reference = scipy.spatial.ConvexHull(points, qhull_options="Qc")
    assert sorted(hull.coplanar[:, 0].tolist()) == sorted(reference.coplanar[:, 0].tolist()) == [8, 9, 11]
    for point, facet, vertex in hull.coplanar.tolist():
        height = hull.equations[facet, :3] @ points[point] + hull.equations[facet, 3]
        assert abs(height) <= 1e-15 and vertex in hull.simplices[facet]


def test_add_points_to_a_merged_hull_keeps_the_certificate():
    cube = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
    points = np.vstack([cube, [[0.5, 0.5, 1 + 2 * np.finfo(float).eps]]])  # merged away, 4e-16 proud
    hull = cudahull.ConvexHull(points, qhull_options="Qt")
    assert hull.coplanar[:, 0].tolist() == [8]
    hull.add_points([[0.5, 0.5, -1.0]])
    whole = np.vstack([points, [[0.5, 0.5, -1.0]]])
    restarted = cudahull.ConvexHull(whole, qhull_options="Qt")
    assert hull.vertices.tolist() == restarted.vertices.tolist()
    assert hull.coplanar.tolist() == restarted.coplanar.tolist()
    heights = whole @ hull.equations[:, :3].T + hull.equations[:, 3]
    assert heights.max() <= hull.max_outside


def test_good_is_exact_for_any_finite_double():
    for scale in (5e-324 * 2**40, 1e-200, 1e200):
        square = np.array([[0, 0], [0, 1], [1, 1], [1, 0], [0.5, 2]]) * scale
        hull = cudahull.ConvexHull(square, qhull_options="QG4")
        top = [k for k, s in enumerate(hull.simplices.tolist()) if sorted(s) == [1, 2]]
        assert hull.good.tolist() == [k in top for k in range(len(hull.simplices))], scale


def test_a_merged_polygon_thinner_than_the_tolerance_is_flat():
    points = np.array([[0, 0], [1, 1], [2, 2], [3, 3 + 1e-15]])
    with pytest.raises(scipy.spatial.QhullError):
        scipy.spatial.ConvexHull(points)
    with pytest.raises(cudahull.QhullError):
        cudahull.ConvexHull(points, qhull_options="Qt")
    assert cudahull.ConvexHull(points).vertices.tolist() == [0, 2, 3]  # exact: a thin triangle, (1, 1) on an edge


def test_2d_lines_are_unit_and_finite_for_any_finite_double():
    for scale in (1.5e308 / 4, 5e-324 * 2**10, 1e-300):
        points = np.array([[0, 0], [2, 0], [2, 1], [0, 1], [1, 0.5]]) * scale
        hull = cudahull.ConvexHull(points)
        assert np.isfinite(hull.equations).all(), scale
        np.testing.assert_allclose(np.linalg.norm(hull.equations[:, :2], axis=1), 1, atol=1e-15)
        assert sorted(hull.vertices.tolist()) == [0, 1, 2, 3]


# --- property: the merge certificate ------------------------------------------------------------------------


def noisy_polytope(rng, dimension):
    """Points on the faces of a rotated box (3-D) or rectangle (2-D), with noise of a few units in the last
    place off the faces: the near-coplanar input merging is for."""
    n = int(rng.integers(50, 600))
    extent = rng.uniform(0.2, 3, size=dimension)
    points = rng.uniform(-1, 1, size=(n, dimension)) * extent
    axis = rng.integers(0, dimension, size=n)
    points[np.arange(n), axis] = np.sign(rng.uniform(-1, 1, size=n)) * extent[axis]  # onto a face
    q, r = np.linalg.qr(rng.normal(size=(dimension, dimension)))
    points = points @ (q * np.sign(np.diag(r))).T + rng.normal(size=dimension) * rng.choice([1, 1e3])
    return points * (1 + rng.integers(-4, 5, size=points.shape) * np.finfo(float).eps)


@pytest.mark.parametrize("dimension", [2, 3])
def test_merge_certificate_holds_on_random_near_coplanar_input(dimension):
    rng = np.random.default_rng(100 + dimension)
    for case in range(60):
        points = noisy_polytope(rng, dimension)
        tolerance = ["qhull", 1e-12, 1e-9, 1e-6][case % 4]
        exact = cudahull.ConvexHull(points)
        merged = cudahull.ConvexHull(points, tolerance=tolerance)
        # Every input point within max_outside of every facet's plane: the proven bound, checked here
        # independently in long double.
        heights = points.astype(np.longdouble) @ merged.equations[:, :-1].T.astype(np.longdouble) + \
            merged.equations[:, -1].astype(np.longdouble)
        assert heights.max() <= merged.max_outside, case
        # Merging drops exact-hull vertices (listed in coplanar) and keeps the rest.
        kept, dropped = set(merged.vertices.tolist()), set(merged.coplanar[:, 0].tolist())
        assert kept | dropped == set(exact.vertices.tolist()) and not kept & dropped, case
        if dimension == 3:
            # No triangle thinner than the tolerance.
            corners = points[merged.simplices]
            edges = np.linalg.norm(corners[:, [1, 2, 0]] - corners, axis=2)
            twice_area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]),
                                        axis=1)
            assert (twice_area / edges.max(axis=1)).min() >= merged.tolerance, case
        else:
            # Counter-clockwise, and no corner within the tolerance of its neighbours' line.
            ring = points[merged.vertices]
            for k in range(len(ring)):
                a, b, c = ring[k - 1], ring[k], ring[(k + 1) % len(ring)]
                normal = np.array([c[1] - a[1], a[0] - c[0]]) / np.linalg.norm(c - a)
                assert (b - a)[0] * (c - b)[1] - (b - a)[1] * (c - b)[0] > 0, case
                assert normal @ (b - a) > merged.tolerance, case


def test_an_angle_merges_facets_that_tilt_less_and_stays_certified():
    rng = np.random.default_rng(21)
    sphere = rng.normal(size=(2000, 3))
    sphere /= np.linalg.norm(sphere, axis=1, keepdims=True)
    exact = cudahull.ConvexHull(sphere)
    counts = []
    for cosine in (0.9999, 0.999, 0.99):
        hull = cudahull.ConvexHull(sphere, qhull_options=f"A{cosine}")
        heights = sphere @ hull.equations[:, :3].T + hull.equations[:, 3]
        assert heights.max() <= hull.max_outside
        # Each facet that merging made stays within the angle of the sphere's surface it replaced: its
        # plane is no further from the centre than the sphere's points (within max_outside).
        assert np.all(-hull.equations[:, 3] <= 1 + hull.max_outside)
        counts.append(len(hull.vertices))
    # A wider angle merges more (fewer vertices), and every one merges some of the exact hull's 2000.
    assert len(exact.vertices) > counts[0] >= counts[1] >= counts[2] > 4


def test_a_merged_slab_thinner_than_the_tolerance_is_flat():
    rng = np.random.default_rng(4)
    slab = np.column_stack([rng.uniform(-1, 1, size=(300, 2)), rng.integers(0, 2, size=300) * 1e-16])
    with pytest.raises(scipy.spatial.QhullError):
        scipy.spatial.ConvexHull(slab)
    with pytest.raises(cudahull.QhullError, match="QH6154"):
        cudahull.ConvexHull(slab, qhull_options="Qt")
    assert cudahull.ConvexHull(slab).dimension == 3  # exact: a body 1e-16 thick
