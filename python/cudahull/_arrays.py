"""How the package takes points: NumPy (and anything NumPy converts), and arrays in CUDA memory through
DLPack or ``__cuda_array_interface__`` (CuPy, PyTorch, Numba ...), which are read in place."""

from __future__ import annotations

import functools
from typing import Any, Sequence

import numpy as np
import numpy.typing as npt

from . import _cudahull

_DLPACK_CPU, _DLPACK_CUDA = 1, 2  # DLPack's device types (kDLCPU, kDLCUDA)


def cuda_protocol(points: object) -> str | None:
    """How an array in CUDA memory offers itself: "dlpack" or "cuda_array_interface"; None for anything
    else (taken through NumPy)."""
    dlpack_device = getattr(points, "__dlpack_device__", None)
    if dlpack_device is not None and hasattr(points, "__dlpack__"):
        device_type = dlpack_device()[0]
        if device_type == _DLPACK_CUDA:
            return "dlpack"
        if device_type == _DLPACK_CPU:
            return None
    # hasattr, not a type check: PyTorch's property raises AttributeError for a tensor on the CPU.
    if hasattr(points, "__cuda_array_interface__"):
        return "cuda_array_interface"
    return None


def host_array(points: object) -> npt.NDArray[Any]:
    """``points`` as a NumPy array (no copy where it is one), refusing arrays in GPU memory and masked arrays."""
    if cuda_protocol(points) is not None:
        raise ValueError("these points are in GPU memory: this function takes host points (cupy.asnumpy(x), "
                         "x.cpu().numpy())")
    if isinstance(points, np.ma.MaskedArray):
        raise ValueError("masked arrays are not supported: pass the points to keep (points.compressed() or "
                         "points[~points.mask.any(axis=1)])")
    return np.asarray(points)


def as_points(points: object, dimensions: Sequence[int] = (3,)) -> npt.NDArray[Any]:
    """(n, d) C-contiguous float32 (kept) or float64 (anything else numeric, converted) points, d one of
    ``dimensions``."""
    array = host_array(points)
    if array.ndim == 2 and array.shape[1] >= 4 and 2 in dimensions:
        raise ValueError(f"points are {array.shape[1]}-dimensional: cudahull's engines compute 2-D and 3-D hulls "
                         f"(cudahull.ConvexHull takes {array.shape[1]}-D points through scipy's Qhull)")
    if array.ndim != 2 or array.shape[1] not in dimensions:
        wanted = " or ".join(f"(n, {d})" for d in dimensions)
        raise ValueError(f"points must be an {wanted} array, not one of shape {array.shape}")
    return numeric(array)


def numeric(array: npt.NDArray[Any]) -> npt.NDArray[Any]:
    """C-contiguous float32 (kept) or float64 (any other number type, converted)."""
    if array.dtype != np.float32 and array.dtype != np.float64:
        if array.dtype.kind not in "biuf":
            raise ValueError(f"points must be numbers, not {array.dtype}")
        array = array.astype(np.float64)
    return np.ascontiguousarray(array)


def index_array(values: npt.ArrayLike, npoints: int) -> npt.NDArray[np.integer[Any]]:
    """Indices as scipy's int32; beyond 2**31 - 1 points int32 could not hold every index: int64."""
    return np.asarray(values, dtype=np.int32 if npoints < 2**31 else np.int64)


def library_of(array: object) -> str:
    """The top-level module of an array's type: "numpy", "cupy", "torch", ..."""
    return type(array).__module__.partition(".")[0]


class DeviceKind:
    """What the package does with the arrays of a CUDA input's library: CuPy and PyTorch are known (results
    as their arrays, add_points, bounds); other libraries' arrays are hulled, with NumPy results."""

    def __init__(self, points: Any) -> None:
        self.library = library_of(points)
        self._device = getattr(points, "device", None)  # PyTorch's, for results on the input's GPU

    @property
    def known(self) -> bool:
        return self.library in ("cupy", "torch")

    def require_known(self, what: str) -> None:
        if not self.known:
            raise ValueError(f"{what} takes CuPy arrays and PyTorch tensors, not {self.library} arrays")

    def like_input(self, array: npt.NDArray[Any]) -> Any:
        """A NumPy result as an array of the input's library, on its device (a small upload)."""
        if self.library == "cupy":
            import cupy  # type: ignore[import-not-found, unused-ignore]

            return cupy.asarray(array)
        import torch  # type: ignore[import-not-found, unused-ignore]

        return torch.from_numpy(np.ascontiguousarray(array)).to(self._device)

    def to_numpy(self, array: Any) -> npt.NDArray[Any]:
        if self.library == "cupy":
            return array.get()  # type: ignore[no-any-return]
        if self.library == "torch":
            return array.detach().cpu().numpy()  # type: ignore[no-any-return]
        return np.asarray(array)

    def bounds(self, points: Any) -> tuple[Any, Any]:
        """Per-axis minimum and maximum, computed on the device (two small read-backs)."""
        if self.library == "torch":
            return points.amin(dim=0), points.amax(dim=0)
        return points.min(axis=0), points.max(axis=0)

    def take(self, points: Any, indices: npt.NDArray[Any]) -> Any:
        """points[indices] (NumPy indices), C-contiguous, on the device."""
        self.require_known("add_points on points in GPU memory")
        if self.library == "cupy":
            import cupy

            return cupy.ascontiguousarray(points[cupy.asarray(indices)])
        import torch

        return points[torch.as_tensor(indices, device=points.device)].contiguous()

    def pack_padded(self, points: Any, lengths: npt.NDArray[np.int64] | None) -> Any:
        """A padded (B, M, 3) array's first lengths[c] rows of each slab, packed into (N, 3), C-contiguous, on
        the device (a device copy, none where every cloud fills its slab (lengths None) and the array is
        contiguous)."""
        self.require_known("padded points in GPU memory")
        slab = int(points.shape[1])
        full = lengths is None
        if self.library == "cupy":
            import cupy

            if full:
                return cupy.ascontiguousarray(points).reshape(-1, 3)
            mask = cupy.arange(slab)[None, :] < cupy.asarray(lengths)[:, None]
            return cupy.ascontiguousarray(points[mask])
        import torch

        if full:
            return points.contiguous().reshape(-1, 3)
        sizes = torch.as_tensor(lengths, device=points.device)
        mask = torch.arange(slab, device=points.device)[None, :] < sizes[:, None]
        return points[mask].contiguous()

    def join(self, arrays: Sequence[Any]) -> Any:
        """Arrays of this library in GPU memory, concatenated along their first axis, C-contiguous, on the
        device."""
        self.require_known("a list of clouds in GPU memory")
        if self.library == "cupy":
            import cupy

            return cupy.ascontiguousarray(cupy.concatenate(list(arrays)))
        import torch

        return torch.cat(list(arrays)).contiguous()

    def concatenate(self, first: Any, second: Any) -> Any:
        self.require_known("add_points on points in GPU memory")
        if library_of(second) != self.library or cuda_protocol(second) is None:
            raise ValueError(f"add_points to a hull of {self.library} points in GPU memory takes {self.library} "
                             f"points in GPU memory, not {type(second).__name__}")
        return self.join([first, second])


def device_shape(points: Any, protocol: str) -> tuple[int, ...]:
    """The shape of an array in CUDA memory, checked to be (n, 2) or (n, 3)."""
    shape = tuple(points.__cuda_array_interface__["shape"] if protocol == "cuda_array_interface" else points.shape)
    if len(shape) == 2 and shape[1] >= 4:
        raise ValueError(f"points are {shape[1]}-dimensional: cudahull's engines compute 2-D and 3-D hulls (for "
                         f"{shape[1]}-D points through scipy's Qhull, pass them as NumPy: cupy.asnumpy(x), "
                         f"x.cpu().numpy())")
    if len(shape) != 2 or shape[1] not in (2, 3):
        raise ValueError(f"points must be an (n, 3) or (n, 2) array, not one of shape {shape}")
    return shape


def checked_interface(points: Any, shape: tuple[int, ...]) -> tuple[int, bool]:
    """The data pointer and whether it is float64, of an array offering ``__cuda_array_interface__``:
    checked before any data is read (a DLPack array is checked by the module, which sees its dtype, shape
    and strides)."""
    interface = points.__cuda_array_interface__
    typestr, strides = interface["typestr"], interface.get("strides")
    if typestr not in ("<f4", "<f8"):
        raise ValueError("points in GPU memory must be float32 or float64 (convert with .astype())")
    itemsize = int(typestr[2])
    if strides is not None and shape[0] > 0 and (
            strides[1] != itemsize or (shape[0] > 1 and strides[0] != shape[1] * itemsize)):
        raise ValueError("points in GPU memory must be C-contiguous: the engine reads them in place")
    return int(interface["data"][0]), itemsize == 8


@functools.lru_cache(maxsize=None)
def cuda_device() -> tuple[bool, str]:
    """(usable, the device's name or why not), asked once: a GPU does not come or go while a process runs."""
    usable, why = _cudahull.cuda_device()
    return bool(usable), str(why)


def require_device() -> None:
    """Raises DeviceError where points in GPU memory meet no usable CUDA device."""
    usable, why_not = cuda_device()
    if not usable:
        raise _cudahull.DeviceError(f"points in GPU memory, but no usable CUDA device: {why_not}")


def host_integers(values: object, name: str) -> npt.NDArray[np.int64]:
    """``offsets`` or ``lengths`` as a 1-D int64 NumPy array; from GPU memory, copied to the host (B + 1 values:
    the batch's plan, which clouds the kernel takes and its room, is made on the host)."""
    if cuda_protocol(values) is not None:
        owner = DeviceKind(values)
        if not owner.known:
            raise ValueError(f"{name} in GPU memory must be a CuPy array or a PyTorch tensor (or NumPy)")
        values = owner.to_numpy(values)
    array = np.asarray(values)
    if array.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of integers, not one of shape {array.shape}")
    if array.size and array.dtype.kind not in "iu":
        raise ValueError(f"{name} must be integers, not {array.dtype}")
    if array.dtype.kind == "u" and array.size and array.max() > np.iinfo(np.int64).max:
        bad = int(np.flatnonzero(array > np.iinfo(np.int64).max)[0])
        raise ValueError(f"{name}[{bad}] is {int(array[bad])}: beyond int64")
    return np.ascontiguousarray(array, dtype=np.int64)
