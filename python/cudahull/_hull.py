"""One cloud's hull as scipy's drop-in: ``ConvexHull`` (its arguments, attributes, methods and errors).
``convex_hull()``, the hull as a dict, is _hull_call's; what qhull_options add to the attributes is
_option_results'."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _cudahull, _qhull
from . import qhull_options as _qhull_options
from ._arrays import DeviceKind, as_points, cuda_protocol, device_shape, host_array, index_array, numeric
from ._errors import InputError, degenerate_error, number_text, qhull_error, too_few_points_error
from ._hull_call import Tolerance, _hull_dict, check_engine, convex_hull
from ._option_results import _good_facets, _joggled, _scaled_measures, _with_other_points

__all__ = ["ConvexHull", "convex_hull"]


class _Default:
    """``tolerance`` not given: None without qhull_options, "qhull" with them."""

    def __repr__(self) -> str:
        return "<default>"


_DEFAULT: Any = _Default()


class ConvexHull:
    """Convex hull of points, a drop-in for ``scipy.spatial.ConvexHull``.

    2-D and 3-D points are hulled exactly by cudahull's engines (on the GPU where one is usable); points of 4
    or more dimensions by scipy's Qhull, with scipy's answer (``backend == "qhull"``; scipy must be
    installed).

    Parameters
    ----------
    points : (n, 3) or (n, 2) array_like, an (n, 3) or (n, 2) array in GPU memory, or (n, d >= 4) array_like
        float32 input is computed in float, float64 (and integer) input in double: the hull is exact for
        those values (a point on a face is not a vertex) unless a ``tolerance`` asks for merging.  A CuPy
        array, a PyTorch CUDA tensor or another array in CUDA memory (``__dlpack__`` or
        ``__cuda_array_interface__``; C-contiguous float32 or float64, on the current device) is read in
        place (3-D by the resident engine; 2-D filtered on the device, only the possible corners read back):
        no host copy of it is made.  Masked arrays raise ValueError, as in scipy.
    incremental : bool
        scipy's.  For 2-D and 3-D points ``add_points`` works either way; for 4-D and higher it is passed to
        Qhull, and ``add_points`` without it recomputes the hull of all the points.
    qhull_options : str, optional
        Parsed as Qhull parses it; every option has a documented meaning here (the README's table,
        ``cudahull.qhull_options``), and one without raises ``QhullError`` naming it.  Giving any options
        makes the default ``tolerance`` "qhull": such code expects Qhull's merged output.  For 4-D and higher
        they go to Qhull as they are.
    tolerance : None, "qhull" or float
        None: the exact hull, every strictly extreme point a vertex (the default without
        ``qhull_options``).  "qhull": facets merged as Qhull's default roundoff-based merging does (the
        default with ``qhull_options``).  A float: merged within that fraction of the bounding box's
        largest side.  A merged hull has no facet thinner than the tolerance, is triangulated as Qhull's
        Qt, lists the points merging set aside in ``coplanar``, and is checked: every input point lies
        within ``max_outside`` of every facet's plane.
    backend : {"auto", "cpu", "cuda"}
        "auto" takes the CUDA backend when a usable GPU is present.  Points in GPU memory need the GPU.
    precision : {"auto", "float", "double"}
        "auto" takes the input's own; "float" rounds double input once, "double" widens float input
        (for points in GPU memory, into a temporary array on the device).
    engine : {"auto", "stepping", "resident"}
        "auto", as the command line's ``--engine auto``: "resident" (every phase on the device) where the
        hull runs on a GPU, which points in GPU memory need; "stepping" (Algorithm 1 an iteration at a
        time, the host editing the mesh) on the CPU.
    device_results : bool
        For a CuPy or PyTorch input: the array attributes as arrays of the input's kind on its device
        instead of NumPy arrays.

    Attributes
    ----------
    points : ndarray of double, shape (npoints, ndim)
        The input points as given: float32 input stays float32, and points in GPU memory stay there.
    vertices : ndarray of ints, shape (nvertices,)
        int32 indices of the hull's vertices: sorted ascending in 3-D, counter-clockwise in 2-D (as scipy's).
    simplices : ndarray of ints, shape (nsimplex, ndim)
        Triangles counter-clockwise seen from outside in 3-D, edges counter-clockwise in 2-D.
    neighbors : ndarray of ints, shape (nsimplex, ndim)
        The k-th neighbour is opposite the k-th vertex.
    equations : ndarray of double, shape (nsimplex, ndim + 1)
        Unit outward normal and offset: normal . x + offset <= 0 inside; the exact normal rounded, so
        every point lies within a few units in the last place of them.  Always in the input's coordinates
        (under ``QbB``/``Qbb`` scipy gives them in Qhull's scaled coordinates instead).
    volume, area : float
        Volume and surface area (in 2-D: area and perimeter, as scipy's).  Under ``QbB``, ``Qbb``,
        ``Qbk:n`` or ``QBk:n`` these are, as scipy's, the measures of the points as Qhull scales them (QbB:
        each coordinate onto [-0.5, 0.5]), not of the input: compute without those options, or with
        ``tolerance`` alone, for the true measures.
    npoints, nsimplex, ndim : int
        As scipy's.
    min_bound, max_bound : ndarray of double, shape (ndim,)
        As scipy's (computed when first asked for).
    coplanar : ndarray of int, shape (ncoplanar, 3)
        The points merging set aside (with Qi, also the interior points), each with its nearest facet and
        nearest vertex, as scipy's; empty for the exact hull.
    good : ndarray of bool or None
        With qhull_options QGn / QG-n, which facets point n sees (does not see), as scipy's; else None.
    tolerance, max_outside : float
        The absolute merge tolerance (0 when exact) and the proven bound on every input point's height above
        every facet's plane (0 when exact); NaN for Qhull's hulls (not reported).
    dimension : int
        The input's dimension.
    precision, backend : str
        What the hull was computed in and on: for the exact engines ``backend`` begins with "cpu" or "cuda"
        (and says the threads or the device, as "cpu (8 threads)"); it is "qhull" where scipy's Qhull
        computed the hull (4 or more dimensions).
    plan : str
        How the hull was run, in one line: the engine, backend and precision chosen, each with its reason
        (as the command line's ``--stats`` prints it).
    stats : dict or None
        The resident engine's counters, None for the others.

    Raises
    ------
    ValueError
        For no points (as scipy), NaN or infinite coordinates (``InputError``), masked arrays, and points of
        one dimension.
    QhullError
        A ``scipy.spatial.QhullError``: for fewer than ndim + 1 points, flat input (its lower-dimensional
        hull is ``cudahull.convex_hull()``'s answer) and unknown ``qhull_options``, with Qhull's code and
        words for the case.
    DeviceError
        A RuntimeError: for backend="cuda", or points in GPU memory, without a usable GPU.

    Examples
    --------
    >>> import numpy as np, cudahull
    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> hull = cudahull.ConvexHull(np.vstack([cube, [[0.5, 0.5, 0.5]]]), backend="cpu")
    >>> hull.vertices.tolist(), hull.volume, hull.nsimplex
    ([0, 1, 2, 3, 4, 5, 6, 7], 1.0, 12)
    """

    points: Any
    vertices: npt.NDArray[np.intc]
    simplices: npt.NDArray[np.intc]
    neighbors: npt.NDArray[np.intc]
    equations: npt.NDArray[np.float64]
    coplanar: npt.NDArray[np.intc]
    good: npt.NDArray[np.bool_] | None
    volume: float
    area: float
    npoints: int
    nsimplex: int
    ndim: int
    dimension: int
    precision: str
    backend: str
    plan: str
    tolerance: float
    max_outside: float
    stats: dict[str, Any] | None

    def __init__(self, points: npt.ArrayLike, incremental: bool = False, qhull_options: str | None = None, *,
                 tolerance: Tolerance = _DEFAULT, backend: str = "auto", precision: str = "auto",
                 engine: str = "auto", device_results: bool = False) -> None:
        self._closed = False
        self._bounds: tuple[Any, Any] | None = None
        self._scipy: Any = None
        self._protocol = cuda_protocol(points)
        if self._protocol is None:
            array = host_array(points)
            if array.ndim == 2 and array.shape[1] >= 4:
                self._init_qhull(array, incremental, qhull_options, tolerance, backend, precision, engine)
                return
        self._options = _qhull_options.parse(qhull_options, qhull_error) if qhull_options is not None else None
        if self._options is not None and not self._options.words:
            self._options = None  # "" asks for nothing, as None (scipy treats them alike)
        if tolerance is _DEFAULT:
            tolerance = self._options.merge("qhull") if self._options is not None else None
        if self._options is not None:
            self._options.check_dimension(int(np.shape(points)[1]) if len(np.shape(points)) == 2 else 3,
                                          qhull_error)
        self._tolerance_choice = tolerance
        self._kind = DeviceKind(points) if self._protocol else None
        self._engine_choice = check_engine(engine, self._protocol is not None)
        self._device_results = bool(device_results) and self._kind is not None
        if self._device_results and self._kind is not None:
            self._kind.require_known("device_results=True")
        self._backend_choice = backend
        self._precision_choice = precision
        if self._protocol:
            device_shape(points, self._protocol)
            taken: Any = points
        else:
            taken = as_points(array, (2, 3))
        self._commit(taken, self._compute(taken, None))

    # --- 4-D and higher: scipy's Qhull -------------------------------------------------------------------

    def _init_qhull(self, array: npt.NDArray[Any], incremental: bool, qhull_options: str | None,
                    tolerance: object, backend: str, precision: str, engine: str) -> None:
        _qhull.check_request(int(array.shape[1]), None if tolerance is _DEFAULT else tolerance, backend,
                             precision, engine)
        self._incremental = bool(incremental)
        self._qhull_options = qhull_options
        self._scipy = _qhull.scipy_hull(numeric(array), self._incremental, qhull_options)
        self._from_scipy()

    def _from_scipy(self) -> None:
        """scipy's attributes, copied (scipy's are views of its own state)."""
        hull = self._scipy
        for key in ("vertices", "simplices", "neighbors", "equations", "coplanar", "good", "points"):
            setattr(self, key, getattr(hull, key))
        self.volume, self.area = float(hull.volume), float(hull.area)
        self.npoints, self.nsimplex, self.ndim = int(hull.npoints), int(hull.nsimplex), int(hull.ndim)
        self._bounds = (hull.min_bound, hull.max_bound)
        self.dimension = self.ndim
        self.precision, self.backend, self.stats = "double", "qhull", None
        self.plan = _qhull.QHULL_PLAN
        self.tolerance = self.max_outside = math.nan

    # --- computing ------------------------------------------------------------------------------------

    @property
    def _good_point(self) -> int | None:
        return None if self._options is None else self._options.good_point

    def _compute(self, points: Any, subset: npt.NDArray[Any] | None) -> dict[str, Any]:
        """The hull of ``points[subset]`` (all of them for None; ``subset`` ascending, so the lowest index
        of duplicates stays it), less the QGn point, as the attributes' values: nothing is changed here,
        so a failure leaves the object as it was."""
        npoints = int(points.shape[0])
        ndim = int(points.shape[1])
        good = self._good_point
        if good is not None and not 0 <= good < npoints:
            raise qhull_error(f"qhull_options QG{good}: there is no point {good} among {npoints} points")
        if good is not None:
            subset = np.arange(npoints) if subset is None else np.asarray(subset)
            subset = subset[subset != good]
        if subset is None:
            chosen = points
        elif self._protocol and self._kind is not None:
            chosen = self._kind.take(points, subset)
        else:
            chosen = np.ascontiguousarray(points[subset])
        if npoints == 0:
            raise ValueError("No points given")  # scipy's words and type
        if int(chosen.shape[0]) <= ndim:
            raise too_few_points_error(int(chosen.shape[0]), ndim)
        options = self._options
        other_points = options is not None and (options.interior or options.coplanar)
        # QbB alone on 3-D host points (trimesh's every call): the module measures the scaled hull in the same
        # call, as the general path below does (the same bits); that path's array operations were most of a
        # small hull's time.
        box = options is not None and not other_points and good is None and self._kind is None and \
            ndim == 3 and list(options.scalings) == [("box",)]
        result = _hull_dict(chosen, self._protocol, self._kind, self._backend_choice, self._precision_choice,
                            self._engine_choice, self._tolerance_choice, box)
        if result["dimension"] == ndim and result["tolerance"] > 0:
            # A merged hull thinner than its tolerance in some facet's direction is flat at that
            # tolerance, as Qhull finds it (QH6154).  The 3-D module measures the thinnest direction itself
            # (exactly, where it is near the tolerance); 2-D hulls are measured here.
            thinnest = result.get("thinnest")
            if thinnest is None and len(result["vertices"]) <= 2000:
                corners = result["vertices"].astype(np.int64)
                hull_corners = np.asarray(self._host(self._kind.take(chosen, corners)) if self._kind is not None
                                          else chosen[corners], dtype=np.float64)
                equations = result["equations"]
                widths = -(hull_corners @ equations[:, :-1].T + equations[:, -1]).min(axis=0)
                thinnest = float(widths.min()) if widths.size else None
            if thinnest is not None and thinnest <= result["tolerance"]:
                raise qhull_error(f"QH6154 Qhull precision error: Initial simplex is flat (the merged hull is "
                                  f"{thinnest:.3g} thick, within its tolerance {result['tolerance']:.3g}: "
                                  f"flat at that tolerance; tolerance=None gives the exact hull)")
        if result["dimension"] < ndim and self._options is not None and self._options.joggle:
            # QJ on flat points: Qhull's answer, the hull of the points each moved by a tiny random amount
            # (its joggle), so that a client retrying with QJ (trimesh does) gets a thin full-dimensional hull.
            joggled = _joggled(np.asarray(self._host(chosen), dtype=np.float64))
            result = _hull_dict(joggled, None, None, self._backend_choice, self._precision_choice,
                                "auto", None)
        if result["dimension"] < ndim:
            low, high = (chosen.min(axis=0), chosen.max(axis=0)) if self._kind is None else self._kind.bounds(chosen)
            raise degenerate_error(self._host(low), self._host(high), int(result["dimension"]),
                                   self._options.scaled_axes(ndim) if self._options is not None else set())

        def original(indices: npt.ArrayLike) -> npt.NDArray[Any]:
            return index_array(indices if subset is None else np.asarray(subset)[np.asarray(indices)], npoints)

        values = {
            "dimension": ndim,
            "precision": result["precision"],
            "backend": result["backend"],
            "plan": result["plan"],
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
        # The exact hull's vertices, merged away or not, are what add_points computes on next: kept as the
        # two arrays they come from and joined only when add_points asks.
        values["exact_vertices"] = (values["vertices"], coplanar[:, 0].copy() if coplanar.size else None)
        scaled = options is not None and bool(options.scalings)
        # Qc, Qi, QG and Qhull's scaling look at the points themselves, on the host (one copy, in double).
        host: npt.NDArray[np.float64] | None = (np.ascontiguousarray(self._host(points), dtype=np.float64)
                                                if other_points or good is not None else None)
        if other_points and host is not None:
            coplanar = _with_other_points(options, host, values, coplanar, result["tolerance"])
        values["coplanar"] = index_array(coplanar.reshape(-1, 3), npoints)
        values["good"] = None
        if good is not None and host is not None:
            values["good"] = _good_facets(options, host, values, good)
        if "box_volume" in result:
            values["volume"], values["area"] = result["box_volume"], result["box_area"]
        elif options is not None and scaled:
            # Qhull's map comes from the points' bounds, which the exact hull's vertices attain (each axis'
            # extreme is a face of the hull, whose corners are vertices): only those points are read, not
            # all of them (docs/benchmarks.md, "The measurements behind the code's constants").
            extreme = np.unique(np.concatenate([values["vertices"], coplanar[:, 0]]))
            corners = (host[extreme] if host is not None else
                       np.asarray(self._host(self._kind.take(points, extreme)) if self._kind is not None
                                  else points[extreme], dtype=np.float64))
            scaling = options.scaling(corners)
            if scaling is not None:
                values["volume"], values["area"] = _scaled_measures(
                    corners, np.searchsorted(extreme, values["simplices"]), scaling, float(values["volume"]))
        return values

    def _host(self, points: Any) -> npt.NDArray[Any]:
        return self._kind.to_numpy(points) if self._kind is not None else np.asarray(points)

    def _commit(self, points: Any, values: dict[str, Any]) -> None:
        self.points = points
        self.npoints = int(points.shape[0])
        self.ndim = int(points.shape[1])
        self._bounds = None
        self.nsimplex = int(values["simplices"].shape[0])
        self._exact_vertices = values["exact_vertices"]
        for key in ("dimension", "precision", "backend", "plan", "stats", "tolerance", "max_outside", "volume",
                    "area", "good"):
            setattr(self, key, values[key])
        for key in ("vertices", "simplices", "neighbors", "equations", "coplanar"):
            setattr(self, key, self._result_array(values[key]))

    def _result_array(self, array: npt.NDArray[Any]) -> Any:
        return self._kind.like_input(array) if self._device_results and self._kind is not None else array

    def _compute_bounds(self) -> tuple[Any, Any]:
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
    def min_bound(self) -> npt.NDArray[np.float64]:
        """Per-axis minimum of the points (scipy's)."""
        if self._bounds is None:
            self._bounds = self._compute_bounds()
        return self._bounds[0]  # type: ignore[no-any-return]

    @property
    def max_bound(self) -> npt.NDArray[np.float64]:
        """Per-axis maximum of the points (scipy's)."""
        if self._bounds is None:
            self._bounds = self._compute_bounds()
        return self._bounds[1]  # type: ignore[no-any-return]

    def add_points(self, points: npt.ArrayLike, restart: bool = False) -> None:
        """Add points and update the hull: afterwards it is the hull of all the points.

        Parameters
        ----------
        points : (m, ndim) array_like
            The new points.  A hull of CuPy or PyTorch points in GPU memory takes new points of the same
            kind, joined on the device.
        restart : bool
            Compute on every point rather than on the old hull's vertices and the new points (the same
            answer: the hull of a union is the hull of its parts' vertices).

        Raises
        ------
        RuntimeError
            After ``close()``.
        ValueError
            For a bad coordinate, named by its row in the new points.  Atomic: a batch that is rejected
            changes nothing.
        """
        if self._closed:
            raise RuntimeError("the hull is closed: add_points is no longer possible")
        if self._scipy is not None:
            new = numeric(host_array(points))
            if new.ndim != 2 or new.shape[1] != self.ndim:
                raise ValueError(f"add_points takes (m, {self.ndim}) points, not an array of shape {new.shape}")
            self._scipy = _qhull.add_points(self._scipy, new, bool(restart), self._incremental, self._qhull_options)
            self._from_scipy()
            return
        old_count = self.npoints
        if self._protocol and self._kind is not None:
            joined = self._kind.concatenate(self.points, points)
        else:
            new = as_points(points, (self.ndim,))
            self._check_batch(new)
            joined = np.ascontiguousarray(np.concatenate([self.points, new]))
        subset: npt.NDArray[Any] | None = None
        if not restart:
            vertices, merged_away = self._exact_vertices
            exact = np.union1d(vertices, merged_away) if merged_away is not None else vertices
            subset = np.concatenate([np.asarray(exact, dtype=np.int64), np.arange(old_count, int(joined.shape[0]))])
            subset.sort()
            if self._good_point is not None:
                subset = np.unique(np.append(subset, self._good_point))
            if self._options is not None and (self._options.interior or self._options.coplanar):
                subset = None  # Qi and Qc look at every point
        self._commit(joined, self._compute(joined, subset))

    def _check_batch(self, new: npt.NDArray[Any]) -> None:
        """A new batch's coordinates checked alone, so that an error names its row in the batch (in float,
        a value beyond float's range too)."""
        lifted = new if new.shape[1] == 3 else np.column_stack([new, np.zeros(new.shape[0], dtype=new.dtype)])
        try:
            _cudahull.check_points(np.ascontiguousarray(lifted))
            if self.precision == "float" and new.dtype == np.float64:
                beyond = np.argwhere(np.abs(new) > np.finfo(np.float32).max)
                if beyond.size:
                    row, axis = beyond[0]
                    raise InputError(f"point {row}: {'xyz'[axis]} coordinate {number_text(new[row, axis])} does "
                                     f"not fit in float")
        except ValueError as error:
            raise type(error)(f"add_points: {error} (a row of the new points; nothing was added)") from None

    def close(self) -> None:
        """Finish: ``add_points`` raises afterwards (as in scipy); the attributes stay."""
        if self._scipy is not None and self._incremental:
            self._scipy.close()
        self._closed = True

    def __repr__(self) -> str:
        return (f"<cudahull.ConvexHull of {self.npoints} {self.ndim}-D points: {len(self.vertices)} vertices, "
                f"{self.nsimplex} simplices, backend={self.backend!r}>")
