"""Exact 3-D convex hulls with the CudaHull algorithm (Stein, Geva, El-Sana 2012).

``ConvexHull`` has the attributes and methods of ``scipy.spatial.ConvexHull`` for 3-D points; ``Engine``
steps the algorithm one iteration at a time (for notebooks); ``convex_hull`` returns the hull as a dict.
"""

import numpy as np

from . import _cudahull
from ._cudahull import SWAP_KINDS, DeviceError, InputError

__all__ = ["ConvexHull", "Engine", "convex_hull", "InputError", "DeviceError", "SWAP_KINDS"]


def _as_points(points):
    """(n, 3) C-contiguous float32 (kept) or float64 (anything else numeric, converted) points."""
    array = np.asarray(points)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"points must be an (n, 3) array of 3-D points, not one of shape {array.shape}")
    if array.dtype != np.float32 and array.dtype != np.float64:
        if array.dtype.kind not in "biuf":
            raise ValueError(f"points must be numbers, not {array.dtype}")
        array = array.astype(np.float64)
    return np.ascontiguousarray(array)


def convex_hull(points, backend="auto", precision="auto", engine="stepping"):
    """The exact hull of (n, 3) ``points`` as a dict of NumPy arrays and numbers.

    Keys: ``dimension``, ``precision``, ``backend``, ``vertices``, ``simplices``, ``neighbors``,
    ``equations``, ``polygon``, ``volume``, ``area`` (as on ``ConvexHull``; indices are uint32 here).
    """
    return _cudahull.convex_hull(_as_points(points), backend, precision, engine)


def _index_array(values, npoints):
    # scipy's index arrays are int32; beyond 2**31 - 1 points they could not hold every index.
    return np.asarray(values, dtype=np.int32 if npoints < 2**31 else np.int64)


class ConvexHull:
    """Exact convex hull of 3-D points, with the interface of ``scipy.spatial.ConvexHull``.

    Parameters
    ----------
    points : (n, 3) array_like
        float32 input is computed in float, float64 (and integer) input in double: the hull is exact for
        those values, with no tolerance (a point on a face is not a vertex).
    backend : "auto", "cpu" or "cuda"
        "auto" takes the CUDA backend when a usable GPU is present.
    precision : "auto", "float" or "double"
        "auto" takes the input's own; "float" rounds double input once, "double" widens float input.
    incremental : bool
        Accepted for scipy's signature; ``add_points`` works either way.

    Attributes
    ----------
    points : the input points (float32 input stays float32)
    vertices : (nvertices,) int32, the indices of the hull's vertices, sorted ascending
    simplices : (nsimplex, 3) int32, the triangles, counter-clockwise seen from outside
    neighbors : (nsimplex, 3) int32, the k-th neighbour is opposite the k-th vertex
    equations : (nsimplex, 4) float64, unit outward normal and offset: normal . x + offset <= 0 inside
    volume, area : the hull's volume and surface area
    npoints, nsimplex, ndim, min_bound, max_bound : as scipy
    coplanar : an empty (0, 3) int32 array (no point is set aside: the hull is exact)
    good : None
    dimension : the input's affine dimension (3, or lower for flat input: see below)
    precision, backend : what the hull was computed in and on

    Flat input
    ----------
    Where scipy raises QhullError (QH6154), the lower-dimensional hull comes back: ``dimension`` is 2 for
    coplanar points (``vertices`` are the polygon's corners, ``polygon`` lists them in order, ``simplices``,
    ``neighbors`` and ``equations`` are empty, ``volume`` is 0 and ``area`` counts both sides of the
    polygon), 1 for collinear points (the segment's two ends), 0 when every point is the same, and -1 for
    no points.  Fewer than 4 points are flat.

    Raises ValueError for NaN or infinite coordinates (and for doubles outside exact arithmetic's range,
    nonzero magnitudes from 2**-250 to 2**250), ``DeviceError`` (a RuntimeError) for backend="cuda"
    without a usable GPU.
    """

    def __init__(self, points, backend="auto", precision="auto", incremental=False, qhull_options=None):
        if qhull_options is not None:
            raise ValueError("qhull_options has no meaning here: the hull is exact, with no tolerance")
        self._backend_choice = backend
        self._precision_choice = precision
        self._closed = False
        self._set_points(_as_points(points))
        self._compute(np.arange(self.npoints))

    def _set_points(self, points):
        self.points = points
        self.npoints = points.shape[0]
        self.ndim = 3
        self.min_bound = points.min(axis=0) if self.npoints else np.full(3, np.nan)
        self.max_bound = points.max(axis=0) if self.npoints else np.full(3, np.nan)

    def _compute(self, subset):
        """The hull of ``points[subset]``; ``subset`` ascending, so the lowest index of duplicates stays it."""
        subset = np.asarray(subset, dtype=np.int64)
        all_points = len(subset) == self.npoints
        result = _cudahull.convex_hull(
            self.points if all_points else np.ascontiguousarray(self.points[subset]),
            self._backend_choice, self._precision_choice, "stepping")

        def original(indices):
            return _index_array(indices if all_points else subset[indices], self.npoints)

        self.dimension = result["dimension"]
        self.precision = result["precision"]
        self.backend = result["backend"]
        self.vertices = original(result["vertices"])
        self.simplices = original(result["simplices"]).reshape(-1, 3)
        self.polygon = original(result["polygon"])
        self.neighbors = result["neighbors"].astype(np.int32)
        self.equations = result["equations"]
        self.volume = result["volume"]
        self.area = result["area"]
        self.nsimplex = self.simplices.shape[0]
        self.coplanar = np.empty((0, 3), dtype=np.int32)
        self.good = None

    def add_points(self, points, restart=False):
        """Add (m, 3) points and update the hull: afterwards it is the hull of all the points.

        The hull of a union is the hull of the old hull's vertices and the new points, so only those are
        computed on (or every point, with ``restart=True``: the same answer).
        """
        if self._closed:
            raise RuntimeError("the hull is closed: add_points is no longer possible")
        new = _as_points(points)
        old_count = self.npoints
        self._set_points(np.ascontiguousarray(np.concatenate([self.points, new])))
        if restart:
            self._compute(np.arange(self.npoints))
        else:
            self._compute(np.concatenate([self.vertices.astype(np.int64), np.arange(old_count, self.npoints)]))

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
