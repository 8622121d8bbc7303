"""The hulls of many clouds in one call: ``convex_hull_batch`` and its result, ``BatchHulls``."""

from __future__ import annotations

import re
from typing import Any, Callable, Sequence

import numpy as np
import numpy.typing as npt

from . import _cudahull
from ._arrays import DeviceKind, checked_interface, cuda_protocol, host_integers, library_of, numeric, require_device
from ._errors import value_text
from ._hull_call import check_engine

__all__ = ["BatchHulls", "convex_hull_batch", "release_device_memory"]

_BATCH_ARRAYS = ("vertex_offsets", "face_offsets", "vertices", "faces", "planes", "volumes", "areas", "dimensions",
                 "polygon_offsets", "polygons")


class BatchHulls:
    """The hulls of B point clouds, packed, as ``convex_hull_batch`` returns them.

    Cloud ``c``'s vertices are ``vertices[vertex_offsets[c]:vertex_offsets[c + 1]]`` and its faces
    ``faces[face_offsets[c]:face_offsets[c + 1]]``; ``cloud(c)`` gives them as a dict.  Arrays are of the
    input's library: NumPy, or CuPy arrays and PyTorch tensors on the input's device.

    Attributes
    ----------
    vertex_offsets, face_offsets, polygon_offsets : array of int64, shape (B + 1,)
        Where each cloud's vertices, faces and polygon corners begin and end.
    vertices : array of ints, shape (nvertices,)
        Each cloud's hull vertices, ascending, counted from the cloud's first point (for padded input, the
        row in the cloud's slab).  int32 (int64 beyond 2**31 points in a cloud, and for PyTorch).
    faces : array of ints, shape (nfaces, 3)
        Outward triangles, counter-clockwise seen from outside.
    planes : array of floats, shape (nfaces, 4)
        Each face's unit outward normal and offset: n . x + d <= 0 inside.
    volumes, areas : array of floats, shape (B,)
        Each cloud's volume and area (a flat cloud: volume 0, area both sides of its polygon).
    dimensions : array of ints, shape (B,)
        Each hull's affine dimension: 3; 2, 1, 0 for a flat cloud, as ``convex_hull()`` answers; -1 for an
        empty cloud.
    polygons : array of ints, shape (npolygon,)
        A flat cloud's polygon corners in order.
    precision, backend : str
        What the hulls were computed in and on.
    report : dict
        What the GPU did: the clouds its batch kernel hulled (``clouds_batched``), its launches, the most
        device memory the call held (``device_bytes_peak``, the points included) and milliseconds
        (``device_ms``, ``kernel_ms``, ``describe_ms``).
    """

    __slots__ = _BATCH_ARRAYS + ("precision", "backend", "report")

    vertex_offsets: Any
    face_offsets: Any
    vertices: Any
    faces: Any
    planes: Any
    volumes: Any
    areas: Any
    dimensions: Any
    polygon_offsets: Any
    polygons: Any
    precision: str
    backend: str
    report: dict[str, Any]

    def __len__(self) -> int:
        return int(self.volumes.shape[0])

    def cloud(self, c: int) -> dict[str, Any]:
        """Cloud ``c``'s hull.

        Parameters
        ----------
        c : int
            The cloud's index (negative counts from the end).

        Returns
        -------
        dict
            ``vertices``, ``faces``, ``planes``, ``polygon`` (arrays), ``volume``, ``area`` (floats) and
            ``dimension`` (int).

        Raises
        ------
        IndexError
            For ``c`` outside the batch.
        """
        if not -len(self) <= c < len(self):
            raise IndexError(f"cloud {c} of {len(self)}")
        c %= len(self)
        v = slice(int(self.vertex_offsets[c]), int(self.vertex_offsets[c + 1]))
        f = slice(int(self.face_offsets[c]), int(self.face_offsets[c + 1]))
        p = slice(int(self.polygon_offsets[c]), int(self.polygon_offsets[c + 1]))
        return {"vertices": self.vertices[v], "faces": self.faces[f], "planes": self.planes[f],
                "polygon": self.polygons[p], "volume": float(self.volumes[c]), "area": float(self.areas[c]),
                "dimension": int(self.dimensions[c])}

    def __repr__(self) -> str:
        return (f"BatchHulls({len(self)} clouds, {int(self.vertices.shape[0])} vertices, "
                f"{int(self.faces.shape[0])} faces, precision={self.precision!r}, backend={self.backend!r})")


def _batch_layout(shape: Sequence[int], offsets: object,
                  lengths: object) -> tuple[bool, npt.NDArray[np.int64], npt.NDArray[np.int64] | None, int]:
    """(padded, offsets as int64, lengths as int64 or None, the largest cloud) for points of ``shape``: a packed
    (N, 3) array with B + 1 offsets, or a padded (B, M, 3) array with B lengths (None: every cloud M points,
    which then needs no packing)."""
    if len(shape) == 2 and shape[1] == 3:
        if lengths is not None:
            raise ValueError("lengths go with padded (B, M, 3) points; packed (N, 3) points take offsets")
        if offsets is None:
            raise ValueError("packed (N, 3) points need offsets: the B + 1 cloud boundaries, from 0 to N")
        bounds = host_integers(offsets, "offsets")
        return False, bounds, None, int(np.diff(bounds).max(initial=0))
    if len(shape) == 3 and shape[2] == 3:
        if offsets is not None:
            raise ValueError("offsets go with packed (N, 3) points; padded (B, M, 3) points take lengths")
        clouds, slab = int(shape[0]), int(shape[1])
        if lengths is not None:
            sizes = host_integers(lengths, "lengths")
            if sizes.shape[0] != clouds:
                raise ValueError(f"lengths must hold one length a cloud: {clouds}, not {sizes.shape[0]}")
            if sizes.size and (sizes.min() < 0 or sizes.max() > slab):
                bad = int(np.flatnonzero((sizes < 0) | (sizes > slab))[0])
                raise ValueError(f"lengths[{bad}] is {int(sizes[bad])}: a cloud holds 0 to {slab} points here")
            if not np.all(sizes == slab):
                bounds = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
                return True, bounds, sizes, int(sizes.max(initial=0))
        # Every cloud fills its slab: the offsets are multiples of M, and the points need no packing (no
        # lengths, sums and checks per cloud: docs/benchmarks.md, "The measurements behind the code's
        # constants").
        return True, np.arange(clouds + 1, dtype=np.int64) * slab, None, slab
    raise ValueError(f"points must be a packed (N, 3) array with offsets, a padded (B, M, 3) array with "
                     f"lengths, or a list of (n, 3) arrays, not one of shape {tuple(shape)}")


def _batch_result(raw: dict[str, Any], offsets: npt.NDArray[np.int64], kind: DeviceKind | None = None) -> BatchHulls:
    """The module's batch dict as a BatchHulls.  Its arrays are NumPy (from the host), or, for points in GPU
    memory, already the input's CuPy arrays or PyTorch tensors, sharing the result's device memory."""
    hulls = BatchHulls()
    on_host = isinstance(raw["volumes"], np.ndarray)
    if on_host:
        # The module's indices are uint32: read in place as int32 where every cloud is shorter than 2^31 points
        # (each index is below its cloud's length, so the bits are the same values), a copy spared (a large
        # batch's faces are some 100 MB); else widened.
        longest = int(np.diff(offsets).max(initial=0))
        index = np.int32 if longest < 2**31 else np.int64
        for key in ("vertices", "polygons", "faces"):
            same_bits = index is np.int32 and raw[key].dtype == np.uint32
            raw[key] = raw[key].view(np.int32) if same_bits else raw[key].astype(index)
        raw["faces"] = raw["faces"].reshape(-1, 3)
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


def _batch_call(strip_rows: bool, function: Callable[..., dict[str, Any]], *arguments: Any) -> dict[str, Any]:
    """The module's batch function; for padded input or a list of clouds an error names the cloud and the
    point without the row of the packed copy, which the caller never saw."""
    try:
        return function(*arguments)
    except ValueError as error:
        if not strip_rows:
            raise
        raise type(error)(re.sub(r" \(row \d+ of the packed points\)", "", str(error))) from None


def release_device_memory() -> None:
    """Hands the GPU memory cudahull keeps between calls back to the driver.

    As ``torch.cuda.empty_cache()`` does PyTorch's, on the current CUDA device.  cudahull keeps at least
    256 MiB, and a batch the memory it used (up to a sixteenth of the device's) for the next batch of its
    size, which then maps none again; call this when PyTorch or CuPy needs that memory.  Results stay valid.
    Without a usable GPU, or before cudahull used it, it does nothing.
    """
    _cudahull.release_device_memory()


def _is_cloud_list(points: object) -> bool:
    """A list or tuple (or any other sequence that is not an array) of clouds, rather than one array."""
    if isinstance(points, (list, tuple)):
        return True
    return (isinstance(points, Sequence) and not isinstance(points, (str, bytes))
            and not hasattr(points, "__array__") and cuda_protocol(points) is None)


def _pack_clouds(clouds: Sequence[Any]) -> tuple[Any, npt.NDArray[np.int64]]:
    """A sequence of (n, 3) clouds as one packed array and its B + 1 offsets: NumPy (NumPy's type
    promotion: any float64 cloud makes all float64, exactly), or, where every cloud is a CuPy array or a
    PyTorch tensor of one library, that library's array, joined by its own concatenate (on the device)."""
    clouds = list(clouds)
    libraries = {library_of(cloud) for cloud in clouds}
    on_device = [cuda_protocol(cloud) is not None for cloud in clouds]
    if any(on_device) or libraries == {"torch"}:  # PyTorch tensors on the CPU: tensors back, as for one
        if any(on_device) and (not all(on_device) or len(libraries) != 1):
            raise ValueError("a list of clouds in GPU memory must all be arrays of one library (CuPy arrays or "
                             "PyTorch tensors) in GPU memory")
        kind = DeviceKind(clouds[0])
        for c, cloud in enumerate(clouds):
            shape = tuple(cloud.shape)
            if len(shape) != 2 or shape[1] != 3:
                raise ValueError(f"cloud {c} must be an (n, 3) array, not one of shape {shape}")
        sizes = [int(cloud.shape[0]) for cloud in clouds]
        joined = kind.join([cloud.detach() if kind.library == "torch" else cloud for cloud in clouds])
        return joined, np.concatenate([[0], np.cumsum(sizes, dtype=np.int64)]).astype(np.int64)
    arrays = []
    for c, cloud in enumerate(clouds):
        if isinstance(cloud, np.ma.MaskedArray):
            raise ValueError(f"cloud {c} is a masked array: pass the points to keep")
        if library_of(cloud) == "torch":
            cloud = cloud.detach()
        array = np.asarray(cloud)
        if array.ndim != 2 or array.shape[1] != 3:
            hint = " (one packed (N, 3) array of points takes offsets)" if array.ndim < 2 else ""
            raise ValueError(f"cloud {c} must be an (n, 3) array, not one of shape {array.shape}{hint}")
        arrays.append(array)
    sizes = [int(array.shape[0]) for array in arrays]
    offsets = np.concatenate([[0], np.cumsum(sizes, dtype=np.int64)]).astype(np.int64)
    if not arrays:
        return np.empty((0, 3)), offsets
    return np.concatenate(arrays), offsets


def convex_hull_batch(points: Any, offsets: npt.ArrayLike | None = None, lengths: npt.ArrayLike | None = None, *,
                      backend: str = "auto", precision: str = "auto", engine: str = "auto",
                      threads: int = 0) -> BatchHulls:
    """The exact hulls of B point clouds in one call.

    Each cloud's hull is ``convex_hull()``'s on that cloud alone: the same vertex set, faces, planes and
    measures, and the lower-dimensional answer for a flat cloud.

    Parameters
    ----------
    points : list of (n, 3) arrays, (N, 3) array with ``offsets``, or (B, M, 3) array with ``lengths``
        The clouds: a list (or any sequence) of (n, 3) arrays, one a cloud; or a packed (N, 3) array with
        ``offsets``; or a padded (B, M, 3) array with ``lengths``.  NumPy (float32 computed in float,
        float64 and integers in double), or CuPy arrays or PyTorch tensors in GPU memory (float32 or
        float64, read there: no host copy of the points; a list of them is joined with that library's
        concatenate, on the device).
    offsets : (B + 1,) array_like of ints, optional
        For packed points: 0, each cloud's end, the last N.
    lengths : (B,) array_like of ints, optional
        For padded points: each cloud's size, at most M (None: M each).
    backend, precision, engine : str
        As for ``convex_hull``.
    threads : int
        CPU clouds hulled at once (0: every core); the result is the same for any.

    Returns
    -------
    BatchHulls
        The hulls, packed; ``cloud(c)`` gives cloud ``c``'s.

    Raises
    ------
    ValueError
        For a NaN or infinite coordinate (naming the cloud, the point in it and, for packed input, its row),
        and for bad shapes, offsets or lengths.
    DeviceError
        As ``convex_hull``.

    Notes
    -----
    On the CPU the clouds run on all cores.  With a GPU one launch hulls every cloud of 4 to 131,072 points, a
    block a cloud (the same vertex sets and faces as ``convex_hull()``, the faces in another order; clouds of
    more than 16,384 points on larger blocks, in a launch of their own); flat, tiny and larger clouds take the
    single-cloud GPU path.  The hulls are described on the GPU, and for CuPy and PyTorch input the result's
    arrays are the GPU's own (the kernel's hulls never cross to the host).

    Examples
    --------
    >>> import numpy as np, cudahull
    >>> rng = np.random.default_rng(0)
    >>> clouds = [rng.normal(size=(n, 3)) for n in (8, 20, 40)]
    >>> hulls = cudahull.convex_hull_batch(clouds, backend="cpu")
    >>> len(hulls), hulls.dimensions.tolist()
    (3, [3, 3, 3])
    """
    if isinstance(threads, (bool, np.bool_)) or not isinstance(threads, (int, np.integer)) or threads < 0:
        raise ValueError(f"threads must be a whole number of CPU clouds at once, 0 for every core, not "
                         f"{value_text(threads)}")
    from_list = offsets is None and lengths is None and _is_cloud_list(points)
    if from_list:
        points, offsets = _pack_clouds(points)
    protocol = cuda_protocol(points)
    if protocol is None:
        return _host_batch(points, offsets, lengths, from_list, backend, precision, engine, int(threads))

    # Points in GPU memory.  Offsets (or lengths) are read to the host, padded clouds are packed on the
    # device (a device copy), and the batch runs there (convex_hull_batch_device in C++).
    if backend == "cpu":
        raise ValueError("points in GPU memory need backend 'auto' or 'cuda', not 'cpu' (for the CPU backend, "
                         "pass them as NumPy: cupy.asnumpy(x), x.cpu().numpy())")
    check_engine(engine, True)
    kind = DeviceKind(points)
    library = kind.library if kind.known else "numpy"  # the result's arrays: the input's, on its device
    interface = points.__cuda_array_interface__ if protocol == "cuda_array_interface" else None
    shape = tuple(interface["shape"] if interface is not None else points.shape)
    padded, bounds, sizes, largest = _batch_layout(shape, offsets, lengths)
    if largest >= 2**31:
        library = "numpy"  # the device's result holds int32 indices: this one comes back, as int64, and goes up
    require_device()
    if padded:
        points = kind.pack_padded(points, sizes)
        protocol = cuda_protocol(points)
        interface = points.__cuda_array_interface__ if protocol == "cuda_array_interface" else None
        shape = tuple(interface["shape"] if interface is not None else points.shape)
    if protocol == "cuda_array_interface":
        pointer, is_double = checked_interface(points, shape)
        raw = _batch_call(padded or from_list, _cudahull.convex_hull_batch_cuda_pointer, pointer, shape[0],
                          is_double, bounds, backend, precision, library)
    else:
        if getattr(points, "requires_grad", False):
            points = points.detach()  # PyTorch exports no tensor that requires grad; the hulls read values only
        raw = _batch_call(padded or from_list, _cudahull.convex_hull_batch_cuda, points, bounds, backend, precision,
                          library)
    return _batch_result(raw, bounds, kind)


def _host_batch(points: Any, offsets: Any, lengths: Any, from_list: bool, backend: str, precision: str,
                engine: str, threads: int) -> BatchHulls:
    """The batch of host points (NumPy, or anything it converts; a PyTorch CPU tensor gets tensors back)."""
    if isinstance(points, np.ma.MaskedArray):
        raise ValueError("masked arrays are not supported: pass the points to keep, packed, with offsets")
    # A PyTorch tensor on the CPU gets tensors back (NumPy's memory, shared: no copy).
    kind = DeviceKind(points) if library_of(points) == "torch" else None
    if kind is not None:
        points = points.detach()
    array = np.asarray(points)
    padded, bounds, sizes, _ = _batch_layout(array.shape, offsets, lengths)
    array = numeric(array)
    if padded:
        if sizes is None:  # every cloud fills its slab
            array = array.reshape(-1, 3)
        else:
            slab = array.shape[1]
            array = array[np.arange(slab)[None, :] < sizes[:, None]]  # packed, in cloud order
    raw = _batch_call(padded or from_list, _cudahull.convex_hull_batch, np.ascontiguousarray(array), bounds, backend,
                      precision, engine, threads)
    return _batch_result(raw, bounds, kind)
