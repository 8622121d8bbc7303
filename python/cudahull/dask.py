"""The hull of a Dask array of points: each chunk's hull on its worker (on its GPU with backend "auto" where
the worker has one), then the hull of the chunk hulls' vertices.

It is exact: the hull of a union is the hull of its parts' hull vertices, and a point that is not a vertex
of its chunk's hull is not one of the whole.  The candidates go in ascending input order, so that among
duplicate points the lowest index stays the vertex, as in a one-shot hull.
"""

from __future__ import annotations

from typing import Any

import re

import dask  # type: ignore[import-untyped, unused-ignore]
import dask.array  # type: ignore[import-untyped, unused-ignore]
import numpy as np
import numpy.typing as npt

from . import _cudahull
from ._arrays import as_points
from ._errors import InputError

__all__ = ["convex_hull"]

_delayed: Any = dask.delayed  # type: ignore[attr-defined, unused-ignore]


def _chunk_vertices(block: Any, offset: int, backend: str, precision: str,
                    engine: str) -> tuple[npt.NDArray[np.int64], npt.NDArray[Any]]:
    """One chunk's hull vertices: their indices in the whole array and their coordinates."""
    points = as_points(block)
    try:
        vertices = _cudahull.convex_hull(points, backend, precision, engine, "exact", 0.0, 1.0)["vertices"]
    except InputError as error:
        raise _in_whole_array(error, offset) from None
    return vertices.astype(np.int64) + offset, points[vertices]


def _in_whole_array(error: InputError, offset: int) -> InputError:
    """A chunk's error for a bad point ("point 177: ..."), naming the point by its row in the whole array."""
    message = str(error)
    found = re.match(r"point (\d+): ", message)
    if found is None:
        return error
    row = offset + int(found.group(1))
    return InputError(f"point {row}: {message[found.end():]} (row {found.group(1)} of the chunk that starts at "
                      f"row {offset})")


def _hull_of_candidates(parts: list[tuple[npt.NDArray[np.int64], npt.NDArray[Any]]], backend: str, precision: str,
                        engine: str) -> dict[str, Any]:
    indices = np.concatenate([part[0] for part in parts])
    points = np.ascontiguousarray(np.concatenate([part[1] for part in parts]))
    result = _cudahull.convex_hull(points, backend, precision, engine, "exact", 0.0, 1.0)
    for key in ("vertices", "simplices", "polygon"):
        result[key] = indices[result[key].astype(np.int64)]
    result["vertex_points"] = points[np.searchsorted(indices, result["vertices"])]
    result["candidates"] = len(indices)
    return result


def convex_hull(array: Any, backend: str = "auto", precision: str = "auto", engine: str = "stepping") -> dict[str, Any]:
    """The exact hull of an (n, 3) Dask array, computed with the current Dask scheduler.

    Parameters
    ----------
    array : dask.array.Array or array_like, shape (n, 3)
        The points, in chunks of whole points (rechunked along the columns if need be).
    backend, precision, engine : str
        As for ``cudahull.convex_hull``, on each worker (a ``distributed.Client`` when one is active).

    Returns
    -------
    dict
        As ``cudahull.convex_hull`` gives it, with indices into the whole array (int64), plus
        ``vertex_points`` (the vertices' coordinates, in the order of ``vertices``) and ``candidates`` (how
        many chunk-hull vertices the last hull was computed on).
    """
    array = dask.array.asarray(array)  # type: ignore[no-untyped-call, unused-ignore]
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"points must be an (n, 3) array of 3-D points, not one of shape {array.shape}")
    if array.numblocks[1] != 1:
        array = array.rechunk({1: 3})  # each chunk holds whole points
    offsets = np.concatenate([[0], np.cumsum(array.chunks[0])[:-1]]).astype(np.int64)
    parts = [
        _delayed(_chunk_vertices)(block, int(offset), backend, precision, engine)
        for block, offset in zip(array.to_delayed()[:, 0], offsets)
    ]
    result: dict[str, Any] = _delayed(_hull_of_candidates)(parts, backend, precision, engine).compute()
    return result
