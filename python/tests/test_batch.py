"""cudahull.convex_hull_batch (issue 27): 10,000 random clouds of 4 to 5,000 points, each cloud's hull against
convex_hull() on that cloud alone and against scipy.spatial.ConvexHull (Qhull) where Qhull is exact; padded
input against packed; edge cases written out; errors naming the cloud and the point."""

from fractions import Fraction

import numpy as np
import pytest
import scipy.spatial

import cudahull

KINDS = ("uniform", "sphere", "flat", "duplicated", "grid")
CLOUDS = 10_000


def make_cloud(rng, kind, n):
    if kind == "uniform":
        return rng.uniform(-1, 1, size=(n, 3))
    if kind == "sphere":  # every point a vertex, in general position
        p = rng.normal(size=(n, 3))
        return p / np.linalg.norm(p, axis=1, keepdims=True)
    if kind == "flat":  # exactly on the plane z = 2x - 3y + 1 (integers: exact in double)
        uv = rng.integers(-1000, 1000, size=(n, 2)).astype(np.float64)
        return np.column_stack([uv, 2 * uv[:, 0] - 3 * uv[:, 1] + 1])
    if kind == "duplicated":  # a few distinct points in general position, each many times
        distinct = rng.normal(size=(int(rng.integers(4, 30)), 3))
        return distinct[rng.integers(0, len(distinct), size=n)]
    side = int(rng.integers(2, 12))  # integer grid: faces, edges and corners full of points
    return rng.integers(0, side, size=(n, 3)).astype(np.float64)


class Batch:
    """CLOUDS clouds of every kind, sizes log-uniform in 4..5,000 (most small, so that 10,000 of them take a
    few seconds, yet some reach 5,000), packed, with the batch's hulls."""

    def __init__(self):
        rng = np.random.default_rng(27)
        self.sizes = np.exp(rng.uniform(np.log(4), np.log(5001), size=CLOUDS)).astype(np.int64)
        self.kinds = [KINDS[c % len(KINDS)] for c in range(CLOUDS)]
        self.clouds = [make_cloud(rng, kind, int(n)) for kind, n in zip(self.kinds, self.sizes)]
        self.offsets = np.concatenate([[0], np.cumsum(self.sizes)])
        self.points = np.concatenate(self.clouds)
        self.hulls = cudahull.convex_hull_batch(self.points, self.offsets, backend="cpu")

    def vertices(self, c, hulls=None):
        h = hulls or self.hulls
        return h.vertices[h.vertex_offsets[c]:h.vertex_offsets[c + 1]]


@pytest.fixture(scope="module")
def batch():
    return Batch()


def lowest_duplicates(points, indices):
    """Each index replaced by the lowest index of a point with the same coordinates, as a sorted set (Qhull
    keeps any one of duplicates; convex_hull keeps the lowest)."""
    _, first, inverse = np.unique(points, axis=0, return_index=True, return_inverse=True)
    return np.unique(first[inverse.ravel()[indices]])


def sorted_triangles(faces):
    """Triangles as sorted index triples, rows in lexicographic order (scipy's are not oriented)."""
    t = np.sort(np.asarray(faces, dtype=np.int64), axis=1)
    return t[np.lexsort(t.T[::-1])]


def test_sizes_and_kinds_span_the_range(batch):
    assert batch.sizes.min() == 4 and batch.sizes.max() >= 4500
    assert len(batch.hulls) == CLOUDS and batch.hulls.precision == "double"
    assert batch.hulls.vertex_offsets.shape == batch.hulls.face_offsets.shape == (CLOUDS + 1,)
    assert batch.hulls.vertex_offsets.dtype == np.int64 and batch.hulls.vertices.dtype == np.int32
    assert batch.hulls.faces.shape == (batch.hulls.face_offsets[-1], 3)
    assert batch.hulls.planes.shape == (batch.hulls.face_offsets[-1], 4)
    dimensions = batch.hulls.dimensions
    kinds = np.array(batch.kinds)
    assert np.all(dimensions[kinds == "flat"] == 2)  # never collinear at these sizes and this seed
    assert np.all(dimensions[(kinds == "uniform") | (kinds == "sphere")] == 3)
    assert (dimensions == 3).sum() >= 7000 and (dimensions == 2).sum() >= 1900


def test_each_cloud_is_its_own_hull(batch):
    """Every cloud against convex_hull() on it alone: the vertex set, dimension, volume and area; the faces
    and planes too for every tenth cloud."""
    h = batch.hulls
    for c, cloud in enumerate(batch.clouds):
        alone = cudahull.convex_hull(cloud, backend="cpu")
        assert np.array_equal(batch.vertices(c), alone["vertices"]), f"cloud {c} ({batch.kinds[c]})"
        assert h.dimensions[c] == alone["dimension"] and h.volumes[c] == alone["volume"]
        assert h.areas[c] == alone["area"], f"cloud {c}"
        if c % 10 == 0:
            faces = slice(h.face_offsets[c], h.face_offsets[c + 1])
            assert np.array_equal(h.faces[faces], alone["simplices"]) and np.array_equal(h.planes[faces],
                                                                                          alone["equations"])
            polygon = h.polygons[h.polygon_offsets[c]:h.polygon_offsets[c + 1]]
            assert np.array_equal(polygon, alone["polygon"])


def test_vertices_are_scipys_where_qhull_is_exact(batch):
    """Qhull is exact on clouds in general position (uniform, sphere, duplicates of a few such points) and on
    integer grids; a flat cloud is compared with Qhull's 2-D hull of its projection on (x, y), the plane's
    points being a graph over it.  Qhull refuses clouds that are flat or too small: those are counted, and
    must stay few."""
    h = batch.hulls
    compared = 0
    for c, cloud in enumerate(batch.clouds):
        kind = batch.kinds[c]
        try:
            theirs = scipy.spatial.ConvexHull(cloud[:, :2] if kind == "flat" else cloud)
        except scipy.spatial.QhullError:
            assert kind in ("duplicated", "grid") and h.dimensions[c] < 3, f"cloud {c}: Qhull refused a solid"
            continue
        compared += 1
        ours = batch.vertices(c)
        # Uniform and sphere clouds have no repeated point; the others do.
        expected = np.sort(theirs.vertices) if kind in ("uniform", "sphere") else lowest_duplicates(
            cloud, theirs.vertices)
        assert np.array_equal(ours, expected), f"cloud {c} ({kind})"
        if kind == "flat":
            # Both sides of the polygon; its area in the plane is the projected area times |n| / |n_z|.
            assert h.dimensions[c] == 2 and h.volumes[c] == 0
            assert h.areas[c] == pytest.approx(2 * theirs.volume * np.sqrt(14), rel=1e-12)
            continue
        assert h.volumes[c] == pytest.approx(theirs.volume, rel=1e-9)
        assert h.areas[c] == pytest.approx(theirs.area, rel=1e-9)
        if kind in ("uniform", "sphere"):  # general position: the same triangles
            faces = h.faces[h.face_offsets[c]:h.face_offsets[c + 1]]
            assert np.array_equal(sorted_triangles(faces), sorted_triangles(theirs.simplices)), f"cloud {c}"
    assert compared >= CLOUDS - 100


def test_planes_bound_every_point(batch):
    """Unit outward normals with every point of the cloud on or below every plane, and each face's corners on
    it, counter-clockwise seen from outside (for clouds small enough to check every pair)."""
    h = batch.hulls
    checked = 0
    for c, cloud in enumerate(batch.clouds):
        faces = h.faces[h.face_offsets[c]:h.face_offsets[c + 1]]
        planes = h.planes[h.face_offsets[c]:h.face_offsets[c + 1]]
        if len(faces) == 0 or len(faces) * len(cloud) > 200_000:
            continue
        checked += 1
        assert np.allclose(np.linalg.norm(planes[:, :3], axis=1), 1, atol=1e-14)
        scale = np.abs(cloud).max()
        heights = cloud @ planes[:, :3].T + planes[:, 3]
        assert heights.max() <= 1e-12 * scale, f"cloud {c}: a point above a plane"
        a, b, d = cloud[faces[:, 0]], cloud[faces[:, 1]], cloud[faces[:, 2]]
        assert np.all(np.einsum("ij,ij->i", np.cross(b - a, d - a), planes[:, :3]) > 0), f"cloud {c}"
        corners = np.einsum("fkj,fj->fk", cloud[faces], planes[:, :3]) + planes[:, 3:]
        assert np.abs(corners).max() <= 1e-12 * scale, f"cloud {c}: a corner off its face's plane"
    assert checked >= 1000


def test_padded_and_packed_agree(batch):
    """The clouds sorted by size and padded 500 at a time (NaN in the padding, which is no cloud's): every
    array the same as the packed batch's, cloud for cloud."""
    h = batch.hulls
    order = np.argsort(batch.sizes, kind="stable")
    for chunk in np.array_split(order, CLOUDS // 500):
        slab = int(batch.sizes[chunk].max())
        padded = np.full((len(chunk), slab, 3), np.nan)
        for row, c in enumerate(chunk):
            padded[row, :batch.sizes[c]] = batch.clouds[c]
        ours = cudahull.convex_hull_batch(padded, lengths=batch.sizes[chunk], backend="cpu")
        assert len(ours) == len(chunk)
        for row, c in enumerate(chunk):
            assert np.array_equal(batch.vertices(row, ours), batch.vertices(c)), f"cloud {c}"
            theirs, mine = slice(h.face_offsets[c], h.face_offsets[c + 1]), slice(ours.face_offsets[row],
                                                                                    ours.face_offsets[row + 1])
            assert np.array_equal(ours.faces[mine], h.faces[theirs]) and np.array_equal(ours.planes[mine],
                                                                                        h.planes[theirs])
            assert (ours.volumes[row], ours.areas[row], ours.dimensions[row]) == (h.volumes[c], h.areas[c],
                                                                                  h.dimensions[c])


def test_release_device_memory_without_gpu_work(batch):
    """release_device_memory() where cudahull has used no GPU (here, or on a machine without one) hands
    nothing back and raises nothing; the CPU batch after it is the same."""
    cudahull.release_device_memory()
    again = cudahull.convex_hull_batch(batch.clouds[0], [0, len(batch.clouds[0])], backend="cpu")
    assert np.array_equal(again.vertices, batch.vertices(0))


def assert_same_batch(a, b):
    for key in cudahull.BatchHulls.__slots__:
        if key != "backend":
            assert np.array_equal(getattr(a, key), getattr(b, key)), key


def test_thread_count_changes_nothing(batch):
    points, offsets = batch.points[:batch.offsets[1500]], batch.offsets[:1501]
    one = cudahull.convex_hull_batch(points, offsets, backend="cpu", threads=1)
    for threads in (2, 5, 0):
        assert_same_batch(cudahull.convex_hull_batch(points, offsets, backend="cpu", threads=threads), one)


def test_edge_cases_written_out():
    cube = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
    clouds = [
        np.empty((0, 3)),  # empty
        np.array([[1.0, 2, 3]]),  # one point
        np.array([[0.0, 0, 0], [1, 1, 1]]),  # two
        np.array([[4.0, 4, 4], [4, 4, 4]]),  # one point twice
        np.array([[0.0, 0, 0], [2, 0, 0], [0, 3, 0]]),  # a triangle
        np.array([[0.0, 0, 0], [1, 1, 1], [2, 2, 2]]),  # three on a line
        np.vstack([[[0.5, 0.5, 0.5]], cube, cube[::-1]]),  # a cube, every corner twice, a point inside
        np.array([[0.0, 0, 5], [2, 0, 5], [1, 1, 5], [2, 2, 5], [0, 2, 5]]),  # a flat square
        np.array([[3.0, 0, 0], [1, 0, 0], [4, 0, 0], [0, 0, 0], [2, 0, 0]]),  # collinear
        np.empty((0, 3)),  # empty, last
    ]
    offsets = np.concatenate([[0], np.cumsum([len(p) for p in clouds])])
    h = cudahull.convex_hull_batch(np.concatenate(clouds), offsets, backend="cpu")
    assert h.dimensions.tolist() == [-1, 0, 1, 0, 2, 1, 3, 2, 1, -1]
    expected = [[], [0], [0, 1], [0], [0, 1, 2], [0, 2], list(range(1, 9)), [0, 1, 3, 4], [2, 3], []]
    assert [h.cloud(c)["vertices"].tolist() for c in range(len(clouds))] == expected
    assert h.face_offsets.tolist() == [0] * 7 + [12] * 4
    assert h.volumes[6] == 1.0 and h.areas[6] == 6.0
    assert h.areas[4] == 6.0 and h.areas[7] == 8.0  # both sides of the triangle and of the square
    assert h.volumes[[0, 1, 2, 3, 4, 5, 7, 8, 9]].tolist() == [0.0] * 9
    assert sorted(h.cloud(7)["polygon"].tolist()) == [0, 1, 3, 4]
    for c, cloud in enumerate(clouds):
        alone = cudahull.convex_hull(cloud, backend="cpu")
        assert h.cloud(c)["vertices"].tolist() == alone["vertices"].tolist()
        assert h.cloud(c)["polygon"].tolist() == alone["polygon"].tolist()
    # One cloud, and none.
    one = cudahull.convex_hull_batch(cube, [0, 8], backend="cpu")
    assert len(one) == 1 and one.cloud(0)["vertices"].tolist() == list(range(8)) and one.cloud(-1)["volume"] == 1
    none = cudahull.convex_hull_batch(np.empty((0, 3)), [0], backend="cpu")
    assert len(none) == 0 and none.vertex_offsets.tolist() == [0] and none.faces.shape == (0, 3)
    padded_none = cudahull.convex_hull_batch(np.empty((0, 5, 3)), backend="cpu")
    assert len(padded_none) == 0
    # Padded without lengths: every cloud fills its slab.
    full = cudahull.convex_hull_batch(np.stack([cube, cube + 1]), backend="cpu")
    assert full.vertex_offsets.tolist() == [0, 8, 16] and full.volumes.tolist() == [1.0, 1.0]


def test_float32_stays_float():
    rng = np.random.default_rng(5)
    clouds = [rng.normal(size=(n, 3)).astype(np.float32) for n in (4, 50, 700, 3000)]
    offsets = np.concatenate([[0], np.cumsum([len(p) for p in clouds])])
    h = cudahull.convex_hull_batch(np.concatenate(clouds), offsets, backend="cpu")
    assert h.precision == "float"
    for c, cloud in enumerate(clouds):
        assert np.array_equal(h.cloud(c)["vertices"], cudahull.convex_hull(cloud, backend="cpu")["vertices"])
        # Qhull computes in double on the same values, widened exactly.
        assert np.array_equal(h.cloud(c)["vertices"], scipy.spatial.ConvexHull(cloud.astype(np.float64)).vertices)
    in_double = cudahull.convex_hull_batch(np.concatenate(clouds), offsets, backend="cpu", precision="double")
    assert in_double.precision == "double" and np.array_equal(in_double.vertices, h.vertices)
    # Integers are taken as float64.
    grid = np.array([[x, y, z] for x in range(3) for y in range(3) for z in range(3)])
    ints = cudahull.convex_hull_batch(grid, [0, 27], backend="cpu")
    assert ints.precision == "double" and ints.vertices.tolist() == [0, 2, 6, 8, 18, 20, 24, 26]


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_points_name_the_cloud_and_the_point(bad):
    points = np.random.default_rng(1).normal(size=(30, 3))
    points[17, 1] = bad
    points[25, 0] = np.nan  # a later one: the first in packed order is named
    offsets = [0, 10, 10, 15, 30]
    with pytest.raises(ValueError, match=r"^cloud 3: point 2: y coordinate .* is not finite \(row 17 of the "
                                         r"packed points\)$"):
        cudahull.convex_hull_batch(points, offsets, backend="cpu")
    with pytest.raises(ValueError, match=r"^cloud 3: point 2: y coordinate"):
        cudahull.convex_hull_batch(points.astype(np.float32), offsets, backend="cpu", threads=1)
    # Padded: the cloud and the point in it (its row in the slab).
    padded = np.zeros((3, 6, 3))
    padded[:, :4] = np.eye(4, 3)
    padded[2, 3, 2] = bad
    with pytest.raises(ValueError, match=r"^cloud 2: point 3: z coordinate .* is not finite$"):
        cudahull.convex_hull_batch(padded, lengths=[4, 4, 4], backend="cpu")
    padded[2, 3, 2] = 0
    padded[2, 5, 0] = bad  # in the padding: no cloud's point
    assert cudahull.convex_hull_batch(padded, lengths=[4, 4, 4], backend="cpu").dimensions.tolist() == [3, 3, 3]


def test_bad_layouts_are_value_errors():
    points = np.zeros((10, 3))
    cases = [
        (dict(points=points), "packed \\(N, 3\\) points need offsets"),
        (dict(points=points, offsets=[0, 10], lengths=[10]), "lengths go with padded"),
        (dict(points=points.reshape(2, 5, 3), offsets=[0, 5, 10]), "offsets go with packed"),
        (dict(points=np.zeros((10, 2)), offsets=[0, 10]), "not one of shape \\(10, 2\\)"),
        (dict(points=points, offsets=[1, 10]), "offsets\\[0\\] is 1, not 0"),
        (dict(points=points, offsets=[0, 6, 4, 10]), "offsets decrease at cloud 1 \\(6 then 4\\)"),
        (dict(points=points, offsets=[0, 5]), "the last offset is 5, not the point count 10"),
        (dict(points=points, offsets=[0, -1, 10]), "offsets\\[1\\] is negative"),
        (dict(points=points, offsets=[0.0, 10.0]), "offsets must be integers"),
        (dict(points=points, offsets=[[0, 10]]), "offsets must be a 1-D array"),
        (dict(points=points, offsets=[]), "offsets must hold B \\+ 1"),
        (dict(points=points.reshape(2, 5, 3), lengths=[5]), "one length a cloud: 2, not 1"),
        (dict(points=points.reshape(2, 5, 3), lengths=[5, 6]), "lengths\\[1\\] is 6: a cloud holds 0 to 5"),
        (dict(points=np.array([["a", "b", "c"]]), offsets=[0, 1]), "points must be numbers"),
        (dict(points=points, offsets=[0, 10], backend="gpu"), "backend must be auto, cpu or cuda"),
        (dict(points=points, offsets=[0, 10], threads=-1), "threads must be a whole number"),
        (dict(points=points, offsets=[0, 10], threads=1.5), "threads must be a whole number"),
        (dict(points=points.reshape(2, 5, 3), lengths=np.array([5, 2**63 + 1], np.uint64)),
         "lengths\\[1\\] is 9223372036854775809: beyond int64"),
    ]
    for arguments, words in cases:
        with pytest.raises(ValueError, match=words):
            cudahull.convex_hull_batch(**arguments)


def test_cuda_backend_request(batch):
    points, offsets = batch.points[:batch.offsets[50]], batch.offsets[:51]
    if cudahull._cudahull.cuda_device()[0]:
        on_gpu = cudahull.convex_hull_batch(points, offsets, backend="cuda")
        assert on_gpu.backend.startswith("cuda")
        assert np.array_equal(on_gpu.vertices, batch.hulls.vertices[:batch.hulls.vertex_offsets[50]])
    else:
        with pytest.raises(cudahull.DeviceError, match="^backend cuda: no usable CUDA device: "):
            cudahull.convex_hull_batch(points, offsets, backend="cuda")
        assert cudahull.convex_hull_batch(points, offsets).backend.startswith("cpu")  # auto falls back


def exact_volume(points, faces):
    """Six times the volume of the closed outward mesh `faces` on `points`, in rational arithmetic, after
    checking that every point is on or below every face (then the mesh is the hull, and this its volume)."""
    q = [[Fraction(float(x)) for x in p] for p in points]

    def det(a, b, c, d):  # (a - d) . ((b - d) x (c - d)), positive when d is below the face (a, b, c)
        u, v, w = ([p[k] - d[k] for k in range(3)] for p in (a, b, c))
        return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + \
            u[2] * (v[0] * w[1] - v[1] * w[0])

    for a, b, c in faces:
        assert all(det(q[a], q[b], q[c], p) >= 0 for p in q)
    return sum(det(q[a], q[b], q[c], q[0]) for a, b, c in faces)


def exact_area(points, faces):
    """The faces' area from their exact cross products (each length to an ulp or so)."""
    q = [[Fraction(float(x)) for x in p] for p in points]
    area = 0.0
    for a, b, c in faces:
        u, v = ([q[i][k] - q[a][k] for k in range(3)] for i in (b, c))
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        area += float(sum(x * x for x in n)) ** 0.5 / 2
    return area


def test_measures_of_slivers_and_wide_ranges():
    """Volumes and areas where the terms cancel (slivers: the exact pass of plane_impl.hpp; needles) and
    where the coordinates leave the fast exact range (the wide path, scaled by powers of two), against
    rational arithmetic and closed forms; the batch and convex_hull() alike."""
    rng = np.random.default_rng(5)
    slivers = [np.array([[1e30, 3e29, 7e29], [-1e30, 1e30, 0], [1e-30, 2e-30, 1e-30], [0, 0, 0]]),
               np.array([[-1.930194037646372, -1.204502626035393, -0.7088424652129783],
                         [-0.21507838266500906, -0.0706887691553342, -0.07921269392390515],
                         [0.5019532202178966, -0.9050357596317037, 1.382136313697382],
                         [0.06497297525256951, -0.39840289853817645, 0.49323463054019184]])]
    for _ in range(40):  # four points on a line but for rounding: needles, where a face's area cancels
        p = rng.normal(size=(2, 3))
        needle = np.array([p[0], p[1], p[0] + 2 * (p[1] - p[0]), p[0] - (p[1] - p[0])])
        if cudahull.convex_hull(needle, backend="cpu")["dimension"] == 3:
            slivers.append(needle)
    for _ in range(6):  # 30 points in a slab 1e-9 thick, tilted: slivers everywhere
        p = rng.uniform(-1, 1, size=(30, 3)) * [1, 1, 1e-9]
        slivers.append(p @ np.linalg.qr(rng.normal(size=(3, 3)))[0])
    hulls = cudahull.convex_hull_batch(np.vstack(slivers), np.cumsum([0] + [len(p) for p in slivers]),
                                       backend="cpu")
    for c, points in enumerate(slivers):
        hull = hulls.cloud(c)
        assert hull["dimension"] == 3
        want = float(exact_volume(points, hull["faces"]) / 6)
        assert hull["volume"] == pytest.approx(want, rel=1e-12), c
        assert hull["area"] == pytest.approx(exact_area(points, hull["faces"]), rel=1e-12), c
        assert cudahull.convex_hull(points, backend="cpu")["volume"] == hull["volume"]
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    square = cube[cube[:, 2] == 0]
    for e in (400, -400, 700, -340):  # the cube 2^e on a side: its measures exact, or beyond a double
        def exactly(k, power):
            return float(k * Fraction(2) ** (power * e)) if power * e < 1020 else np.inf
        hull = cudahull.convex_hull_batch(cube * 2.0**e, [0, 8], backend="cpu").cloud(0)
        assert (hull["volume"], hull["area"]) == (exactly(1, 3), exactly(6, 2)), e
        flat = cudahull.convex_hull_batch(square * 2.0**e, [0, 4], backend="cpu").cloud(0)
        assert (flat["dimension"], flat["area"]) == (2, exactly(2, 2)), e
    # A sliver at 1e300 (the wide path): its planes as tight as the same sliver's in range.
    t = rng.integers(-50, 50, 8)
    wide = ((np.array([3.0, -4.0, 1.0]) + t[:, None] * np.array([1.0, 2.0, 3.0])) * 1e300
            + rng.normal(size=(8, 3)) * 1e287)
    hulls = cudahull.convex_hull_batch(wide, [0, 8], backend="cpu")
    assert hulls.backend == "cpu-wide"
    heights = wide @ hulls.planes[:, :3].T + hulls.planes[:, 3]
    assert heights.max() <= 1e-13 * np.abs(wide).max()


def test_measures_of_a_hull_of_many_chunks():
    """A hull of more than 2^20 faces is measured on all cores, a fixed chunk of faces a task
    (describe.cpp, measure_on_cores()): its volume and area against a compensated sum of its faces' terms
    (math.fsum of numpy's)."""
    import math
    rng = np.random.default_rng(11)
    points = rng.normal(size=(530_000, 3))
    points /= np.linalg.norm(points, axis=1, keepdims=True)  # every point a vertex: 1,059,996 faces
    hull = cudahull.convex_hull(points, backend="cpu")
    faces = hull["simplices"]
    assert len(faces) > 2**20
    a, b, c = (points[faces[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    volume = math.fsum((n * (a - a[0])).sum(axis=1)) / 6
    area = math.fsum(np.linalg.norm(n, axis=1)) / 2
    assert hull["volume"] == pytest.approx(volume, rel=1e-12)
    assert hull["area"] == pytest.approx(area, rel=1e-12)


# --- a list of clouds, as scipy users reach for it ----------------------------------------------------------


def test_a_list_of_clouds_is_each_clouds_hull():
    """10,000 clouds of 6-40 points given as a list: each cloud's vertices are convex_hull()'s on it alone and
    Qhull's (general position: no repeated point, so the vertex sets are the same), with scipy's measures."""
    rng = np.random.default_rng(20118)
    clouds = [rng.normal(size=(int(n), 3)) for n in rng.integers(6, 41, size=10_000)]
    hulls = cudahull.convex_hull_batch(clouds, backend="cpu")
    assert len(hulls) == len(clouds) and hulls.dimensions.tolist() == [3] * len(clouds)
    for c in range(0, len(clouds), 97):  # every 97th against both oracles
        vertices = hulls.cloud(c)["vertices"].tolist()
        assert vertices == cudahull.convex_hull(clouds[c], backend="cpu")["vertices"].tolist(), c
        theirs = scipy.spatial.ConvexHull(clouds[c])
        assert vertices == sorted(theirs.vertices.tolist()), c
        assert hulls.volumes[c] == pytest.approx(theirs.volume, rel=1e-9)
        assert hulls.areas[c] == pytest.approx(theirs.area, rel=1e-9)
    # The same answer as the packed call.
    packed = cudahull.convex_hull_batch(np.concatenate(clouds), np.cumsum([0] + [len(p) for p in clouds]),
                                        backend="cpu")
    for key in ("vertex_offsets", "vertices", "face_offsets", "faces", "planes", "volumes", "areas"):
        assert np.array_equal(getattr(hulls, key), getattr(packed, key)), key


def test_lists_tuples_and_mixed_clouds():
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float32)
    clouds = (cube, np.empty((0, 3)), [[0.0, 0, 0], [1, 0, 0], [0, 1, 0]], cube.astype(np.float64) * 2,
              np.ones((5, 3), dtype=np.int64))
    hulls = cudahull.convex_hull_batch(clouds, backend="cpu")
    assert hulls.dimensions.tolist() == [3, -1, 2, 3, 0]
    assert hulls.volumes.tolist()[0] == 1.0 and hulls.volumes.tolist()[3] == 8.0
    assert hulls.precision == "double"  # NumPy's promotion of float32 with float64: exact, in double
    for c, cloud in enumerate(clouds):
        alone = cudahull.convex_hull(np.asarray(cloud, dtype=np.float64).reshape(-1, 3), backend="cpu")
        assert hulls.cloud(c)["vertices"].tolist() == alone["vertices"].tolist(), c
    assert hulls.vertex_offsets.tolist() == [0, 8, 8, 11, 19, 20]
    assert len(cudahull.convex_hull_batch([], backend="cpu")) == 0
    # All float32: computed in float.
    assert cudahull.convex_hull_batch([cube, cube + 1], backend="cpu").precision == "float"
    # Equal-sized clouds written as nested lists: the same as the padded array they also are.
    nested = [cube.tolist(), (cube + 3).tolist()]
    assert cudahull.convex_hull_batch(nested, backend="cpu").vertices.tolist() == list(range(8)) * 2


def test_a_list_of_clouds_names_the_bad_cloud():
    clouds = [np.eye(4, 3), np.eye(4, 3) + 1, np.random.default_rng(0).normal(size=(6, 3))]
    clouds[2][3, 2] = np.nan
    # The cloud and the point in it: the packed copy's row is nothing the caller saw.
    with pytest.raises(ValueError, match=r"^cloud 2: point 3: z coordinate nan is not finite$"):
        cudahull.convex_hull_batch(clouds, backend="cpu")
    with pytest.raises(ValueError, match=r"^cloud 1 must be an \(n, 3\) array, not one of shape \(4, 2\)"):
        cudahull.convex_hull_batch([np.eye(4, 3), np.eye(4, 2)], backend="cpu")
    with pytest.raises(ValueError, match=r"^cloud 0 must be an \(n, 3\) array, not one of shape \(3,\)"):
        cudahull.convex_hull_batch([np.zeros(3)], backend="cpu")
    with pytest.raises(ValueError, match="points must be numbers"):
        cudahull.convex_hull_batch([np.array([["a", "b", "c"]])], backend="cpu")
