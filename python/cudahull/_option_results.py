"""What qhull_options add to a ``ConvexHull``'s attributes beyond the hull itself: QGn's good facets, Qc's
and Qi's other points, QJ's joggle of flat input, and the measures of the points as Qbb, QbB, Qbk:n and
QBk:n scale them."""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
import numpy.typing as npt

from . import _cudahull
from .qhull_options import ParsedOptions


def _good_facets(options: ParsedOptions | None, host: npt.NDArray[np.float64], values: dict[str, Any],
                 good: int) -> npt.NDArray[np.bool_]:
    """QGn: the facets point n sees (strictly above their planes, decided exactly); QG-n: the others."""
    visible: npt.NDArray[np.bool_] = np.asarray(_cudahull.facets_visible(host, np.ascontiguousarray(values["simplices"], dtype=np.int64),
                                       host[good].copy()), dtype=bool)
    assert options is not None
    return np.asarray(visible if options.good_visible else ~visible, dtype=bool)


def _with_other_points(options: ParsedOptions | None, host: npt.NDArray[np.float64], values: dict[str, Any],
                       coplanar: npt.NDArray[np.int64], tolerance: float) -> npt.NDArray[np.int64]:
    """Qc: also every point that is neither a vertex nor already listed but lies within the tolerance of
    a facet (within rounding, 8 units in the last place of the largest coordinate, for the exact hull),
    as scipy's coplanar points; Qi: every other point too (the interior ones).  Each with its nearest
    facet (the one it is least below) and that facet's nearest vertex.  O(n x facets), on the host."""
    assert options is not None
    listed = np.zeros(host.shape[0], dtype=bool)
    listed[values["vertices"]] = True
    listed[coplanar[:, 0]] = True
    if options.good_point is not None:
        listed[options.good_point] = True
    rest = np.flatnonzero(~listed)
    within = max(tolerance, 8 * float(np.finfo(np.float64).eps) * float(np.abs(host).max(initial=0.0)))
    equations, simplices = values["equations"], values["simplices"]
    rows = [coplanar]
    for begin in range(0, rest.size, 4096):
        chunk = rest[begin:begin + 4096]
        heights = host[chunk] @ equations[:, :-1].T + equations[:, -1]
        facet = np.argmax(heights, axis=1)
        if not options.interior:
            near = heights[np.arange(chunk.size), facet] >= -within
            chunk, facet = chunk[near], facet[near]
        corners = simplices[facet]
        distance = np.linalg.norm(host[corners] - host[chunk][:, None, :], axis=2)
        vertex = corners[np.arange(chunk.size), np.argmin(distance, axis=1)]
        rows.append(np.column_stack([chunk, facet, vertex]))
    return np.concatenate(rows).astype(np.int64)


def _joggled(points: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """The points moved as Qhull's QJ moves them: each coordinate by a uniform random amount within
    30,000 times Qhull's distance roundoff (qh_detjoggle), from a fixed seed, so the result repeats."""
    epsilon = float(np.finfo(np.float64).eps)
    magnitudes = np.abs(points)
    largest = float(magnitudes.max(initial=0.0))
    largest_sum = float(magnitudes.sum(axis=1).max(initial=0.0))
    roundoff = epsilon * (points.shape[1] * largest_sum * 1.01 + largest)
    joggle = 30000.0 * max(roundoff, epsilon)
    return points + np.random.default_rng(1).uniform(-joggle, joggle, size=points.shape)


def _scaled_measures(host: npt.NDArray[np.float64], simplices: npt.NDArray[Any],
                     scaling: tuple[Sequence[float], Sequence[float]], volume: float) -> tuple[float, float]:
    """The volume and area Qhull reports under QbB / Qbb / Qbk:n / QBk:n: those of the points mapped by
    x -> x * scale + shift per axis.  The volume is the true one times the map's determinant; the area
    (perimeter in 2-D) is summed over the simplices in the scaled coordinates."""
    scale = np.asarray(scaling[0])
    if host.shape[1] == 2:
        # Edges of the scaled simplices: the map's shift cancels, so only the hull's edges are scaled.
        corners = host[simplices]
        edges = (corners[:, 1:] - corners[:, :1]) * scale
        area = float(np.sqrt(np.einsum("ij,ij->i", edges[:, 0], edges[:, 0])).sum())
    else:
        # The module's sum, which the hull call's QbB shortcut also takes: the same bits either way.
        area = float(_cudahull.scaled_area(np.ascontiguousarray(host, dtype=np.float64),
                                           np.ascontiguousarray(simplices, dtype=np.int64),
                                           [float(v) for v in scale]))
    return volume * float(np.prod(np.abs(scale))), area
