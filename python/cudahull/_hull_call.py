"""One cloud's hull as the module's dict: ``convex_hull()`` (with the lower-dimensional answer for flat
input), and the engine and tolerance arguments checked and converted into the module's, for points in GPU
memory or on the host."""

from __future__ import annotations

import math
from typing import Any, Union

import numpy as np
import numpy.typing as npt

from . import _cudahull, _qhull
from ._arrays import (DeviceKind, as_points, checked_interface, cuda_protocol, device_shape, host_array,
                      numeric, require_device)
from ._errors import value_text

__all__ = ["Tolerance", "check_engine", "convex_hull"]

Tolerance = Union[None, str, float]
_Merge = tuple[str, float, float]

_RESULT_ARRAYS = ("vertices", "simplices", "neighbors", "equations", "polygon", "coplanar")


def check_engine(engine: str, on_device: bool) -> str:
    # "auto" stays "auto": the module's plan_hull() (hull_plan.hpp) resolves it, as for the command line's
    # --engine auto: the resident engine where it runs on a GPU (only it reads GPU memory), the stepping
    # engine on the CPU, whose worker threads make it the faster one there.
    if engine not in ("auto", "stepping", "resident"):
        raise ValueError(f"engine must be auto, stepping or resident, not '{engine}'")
    if on_device and engine == "stepping":
        raise ValueError("the stepping engine edits the mesh on the host and takes host points: points in GPU "
                         "memory take engine 'resident' (or 'auto')")
    return engine


def _device_hull(points: Any, protocol: str, backend: str, precision: str, merge: _Merge) -> dict[str, Any]:
    """The hull dict of (n, 3) or (n, 2) points in CUDA memory: 3-D read in place by the resident engine,
    2-D filtered on the device with only the possible corners read back."""
    if backend == "cpu":
        raise ValueError("points in GPU memory need backend 'auto' or 'cuda', not 'cpu' (for the CPU backend, "
                         "pass them as NumPy: cupy.asnumpy(x), x.cpu().numpy())")
    shape = device_shape(points, protocol)
    if protocol == "cuda_array_interface":
        pointer, is_double = checked_interface(points, shape)  # checked before any data is read
        require_device()
        return _cudahull.convex_hull_cuda_pointer(pointer, shape[0], shape[1], is_double, backend, precision,
                                                  *merge)
    require_device()
    if getattr(points, "requires_grad", False):
        points = points.detach()  # PyTorch exports no tensor that requires grad; the hull reads values only
    return _cudahull.convex_hull_cuda(points, backend, precision, *merge)


def _merge_arguments(tolerance: object, low: Any = None, high: Any = None) -> _Merge:
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
    try:
        value = float(tolerance)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        value = math.nan
    if not math.isfinite(value) or value < 0:
        raise ValueError(f"tolerance must be None, 'qhull' or a finite number >= 0, not {value_text(tolerance)}")
    return ("relative", value, 1.0)


def _bounds_of(points: Any, tolerance: object, kind: DeviceKind | None = None) -> tuple[Any, Any]:
    """The bounding box, only where an absolute tolerance needs it (else (None, None))."""
    if not isinstance(tolerance, tuple) or tolerance[1] is None or points.shape[0] == 0:
        return None, None
    if kind is None:
        return points.min(axis=0), points.max(axis=0)
    low, high = kind.bounds(points)
    return kind.to_numpy(low), kind.to_numpy(high)


def _hull_dict(points: Any, protocol: str | None, kind: DeviceKind | None, backend: str, precision: str,
               engine: str, tolerance: object, box_measures: bool = False) -> dict[str, Any]:
    """The module's hull dict of (n, 2) or (n, 3) points (host points already through as_points): in GPU
    memory through _device_hull, else the 2-D or 3-D hull on the host's array; ``box_measures``: with
    Qhull's QbB volume and area of a 3-D host hull ("box_volume", "box_area")."""
    merge = _merge_arguments(tolerance, *_bounds_of(points, tolerance, kind))
    if protocol is not None:
        return _device_hull(points, protocol, backend, precision, merge)
    if points.shape[1] == 2:
        return _cudahull.convex_hull_2d(points, backend, precision, *merge)
    return _cudahull.convex_hull(points, backend, precision, engine, *merge, box_measures)


def convex_hull(points: npt.ArrayLike, backend: str = "auto", precision: str = "auto", engine: str = "auto",
                device_results: bool = False, tolerance: Tolerance = None) -> dict[str, Any]:
    """The hull of ``points`` as a dict of arrays and numbers, with the lower-dimensional answer for flat input.

    Parameters
    ----------
    points : (n, 3) or (n, 2) array_like, an (n, 3) or (n, 2) array in GPU memory, or (n, d >= 4) array_like
        As for ``ConvexHull``.  Points of 4 or more dimensions are hulled by scipy's Qhull (scipy must be
        installed): its answer, ``backend`` "qhull", and its QhullError for flat input.
    backend : {"auto", "cpu", "cuda"}
        "auto" takes the CUDA backend when a usable GPU is present.  Points in GPU memory need the GPU.
    precision : {"auto", "float", "double"}
        "auto" takes the input's own; "float" rounds double input once, "double" widens float input.
    engine : {"auto", "stepping", "resident"}
        "auto" is "resident" where the hull runs on a GPU (points in GPU memory, which only it reads in
        place, or host points with a usable GPU and backend "auto" or "cuda") and "stepping" on the CPU,
        as the command line's ``--engine auto``.
    device_results : bool
        Return the arrays of a CuPy or PyTorch input as CuPy arrays or tensors on its device.
    tolerance : None, "qhull" or float
        None: the exact hull.  "qhull": merged as Qhull's default merging does.  A number: merged within
        that fraction of the bounding box's largest side.

    Returns
    -------
    dict
        ``dimension`` (the hull's affine dimension: below the input's for flat input), ``input_dimension``,
        ``precision``, ``backend``, ``vertices``, ``simplices``, ``neighbors``, ``equations``, ``polygon``
        (a flat or 2-D hull's corners in order), ``coplanar``, ``volume``, ``area``, ``tolerance``,
        ``max_outside`` (as on ``ConvexHull``; indices are uint32 here), ``plan`` (as on ``ConvexHull``), and
        ``stats``: the resident engine's counters (``host_syncs``, ``bytes_from_device``,
        ``points_read_back``, ...), None otherwise.
        2-D points in GPU memory are filtered there: only the points that can be corners come back.

    Raises
    ------
    ValueError
        For NaN or infinite coordinates (``InputError``), bad shapes and bad arguments.
    DeviceError
        For ``backend="cuda"``, or points in GPU memory, without a usable GPU.

    Examples
    --------
    >>> import numpy as np, cudahull
    >>> square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]])
    >>> hull = cudahull.convex_hull(square, backend="cpu")
    >>> hull["dimension"], hull["polygon"].tolist(), hull["area"]
    (2, [0, 1, 2, 3], 2.0)
    """
    protocol = cuda_protocol(points)
    engine = check_engine(engine, protocol is not None)
    if protocol is None:
        array = host_array(points)
        if array.ndim == 2 and array.shape[1] >= 4:
            _qhull.check_request(int(array.shape[1]), tolerance, backend, precision, engine)
            return _qhull.hull_dict(numeric(array))
        return _hull_dict(as_points(array, (2, 3)), None, None, backend, precision, engine, tolerance)
    kind = DeviceKind(points)
    if device_results:
        kind.require_known("device_results=True")
    result = _hull_dict(points, protocol, kind, backend, precision, engine, tolerance)
    if device_results:
        for key in _RESULT_ARRAYS:
            array = result[key]
            # Indices as int64 on the device: PyTorch has few operations on uint32.
            result[key] = kind.like_input(array.astype(np.int64) if array.dtype == np.uint32 else array)
    return result
