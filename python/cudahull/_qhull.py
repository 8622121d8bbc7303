"""Hulls of 4 or more dimensions: scipy's ConvexHull (Qhull) computes them, as a drop-in's caller expects.

cudahull's exact engines are 2-D and 3-D; for d >= 4 ``ConvexHull`` and ``convex_hull()`` hand the points
to ``scipy.spatial.ConvexHull`` unchanged and report its answer with ``backend == "qhull"``.  scipy is
imported only here, when such points come.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from ._errors import qhull_error, value_text

QHULL_PLAN = "scipy's Qhull (4 or more dimensions: the exact engines are 2-D and 3-D)"


def check_request(ndim: int, tolerance: object, backend: str, precision: str, engine: str) -> None:
    """Refuses what Qhull cannot do for d-dimensional points, rather than silently doing something else."""
    what = f"{ndim}-D points are hulled by scipy's Qhull, on the CPU in double"
    if backend not in ("auto", "cpu"):
        raise ValueError(f"{what}: backend must be 'auto' or 'cpu', not {backend!r} (the GPU engines are 2-D and 3-D)")
    if precision not in ("auto", "double"):
        raise ValueError(f"{what}: precision must be 'auto' or 'double', not {precision!r}")
    if engine != "auto":
        raise ValueError(f"{what}: engine must be 'auto', not {engine!r} (the engines are 2-D and 3-D)")
    if tolerance is not None and tolerance != "qhull":
        raise ValueError(f"{what}, which merges facets with its own roundoff tolerance: tolerance must be None or "
                         f"'qhull', not {value_text(tolerance)}")


def _scipy_convex_hull() -> Any:
    """scipy's own ConvexHull class, also where a caller has put cudahull's in its place (trimesh's tests
    swap ``scipy.spatial.ConvexHull``): asking for it by name would then call cudahull again, for ever."""
    from scipy.spatial import _qhull  # type: ignore[import-untyped, unused-ignore]

    named = getattr(_qhull, "ConvexHull", None)
    if named is not None and str(getattr(named, "__module__", "")).startswith("scipy."):
        return named
    for candidate in _qhull._QhullUser.__subclasses__():
        if candidate.__name__ == "ConvexHull" and candidate.__module__.startswith("scipy."):
            return candidate
    raise ImportError("scipy.spatial's ConvexHull class was not found")


def scipy_hull(points: npt.NDArray[Any], incremental: bool, qhull_options: str | None) -> Any:
    """``scipy.spatial.ConvexHull(points, incremental, qhull_options)``; its QhullError raised as ours (a
    subclass of scipy's), so that code catching ``cudahull.QhullError`` catches it too."""
    try:
        from scipy.spatial import QhullError as ScipyQhullError  # type: ignore[import-untyped, unused-ignore]

        ScipyConvexHull = _scipy_convex_hull()
    except ImportError:
        raise ValueError(f"points are {points.shape[1]}-dimensional: cudahull's engines compute 2-D and 3-D "
                         f"hulls, and higher dimensions go through scipy's Qhull, which is not installed "
                         f"(pip install scipy)") from None
    try:
        return ScipyConvexHull(points, incremental, qhull_options)
    except ScipyQhullError as error:
        raise qhull_error(str(error)) from error


def add_points(hull: Any, points: npt.NDArray[Any], restart: bool, incremental: bool,
               qhull_options: str | None) -> Any:
    """The scipy hull of ``hull``'s points and ``points``: Qhull's own add_points for an incremental hull,
    else a new hull of them all (cudahull's add_points works either way)."""
    if incremental:
        try:
            from scipy.spatial import QhullError as ScipyQhullError  # type: ignore[import-untyped, unused-ignore]

            hull.add_points(points, restart)
        except ScipyQhullError as error:
            raise qhull_error(str(error)) from error
        return hull
    return scipy_hull(np.concatenate([hull.points, points]), False, qhull_options)


def hull_dict(points: npt.NDArray[Any]) -> dict[str, Any]:
    """``convex_hull()``'s dict of (n, d >= 4) points, from scipy's hull (indices uint32, as the engines')."""
    hull = scipy_hull(points, False, None)
    ndim = int(points.shape[1])

    def indices(array: Any, width: int) -> npt.NDArray[np.uint32]:
        return np.asarray(array, dtype=np.uint32).reshape(-1, width)

    return {
        "dimension": ndim,
        "input_dimension": ndim,
        "precision": "double",
        "backend": "qhull",
        "vertices": indices(hull.vertices, 1).ravel(),
        "simplices": indices(hull.simplices, ndim),
        "neighbors": indices(hull.neighbors, ndim),
        "equations": np.asarray(hull.equations, dtype=np.float64),
        "polygon": np.zeros(0, dtype=np.uint32),
        "coplanar": indices(hull.coplanar, 3),
        "volume": float(hull.volume),
        "area": float(hull.area),
        "tolerance": float("nan"),
        "max_outside": float("nan"),
        "stats": None,
        "plan": QHULL_PLAN,
    }
