"""The installed wheel as a scipy user meets it: cudahull.ConvexHull against scipy.spatial.ConvexHull.

Run by tests/wheel/check_installed_wheel.sh in a fresh virtual environment holding only the wheel and
its test packages.  Exits non-zero on the first disagreement.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import scipy.spatial

import cudahull


def same_hull(points: np.ndarray, **options: object) -> None:
    ours = cudahull.ConvexHull(points, **options)
    theirs = scipy.spatial.ConvexHull(points, **options)
    assert np.array_equal(np.sort(ours.vertices), np.sort(theirs.vertices)), "vertex sets differ"
    assert np.isclose(ours.volume, theirs.volume, rtol=1e-9), (ours.volume, theirs.volume)
    assert np.isclose(ours.area, theirs.area, rtol=1e-9), (ours.area, theirs.area)


def main() -> int:
    site = Path(cudahull.__file__).resolve()
    source = Path(__file__).resolve().parents[2] / "python"
    assert source not in site.parents, f"cudahull imported from the source tree ({site}), not the installed wheel"
    assert (site.parent / "_bin" / "cudahull").is_file(), f"{site.parent} holds no command line: not the wheel"
    rng = np.random.default_rng(20261206)
    same_hull(rng.standard_normal((2000, 3)))
    same_hull(rng.random((500, 2)))
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    same_hull(np.vstack([cube, rng.random((300, 3))]), qhull_options="QbB Pp Qt")
    # The bundled model the viewer opens: 35,947 points, 1,564 strictly extreme (assets/README.md).
    from cudahull import _commands

    ply = _commands.BUNDLED_MODEL.read_text().splitlines()
    count = next(int(line.split()[2]) for line in ply if line.startswith("element vertex"))
    start = ply.index("end_header") + 1
    bunny = np.array([[float(v) for v in line.split()[:3]] for line in ply[start:start + count]], dtype=np.float32)
    hull = cudahull.ConvexHull(bunny)
    assert len(hull.vertices) == 1564, len(hull.vertices)
    assert np.isclose(hull.volume, scipy.spatial.ConvexHull(bunny).volume, rtol=1e-6)
    print(f"drop-in smoke: cudahull from {site.parent} agrees with scipy {scipy.__version__}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
