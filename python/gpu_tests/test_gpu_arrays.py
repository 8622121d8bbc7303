"""CuPy arrays and PyTorch CUDA tensors, read in place (issue 16), against the same points given as NumPy: the
same hull (vertices, triangles, neighbours, planes, volume, area), the same errors, and far fewer bytes read
back than the points hold.  ctest label gpu: skipped (exit 77) where there is no GPU, CuPy or PyTorch."""

import numpy as np
import pytest
import scipy.spatial

import cudahull
from device_arrays import gpu_only, on_device, to_numpy

pytestmark = gpu_only


def distributions():
    rng = np.random.default_rng(2026)
    n = 20000
    ball = rng.uniform(-1, 1, size=(3 * n, 3))
    ball = ball[np.linalg.norm(ball, axis=1) <= 1][:n]
    sphere = rng.normal(size=(2000, 3))
    sphere /= np.linalg.norm(sphere, axis=1, keepdims=True)
    grid = np.array([[x, y, z] for x in range(12) for y in range(12) for z in range(12)], dtype=np.float64)
    a, b = rng.integers(-50, 50, size=(2, 3000))
    tilted = np.outer(a, [1, 2, 3]) + np.outer(b, [-2, 1, 0])  # exactly coplanar, in float32 too
    corners = np.array([[x, y, z] for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, 1.0)])
    duplicates = np.concatenate([rng.uniform(0.1, 0.9, size=(500, 3)), np.repeat(corners, 40, axis=0)])
    return {
        # In general position: the triangulation is unique, scipy is an oracle.
        "ball": ball,
        "cube": rng.uniform(-1, 1, size=(n, 3)),
        "gauss": rng.normal(size=(n, 3)),
        "sphere": sphere,  # every point a vertex
        "shifted": ball * [1e3, 1, 1e-3] + [1e6, -5, 7],
        # Degenerate: coplanar points on faces, flat, collinear, repeated, too few, none.
        "grid": grid,
        "duplicates": duplicates,
        "flat": np.column_stack([rng.uniform(-1, 1, size=(5000, 2)), np.zeros(5000)]),
        "tilted_flat": tilted.astype(np.float64),
        "collinear": np.outer(rng.integers(-1000, 1000, size=500), [1, 2, 3]).astype(np.float64),
        "one_point": np.full((100, 3), 0.5),
        "three": rng.normal(size=(3, 3)),
        "empty": np.empty((0, 3)),
    }


DISTRIBUTIONS = distributions()
GENERAL_POSITION = {"ball", "cube", "gauss", "sphere", "shifted"}


def faces(hull):
    """Each triangle (rotated to start at its smallest index, orientation kept) -> its neighbours' vertex
    sets in the same corner order, and its plane."""
    s, n, e = to_numpy(hull.simplices), to_numpy(hull.neighbors), to_numpy(hull.equations)
    out = {}
    for f in range(len(s)):
        t = s[f].tolist()
        k = t.index(min(t))
        across = [tuple(sorted(s[g].tolist())) for g in n[f].tolist()]
        out[tuple(t[k:] + t[:k])] = (tuple(across[k:] + across[:k]), tuple(e[f].tolist()))
    return out


def assert_same_hull(got, want, exact_mesh=True):
    assert got.dimension == want.dimension
    assert got.precision == want.precision
    assert np.array_equal(to_numpy(got.vertices), want.vertices)
    if exact_mesh:
        assert faces(got) == faces(want)
    assert got.volume == pytest.approx(want.volume, rel=1e-12, abs=0)
    assert got.area == pytest.approx(want.area, rel=1e-12, abs=0)


FLAT = {"flat", "tilted_flat", "collinear", "one_point", "three", "empty"}


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("name", sorted(FLAT))
def test_flat_input_as_numpys(lib, name, dtype):
    """ConvexHull raises scipy's error for flat input (QhullError; ValueError for none), on the device as on
    the host; convex_hull() gives the same lower-dimensional hull from both."""
    points = DISTRIBUTIONS[name].astype(dtype)
    device_points = on_device(lib, points)
    expected = ValueError if len(points) == 0 else cudahull.QhullError
    with pytest.raises(expected):
        cudahull.ConvexHull(points)
    with pytest.raises(expected):
        cudahull.ConvexHull(device_points)
    got, want = cudahull.convex_hull(device_points), cudahull.convex_hull(points, engine="resident")
    assert got["dimension"] == want["dimension"] < 3
    for key in ("vertices", "polygon"):
        assert np.array_equal(got[key], want[key]), key
    assert got["area"] == pytest.approx(want["area"], rel=1e-12, abs=0)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("name", sorted(set(DISTRIBUTIONS) - FLAT))
def test_same_hull_as_numpy(lib, name, dtype):
    points = DISTRIBUTIONS[name].astype(dtype)
    device_points = on_device(lib, points)
    got = cudahull.ConvexHull(device_points)
    assert got.points is device_points and got.npoints == len(points)
    # The same engine from host memory: the same mesh, face for face, in as many iterations (at least one in
    # general position; the grid's and the duplicates' 8 corners can be the first hull's).
    host = cudahull.ConvexHull(points, engine="resident")
    assert got.backend == host.backend == "cuda-resident"
    # Each says how it ran: the device array as points in GPU memory, the host array as the plan for host
    # points (uploaded, then read in place), not as its uploaded copy.
    assert "backend cuda (points in GPU memory)" in got.plan and got.stats["plan"] == got.plan
    assert host.plan.startswith("resident engine (as requested); backend cuda (auto: a usable CUDA device)")
    assert got.stats["iterations"] == host.stats["iterations"]
    assert got.stats["iterations"] > 0 or name not in GENERAL_POSITION
    assert_same_hull(got, host)
    # The stepping engine, host points checked on the host: the same exact hull; the same triangles where
    # they are unique.
    stepping = cudahull.ConvexHull(points, engine="stepping")
    assert_same_hull(got, stepping, exact_mesh=False)
    # shifted in float32 rounds to a coarse grid, where four points on a plane are no longer rare.
    if name in GENERAL_POSITION and not (name == "shifted" and dtype == np.float32):
        assert faces(got).keys() == faces(stepping).keys()
        qhull = scipy.spatial.ConvexHull(points.astype(np.float64))
        assert np.array_equal(to_numpy(got.vertices), qhull.vertices)
        assert got.volume == pytest.approx(qhull.volume, rel=1e-9)
        assert got.area == pytest.approx(qhull.area, rel=1e-9)
    assert np.array_equal(got.min_bound, points.min(axis=0))
    assert np.array_equal(got.max_bound, points.max(axis=0))


@pytest.mark.parametrize("dtype, precision", [(np.float64, "float"), (np.float32, "double")])
@pytest.mark.parametrize("name", ["ball", "grid", "shifted"])
def test_precision_conversion_on_the_device(lib, name, dtype, precision):
    points = DISTRIBUTIONS[name].astype(dtype)
    got = cudahull.ConvexHull(on_device(lib, points), precision=precision)
    assert got.precision == precision
    assert_same_hull(got, cudahull.ConvexHull(points, precision=precision, engine="resident"))


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("name", ["ball", "cube", "gauss"])
def test_bytes_read_back_are_far_below_the_points(lib, name, dtype):
    """2M points: the result and the exact checks' coordinates come back, not the points."""
    rng = np.random.default_rng(7)
    n = 2_000_000
    if name == "ball":
        points = rng.uniform(-1, 1, size=(2 * n, 3))
        points = points[np.linalg.norm(points, axis=1) <= 1][:n]
    elif name == "cube":
        points = rng.uniform(-1, 1, size=(n, 3))
    else:
        points = rng.normal(size=(n, 3))
    points = points.astype(dtype)
    got = cudahull.ConvexHull(on_device(lib, points))
    point_bytes = points.nbytes
    stats = got.stats
    assert stats["bytes_from_device"] < point_bytes / 50, stats
    assert stats["points_read_back"] < n / 100, stats
    assert stats["bytes_to_device"] < point_bytes / 50, stats
    want = cudahull.ConvexHull(points, engine="resident")
    assert np.array_equal(to_numpy(got.vertices), want.vertices)
    assert got.volume == pytest.approx(want.volume, rel=1e-12)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_points_raise_the_numpy_paths_error(lib, dtype, bad):
    points = DISTRIBUTIONS["cube"].astype(dtype).copy()
    points[1234, 1] = bad
    points[5678, 0] = np.nan  # a later bad point: the first is named, as on the host
    with pytest.raises(ValueError) as host_error:
        cudahull.ConvexHull(points, engine="stepping")  # checked on the host
    with pytest.raises(ValueError) as device_error:
        cudahull.ConvexHull(on_device(lib, points))
    assert str(device_error.value) == str(host_error.value)
    assert str(device_error.value).startswith("point 1234: y coordinate ")


def test_a_double_beyond_float_raises_the_numpy_paths_error(lib):
    points = DISTRIBUTIONS["gauss"].copy()
    points[42, 2] = 1e39
    with pytest.raises(ValueError) as host_error:
        cudahull.ConvexHull(points, precision="float", engine="stepping")
    with pytest.raises(ValueError) as device_error:
        cudahull.ConvexHull(on_device(lib, points), precision="float")
    assert str(device_error.value) == str(host_error.value)
    assert str(device_error.value).startswith("point 42: z coordinate ")


@pytest.mark.parametrize("value", [1e300, -1e-300, 5e-324])
@pytest.mark.parametrize("columns", [3, 2])
def test_doubles_outside_the_engines_range_take_the_wide_path(lib, value, columns):
    """Every finite double (issue 25): the device's check sends such input to the host's exact wide path,
    which gives the NumPy path's hull."""
    points = DISTRIBUTIONS["gauss"][:, :columns].copy()  # not the shared array: it is changed below
    points[42, columns - 1] = value
    got = cudahull.ConvexHull(on_device(lib, points))
    want = cudahull.ConvexHull(points)
    assert want.backend == "cpu-wide" or columns == 2
    assert np.array_equal(got.vertices, want.vertices)
    assert np.array_equal(got.simplices, want.simplices)


def test_device_results_are_arrays_of_the_inputs_kind(lib):
    points = DISTRIBUTIONS["gauss"]
    device_points = on_device(lib, points)
    got = cudahull.ConvexHull(device_points, device_results=True)
    want = cudahull.ConvexHull(points, engine="resident")
    for name in ("vertices", "simplices", "neighbors", "equations", "coplanar", "min_bound", "max_bound"):
        value = getattr(got, name)
        assert type(value) is type(device_points), name
        assert value.device == device_points.device, name
        if name not in ("simplices", "neighbors", "equations"):  # the mesh is compared face by face below
            assert np.array_equal(to_numpy(value), getattr(want, name)), name
    assert faces(got) == faces(want)
    as_dict = cudahull.convex_hull(device_points, device_results=True)
    assert type(as_dict["vertices"]) is type(device_points)
    assert np.array_equal(to_numpy(as_dict["vertices"]), want.vertices)
    assert as_dict["stats"]["bytes_from_device"] > 0
    plain = cudahull.convex_hull(device_points)
    assert isinstance(plain["vertices"], np.ndarray)
    assert np.array_equal(plain["vertices"], want.vertices)


def test_add_points_on_the_device(lib):
    points = DISTRIBUTIONS["ball"]
    half = len(points) // 2
    hull = cudahull.ConvexHull(on_device(lib, points[:half]))
    hull.add_points(on_device(lib, points[half:]))
    assert hull.npoints == len(points)
    want = cudahull.ConvexHull(points, engine="stepping")
    assert np.array_equal(hull.vertices, want.vertices)
    assert hull.volume == pytest.approx(want.volume, rel=1e-12)
    with pytest.raises(ValueError, match="takes .* points in GPU memory"):
        hull.add_points(points[:10])


def test_cuda_array_interface_alone(lib):
    """An array offering only __cuda_array_interface__ (as Numba's), read through its pointer."""

    class InterfaceOnly:
        def __init__(self, array):
            self.array = array  # keeps the memory alive
            self.__cuda_array_interface__ = array.__cuda_array_interface__
            self.shape = tuple(array.shape)

    for dtype in (np.float32, np.float64):
        points = DISTRIBUTIONS["grid"].astype(dtype)
        got = cudahull.ConvexHull(InterfaceOnly(on_device(lib, points)))
        assert_same_hull(got, cudahull.ConvexHull(points, engine="resident"))


def test_layouts_and_types_the_engine_cannot_read(lib):
    points = on_device(lib, DISTRIBUTIONS["cube"])
    with pytest.raises(ValueError, match="must be C-contiguous"):
        cudahull.ConvexHull(points[::2])
    with pytest.raises(ValueError, match="must be float32 or float64"):
        cudahull.ConvexHull(points[:, :3].to(lib.float16) if lib.__name__ == "torch" else points.astype("f2"))
    with pytest.raises(ValueError, match=r"must be an \(n, 3\) or \(n, 2\) array"):
        cudahull.ConvexHull(points[:, 0].copy() if lib.__name__ == "cupy" else points[:, 0].contiguous())
    with pytest.raises(ValueError, match="need backend 'auto' or 'cuda'"):
        cudahull.ConvexHull(points, backend="cpu")


def test_torch_specifics():
    torch = pytest.importorskip("torch")
    if not torch.cuda.is_available():
        pytest.skip("PyTorch sees no CUDA device")
    points = DISTRIBUTIONS["gauss"]
    want = cudahull.ConvexHull(points, engine="resident")
    # A tensor that requires grad is read as values.
    tensor = torch.from_numpy(points).cuda().requires_grad_(True)
    assert np.array_equal(cudahull.ConvexHull(tensor).vertices, want.vertices)
    # Written on a side stream: the hull waits for the producer.
    stream = torch.cuda.Stream()
    with torch.cuda.stream(stream):
        late = torch.from_numpy(points).cuda(non_blocking=True) * 2
    got = cudahull.ConvexHull(late)
    assert np.array_equal(got.vertices, want.vertices)
    assert got.volume == pytest.approx(want.volume * 8, rel=1e-12)


def planar_sets():
    rng = np.random.default_rng(25)
    n = 200_000
    angle = rng.uniform(0, 2 * np.pi, size=n)
    radius = np.sqrt(rng.uniform(0, 1, size=n))
    circle = rng.uniform(0, 2 * np.pi, size=3000)
    t = rng.integers(-500, 500, size=5000).astype(np.float64)
    square = rng.uniform(-1, 1, size=(n, 2))
    return {
        "square": square,
        "disc": np.column_stack([radius * np.cos(angle), radius * np.sin(angle)]),
        "gauss": rng.normal(size=(n, 2)) * [1e3, 1e-3] + [1e6, -5],
        "circle": np.column_stack([np.cos(circle), np.sin(circle)]),  # every point a corner
        "grid": rng.integers(-20, 21, size=(n, 2)).astype(np.float64),  # collinear points on every edge
        "duplicates": np.concatenate([square[:1000], square[:1000], [[2, 2], [2, 2], [-2, -2]]]),
        "collinear": np.column_stack([t, 3 * t - 1]),  # degenerate: the device leaves it to the host
        "one_point": np.full((50, 2), 0.25),
    }


PLANAR = planar_sets()


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("name", sorted(PLANAR))
def test_2d_points_on_the_device_give_the_numpy_paths_hull(lib, name, dtype):
    """2-D points in GPU memory (issue 25): filtered on the device, finished on the host, the same hull as
    from NumPy (vertices counter-clockwise, edges, lines, area, perimeter), and few bytes read back."""
    points = PLANAR[name].astype(dtype)
    device_points = on_device(lib, points)
    want = cudahull.convex_hull(points)
    got = cudahull.convex_hull(device_points)
    assert got["dimension"] == want["dimension"] and got["precision"] == want["precision"]
    for key in ("vertices", "polygon", "simplices", "neighbors", "equations"):
        assert np.array_equal(got[key], want[key]), key
    assert got["volume"] == want["volume"] and got["area"] == want["area"]
    if want["dimension"] == 2:
        hull = cudahull.ConvexHull(device_points)
        assert hull.backend == "cuda" and np.array_equal(hull.vertices, want["polygon"])
        if name in ("square", "disc", "gauss"):
            reference = scipy.spatial.ConvexHull(points.astype(np.float64))  # exact in general position
            assert sorted(hull.vertices.tolist()) == sorted(reference.vertices.tolist())


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_2d_bad_points_on_the_device_raise_the_numpy_paths_error(lib, bad):
    points = PLANAR["square"].copy()
    points[777, 1] = bad
    points[9999, 0] = bad
    with pytest.raises(ValueError) as host_error:
        cudahull.ConvexHull(points)
    with pytest.raises(ValueError) as device_error:
        cudahull.ConvexHull(on_device(lib, points))
    assert str(device_error.value) == str(host_error.value)
    assert str(device_error.value).startswith("point 777: y coordinate ")


def test_merging_on_the_device_as_on_the_host(lib):
    """qhull_options on points in GPU memory: the same merged hull and certificate as from NumPy."""
    rng = np.random.default_rng(3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    box = rng.uniform(-1, 1, size=(20000, 3)) * [2, 1, 0.5]
    box = np.clip(box, [-1.9, -0.9, -0.45], [1.9, 0.9, 0.45]) @ q.T + [3, -2, 7]  # points on flat faces
    got = cudahull.ConvexHull(on_device(lib, box), qhull_options="Qt")
    want = cudahull.ConvexHull(box, qhull_options="Qt")
    assert np.array_equal(got.vertices, want.vertices)
    assert got.max_outside == want.max_outside and got.tolerance == want.tolerance
    # Qhull's vertices, as points (the clipped corners are many duplicate points: Qhull keeps any one of them).
    assert {tuple(p) for p in box[to_numpy(got.vertices)].tolist()} == \
        {tuple(p) for p in box[scipy.spatial.ConvexHull(box).vertices].tolist()}
