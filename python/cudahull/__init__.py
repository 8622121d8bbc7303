"""Exact 2-D and 3-D convex hulls with the CudaHull algorithm (Stein, Geva, El-Sana 2012).

``ConvexHull``
    A drop-in for ``scipy.spatial.ConvexHull``: the same arguments (``qhull_options`` included),
    attributes, methods and errors (``QhullError``).  Points of 4 or more dimensions go to scipy's Qhull.
``convex_hull``
    The hull as a dict, with the lower-dimensional answer for flat input.
``convex_hull_batch``
    The hulls of many clouds in one call (a list of arrays, packed or padded), as ``BatchHulls``.
``Engine``
    Steps the algorithm one iteration at a time (for notebooks).
``release_device_memory``
    Hands the GPU memory kept between calls back to the driver.
``QhullError``, ``InputError``, ``DeviceError``
    The errors: scipy's (a subclass of ``scipy.spatial.QhullError``), bad points (a ``ValueError``), no
    usable GPU (a ``RuntimeError``).
``SWAP_KINDS``
    The names of the edge swaps an ``Engine`` step records (its ``swap_kind`` indexes them).

Points already on the GPU (a CuPy array, a PyTorch CUDA tensor, anything with ``__dlpack__`` or
``__cuda_array_interface__`` in CUDA memory) are read in place: no host copy of them is made, and the
results come back as NumPy arrays, or, with ``device_results=True``, as arrays of the input's kind.
"""

from typing import TYPE_CHECKING

from . import _errors
from ._batch import BatchHulls, convex_hull_batch, release_device_memory
from ._cudahull import SWAP_KINDS
from ._engine import Engine
from ._errors import DeviceError, InputError
from ._hull import ConvexHull, convex_hull

if TYPE_CHECKING:
    from ._errors import QhullError

__all__ = ["BatchHulls", "ConvexHull", "DeviceError", "Engine", "InputError", "QhullError", "SWAP_KINDS",
           "convex_hull", "convex_hull_batch", "release_device_memory"]


def __getattr__(name: str) -> object:
    # QhullError is built on first use: its base class, scipy's, costs the import of scipy.spatial.
    if name == "QhullError":
        return _errors.qhull_error_class()
    raise AttributeError(f"module 'cudahull' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) - {"TYPE_CHECKING"} | {"QhullError"})


del TYPE_CHECKING
