"""What the package does with arrays in GPU memory before any of their data is read, testable without a GPU:
how it recognises them, the arguments it refuses, and the error with no usable GPU.  The hulls of real CuPy
and PyTorch arrays are tested in python/gpu_tests (ctest label gpu)."""

import ctypes

import numpy as np
import pytest

import cudahull
from cudahull._arrays import cuda_protocol

GPU_USABLE, GPU_WHY = cudahull._cudahull.cuda_device()


class FakeDLPackArray:
    """Says it is a CUDA array through DLPack; its data is never there to read."""

    shape = (8, 3)

    def __dlpack_device__(self):
        return (2, 0)  # kDLCUDA, device 0

    def __dlpack__(self, **kwargs):
        raise AssertionError("the package read the data of an array it should have refused")


class FakeInterfaceArray:
    """An array in CUDA memory through __cuda_array_interface__ only (as Numba's device arrays)."""

    def __init__(self, shape=(8, 3), typestr="<f8", strides=None):
        self.shape = shape
        self.__cuda_array_interface__ = {"shape": shape, "typestr": typestr, "strides": strides,
                                         "data": (0, True), "version": 3}


class HostDLPackArray:
    """A host array offering DLPack (a PyTorch CPU tensor, say): taken through NumPy."""

    def __init__(self, array):
        self.array = array

    def __dlpack_device__(self):
        return (1, 0)  # kDLCPU

    def __dlpack__(self, **kwargs):
        return self.array.__dlpack__(**kwargs)

    def __array__(self, dtype=None, copy=None):
        return self.array


def test_recognises_arrays_in_cuda_memory():
    assert cuda_protocol(np.zeros((4, 3))) is None
    assert cuda_protocol([[0, 0, 0]]) is None
    assert cuda_protocol(FakeDLPackArray()) == "dlpack"
    assert cuda_protocol(FakeInterfaceArray()) == "cuda_array_interface"
    assert cuda_protocol(HostDLPackArray(np.zeros((4, 3)))) is None


def test_host_dlpack_array_is_taken_through_numpy():
    points = np.random.default_rng(3).normal(size=(200, 3))
    hull = cudahull.ConvexHull(HostDLPackArray(points), backend="cpu")
    assert np.array_equal(hull.vertices, cudahull.ConvexHull(points, backend="cpu").vertices)


@pytest.mark.parametrize("array", [FakeDLPackArray(), FakeInterfaceArray()], ids=["dlpack", "interface"])
def test_device_arrays_refuse_the_stepping_engine_and_the_cpu(array):
    with pytest.raises(ValueError, match="^the stepping engine edits the mesh on the host"):
        cudahull.ConvexHull(array, engine="stepping")
    with pytest.raises(ValueError, match="^points in GPU memory need backend 'auto' or 'cuda', not 'cpu'"):
        cudahull.ConvexHull(array, backend="cpu")
    with pytest.raises(ValueError, match="^points in GPU memory need backend"):
        cudahull.convex_hull(array, backend="cpu")
    with pytest.raises(ValueError, match="^engine must be auto, stepping or resident, not 'fast'"):
        cudahull.ConvexHull(array, engine="fast")
    # Only CuPy and PyTorch arrays can be made from the results.
    with pytest.raises(ValueError, match="^device_results=True takes CuPy arrays and PyTorch tensors"):
        cudahull.ConvexHull(array, device_results=True)
    # The stepping Engine works on the host.
    with pytest.raises(ValueError, match="^these points are in GPU memory: this function takes host points"):
        cudahull.Engine(array)


@pytest.mark.parametrize(
    "interface, message",
    [
        (dict(shape=(8, 4)), r"^points are 4-dimensional: cudahull's engines compute 2-D and 3-D hulls \(for 4-D points "
                             r"through scipy's Qhull, pass them as NumPy"),
        (dict(shape=(8,)), r"^points must be an \(n, 3\) or \(n, 2\) array, not one of shape \(8,\)"),
        (dict(typestr="<f2"), "^points in GPU memory must be float32 or float64"),
        (dict(typestr="<i4"), "^points in GPU memory must be float32 or float64"),
        (dict(strides=(48, 8)), "^points in GPU memory must be C-contiguous"),
        (dict(typestr="<f4", strides=(12, 8)), "^points in GPU memory must be C-contiguous"),
    ],
)
def test_cuda_array_interface_is_checked_before_its_data_is_read(interface, message):
    with pytest.raises(ValueError, match=message):
        cudahull.ConvexHull(FakeInterfaceArray(**interface))


@pytest.mark.skipif(GPU_USABLE, reason="a usable GPU is here; the error is for machines without one")
@pytest.mark.parametrize("array", [FakeDLPackArray(), FakeInterfaceArray()], ids=["dlpack", "interface"])
def test_device_array_without_a_gpu_is_a_clear_device_error(array):
    expected = f"points in GPU memory, but no usable CUDA device: {GPU_WHY}"
    for call in (cudahull.ConvexHull, cudahull.convex_hull):
        with pytest.raises(cudahull.DeviceError) as error:
            call(array)
        assert str(error.value) == expected


def test_the_reason_for_no_device_names_a_missing_driver():
    # Without any NVIDIA driver the CUDA runtime says its driver is "insufficient", as if only an update
    # were due; the module says what is missing.  With a driver, that misleading phrase never appears.
    try:
        ctypes.CDLL("libcuda.so.1")
        has_driver = True
    except OSError:
        has_driver = False
    if has_driver:
        assert "insufficient for CUDA runtime" not in GPU_WHY
    else:
        assert not GPU_USABLE
        assert GPU_WHY == "libcuda.so.1, the NVIDIA driver, was not found"


def test_host_engines_and_stats():
    """engine="auto" on the CPU backend is the stepping engine (no counters); the resident engine reports
    its counters and gives the same exact hull."""
    points = np.random.default_rng(5).uniform(-1, 1, size=(3000, 3))
    stepping = cudahull.ConvexHull(points, backend="cpu")
    resident = cudahull.ConvexHull(points, backend="cpu", engine="resident")
    assert stepping.stats is None and stepping.backend.startswith("cpu (")
    assert resident.backend == "cpu-resident"
    assert resident.stats["iterations"] > 0 and resident.stats["points_read_back"] == 0
    assert np.array_equal(resident.vertices, stepping.vertices)
    assert resident.volume == pytest.approx(stepping.volume, rel=1e-12)
    assert resident.area == pytest.approx(stepping.area, rel=1e-12)
    as_dict = cudahull.convex_hull(points, backend="cpu", engine="resident")
    stats = as_dict["stats"]
    assert set(stats) >= {"host_syncs", "bytes_from_device", "points_read_back", "device_bytes_peak", "work_items"}
    assert stats["work_items"] >= stats["edits"] > 0
    assert stats["round_phase_ms"] == [0.0] * 4  # the device's clock inside the rounds; none on the host
    assert cudahull.convex_hull(points, backend="cpu")["stats"] is None


def test_bounds_are_computed_when_asked_for():
    points = np.random.default_rng(6).normal(size=(500, 3)).astype(np.float32)
    hull = cudahull.ConvexHull(points, backend="cpu")
    assert np.array_equal(hull.min_bound, points.min(axis=0))
    assert np.array_equal(hull.max_bound, points.max(axis=0))
    assert hull.min_bound.dtype == np.float32
    hull.add_points(points * 2)
    assert np.array_equal(hull.max_bound, np.maximum(points.max(axis=0), (points * 2).max(axis=0)))
    with pytest.raises(ValueError, match="No points given"):  # as scipy
        cudahull.ConvexHull(np.empty((0, 3)), backend="cpu")
