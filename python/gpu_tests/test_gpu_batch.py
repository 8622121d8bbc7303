"""convex_hull_batch (issue 27) from CuPy arrays and PyTorch CUDA tensors, against the same clouds given as
NumPy on the CPU backend: cloud for cloud the same hulls, results of the input's kind on its device, the same
errors.  The GPU runs the small clouds on its batch kernels (a warp a cloud up to 256 points, a furthest point at a
time; a block a cloud above, the resident iteration; a block's flat-faced leftovers on warps again), the
CPU each cloud alone: the same vertex sets, and the same faces in another order.  ctest label gpu:
skipped (exit 77) where there is no GPU, CuPy or PyTorch."""

import numpy as np
import pytest

import cudahull
from device_arrays import gpu_only, on_device, to_numpy

pytestmark = gpu_only


def clouds():
    """Clouds of every kind and size that the batch must take, small ones most."""
    rng = np.random.default_rng(27)
    out = [np.empty((0, 3)), rng.normal(size=(1, 3)), rng.normal(size=(2, 3)), rng.normal(size=(3, 3)),
           np.repeat(rng.normal(size=(1, 3)), 5, axis=0),  # one point, five times
           np.outer(np.arange(-20, 20), [1.0, 2, 3]),  # collinear
           np.column_stack([rng.integers(-50, 50, size=(300, 2)), np.zeros(300)]).astype(np.float64),  # flat
           rng.integers(0, 6, size=(400, 3)).astype(np.float64)]  # integer grid
    for n in np.exp(rng.uniform(np.log(4), np.log(5000), size=120)).astype(int):
        out.append(rng.uniform(-1, 1, size=(n, 3)) if n % 2 else rng.normal(size=(n, 3)))
    return out


CLOUDS = clouds()


def canonical(faces, planes):
    """A cloud's faces each from its least corner (orientation kept), in order, with their planes."""
    faces = np.asarray(faces).copy()
    roll = np.argmin(faces, axis=1)
    for r in (1, 2):
        faces[roll == r] = np.roll(faces[roll == r], -r, axis=1)
    order = np.lexsort(faces.T[::-1])
    return faces[order], np.asarray(planes)[order]


def assert_as_on_the_cpu(got, points, offsets, library):
    """Against the CPU's batch with the resident engine (the GPU's blocks run its iteration, its warps
    QuickHull's step): the same vertex sets, measures and flat answers, as arrays of `library`; the same faces
    with the same planes, in any order, for every cloud in general position (a coplanar facet may be cut
    along either diagonal); and against the CPU's default engine (stepping): the same vertex sets."""
    want = cudahull.convex_hull_batch(points, offsets, backend="cpu", engine="resident")
    assert len(got) == len(want)
    for key in ("vertex_offsets", "face_offsets", "vertices", "faces", "planes", "dimensions", "polygon_offsets",
                "polygons", "volumes", "areas"):
        array = getattr(got, key)
        assert type(array).__module__.partition(".")[0] == library, key
        if key in ("volumes", "areas"):
            assert to_numpy(array) == pytest.approx(getattr(want, key), rel=1e-12, abs=0), key
        elif key not in ("faces", "planes"):
            assert np.array_equal(to_numpy(array), getattr(want, key)), key
    bounds = to_numpy(got.face_offsets)
    faces, planes = to_numpy(got.faces), to_numpy(got.planes)
    general = 0
    for c in range(len(want)):
        points_c = points[offsets[c]:offsets[c + 1]]
        if len(points_c) < 4 or np.all(points_c == np.round(points_c)):
            continue  # tiny, or integer coordinates: coplanar facets
        b, e = bounds[c], bounds[c + 1]
        got_faces, got_planes = canonical(faces[b:e], planes[b:e])
        want_faces, want_planes = canonical(want.faces[b:e], want.planes[b:e])
        assert np.array_equal(got_faces, want_faces), c
        assert got_planes == pytest.approx(want_planes, rel=0, abs=1e-12), c
        general += 1
    assert general > 100
    stepping = cudahull.convex_hull_batch(points, offsets, backend="cpu")
    assert np.array_equal(to_numpy(got.vertices), stepping.vertices)
    assert np.array_equal(to_numpy(got.vertex_offsets), stepping.vertex_offsets)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_packed_on_the_device_as_numpys(lib, dtype):
    points = np.concatenate(CLOUDS).astype(dtype)
    offsets = np.concatenate([[0], np.cumsum([len(p) for p in CLOUDS])])
    got = cudahull.convex_hull_batch(on_device(lib, points), offsets)
    assert got.backend.startswith("cuda") and got.precision == ("float" if dtype == np.float32 else "double")
    assert_as_on_the_cpu(got, points, offsets, lib.__name__)
    # Offsets given on the device too.
    again = cudahull.convex_hull_batch(on_device(lib, points), on_device(lib, offsets.astype(np.int64)))
    assert np.array_equal(to_numpy(again.vertices), to_numpy(got.vertices))


def test_padded_on_the_device_as_packed(lib):
    slab = max(len(p) for p in CLOUDS)
    padded = np.full((len(CLOUDS), slab, 3), np.nan)  # NaN padding: no cloud's points
    for row, cloud in enumerate(CLOUDS):
        padded[row, :len(cloud)] = cloud
    lengths = np.array([len(p) for p in CLOUDS])
    got = cudahull.convex_hull_batch(on_device(lib, padded), lengths=lengths)
    offsets = np.concatenate([[0], np.cumsum(lengths)])
    assert_as_on_the_cpu(got, np.concatenate(CLOUDS), offsets, lib.__name__)


def test_errors_name_the_cloud_and_the_point(lib):
    points = np.random.default_rng(3).normal(size=(30, 3))
    points[17, 1] = np.nan
    with pytest.raises(ValueError, match=r"^cloud 3: point 2: y coordinate nan is not finite \(row 17 of the "
                                         r"packed points\)$"):
        cudahull.convex_hull_batch(on_device(lib, points), [0, 10, 10, 15, 30])
    with pytest.raises(ValueError, match="need backend 'auto' or 'cuda'"):
        cudahull.convex_hull_batch(on_device(lib, points), [0, 30], backend="cpu")


def test_cuda_backend_on_host_points():
    """Host points on the CUDA backend are uploaded as given and checked on the device: the CPU's hulls, a
    double cloud beyond the fast exact range alone on the wide path, and a bad point named as the CPU names
    it (in the precision asked for)."""
    points = np.concatenate(CLOUDS)
    offsets = np.concatenate([[0], np.cumsum([len(p) for p in CLOUDS])])
    got = cudahull.convex_hull_batch(points, offsets, backend="cuda")
    want = cudahull.convex_hull_batch(points, offsets, backend="cpu")
    assert got.backend.startswith("cuda")
    assert np.array_equal(got.vertices, want.vertices) and np.array_equal(got.dimensions, want.dimensions)
    rng = np.random.default_rng(13)
    clouds = [rng.normal(size=(300, 3)) for _ in range(5)]
    clouds[1] = clouds[1] * 1e80
    wide = np.concatenate(clouds)
    offsets = np.concatenate([[0], np.cumsum([len(c) for c in clouds])])
    got = cudahull.convex_hull_batch(wide, offsets, backend="cuda")
    want = cudahull.convex_hull_batch(wide, offsets, backend="cpu")
    assert got.report["clouds_batched"] == 4 and "cpu-wide" in got.backend
    assert np.array_equal(got.vertex_offsets, want.vertex_offsets) and np.array_equal(got.vertices, want.vertices)
    assert_many_wide_clouds_stay_apart(lambda points: points)
    narrow = np.concatenate([clouds[0], clouds[2], clouds[3]])
    for value, precision, message in ((np.nan, "auto", "nan is not finite"),
                                      (1e39, "float", "1e\\+39 does not fit in float")):
        bad = narrow.copy()
        bad[610, 1] = value  # cloud 2, point 10
        for backend in ("cpu", "cuda"):
            with pytest.raises(ValueError, match=r"^cloud 2: point 10: y coordinate " + message +
                                                 r" \(row 610 of the packed points\)$"):
                cudahull.convex_hull_batch(bad, [0, 300, 600, 900], backend=backend, precision=precision)


def test_large_host_batch_crosses_the_bus_intact(lib):
    """A batch of host points large enough that its upload (48 MB) and its planes (25 MB) cross through
    the pinned staging buffers, chunk by chunk on all cores: every column the same bits as the same clouds'
    result read from the device by `lib` itself, and the vertex sets and measures the CPU's."""
    rng = np.random.default_rng(45)
    points = rng.normal(size=(20_000 * 100, 3))
    offsets = np.arange(0, len(points) + 1, 100)
    got = cudahull.convex_hull_batch(points, offsets, backend="cuda")
    assert got.backend.startswith("cuda") and got.planes.nbytes > 16 << 20  # host_transfer.hpp's kStagedFrom
    on_gpu = cudahull.convex_hull_batch(on_device(lib, points), offsets)
    for key in ("vertex_offsets", "face_offsets", "polygon_offsets", "vertices", "faces", "planes", "polygons",
                "volumes", "areas", "dimensions"):
        assert np.array_equal(getattr(got, key), to_numpy(getattr(on_gpu, key))), key
    want = cudahull.convex_hull_batch(points, offsets, backend="cpu")
    assert np.array_equal(got.vertex_offsets, want.vertex_offsets) and np.array_equal(got.vertices, want.vertices)
    assert np.array_equal(got.face_offsets, want.face_offsets)
    assert got.volumes == pytest.approx(want.volumes, rel=1e-12, abs=0)


def test_results_are_the_devices_own(lib):
    """The result's arrays are the input library's, on the GPU, of the documented dtypes and shapes (PyTorch's
    indices int64, CuPy's int32), equal to the host result's values; they outlive the input and the call's
    other arrays; an empty batch and a batch of only tiny clouds (all on the single-cloud path) come back the
    same way; `report` says what the GPU did."""
    rng = np.random.default_rng(5)
    points = rng.normal(size=(3000, 3))
    offsets = np.array([0, 1000, 1003, 3000])
    got = cudahull.convex_hull_batch(on_device(lib, points), offsets)
    want = cudahull.convex_hull_batch(points, offsets, backend="cpu", engine="resident")
    index = "int64" if lib.__name__ == "torch" else "int32"
    for key, dtype, shape in (("vertex_offsets", "int64", (4,)), ("face_offsets", "int64", (4,)),
                              ("vertices", index, want.vertices.shape), ("faces", index, want.faces.shape),
                              ("planes", "float64", want.planes.shape), ("volumes", "float64", (3,)),
                              ("areas", "float64", (3,)), ("dimensions", index, (3,))):
        array = getattr(got, key)
        assert type(array).__module__.partition(".")[0] == lib.__name__, key
        assert str(array.dtype).rpartition(".")[2] == dtype, key
        assert tuple(array.shape) == shape, key
    assert got.report["clouds_batched"] == 2 and got.report["batch_launches"] >= 1
    assert got.report["device_bytes_peak"] > points.nbytes
    vertices = got.vertices
    del got
    import gc
    gc.collect()
    cudahull.convex_hull_batch(on_device(lib, rng.normal(size=(5000, 3))), [0, 5000])  # reuses freed blocks
    assert np.array_equal(to_numpy(vertices), want.vertices)
    empty = cudahull.convex_hull_batch(on_device(lib, np.empty((0, 3))), [0])
    assert len(empty) == 0 and tuple(empty.vertex_offsets.shape) == (1,)
    tiny = cudahull.convex_hull_batch(on_device(lib, points[:9]), [0, 3, 3, 9])
    assert tiny.report["clouds_batched"] == 1  # the 6-point cloud; the others are lower-dimensional
    assert np.array_equal(to_numpy(tiny.dimensions), [2, -1, 3])


def test_one_wide_cloud_leaves_the_others_on_the_kernel(lib):
    """A double cloud beyond the fast exact range (coordinates near 1e80) takes the wide path alone: the
    clouds around it stay on the batch kernel, and every cloud equals the CPU's."""
    rng = np.random.default_rng(11)
    clouds = [rng.normal(size=(200, 3)) for _ in range(6)]
    clouds[2] = clouds[2] * 1e80
    points = np.concatenate(clouds)
    offsets = np.concatenate([[0], np.cumsum([len(c) for c in clouds])])
    got = cudahull.convex_hull_batch(on_device(lib, points), offsets)
    want = cudahull.convex_hull_batch(points, offsets, backend="cpu")
    assert got.report["clouds_batched"] == 5
    assert "cpu-wide" in got.backend
    assert np.array_equal(to_numpy(got.vertex_offsets), want.vertex_offsets)
    assert np.array_equal(to_numpy(got.vertices), want.vertices)
    bad = points.copy()
    bad[850, 2] = np.inf  # cloud 4, point 50
    with pytest.raises(ValueError, match=r"^cloud 4: point 50: z coordinate .* is not finite"):
        cudahull.convex_hull_batch(on_device(lib, bad), offsets)
    assert_many_wide_clouds_stay_apart(lambda points: on_device(lib, points))


def assert_many_wide_clouds_stay_apart(place):
    """75 wide clouds among 150, from points placed by `place`: each takes the wide path alone, the other 75
    the kernel, every cloud the CPU's."""
    rng = np.random.default_rng(17)
    clouds = [rng.normal(size=(50, 3)) * (1e80 if c % 2 else 1) for c in range(150)]
    points = np.concatenate(clouds)
    offsets = np.arange(151) * 50
    got = cudahull.convex_hull_batch(place(points), offsets)
    want = cudahull.convex_hull_batch(points, offsets, backend="cpu")
    assert got.report["clouds_batched"] == 75
    assert np.array_equal(to_numpy(got.vertex_offsets), want.vertex_offsets)
    assert np.array_equal(to_numpy(got.vertices), want.vertices)


def test_release_device_memory_hands_the_batchs_memory_back(lib):
    """A batch keeps the memory it used for the next one of its size; release_device_memory() hands it back to
    the driver (with no result alive, the device's free memory grows by most of the batch's peak), and a
    result alive through it stays valid."""
    import gc

    def free_bytes():
        return lib.cuda.mem_get_info()[0] if lib.__name__ == "torch" else lib.cuda.runtime.memGetInfo()[0]

    rng = np.random.default_rng(11)
    points = rng.normal(size=(20000 * 100, 3)).astype(np.float32)
    offsets = np.arange(0, len(points) + 1, 100)
    device_points = on_device(lib, points)
    got = cudahull.convex_hull_batch(device_points, offsets)
    cudahull.release_device_memory()
    first = slice(0, int(to_numpy(got.vertex_offsets)[50]))
    want = cudahull.convex_hull_batch(points[:5000], offsets[:51], backend="cpu")
    assert np.array_equal(to_numpy(got.vertices)[first], want.vertices)
    del got
    again = cudahull.convex_hull_batch(device_points, offsets)
    peak = again.report["device_bytes_peak"] - points.nbytes
    del again
    gc.collect()
    before = free_bytes()
    cudahull.release_device_memory()
    released = free_bytes() - before
    assert released >= 0.5 * peak, (released, peak)
    cudahull.release_device_memory()  # nothing held: nothing to do
