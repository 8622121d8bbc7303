"""The extension's array boundary, testable without a GPU: DLPack tensors that say they are in CUDA memory
(built here with ctypes: shapes, strides, dtypes a library might export), __cuda_array_interface__'s bare
pointer, and host arrays of any layout.  Each is checked before any data is read; an array it accepts goes
to the device path, which without a usable GPU raises DeviceError and reads nothing (the data here is host
memory of exactly the stated size: tests/python_sanitizer.sh runs this file under AddressSanitizer and
UBSan, which would report a read beyond it).  The capsule's deleter runs once, whatever the outcome."""

import ctypes
import gc

import numpy as np
import pytest

import cudahull
from cudahull import _cudahull

GPU_USABLE = cudahull._cudahull.cuda_device()[0]
# The reason conftest.py allows: on a machine with a GPU the device path would read this host memory as
# device memory.
without_gpu = pytest.mark.skipif(GPU_USABLE, reason="a usable GPU is here; the error is for machines without one")

_CPU, _CUDA = 1, 2  # DLPack's device types
_INT, _FLOAT = 0, 2  # DLPack's type codes


class _Device(ctypes.Structure):
    _fields_ = [("device_type", ctypes.c_int32), ("device_id", ctypes.c_int32)]


class _DataType(ctypes.Structure):
    _fields_ = [("code", ctypes.c_uint8), ("bits", ctypes.c_uint8), ("lanes", ctypes.c_uint16)]


class _Tensor(ctypes.Structure):
    _fields_ = [("data", ctypes.c_void_p), ("device", _Device), ("ndim", ctypes.c_int32), ("dtype", _DataType),
                ("shape", ctypes.POINTER(ctypes.c_int64)), ("strides", ctypes.POINTER(ctypes.c_int64)),
                ("byte_offset", ctypes.c_uint64)]


class _Managed(ctypes.Structure):
    pass


_DELETER = ctypes.CFUNCTYPE(None, ctypes.POINTER(_Managed))
_Managed._fields_ = [("dl_tensor", _Tensor), ("manager_ctx", ctypes.c_void_p), ("deleter", _DELETER)]
_capsule_new = ctypes.pythonapi.PyCapsule_New
_capsule_new.restype = ctypes.py_object
_capsule_new.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_void_p]
_NAME = b"dltensor"  # the capsule keeps a pointer to its name: it must outlive every capsule


class Capsule:
    """An unversioned DLPack capsule over host memory of exactly the elements its shape and strides reach,
    on the device it names; `deleted` counts its deleter's calls."""

    def __init__(self, shape, strides=None, code=_FLOAT, bits=64, device=_CUDA):
        reach = 1 + sum((n - 1) * abs(s) for n, s in zip(shape, strides or self._compact(shape)))
        self.memory = (ctypes.c_uint8 * (reach * bits // 8 if all(shape) else 1))()
        self.shape = (ctypes.c_int64 * len(shape))(*shape)
        self.strides = (ctypes.c_int64 * len(shape))(*strides) if strides is not None else None
        self.deleted = 0

        def deleter(_):
            self.deleted += 1

        self.deleter = _DELETER(deleter)
        self.managed = _Managed()
        self.managed.dl_tensor = _Tensor(
            ctypes.cast(self.memory, ctypes.c_void_p), _Device(device, 0), len(shape), _DataType(code, bits, 1),
            self.shape, self.strides if self.strides is not None else ctypes.POINTER(ctypes.c_int64)(), 0)
        self.managed.deleter = self.deleter
        self.capsule = _capsule_new(ctypes.addressof(self.managed), _NAME, None)

    @staticmethod
    def _compact(shape):
        strides, step = [], 1
        for n in reversed(shape):
            strides.append(step)
            step *= n
        return tuple(reversed(strides))

    def consumed(self):
        """Drops the capsule and returns how many times the deleter ran."""
        self.capsule = None
        gc.collect()
        return self.deleted


def hull_of(capsule):
    return _cudahull.convex_hull_cuda(capsule.capsule, "auto", "auto", "exact", 0.0, 1.0)


def batch_of(capsule, offsets):
    return _cudahull.convex_hull_batch_cuda(capsule.capsule, np.asarray(offsets, dtype=np.int64), "auto", "auto",
                                            "cupy")


@pytest.mark.parametrize("shape, strides, code, bits, message", [
    ((8, 3), (1, 8), _FLOAT, 64, "must be C-contiguous"),            # Fortran order
    ((8, 3), (6, 1), _FLOAT, 64, "must be C-contiguous"),            # every other row
    ((8, 3), (3, 2), _FLOAT, 32, "must be C-contiguous"),            # every other column
    ((8, 3), (-3, 1), _FLOAT, 64, "must be C-contiguous"),           # rows reversed
    ((8, 2), (1, 8), _FLOAT, 32, "must be C-contiguous"),
    ((8, 4), None, _FLOAT, 64, r"not one of shape \(8, 4\)$"),
    ((8,), None, _FLOAT, 64, r"not one of shape \(8,\)$"),
    ((2, 4, 3), None, _FLOAT, 64, r"not one of shape \(2, 4, 3\)$"),
    ((8, 3), None, _INT, 32, "must be float32 or float64"),
    ((8, 3), None, _FLOAT, 16, "must be float32 or float64"),
])
def test_a_cuda_tensor_the_engine_cannot_read_in_place_is_refused(shape, strides, code, bits, message):
    capsule = Capsule(shape, strides, code, bits)
    with pytest.raises(ValueError, match=message):
        hull_of(capsule)
    assert capsule.consumed() == 1


@pytest.mark.parametrize("shape, strides, message", [
    ((8, 3), (1, 8), "must be C-contiguous"),
    ((8, 2), None, r"must be an \(n, 3\) array"),
])
def test_a_cuda_batch_the_kernels_cannot_read_in_place_is_refused(shape, strides, message):
    capsule = Capsule(shape, strides)
    with pytest.raises(ValueError, match=message):
        batch_of(capsule, [0, shape[0]])
    assert capsule.consumed() == 1


@without_gpu
@pytest.mark.parametrize("shape, strides, bits", [
    ((8, 3), (3, 1), 64), ((8, 3), None, 32), ((8, 2), (2, 1), 64),
    ((1, 3), (99, 1), 64),   # a single row's first stride means nothing
    ((0, 3), (3, 1), 32),
])
def test_an_accepted_cuda_tensor_reaches_the_device_check_unread(shape, strides, bits):
    capsule = Capsule(shape, strides, bits=bits)
    with pytest.raises(cudahull.DeviceError, match="no usable CUDA device"):
        hull_of(capsule)
    assert capsule.consumed() == 1
    batch = Capsule((8, 3), None, bits=bits)
    with pytest.raises(cudahull.DeviceError, match="no usable CUDA device"):
        batch_of(batch, [0, 4, 8])
    assert batch.consumed() == 1


@without_gpu
@pytest.mark.parametrize("is_double", [False, True])
def test_a_cuda_array_interface_pointer_reaches_the_device_check_unread(is_double):
    memory = (ctypes.c_uint8 * 8)()  # far fewer bytes than the counts below claim
    pointer = ctypes.addressof(memory)
    with pytest.raises(cudahull.DeviceError, match="no usable CUDA device"):
        _cudahull.convex_hull_cuda_pointer(pointer, 1000, 3, is_double, "auto", "auto", "exact", 0.0, 1.0)
    with pytest.raises(cudahull.DeviceError, match="no usable CUDA device"):
        _cudahull.convex_hull_batch_cuda_pointer(pointer, 1000, is_double, np.array([0, 500, 1000]), "auto",
                                                 "auto", "cupy")


def test_a_host_tensor_is_not_taken_for_a_cuda_one():
    capsule = Capsule((8, 3), device=_CPU)
    with pytest.raises(TypeError):
        hull_of(capsule)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_host_arrays_of_any_layout_give_the_contiguous_arrays_hull(dtype):
    """The host entry points take C-contiguous arrays; views of other layouts are copied on the way in (by
    nanobind, or by the package), never read with the wrong strides."""
    rng = np.random.default_rng(50)
    base = rng.normal(size=(400, 6)).astype(dtype)
    views = {"every other row and column": base[::2, 1:4], "Fortran": np.asfortranarray(base[::2, 1:4]),
             "rows reversed": base[::-2, 1:4], "columns reversed": base[::2, 3:0:-1]}
    for name, view in views.items():
        assert not view.flags.c_contiguous, name
        want = cudahull.convex_hull(np.ascontiguousarray(view), backend="cpu")
        got = cudahull.convex_hull(view, backend="cpu")
        assert np.array_equal(got["vertices"], want["vertices"]), name
        assert np.array_equal(got["simplices"], want["simplices"]), name
        direct = _cudahull.convex_hull(view, "cpu", "auto", "auto", "exact", 0.0, 1.0)
        assert np.array_equal(direct["vertices"], want["vertices"]), name
    planar = base[::3, [0, 2]]
    assert np.array_equal(cudahull.convex_hull(planar, backend="cpu")["vertices"],
                          cudahull.convex_hull(np.ascontiguousarray(planar), backend="cpu")["vertices"])
    offsets = np.array([0, 50, 120, 200], dtype=np.int64)
    strided = cudahull.convex_hull_batch(base[::2, 1:4], offsets[::1], backend="cpu")
    packed = cudahull.convex_hull_batch(np.ascontiguousarray(base[::2, 1:4]), offsets, backend="cpu")
    assert np.array_equal(strided.vertices, packed.vertices) and np.array_equal(strided.faces, packed.faces)
