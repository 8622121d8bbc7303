"""trimesh on cudahull: a mesh's convex hull and its volume.

trimesh computes its hulls with ``scipy.spatial.ConvexHull``, which it imports into ``trimesh.convex`` and
``trimesh.bounds``.  Put ``cudahull.ConvexHull`` in its place there: it takes scipy's arguments (trimesh's
``qhull_options`` included, merged as Qhull merges) and gives scipy's attributes, so every hull trimesh
computes from then on is cudahull's.

    python examples/trimesh_hull.py [MESH]      (default: the bundled Stanford bunny)
"""

from __future__ import annotations

import sys
from pathlib import Path

import trimesh

import cudahull

BUNNY = Path(__file__).resolve().parent.parent / "assets" / "bun_zipper.ply"


def use_cudahull_in_trimesh() -> None:
    """cudahull's ConvexHull where trimesh calls scipy's (the name each of the two modules imported)."""
    for module in (trimesh.convex, trimesh.bounds):
        setattr(module, "ConvexHull", cudahull.ConvexHull)


def main(arguments: list[str]) -> int:
    path = Path(arguments[0]) if arguments else BUNNY
    mesh = trimesh.load_mesh(path)
    use_cudahull_in_trimesh()

    hull = mesh.convex_hull
    print(f"{path.name}: {len(mesh.vertices)} vertices, {len(mesh.faces)} faces")
    print(f"convex hull: {len(hull.vertices)} vertices, {len(hull.faces)} faces, "
          f"watertight {hull.is_watertight}, convex {hull.is_convex}")
    print(f"hull volume {float(hull.volume)!r}, area {float(hull.area)!r}")
    print(f"the hull holds {float(hull.volume) / max(abs(float(mesh.volume)), 1e-300):.2f} times the mesh's volume"
          if mesh.is_watertight else "the mesh is not closed: it has no volume of its own")

    # The same points through cudahull directly: the exact hull keeps every strictly extreme point.
    exact = cudahull.ConvexHull(mesh.vertices)
    print(f"cudahull.ConvexHull directly (exact): {len(exact.vertices)} vertices, volume {float(exact.volume)!r}")
    return 0 if hull.is_watertight and hull.is_convex else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
