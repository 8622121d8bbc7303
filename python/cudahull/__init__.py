"""Exact 3-D convex hulls with the CudaHull algorithm (Stein, Geva, El-Sana 2012).

``ConvexHull`` has the attributes and methods of ``scipy.spatial.ConvexHull`` for 3-D points; ``Engine``
steps the algorithm one iteration at a time (for notebooks); ``convex_hull`` returns the hull as a dict.

Points already on the GPU (a CuPy array, a PyTorch CUDA tensor, anything with ``__dlpack__`` or
``__cuda_array_interface__`` in CUDA memory) are read in place: no host copy of them is made, and the
results come back as NumPy arrays, or, with ``device_results=True``, as arrays of the input's kind.
"""

import functools

import numpy as np

from . import _cudahull
from ._cudahull import SWAP_KINDS, DeviceError, InputError

__all__ = ["ConvexHull", "Engine", "convex_hull", "InputError", "DeviceError", "SWAP_KINDS"]

_DLPACK_CPU, _DLPACK_CUDA = 1, 2  # DLPack's device types (kDLCPU, kDLCUDA)


def _cuda_protocol(points):
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


def _as_points(points):
    """(n, 3) C-contiguous float32 (kept) or float64 (anything else numeric, converted) points."""
    if _cuda_protocol(points) is not None:
        raise ValueError("these points are in GPU memory: this function takes host points (cupy.asnumpy(x), "
                         "x.cpu().numpy())")
    array = np.asarray(points)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"points must be an (n, 3) array of 3-D points, not one of shape {array.shape}")
    if array.dtype != np.float32 and array.dtype != np.float64:
        if array.dtype.kind not in "biuf":
            raise ValueError(f"points must be numbers, not {array.dtype}")
        array = array.astype(np.float64)
    return np.ascontiguousarray(array)


class _DeviceKind:
    """What the package does with the arrays of a CUDA input's library: CuPy and PyTorch are known (results
    as their arrays, add_points, bounds); other libraries' arrays are hulled, with NumPy results."""

    def __init__(self, points):
        self.library = type(points).__module__.partition(".")[0]
        self._device = getattr(points, "device", None)  # PyTorch's, for results on the input's GPU

    @property
    def known(self):
        return self.library in ("cupy", "torch")

    def require_known(self, what):
        if not self.known:
            raise ValueError(f"{what} takes CuPy arrays and PyTorch tensors, not {self.library} arrays")

    def like_input(self, array):
        """A NumPy result as an array of the input's library, on its device (a small upload)."""
        if self.library == "cupy":
            import cupy

            return cupy.asarray(array)
        import torch

        return torch.from_numpy(np.ascontiguousarray(array)).to(self._device)

    def to_numpy(self, array):
        if self.library == "cupy":
            return array.get()
        if self.library == "torch":
            return array.detach().cpu().numpy()
        return np.asarray(array)

    def bounds(self, points):
        """Per-axis minimum and maximum, computed on the device (two small read-backs)."""
        if self.library == "torch":
            return points.amin(dim=0), points.amax(dim=0)
        return points.min(axis=0), points.max(axis=0)

    def take(self, points, indices):
        """points[indices] (NumPy indices), C-contiguous, on the device."""
        self.require_known("add_points on points in GPU memory")
        if self.library == "cupy":
            import cupy

            return cupy.ascontiguousarray(points[cupy.asarray(indices)])
        import torch

        return points[torch.as_tensor(indices, device=points.device)].contiguous()

    def concatenate(self, first, second):
        self.require_known("add_points on points in GPU memory")
        if type(second).__module__.partition(".")[0] != self.library or _cuda_protocol(second) is None:
            raise ValueError(f"add_points to a hull of {self.library} points in GPU memory takes {self.library} "
                             f"points in GPU memory, not {type(second).__name__}")
        if self.library == "cupy":
            import cupy

            return cupy.ascontiguousarray(cupy.concatenate([first, second]))
        import torch

        return torch.cat([first, second]).contiguous()


def _check_engine(engine, on_device, backend="auto"):
    if engine not in ("auto", "stepping", "resident"):
        raise ValueError(f"engine must be auto, stepping or resident, not '{engine}'")
    if engine == "auto":
        # As the command line's --engine auto: the resident engine where it runs on a GPU (only it reads
        # GPU memory), the stepping engine on the CPU, whose worker threads make it the faster one there.
        if on_device:
            return "resident"
        return "resident" if backend != "cpu" and _cuda_device()[0] else "stepping"
    if on_device and engine == "stepping":
        raise ValueError("the stepping engine edits the mesh on the host and takes host points: points in GPU "
                         "memory take engine 'resident' (or 'auto')")
    return engine


def _device_hull(points, protocol, backend, precision):
    """The hull dict of (n, 3) points in CUDA memory, read in place by the resident engine."""
    if backend == "cpu":
        raise ValueError("points in GPU memory need backend 'auto' or 'cuda', not 'cpu' (for the CPU backend, "
                         "pass them as NumPy: cupy.asnumpy(x), x.cpu().numpy())")
    if protocol == "cuda_array_interface":
        # Checked here, before any data is read; a DLPack array is checked by the module (it sees its
        # dtype, shape and strides).
        interface = points.__cuda_array_interface__
        shape, typestr, strides = tuple(interface["shape"]), interface["typestr"], interface.get("strides")
        if len(shape) != 2 or shape[1] != 3:
            raise ValueError(f"points must be an (n, 3) array of 3-D points, not one of shape {shape}")
        if typestr not in ("<f4", "<f8"):
            raise ValueError("points in GPU memory must be float32 or float64 (convert with .astype())")
        itemsize = int(typestr[2])
        if strides is not None and shape[0] > 0 and (
                strides[1] != itemsize or (shape[0] > 1 and strides[0] != 3 * itemsize)):
            raise ValueError("points in GPU memory must be C-contiguous: the engine reads them in place")
    usable, why_not = _cuda_device()
    if not usable:
        raise DeviceError(f"points in GPU memory, but no usable CUDA device: {why_not}")
    if protocol == "cuda_array_interface":
        return _cudahull.convex_hull_cuda_pointer(interface["data"][0], shape[0], itemsize == 8, backend,
                                                  precision)
    if getattr(points, "requires_grad", False):
        points = points.detach()  # PyTorch exports no tensor that requires grad; the hull reads values only
    return _cudahull.convex_hull_cuda(points, backend, precision)


@functools.lru_cache(maxsize=None)
def _cuda_device():
    """(usable, the device's name or why not), asked once: a GPU does not come or go while a process runs."""
    return _cudahull.cuda_device()


_RESULT_ARRAYS = ("vertices", "simplices", "neighbors", "equations", "polygon")


def convex_hull(points, backend="auto", precision="auto", engine="auto", device_results=False):
    """The exact hull of (n, 3) ``points`` as a dict of NumPy arrays and numbers.

    Keys: ``dimension``, ``precision``, ``backend``, ``vertices``, ``simplices``, ``neighbors``,
    ``equations``, ``polygon``, ``volume``, ``area`` (as on ``ConvexHull``; indices are uint32 here), and
    ``stats``: the resident engine's counters (``host_syncs``, ``bytes_from_device``,
    ``points_read_back``, ...), None for the stepping engine.

    ``engine``: "auto" is "resident" where the hull runs on a GPU (points in GPU memory, which only it reads
    in place, or host points with a usable GPU and backend "auto" or "cuda") and "stepping" on the CPU, as
    the command line's ``--engine auto``.  ``device_results=True`` returns the arrays of a CuPy or
    PyTorch input as CuPy arrays or tensors on its device.
    """
    protocol = _cuda_protocol(points)
    engine = _check_engine(engine, protocol is not None, backend)
    if protocol is None:
        return _cudahull.convex_hull(_as_points(points), backend, precision, engine)
    kind = _DeviceKind(points)
    if device_results:
        kind.require_known("device_results=True")
    result = _device_hull(points, protocol, backend, precision)
    if device_results:
        for key in _RESULT_ARRAYS:
            array = result[key]
            # Indices as int64 on the device: PyTorch has few operations on uint32.
            result[key] = kind.like_input(array.astype(np.int64) if array.dtype == np.uint32 else array)
    return result


def _index_array(values, npoints):
    # scipy's index arrays are int32; beyond 2**31 - 1 points they could not hold every index.
    return np.asarray(values, dtype=np.int32 if npoints < 2**31 else np.int64)


class ConvexHull:
    """Exact convex hull of 3-D points, with the interface of ``scipy.spatial.ConvexHull``.

    Parameters
    ----------
    points : (n, 3) array_like, or an (n, 3) array in GPU memory
        float32 input is computed in float, float64 (and integer) input in double: the hull is exact for
        those values, with no tolerance (a point on a face is not a vertex).  A CuPy array, a PyTorch CUDA
        tensor or another array in CUDA memory (``__dlpack__`` or ``__cuda_array_interface__``;
        C-contiguous float32 or float64, on the current device) is read in place by the resident engine:
        no host copy of it is made, and only the coordinates the exact checks need are read back
        (``stats`` counts them).
    backend : "auto", "cpu" or "cuda"
        "auto" takes the CUDA backend when a usable GPU is present.  Points in GPU memory need the GPU.
    precision : "auto", "float" or "double"
        "auto" takes the input's own; "float" rounds double input once, "double" widens float input
        (for points in GPU memory, into a temporary array on the device).
    incremental : bool
        Accepted for scipy's signature; ``add_points`` works either way.
    engine : "auto", "stepping" or "resident"
        "auto", as the command line's ``--engine auto``: "resident" (every phase on the device) where the
        hull runs on a GPU, which points in GPU memory need; "stepping" (Algorithm 1 an iteration at a
        time, the host editing the mesh) on the CPU.
    device_results : bool
        For a CuPy or PyTorch input: the array attributes (``vertices``, ``simplices``, ``neighbors``,
        ``equations``, ``polygon``, ``coplanar``, ``min_bound``, ``max_bound``) as arrays of the input's
        kind on its device instead of NumPy arrays.

    Attributes
    ----------
    points : the input points as given: float32 input stays float32, and points in GPU memory stay there
        (the CuPy array or tensor itself)
    vertices : (nvertices,) int32, the indices of the hull's vertices, sorted ascending
    simplices : (nsimplex, 3) int32, the triangles, counter-clockwise seen from outside
    neighbors : (nsimplex, 3) int32, the k-th neighbour is opposite the k-th vertex
    equations : (nsimplex, 4) float64, unit outward normal and offset: normal . x + offset <= 0 inside
    volume, area : the hull's volume and surface area
    npoints, nsimplex, ndim, min_bound, max_bound : as scipy
    coplanar : an empty (0, 3) int32 array (no point is set aside: the hull is exact)
    good : None
    dimension : the input's affine dimension (3, or lower for flat input: see below)
    precision, backend : what the hull was computed in and on ("cuda-resident" for the resident engine)
    stats : the resident engine's counters as a dict (``iterations``, ``host_syncs``,
        ``bytes_from_device``, ``points_read_back``, ``device_bytes_peak``, phase times in ms, ...), None
        for the stepping engine

    Flat input
    ----------
    Where scipy raises QhullError (QH6154), the lower-dimensional hull comes back: ``dimension`` is 2 for
    coplanar points (``vertices`` are the polygon's corners, ``polygon`` lists them in order, ``simplices``,
    ``neighbors`` and ``equations`` are empty, ``volume`` is 0 and ``area`` counts both sides of the
    polygon), 1 for collinear points (the segment's two ends), 0 when every point is the same, and -1 for
    no points.  Fewer than 4 points are flat.

    Raises ValueError for NaN or infinite coordinates (and for doubles outside exact arithmetic's range,
    nonzero magnitudes from 2**-250 to 2**250), on the host or the device alike, ``DeviceError`` (a
    RuntimeError) for backend="cuda", or points in GPU memory, without a usable GPU.
    """

    def __init__(self, points, backend="auto", precision="auto", incremental=False, qhull_options=None, *,
                 engine="auto", device_results=False):
        if qhull_options is not None:
            raise ValueError("qhull_options has no meaning here: the hull is exact, with no tolerance")
        self._protocol = _cuda_protocol(points)
        self._kind = _DeviceKind(points) if self._protocol else None
        self._engine_choice = _check_engine(engine, self._protocol is not None, backend)
        self._device_results = bool(device_results) and self._kind is not None
        if self._device_results:
            self._kind.require_known("device_results=True")
        self._backend_choice = backend
        self._precision_choice = precision
        self._closed = False
        self._set_points(points if self._protocol else _as_points(points))
        self._compute(None)

    def _set_points(self, points):
        self.points = points
        self.npoints = int(points.shape[0])
        self.ndim = 3
        self._bounds = None

    def _result_array(self, array):
        return self._kind.like_input(array) if self._device_results else array

    def _compute_bounds(self):
        if self.npoints == 0:
            empty = np.full(3, np.nan)
            return self._result_array(empty), self._result_array(empty)
        if self._kind is None:
            return self.points.min(axis=0), self.points.max(axis=0)
        low, high = self._kind.bounds(self.points)
        if self._device_results:
            return low, high
        return self._kind.to_numpy(low), self._kind.to_numpy(high)

    # Computed when first asked for: over millions of points they cost more than a resident hull.
    @property
    def min_bound(self):
        if self._bounds is None:
            self._bounds = self._compute_bounds()
        return self._bounds[0]

    @property
    def max_bound(self):
        if self._bounds is None:
            self._bounds = self._compute_bounds()
        return self._bounds[1]

    def _compute(self, subset):
        """The hull of ``points[subset]`` (all of them for None); ``subset`` ascending, so the lowest index
        of duplicates stays it."""
        if subset is None:
            points = self.points
        elif self._protocol:
            points = self._kind.take(self.points, subset)
        else:
            points = np.ascontiguousarray(self.points[subset])
        if self._protocol:
            result = _device_hull(points, self._protocol, self._backend_choice, self._precision_choice)
        else:
            result = _cudahull.convex_hull(points, self._backend_choice, self._precision_choice,
                                           self._engine_choice)

        def original(indices):
            return _index_array(indices if subset is None else subset[indices], self.npoints)

        self.dimension = result["dimension"]
        self.precision = result["precision"]
        self.backend = result["backend"]
        self.stats = result["stats"]
        self._host_vertices = original(result["vertices"])
        self.vertices = self._result_array(self._host_vertices)
        self.simplices = self._result_array(original(result["simplices"]).reshape(-1, 3))
        self.polygon = self._result_array(original(result["polygon"]))
        self.neighbors = self._result_array(result["neighbors"].astype(np.int32, copy=False))
        self.equations = self._result_array(result["equations"])
        self.volume = result["volume"]
        self.area = result["area"]
        self.nsimplex = int(result["simplices"].shape[0])
        self.coplanar = self._result_array(np.empty((0, 3), dtype=np.int32))
        self.good = None

    def add_points(self, points, restart=False):
        """Add (m, 3) points and update the hull: afterwards it is the hull of all the points.

        The hull of a union is the hull of the old hull's vertices and the new points, so only those are
        computed on (or every point, with ``restart=True``: the same answer).  A hull of CuPy or PyTorch
        points in GPU memory takes new points of the same kind, joined on the device.
        """
        if self._closed:
            raise RuntimeError("the hull is closed: add_points is no longer possible")
        old_count = self.npoints
        if self._protocol:
            self._set_points(self._kind.concatenate(self.points, points))
        else:
            new = _as_points(points)
            self._set_points(np.ascontiguousarray(np.concatenate([self.points, new])))
        if restart:
            self._compute(None)
        else:
            self._compute(np.concatenate([self._host_vertices.astype(np.int64),
                                          np.arange(old_count, self.npoints)]))

    def close(self):
        """Finish: ``add_points`` raises afterwards (as in scipy); the attributes stay."""
        self._closed = True


class Engine:
    """Algorithm 1 one iteration at a time, for notebooks: ``step()`` returns what the iteration did.

    ``step()`` gives a dict: counts (``faces_after``, ``external_after``, ...), the refined faces and their
    apexes (Fig. 3a), the swaps tried with their kinds (``swap_kind`` indexes ``SWAP_KINDS``; Figs. 3b, 4,
    5), the removed degree-3 vertices (Fig. 4) and the decision array (Fig. 7), as NumPy arrays.
    ``mesh()`` gives the current mesh (``faces``: input indices, counter-clockwise from outside;
    ``neighbors``: the k-th opposite the k-th corner), ``result()`` the exact hull once ``done``.
    """

    def __init__(self, points, backend="auto", precision="auto"):
        # The stepping engine edits the mesh on the host, so points in GPU memory are refused here.
        self.points = _as_points(points)
        self._engine = _cudahull.Engine(self.points, backend, precision)

    @property
    def done(self):
        return self._engine.done

    @property
    def dimension(self):
        """The input's affine dimension, known after the first step."""
        return self._engine.dimension

    @property
    def precision(self):
        return self._engine.precision

    @property
    def backend(self):
        return self._engine.backend

    def step(self):
        return self._engine.step()

    def run(self):
        """Steps until done; returns every step's record."""
        records = []
        while not self.done:
            records.append(self.step())
        return records

    def restart(self):
        self._engine.restart()

    def mesh(self):
        return self._engine.mesh()

    def result(self):
        return self._engine.result()
