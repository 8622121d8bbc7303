"""Exact 2-D and 3-D convex hulls with the CudaHull algorithm (Stein, Geva, El-Sana 2012).

``ConvexHull`` is a drop-in for ``scipy.spatial.ConvexHull`` in 2-D and 3-D: the same arguments
(``qhull_options`` included), attributes, methods and errors (``QhullError``); ``Engine`` steps the
algorithm one iteration at a time (for notebooks); ``convex_hull`` returns the hull as a dict, with the
lower-dimensional answer for flat input; ``convex_hull_batch`` computes the hulls of many clouds in one call.

Points already on the GPU (a CuPy array, a PyTorch CUDA tensor, anything with ``__dlpack__`` or
``__cuda_array_interface__`` in CUDA memory) are read in place: no host copy of them is made, and the
results come back as NumPy arrays, or, with ``device_results=True``, as arrays of the input's kind.
"""

import functools
import math
import re

import numpy as np

from . import _cudahull, qhull_options as _qhull_options
from ._cudahull import SWAP_KINDS, DeviceError, InputError

__all__ = ["ConvexHull", "Engine", "convex_hull", "convex_hull_batch", "BatchHulls", "InputError", "DeviceError",
           "QhullError", "SWAP_KINDS", "release_device_memory"]

try:  # scipy's own, where scipy is importable, so that code catching it catches ours
    from scipy.spatial import QhullError as _QhullErrorBase
except ImportError:  # pragma: no cover - exercised where scipy is absent
    _QhullErrorBase = RuntimeError


class QhullError(_QhullErrorBase):
    """Raised where ``scipy.spatial.ConvexHull`` raises ``QhullError``: too few points, flat input (their
    lower-dimensional hull is ``cudahull.convex_hull()``'s answer), and ``qhull_options`` with an option
    that has no defined behaviour here.  A subclass of ``scipy.spatial.QhullError`` where scipy is
    importable, else of ``RuntimeError``."""

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


def _as_points(points, dimensions=(3,)):
    """(n, d) C-contiguous float32 (kept) or float64 (anything else numeric, converted) points, d one of
    ``dimensions``."""
    if _cuda_protocol(points) is not None:
        raise ValueError("these points are in GPU memory: this function takes host points (cupy.asnumpy(x), "
                         "x.cpu().numpy())")
    if isinstance(points, np.ma.MaskedArray):
        raise ValueError("masked arrays are not supported: pass the points to keep (points.compressed() or "
                         "points[~points.mask.any(axis=1)])")
    array = np.asarray(points)
    if array.ndim == 2 and array.shape[1] >= 4 and 2 in dimensions:
        raise ValueError(f"points are {array.shape[1]}-dimensional: cudahull computes 2-D and 3-D hulls only "
                         f"(scipy.spatial.ConvexHull takes {array.shape[1]}-D points)")
    if array.ndim != 2 or array.shape[1] not in dimensions:
        wanted = " or ".join(f"(n, {d})" for d in dimensions)
        raise ValueError(f"points must be an {wanted} array, not one of shape {array.shape}")
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

    def pack_padded(self, points, lengths):
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


def _check_engine(engine, on_device):
    # "auto" stays "auto": the module's plan_hull() (hull_plan.hpp) resolves it, as for the command line's
    # --engine auto: the resident engine where it runs on a GPU (only it reads GPU memory), the stepping
    # engine on the CPU, whose worker threads make it the faster one there.
    if engine not in ("auto", "stepping", "resident"):
        raise ValueError(f"engine must be auto, stepping or resident, not '{engine}'")
    if on_device and engine == "stepping":
        raise ValueError("the stepping engine edits the mesh on the host and takes host points: points in GPU "
                         "memory take engine 'resident' (or 'auto')")
    return engine


def _device_shape(points, protocol):
    """The shape of an array in CUDA memory, checked to be (n, 2) or (n, 3)."""
    shape = tuple(points.__cuda_array_interface__["shape"] if protocol == "cuda_array_interface" else points.shape)
    if len(shape) == 2 and shape[1] >= 4:
        raise ValueError(f"points are {shape[1]}-dimensional: cudahull computes 2-D and 3-D hulls only")
    if len(shape) != 2 or shape[1] not in (2, 3):
        raise ValueError(f"points must be an (n, 3) or (n, 2) array, not one of shape {shape}")
    return shape


def _device_hull(points, protocol, backend, precision, merge=("exact", 0.0, 1.0)):
    """The hull dict of (n, 3) or (n, 2) points in CUDA memory: 3-D read in place by the resident engine,
    2-D filtered on the device with only the possible corners read back."""
    if backend == "cpu":
        raise ValueError("points in GPU memory need backend 'auto' or 'cuda', not 'cpu' (for the CPU backend, "
                         "pass them as NumPy: cupy.asnumpy(x), x.cpu().numpy())")
    shape = _device_shape(points, protocol)
    if protocol == "cuda_array_interface":
        # Checked here, before any data is read; a DLPack array is checked by the module (it sees its
        # dtype, shape and strides).
        interface = points.__cuda_array_interface__
        typestr, strides = interface["typestr"], interface.get("strides")
        if typestr not in ("<f4", "<f8"):
            raise ValueError("points in GPU memory must be float32 or float64 (convert with .astype())")
        itemsize = int(typestr[2])
        if strides is not None and shape[0] > 0 and (
                strides[1] != itemsize or (shape[0] > 1 and strides[0] != shape[1] * itemsize)):
            raise ValueError("points in GPU memory must be C-contiguous: the engine reads them in place")
    usable, why_not = _cuda_device()
    if not usable:
        raise DeviceError(f"points in GPU memory, but no usable CUDA device: {why_not}")
    if protocol == "cuda_array_interface":
        return _cudahull.convex_hull_cuda_pointer(interface["data"][0], shape[0], shape[1], itemsize == 8, backend,
                                                  precision, *merge)
    if getattr(points, "requires_grad", False):
        points = points.detach()  # PyTorch exports no tensor that requires grad; the hull reads values only
    return _cudahull.convex_hull_cuda(points, backend, precision, *merge)


@functools.lru_cache(maxsize=None)
def _cuda_device():
    """(usable, the device's name or why not), asked once: a GPU does not come or go while a process runs."""
    return _cudahull.cuda_device()


_RESULT_ARRAYS = ("vertices", "simplices", "neighbors", "equations", "polygon", "coplanar")


def _merge_arguments(tolerance, low=None, high=None):
    """The module's (merge, tolerance, angle_cosine) for a ``tolerance``: None (exact), "qhull", a float
    (relative to the bounding box's largest side), or ("options", distance, cosine) from qhull_options' C
    and A: an absolute distance (None: Qhull's), which needs the bounding box (``low``, ``high``) to become
    relative, and An's cosine (None: no angle)."""
    if tolerance is None:
        return ("exact", 0.0, 1.0)
    if isinstance(tolerance, str):
        if tolerance != "qhull":
            raise ValueError(f"tolerance must be None, 'qhull' or a number, not '{tolerance}'")
        return ("qhull", 0.0, 1.0)
    if isinstance(tolerance, tuple):
        _, distance, cosine = tolerance
        cosine = 1.0 if cosine is None else float(cosine)
        if distance is None:
            return ("qhull", 0.0, cosine)
        low, high = np.asarray(low, dtype=np.float64), np.asarray(high, dtype=np.float64)
        side = float(np.max(high - low)) if low.size else 0.0
        return ("relative", distance / side if side > 0 else 0.0, cosine)
    value = float(tolerance)
    if not math.isfinite(value) or value < 0:
        raise ValueError(f"tolerance must be None, 'qhull' or a finite number >= 0, not {tolerance!r}")
    return ("relative", value, 1.0)


def convex_hull(points, backend="auto", precision="auto", engine="auto", device_results=False, tolerance=None):
    """The hull of (n, 3) or (n, 2) ``points`` as a dict of NumPy arrays and numbers.

    Keys: ``dimension``, ``input_dimension``, ``precision``, ``backend``, ``vertices``, ``simplices``,
    ``neighbors``, ``equations``, ``polygon``, ``coplanar``, ``volume``, ``area``, ``tolerance``,
    ``max_outside`` (as on ``ConvexHull``; indices are uint32 here), and ``stats``: the resident engine's
    counters (``host_syncs``, ``bytes_from_device``, ``points_read_back``, ...), None otherwise.  Flat
    input gives its lower-dimensional hull (``dimension`` below the input's; ``polygon`` the corners in
    order), where ``ConvexHull`` raises QhullError as scipy does.

    ``engine``: "auto" is "resident" where the hull runs on a GPU (points in GPU memory, which only it reads
    in place, or host points with a usable GPU and backend "auto" or "cuda") and "stepping" on the CPU, as
    the command line's ``--engine auto``.  ``device_results=True`` returns the arrays of a CuPy or
    PyTorch input as CuPy arrays or tensors on its device.  ``tolerance``: None (the exact hull), "qhull"
    (merged as Qhull's default merging does) or a number (merged within that fraction of the bounding
    box's largest side).  2-D points in GPU memory are filtered there: only the points that can be corners
    come back.
    """
    protocol = _cuda_protocol(points)
    engine = _check_engine(engine, protocol is not None)
    if protocol is None:
        return _hull_dict(_as_points(points, (2, 3)), None, None, backend, precision, engine, tolerance)
    kind = _DeviceKind(points)
    if device_results:
        kind.require_known("device_results=True")
    result = _hull_dict(points, protocol, kind, backend, precision, engine, tolerance)
    if device_results:
        for key in _RESULT_ARRAYS:
            array = result[key]
            # Indices as int64 on the device: PyTorch has few operations on uint32.
            result[key] = kind.like_input(array.astype(np.int64) if array.dtype == np.uint32 else array)
    return result


def _hull_dict(points, protocol, kind, backend, precision, engine, tolerance):
    """The module's hull dict of (n, 2) or (n, 3) points (host points already through _as_points): in GPU
    memory through _device_hull, else the 2-D or 3-D hull on the host's array."""
    merge = _merge_arguments(tolerance, *_bounds_of(points, tolerance, kind))
    if protocol is not None:
        return _device_hull(points, protocol, backend, precision, merge)
    if points.shape[1] == 2:
        return _cudahull.convex_hull_2d(points, backend, precision, *merge)
    return _cudahull.convex_hull(points, backend, precision, engine, *merge)


def _bounds_of(points, tolerance, kind=None):
    """The bounding box, only where an absolute tolerance needs it (else (None, None))."""
    if not isinstance(tolerance, tuple) or tolerance[1] is None or points.shape[0] == 0:
        return None, None
    if kind is None:
        return points.min(axis=0), points.max(axis=0)
    low, high = kind.bounds(points)
    return kind.to_numpy(low), kind.to_numpy(high)


def _index_array(values, npoints):
    # scipy's index arrays are int32; beyond 2**31 - 1 points they could not hold every index.
    return np.asarray(values, dtype=np.int32 if npoints < 2**31 else np.int64)


_DEFAULT = object()  # tolerance not given: None without qhull_options, "qhull" with them


class ConvexHull:
    """Convex hull of 2-D or 3-D points, a drop-in for ``scipy.spatial.ConvexHull``.

    Parameters
    ----------
    points : (n, 3) or (n, 2) array_like, or an (n, 3) array in GPU memory
        float32 input is computed in float, float64 (and integer) input in double: the hull is exact for
        those values (a point on a face is not a vertex) unless a ``tolerance`` asks for merging.  A CuPy
        array, a PyTorch CUDA tensor or another array in CUDA memory (``__dlpack__`` or
        ``__cuda_array_interface__``; C-contiguous float32 or float64, on the current device) is read in
        place (3-D by the resident engine; 2-D filtered on the device, only the possible corners read back):
        no host copy of it is made.  Masked arrays raise ValueError, as in scipy.
    incremental : bool
        scipy's: accepted; ``add_points`` works either way.
    qhull_options : str, optional
        Parsed as Qhull parses it; every option has a documented meaning here (the README's table,
        ``cudahull.qhull_options``), and one without raises ``QhullError`` naming it.  Giving any options
        makes the default ``tolerance`` "qhull": such code expects Qhull's merged output.
    tolerance : None, "qhull" or float
        None: the exact hull, every strictly extreme point a vertex (the default without
        ``qhull_options``).  "qhull": facets merged as Qhull's default roundoff-based merging does (the
        default with ``qhull_options``).  A float: merged within that fraction of the bounding box's
        largest side.  A merged hull has no facet thinner than the tolerance, is triangulated as Qhull's
        Qt, lists the points merging set aside in ``coplanar``, and is checked: every input point lies
        within ``max_outside`` of every facet's plane.
    backend : "auto", "cpu" or "cuda"
        "auto" takes the CUDA backend when a usable GPU is present.  Points in GPU memory need the GPU.
    precision : "auto", "float" or "double"
        "auto" takes the input's own; "float" rounds double input once, "double" widens float input
        (for points in GPU memory, into a temporary array on the device).
    engine : "auto", "stepping" or "resident"
        "auto", as the command line's ``--engine auto``: "resident" (every phase on the device) where the
        hull runs on a GPU, which points in GPU memory need; "stepping" (Algorithm 1 an iteration at a
        time, the host editing the mesh) on the CPU.
    device_results : bool
        For a CuPy or PyTorch input: the array attributes as arrays of the input's kind on its device
        instead of NumPy arrays.

    Attributes
    ----------
    points : the input points as given: float32 input stays float32, and points in GPU memory stay there
    vertices : int32 indices of the hull's vertices: sorted ascending in 3-D, counter-clockwise in 2-D (as
        scipy's)
    simplices : (nsimplex, ndim) int32: triangles counter-clockwise seen from outside in 3-D, edges
        counter-clockwise in 2-D
    neighbors : (nsimplex, ndim) int32, the k-th neighbour is opposite the k-th vertex
    equations : (nsimplex, ndim + 1) float64, unit outward normal and offset: normal . x + offset <= 0
        inside; the exact normal rounded, so every point lies within a few units in the last place of them
    volume, area : volume and surface area (in 2-D: area and perimeter, as scipy's)
    npoints, nsimplex, ndim, min_bound, max_bound : as scipy
    coplanar : (ncoplanar, 3) int32: the points merging set aside (with Qi, also the interior points),
        each with its nearest facet and nearest vertex, as scipy's; empty for the exact hull
    good : with qhull_options QGn / QG-n, which facets point n sees (does not see), as scipy's; else None
    tolerance, max_outside : the absolute merge tolerance (0 when exact) and the proven bound on every
        input point's height above every facet's plane (0 when exact)
    dimension : the input's dimension (3 or 2); precision, backend : what the hull was computed in and on
    stats : the resident engine's counters as a dict, None for the others

    Raises
    ------
    ValueError for no points, as scipy; QhullError (a ``scipy.spatial.QhullError``) for fewer than ndim + 1 points, flat input (its
    lower-dimensional hull is ``cudahull.convex_hull()``'s answer) and unknown ``qhull_options``;
    ValueError for NaN or infinite coordinates, masked arrays, and points of other than 2 or 3 dimensions;
    ``DeviceError`` (a RuntimeError) for backend="cuda", or points in GPU memory, without a usable GPU.
    """

    def __init__(self, points, incremental=False, qhull_options=None, *, tolerance=_DEFAULT, backend="auto",
                 precision="auto", engine="auto", device_results=False):
        self._options = _qhull_options.parse(qhull_options, QhullError) if qhull_options is not None else None
        if self._options is not None and not self._options.words:
            self._options = None  # "" asks for nothing, as None (scipy treats them alike)
        if tolerance is _DEFAULT:
            tolerance = self._options.merge("qhull") if self._options is not None else None
        self._tolerance_choice = tolerance
        self._protocol = _cuda_protocol(points)
        self._kind = _DeviceKind(points) if self._protocol else None
        self._engine_choice = _check_engine(engine, self._protocol is not None)
        self._device_results = bool(device_results) and self._kind is not None
        if self._device_results:
            self._kind.require_known("device_results=True")
        self._backend_choice = backend
        self._precision_choice = precision
        self._closed = False
        if self._protocol:
            _device_shape(points, self._protocol)
        else:
            points = _as_points(points, (2, 3))
        self._commit(points, self._compute(points, None))

    # --- computing ------------------------------------------------------------------------------------

    @property
    def _good_point(self):
        return None if self._options is None else self._options.good_point

    def _compute(self, points, subset):
        """The hull of ``points[subset]`` (all of them for None; ``subset`` ascending, so the lowest index
        of duplicates stays it), less the QGn point, as the attributes' values: nothing is changed here,
        so a failure leaves the object as it was."""
        npoints = int(points.shape[0])
        ndim = int(points.shape[1])
        good = self._good_point
        if good is not None and not 0 <= good < npoints:
            raise QhullError(f"qhull_options QG{good}: there is no point {good} among {npoints} points")
        if good is not None:
            subset = np.arange(npoints) if subset is None else np.asarray(subset)
            subset = subset[subset != good]
        if subset is None:
            chosen = points
        elif self._protocol:
            chosen = self._kind.take(points, subset)
        else:
            chosen = np.ascontiguousarray(points[subset])
        if npoints == 0:
            raise ValueError("No points given")  # scipy's words and type
        if int(chosen.shape[0]) <= ndim:
            raise QhullError(f"QH6214 qhull input error: not enough points({int(chosen.shape[0])}) to construct "
                             f"initial simplex (need {ndim + 1})")
        result = _hull_dict(chosen, self._protocol, self._kind, self._backend_choice, self._precision_choice,
                            self._engine_choice, self._tolerance_choice)
        if result["dimension"] == ndim and result["tolerance"] > 0 and len(result["vertices"]) <= 2000:
            # A merged hull thinner than its tolerance in some facet's direction is flat at that
            # tolerance, as Qhull finds it (QH6154).  (Merging leaves a thin body few vertices.)
            corners = result["vertices"].astype(np.int64)
            host = np.asarray(self._kind.to_numpy(self._kind.take(chosen, corners)) if self._protocol
                              else chosen[corners], dtype=np.float64)
            equations = result["equations"]
            widths = -(host @ equations[:, :-1].T + equations[:, -1]).min(axis=0)
            if widths.size and widths.min() <= result["tolerance"]:
                raise QhullError(f"QH6154 qhull precision error: the merged hull is {widths.min():.3g} thick, within "
                                 f"its tolerance {result['tolerance']:.3g}: flat at that tolerance "
                                 f"(tolerance=None gives the exact hull)")
        if result["dimension"] < ndim:
            raise QhullError(
                f"QH6154 qhull precision error: initial simplex is flat: the points span {result['dimension']} "
                f"of {ndim} dimensions (cudahull.convex_hull() gives their lower-dimensional hull)")

        def original(indices):
            return _index_array(indices if subset is None else np.asarray(subset)[indices], npoints)

        values = {
            "dimension": ndim,
            "precision": result["precision"],
            "backend": result["backend"],
            "stats": result["stats"],
            "tolerance": result["tolerance"],
            "max_outside": result["max_outside"],
            "volume": result["volume"],
            "area": result["area"],
            # scipy's vertices run counter-clockwise in 2-D (the polygon), ascending in 3-D.
            "vertices": original(result["polygon"] if ndim == 2 else result["vertices"]),
            "simplices": original(result["simplices"]).reshape(-1, ndim),
            "neighbors": result["neighbors"].astype(np.int32, copy=False),
            "equations": result["equations"],
        }
        coplanar = result["coplanar"].astype(np.int64).reshape(-1, 3)
        if coplanar.size:
            coplanar[:, 0] = original(coplanar[:, 0])
            coplanar[:, 2] = original(coplanar[:, 2])
        # The exact hull's vertices, merged away or not: what add_points computes on next.
        values["exact_vertices"] = (np.union1d(values["vertices"], coplanar[:, 0]) if coplanar.size
                                    else values["vertices"]).astype(np.int64)
        other_points = self._options is not None and (self._options.interior or self._options.coplanar)
        # Qc, Qi and QG look at the points themselves, on the host (one copy, in double, for all three).
        host = (np.ascontiguousarray(self._kind.to_numpy(points) if self._protocol else points, dtype=np.float64)
                if other_points or good is not None else None)
        if other_points:
            coplanar = self._with_other_points(host, values, coplanar, result["tolerance"])
        values["coplanar"] = _index_array(coplanar.reshape(-1, 3), npoints)
        values["good"] = None
        if good is not None:
            values["good"] = self._good(host, values, good)
        return values

    def _good(self, host, values, good):
        """QGn: the facets point n sees (strictly above their planes, decided exactly); QG-n: the others."""
        visible = _cudahull.facets_visible(host, np.ascontiguousarray(values["simplices"], dtype=np.int64),
                                           host[good].copy())
        return visible if self._options.good_visible else ~visible

    def _with_other_points(self, host, values, coplanar, tolerance):
        """Qc: also every point that is neither a vertex nor already listed but lies within the tolerance of
        a facet (within rounding, 8 units in the last place of the largest coordinate, for the exact hull),
        as scipy's coplanar points; Qi: every other point too (the interior ones).  Each with its nearest
        facet (the one it is least below) and that facet's nearest vertex.  O(n x facets), on the host."""
        listed = np.zeros(host.shape[0], dtype=bool)
        listed[values["vertices"]] = True
        listed[coplanar[:, 0]] = True
        if self._good_point is not None:
            listed[self._good_point] = True
        rest = np.flatnonzero(~listed)
        within = max(tolerance, 8 * np.finfo(np.float64).eps * float(np.abs(host).max(initial=0.0)))
        equations, simplices = values["equations"], values["simplices"]
        rows = [coplanar]
        for begin in range(0, rest.size, 4096):
            chunk = rest[begin:begin + 4096]
            heights = host[chunk] @ equations[:, :-1].T + equations[:, -1]
            facet = np.argmax(heights, axis=1)
            if not self._options.interior:
                near = heights[np.arange(chunk.size), facet] >= -within
                chunk, facet = chunk[near], facet[near]
            corners = simplices[facet]
            distance = np.linalg.norm(host[corners] - host[chunk][:, None, :], axis=2)
            vertex = corners[np.arange(chunk.size), np.argmin(distance, axis=1)]
            rows.append(np.column_stack([chunk, facet, vertex]))
        return np.concatenate(rows).astype(np.int64)

    def _commit(self, points, values):
        self.points = points
        self.npoints = int(points.shape[0])
        self.ndim = int(points.shape[1])
        self._bounds = None
        self.nsimplex = int(values["simplices"].shape[0])
        self._exact_vertices = values["exact_vertices"]
        for key in ("dimension", "precision", "backend", "stats", "tolerance", "max_outside", "volume", "area",
                    "good"):
            setattr(self, key, values[key])
        for key in ("vertices", "simplices", "neighbors", "equations", "coplanar"):
            setattr(self, key, self._result_array(values[key]))

    def _result_array(self, array):
        return self._kind.like_input(array) if self._device_results else array

    def _compute_bounds(self):
        if self.npoints == 0:
            empty = np.full(self.ndim, np.nan)
            return self._result_array(empty), self._result_array(empty)
        if self._kind is None or not self._protocol:
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

    def add_points(self, points, restart=False):
        """Add (m, ndim) points and update the hull: afterwards it is the hull of all the points.

        The hull of a union is the hull of the old hull's vertices and the new points, so only those are
        computed on (or every point, with ``restart=True``: the same answer).  A hull of CuPy or PyTorch
        points in GPU memory takes new points of the same kind, joined on the device.  Atomic: a batch that
        is rejected (a bad coordinate, named by its row in the batch) changes nothing.
        """
        if self._closed:
            raise RuntimeError("the hull is closed: add_points is no longer possible")
        old_count = self.npoints
        if self._protocol:
            joined = self._kind.concatenate(self.points, points)
        else:
            new = _as_points(points, (self.ndim,))
            self._check_batch(new)
            joined = np.ascontiguousarray(np.concatenate([self.points, new]))
        if restart:
            values = self._compute(joined, None)
        else:
            subset = np.concatenate([self._exact_vertices, np.arange(old_count, int(joined.shape[0]))])
            subset.sort()
            if self._good_point is not None:
                subset = np.unique(np.append(subset, self._good_point))
            if self._options is not None and (self._options.interior or self._options.coplanar):
                subset = None  # Qi and Qc look at every point
            values = self._compute(joined, subset)
        self._commit(joined, values)

    def _check_batch(self, new):
        """A new batch's coordinates checked alone, so that an error names its row in the batch (in float,
        a value beyond float's range too)."""
        lifted = new if new.shape[1] == 3 else np.column_stack([new, np.zeros(new.shape[0], dtype=new.dtype)])
        try:
            _cudahull.check_points(np.ascontiguousarray(lifted))
            if self.precision == "float" and new.dtype == np.float64:
                beyond = np.argwhere(np.abs(new) > np.finfo(np.float32).max)
                if beyond.size:
                    row, axis = beyond[0]
                    raise InputError(f"point {row}: {'xyz'[axis]} coordinate {new[row, axis]!r} does not fit in "
                                     f"float")
        except ValueError as error:
            raise type(error)(f"add_points: {error} (a row of the new points; nothing was added)") from None

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


# --- batched hulls (issue 27) ---------------------------------------------------------------------------------

_BATCH_ARRAYS = ("vertex_offsets", "face_offsets", "vertices", "faces", "planes", "volumes", "areas", "dimensions",
                 "polygon_offsets", "polygons")


class BatchHulls:
    """The hulls of B point clouds, packed, as ``convex_hull_batch`` returns them.

    Cloud ``c``'s vertices are ``vertices[vertex_offsets[c]:vertex_offsets[c + 1]]`` (ascending) and its faces
    ``faces[face_offsets[c]:face_offsets[c + 1]]`` (outward triangles, counter-clockwise seen from outside)
    with their ``planes`` (unit outward normal and offset: n . x + d <= 0 inside); indices count from the
    cloud's first point (for padded input, the row in the cloud's slab).  ``volumes``, ``areas`` and
    ``dimensions`` hold one value a cloud: a flat cloud gives its lower-dimensional answer as
    ``convex_hull()`` does (dimension 2, 1, 0; -1 for an empty cloud; volume 0, area both sides of its
    polygon), with its polygon's corners in order in ``polygons[polygon_offsets[c]:polygon_offsets[c + 1]]``.
    Offsets are int64; indices int32 (int64 beyond 2**31 points in a cloud, and for PyTorch).  Arrays are of
    the input's library: NumPy, or CuPy arrays and PyTorch tensors on the input's device.  ``precision`` and
    ``backend`` say what the hulls were computed in and on; ``report`` (a dict) what the GPU did: the clouds
    its batch kernel hulled (``clouds_batched``), its launches, the most device memory the call held
    (``device_bytes_peak``, the points included) and milliseconds (``device_ms``, ``kernel_ms``,
    ``describe_ms``).
    """

    __slots__ = _BATCH_ARRAYS + ("precision", "backend", "report")

    def __len__(self):
        return int(self.volumes.shape[0])

    def cloud(self, c):
        """Cloud ``c``'s hull as a dict: ``vertices``, ``faces``, ``planes``, ``polygon``, ``volume``, ``area``,
        ``dimension``."""
        if not -len(self) <= c < len(self):
            raise IndexError(f"cloud {c} of {len(self)}")
        c %= len(self)
        v = slice(int(self.vertex_offsets[c]), int(self.vertex_offsets[c + 1]))
        f = slice(int(self.face_offsets[c]), int(self.face_offsets[c + 1]))
        p = slice(int(self.polygon_offsets[c]), int(self.polygon_offsets[c + 1]))
        return {"vertices": self.vertices[v], "faces": self.faces[f], "planes": self.planes[f],
                "polygon": self.polygons[p], "volume": float(self.volumes[c]), "area": float(self.areas[c]),
                "dimension": int(self.dimensions[c])}

    def __repr__(self):
        return (f"BatchHulls({len(self)} clouds, {int(self.vertices.shape[0])} vertices, "
                f"{int(self.faces.shape[0])} faces, precision={self.precision!r}, backend={self.backend!r})")


def _host_integers(values, name):
    """``offsets`` or ``lengths`` as a 1-D int64 NumPy array; from GPU memory, copied to the host (B + 1 values:
    the batch's plan, which clouds the kernel takes and its room, is made on the host)."""
    if _cuda_protocol(values) is not None:
        owner = _DeviceKind(values)
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


def _batch_layout(shape, offsets, lengths):
    """(padded, offsets as int64, lengths as int64 or None, the largest cloud) for points of ``shape``: a packed
    (N, 3) array with B + 1 offsets, or a padded (B, M, 3) array with B lengths (None: every cloud M points,
    which then needs no packing)."""
    if len(shape) == 2 and shape[1] == 3:
        if lengths is not None:
            raise ValueError("lengths go with padded (B, M, 3) points; packed (N, 3) points take offsets")
        if offsets is None:
            raise ValueError("packed (N, 3) points need offsets: the B + 1 cloud boundaries, from 0 to N")
        bounds = _host_integers(offsets, "offsets")
        return False, bounds, None, int(np.diff(bounds).max(initial=0))
    if len(shape) == 3 and shape[2] == 3:
        if offsets is not None:
            raise ValueError("offsets go with packed (N, 3) points; padded (B, M, 3) points take lengths")
        clouds, slab = int(shape[0]), int(shape[1])
        if lengths is not None:
            lengths = _host_integers(lengths, "lengths")
            if lengths.shape[0] != clouds:
                raise ValueError(f"lengths must hold one length a cloud: {clouds}, not {lengths.shape[0]}")
            if lengths.size and (lengths.min() < 0 or lengths.max() > slab):
                bad = int(np.flatnonzero((lengths < 0) | (lengths > slab))[0])
                raise ValueError(f"lengths[{bad}] is {int(lengths[bad])}: a cloud holds 0 to {slab} points here")
            if not np.all(lengths == slab):
                bounds = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64)
                return True, bounds, lengths, int(lengths.max(initial=0))
        # Every cloud fills its slab: the offsets are multiples of M, and the points need no packing (PyTorch,
        # 100,000 clouds: NumPy's lengths, sums and checks cost some 0.3 ms a call).
        return True, np.arange(clouds + 1, dtype=np.int64) * slab, None, slab
    raise ValueError(f"points must be a packed (N, 3) array with offsets or a padded (B, M, 3) array with "
                     f"lengths, not one of shape {tuple(shape)}")


def _batch_result(raw, offsets, kind=None):
    """The module's batch dict as a BatchHulls.  Its arrays are NumPy (from the host), or, for points in GPU
    memory, already the input's CuPy arrays or PyTorch tensors, sharing the result's device memory."""
    hulls = BatchHulls()
    on_host = isinstance(raw["volumes"], np.ndarray)
    if on_host:
        longest = int(np.diff(offsets).max(initial=0))
        index = np.int32 if longest < 2**31 else np.int64
        raw["vertices"] = raw["vertices"].astype(index)
        raw["polygons"] = raw["polygons"].astype(index)
        raw["faces"] = raw["faces"].astype(index).reshape(-1, 3)
        raw["planes"] = raw["planes"].reshape(-1, 4)
    torch_indices = kind is not None and kind.library == "torch"
    for key in _BATCH_ARRAYS:
        array = raw[key]
        if on_host and kind is not None and kind.known:
            # A PyTorch tensor on the CPU: tensors back.  Indices int64, as for device_results (few PyTorch
            # operations take int32).
            if torch_indices and array.dtype == np.int32:
                array = array.astype(np.int64)
            array = kind.like_input(array)
        elif not on_host and torch_indices and key in ("vertices", "faces", "polygons", "dimensions"):
            array = array.long()  # on the device
        setattr(hulls, key, array)
    hulls.precision = raw["precision"]
    hulls.backend = raw["backend"]
    hulls.report = raw["report"]
    return hulls


def _batch_call(padded, function, *arguments):
    """The module's batch function; for padded input an error names the cloud and the point without the row
    of the packed copy, which the caller never saw."""
    try:
        return function(*arguments)
    except ValueError as error:
        if not padded:
            raise
        raise type(error)(re.sub(r" \(row \d+ of the packed points\)", "", str(error))) from None


def release_device_memory():
    """Hands the GPU memory cudahull keeps between calls on the current CUDA device back to the driver, as
    ``torch.cuda.empty_cache()`` does PyTorch's.

    cudahull keeps at least 256 MiB, and a batch the memory it used (up to a sixteenth of the device's) for
    the next batch of its size, which then maps none again; call this when PyTorch or CuPy needs that memory.
    Results stay valid.  Without a usable GPU, or before cudahull used it, it does nothing.
    """
    _cudahull.release_device_memory()


def convex_hull_batch(points, offsets=None, lengths=None, *, backend="auto", precision="auto", engine="auto",
                      threads=0):
    """The exact hulls of B point clouds in one call (issue 27), as a ``BatchHulls``.

    ``points``: a packed (N, 3) array with ``offsets`` (B + 1 cloud boundaries: 0, each cloud's end, the last
    N), or a padded (B, M, 3) array with ``lengths`` (B cloud sizes, each at most M; None: M each).  NumPy
    (float32 computed in float, float64 and integers in double), or a CuPy array or PyTorch tensor in GPU
    memory (float32 or float64, read there: no host copy of the points).  Each cloud's hull is
    ``convex_hull()``'s on that cloud alone: the same vertex set, faces, planes and measures, and the
    lower-dimensional answer for a flat cloud.  ``backend``, ``precision`` and ``engine`` as for
    ``convex_hull``; ``threads``: CPU clouds hulled at once (0: every core), the same result for any.

    On the CPU the clouds run on all cores.  With a GPU one launch hulls every cloud of 4 to 131,072 points, a
    block a cloud (the same vertex sets and faces as ``convex_hull()``, the faces in another order; clouds of
    more than 16,384 points on larger blocks, in a launch of their own); flat, tiny and larger clouds take the
    single-cloud GPU path.  The hulls are described on the GPU, and for CuPy and PyTorch input the result's
    arrays are the GPU's own (the kernel's hulls never cross to the host).

    Raises ValueError for a NaN or infinite coordinate (naming the cloud, the point in it and its row in the
    packed points), and for bad shapes, offsets or lengths; DeviceError as ``convex_hull``.
    """
    if isinstance(threads, (bool, np.bool_)) or not isinstance(threads, (int, np.integer)) or threads < 0:
        raise ValueError(f"threads must be a whole number of CPU clouds at once, 0 for every core, not {threads!r}")
    protocol = _cuda_protocol(points)
    if protocol is None:
        if isinstance(points, np.ma.MaskedArray):
            raise ValueError("masked arrays are not supported: pass the points to keep, packed, with offsets")
        # A PyTorch tensor on the CPU gets tensors back (NumPy's memory, shared: no copy).
        kind = _DeviceKind(points) if _DeviceKind(points).library == "torch" else None
        if kind is not None:
            points = points.detach()
        array = np.asarray(points)
        padded, bounds, lengths, _ = _batch_layout(array.shape, offsets, lengths)
        if array.dtype != np.float32 and array.dtype != np.float64:
            if array.dtype.kind not in "biuf":
                raise ValueError(f"points must be numbers, not {array.dtype}")
            array = array.astype(np.float64)
        array = np.ascontiguousarray(array)
        if padded:
            if lengths is None:  # every cloud fills its slab
                array = array.reshape(-1, 3)
            else:
                slab = array.shape[1]
                array = array[np.arange(slab)[None, :] < lengths[:, None]]  # packed, in cloud order
        raw = _batch_call(padded, _cudahull.convex_hull_batch, np.ascontiguousarray(array), bounds, backend,
                          precision, engine, int(threads))
        return _batch_result(raw, bounds, kind)

    # Points in GPU memory.  Offsets (or lengths) are read to the host, padded clouds are packed on the
    # device (a device copy), and the batch runs there (convex_hull_batch_device in C++).
    if backend == "cpu":
        raise ValueError("points in GPU memory need backend 'auto' or 'cuda', not 'cpu' (for the CPU backend, "
                         "pass them as NumPy: cupy.asnumpy(x), x.cpu().numpy())")
    _check_engine(engine, True)
    kind = _DeviceKind(points)
    library = kind.library if kind.known else "numpy"  # the result's arrays: the input's, on its device
    interface = points.__cuda_array_interface__ if protocol == "cuda_array_interface" else None
    shape = tuple(interface["shape"] if interface is not None else points.shape)
    padded, bounds, lengths, largest = _batch_layout(shape, offsets, lengths)
    if largest >= 2**31:
        library = "numpy"  # the device's result holds int32 indices: this one comes back, as int64, and goes up
    usable, why_not = _cuda_device()
    if not usable:
        raise DeviceError(f"points in GPU memory, but no usable CUDA device: {why_not}")
    if padded:
        points = kind.pack_padded(points, lengths)
        protocol = _cuda_protocol(points)
        interface = points.__cuda_array_interface__ if protocol == "cuda_array_interface" else None
        shape = tuple(interface["shape"] if interface is not None else points.shape)
    if protocol == "cuda_array_interface":
        typestr, strides = interface["typestr"], interface.get("strides")
        if typestr not in ("<f4", "<f8"):
            raise ValueError("points in GPU memory must be float32 or float64 (convert with .astype())")
        itemsize = int(typestr[2])
        if strides is not None and shape[0] > 0 and (
                strides[1] != itemsize or (shape[0] > 1 and strides[0] != 3 * itemsize)):
            raise ValueError("points in GPU memory must be C-contiguous: the engine reads them in place")
        raw = _batch_call(padded, _cudahull.convex_hull_batch_cuda_pointer, interface["data"][0], shape[0],
                          itemsize == 8, bounds, backend, precision, library)
    else:
        if getattr(points, "requires_grad", False):
            points = points.detach()  # PyTorch exports no tensor that requires grad; the hulls read values only
        raw = _batch_call(padded, _cudahull.convex_hull_batch_cuda, points, bounds, backend, precision, library)
    return _batch_result(raw, bounds, kind)
