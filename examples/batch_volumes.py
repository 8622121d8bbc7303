"""The volumes of 10,000 small polyhedra in one call.

Each polyhedron is the convex hull of a cloud of 6 to 40 random points.  The clouds go to
``cudahull.convex_hull_batch`` as one padded (B, M, 3) array, cloud ``c`` being ``points[c, :lengths[c]]``
(the rows after its length are ignored), and the result holds one volume a cloud.  A few clouds are
checked against ``scipy.spatial.ConvexHull`` where scipy is installed, and the same batch runs from a
PyTorch tensor where PyTorch is installed (on its GPU where it has one).  On a GPU the NumPy batch runs
there too, its points copied up once.

    python examples/batch_volumes.py
"""

from __future__ import annotations

import importlib
import sys
import time
from types import ModuleType

import numpy as np
import numpy.typing as npt

import cudahull

CLOUDS = 10_000
SMALLEST, LARGEST = 6, 40
SEED = 20118
CHECKED = 20  # clouds compared with scipy


def random_clouds(clouds: int = CLOUDS, seed: int = SEED) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """``clouds`` clouds of SMALLEST to LARGEST normal points, padded to LARGEST rows: (points, lengths)."""
    rng = np.random.default_rng(seed)
    lengths = rng.integers(SMALLEST, LARGEST + 1, size=clouds)
    points = rng.standard_normal((clouds, LARGEST, 3))
    return points, lengths


def optional_module(name: str) -> ModuleType | None:
    """The module, or None where it is not installed."""
    try:
        return importlib.import_module(name)
    except ImportError:
        return None


def main() -> int:
    points, lengths = random_clouds()

    start = time.perf_counter()
    hulls = cudahull.convex_hull_batch(points, lengths=lengths)
    milliseconds = (time.perf_counter() - start) * 1e3
    volumes = np.asarray(hulls.volumes, dtype=np.float64)
    vertex_counts = np.diff(np.asarray(hulls.vertex_offsets))
    print(f"numpy: {len(hulls)} clouds of {SMALLEST} to {LARGEST} points, their volumes in one call: "
          f"{milliseconds:.0f} ms (backend {hulls.backend}, {hulls.precision})")
    for c in range(5):
        print(f"cloud {c}: {lengths[c]} points, {vertex_counts[c]} hull vertices, volume {float(volumes[c])!r}")
    print(f"total volume {float(volumes.sum())!r}")

    spatial = optional_module("scipy.spatial")
    if spatial is None:
        print("scipy: not installed, nothing checked")
    else:
        worst = 0.0
        for c in range(CHECKED):
            expected = float(spatial.ConvexHull(points[c, : lengths[c]]).volume)
            worst = max(worst, abs(float(volumes[c]) - expected) / expected)
        print(f"scipy: clouds 0 to {CHECKED - 1} checked, largest relative difference {worst:.1e}")
        if worst > 1e-12:
            print("scipy: the volumes differ", file=sys.stderr)
            return 1

    torch = optional_module("torch")
    if torch is None:
        print("torch: not installed, skipped")
    else:
        device = "cuda" if torch.cuda.is_available() else "cpu"
        tensor_hulls = cudahull.convex_hull_batch(torch.as_tensor(points, device=device),
                                                  lengths=torch.as_tensor(lengths))
        # The result's arrays are tensors on the input's device.
        tensor_volumes = np.asarray(torch.as_tensor(tensor_hulls.volumes).cpu().numpy(), dtype=np.float64)
        same = bool(np.allclose(tensor_volumes, volumes, rtol=1e-12, atol=0.0))
        print(f"torch ({device}): {tensor_volumes.shape[0]} volumes, the same as NumPy's: {same}")
        if not same:
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
