"""The stepping engine, one iteration at a time (for notebooks and teaching)."""

from __future__ import annotations

from typing import Any

import numpy.typing as npt

from . import _cudahull
from ._arrays import as_points

__all__ = ["Engine"]


class Engine:
    """Algorithm 1 of CudaHull one iteration at a time, for notebooks.

    Parameters
    ----------
    points : (n, 3) array_like
        Host points (NumPy or anything it converts); float32 is computed in float, anything else in double.
    backend : {"auto", "cpu", "cuda"}
        Where the iterations' parallel phases run.
    precision : {"auto", "float", "double"}
        As for ``cudahull.convex_hull``.

    Attributes
    ----------
    points : ndarray, shape (n, 3)
        The points, as taken (C-contiguous float32 or float64).

    Notes
    -----
    ``step()`` returns what the iteration did: counts (``faces_after``, ``external_after``, ...), the refined
    faces and their apexes (Fig. 3a), the swaps tried with their kinds (``swap_kind`` indexes
    ``cudahull.SWAP_KINDS``; Figs. 3b, 4, 5), the removed degree-3 vertices (Fig. 4) and the decision array
    (Fig. 7), as NumPy arrays.  ``mesh()`` gives the current mesh, ``result()`` the exact hull once ``done``.

    Examples
    --------
    >>> import numpy as np, cudahull
    >>> engine = cudahull.Engine(np.random.default_rng(0).normal(size=(100, 3)), backend="cpu")
    >>> records = engine.run()
    >>> engine.done, engine.result()["dimension"]
    (True, 3)
    """

    def __init__(self, points: npt.ArrayLike, backend: str = "auto", precision: str = "auto") -> None:
        # The stepping engine edits the mesh on the host, so points in GPU memory are refused here.
        self.points = as_points(points)
        self._engine = _cudahull.Engine(self.points, backend, precision)

    @property
    def done(self) -> bool:
        """Whether the hull is complete."""
        return bool(self._engine.done)

    @property
    def dimension(self) -> int:
        """The input's affine dimension, known after the first step."""
        return int(self._engine.dimension)

    @property
    def precision(self) -> str:
        """"float" or "double": what the engine computes in."""
        return str(self._engine.precision)

    @property
    def backend(self) -> str:
        """"cpu" or "cuda": where the engine runs."""
        return str(self._engine.backend)

    def step(self) -> dict[str, Any]:
        """Runs one iteration.

        Returns
        -------
        dict
            The iteration's record: its counts and the arrays of what it did.

        Raises
        ------
        RuntimeError
            When the hull is already done.
        """
        return self._engine.step()

    def run(self) -> list[dict[str, Any]]:
        """Steps until done.

        Returns
        -------
        list of dict
            Every step's record, in order.
        """
        records = []
        while not self.done:
            records.append(self.step())
        return records

    def restart(self) -> None:
        """Starts again from the first iteration."""
        self._engine.restart()

    def mesh(self) -> dict[str, Any]:
        """The current mesh.

        Returns
        -------
        dict
            ``faces`` (input indices, counter-clockwise from outside), ``neighbors`` (the k-th opposite the
            k-th corner) and ``vertices``.
        """
        return self._engine.mesh()

    def result(self) -> dict[str, Any]:
        """The exact hull, as ``cudahull.convex_hull`` gives it.

        Returns
        -------
        dict
            The hull's dict.

        Raises
        ------
        RuntimeError
            Before the hull is done.
        """
        return self._engine.result()
