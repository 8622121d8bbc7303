"""trimesh (from PyPI) with cudahull.ConvexHull put in scipy's place, as its users would: its convex hulls
and oriented bounding boxes must match stock trimesh's (on scipy's Qhull) within tolerance, and its
hulls must be convex and watertight."""

import os

import numpy as np
import pytest

import cudahull

trimesh = pytest.importorskip("trimesh")  # python/requirements-test.txt pins it; scripts/setup installs it

ASSETS = os.path.join(os.path.dirname(__file__), "..", "..", "assets")


def rotated_chamfered_boxes():
    """Boxes with chamfered edges and corners, sampled on their faces, rotated arbitrarily in double."""
    from test_scipy_drop_in import chamfered_box

    rng = np.random.default_rng(2025)
    return [chamfered_box(rng, size=(1.0 + k, 0.7, 0.3 + 0.1 * k), chamfer=0.04 + 0.02 * k) for k in range(4)]


def models():
    meshes = {name: trimesh.load(os.path.join(ASSETS, name), force="mesh") for name in ("bun_zipper.ply", "teapot.obj")}
    for k, points in enumerate(rotated_chamfered_boxes()):
        meshes[f"chamfered-box-{k}"] = trimesh.points.PointCloud(points)
    return meshes


@pytest.fixture
def cudahull_in_scipys_place(monkeypatch):
    """trimesh imports scipy's ConvexHull into its modules: replaced there, as a user patching it would."""
    import trimesh.bounds
    import trimesh.convex

    def patch():
        monkeypatch.setattr(trimesh.convex, "ConvexHull", cudahull.ConvexHull)
        monkeypatch.setattr(trimesh.bounds, "ConvexHull", cudahull.ConvexHull)

    return patch


def as_mesh(name, points):
    if name.startswith("chamfered"):
        return trimesh.Trimesh(vertices=points, faces=np.zeros((0, 3), dtype=np.int64), process=False)
    return trimesh.load(os.path.join(ASSETS, name), force="mesh")


def vertices_of(model):
    return np.asarray(model.vertices, dtype=np.float64)


@pytest.mark.parametrize("name", ["bun_zipper.ply", "teapot.obj", "chamfered-box-0", "chamfered-box-1",
                                  "chamfered-box-2", "chamfered-box-3"])
def test_trimesh_hulls_and_bounds_match_stock_trimesh(name, cudahull_in_scipys_place):
    model = models()[name]
    points = vertices_of(model)
    stock_hull = trimesh.convex.convex_hull(points)
    stock_obb, stock_extents = trimesh.bounds.oriented_bounds(points)
    stock_mesh_hull = as_mesh(name, points).convex_hull

    cudahull_in_scipys_place()
    hull = trimesh.convex.convex_hull(points)
    assert hull.is_watertight and hull.is_winding_consistent
    assert hull.is_convex, "trimesh finds cudahull's hull not convex"
    assert hull.volume == pytest.approx(stock_hull.volume, rel=1e-9)
    assert hull.area == pytest.approx(stock_hull.area, rel=1e-9)
    # Merged as Qhull merges.  trimesh passes "QbB": Qhull then merges in the unit box, where on one box its
    # roundoff keeps a point 1e-16 proud of a face that the part's geometry does not have (25 against 24).
    ours, stock = ({tuple(p) for p in h.vertices.tolist()} for h in (hull, stock_hull))
    assert ours <= stock and len(stock - ours) <= 1, (len(ours), len(stock))
    obb, extents = trimesh.bounds.oriented_bounds(points)
    # A true bounding box: every point inside it.
    local = trimesh.transform_points(points, obb)
    assert np.all(np.abs(local) <= extents / 2 + 1e-9 * np.abs(points).max())
    # oriented_bounds tries one face normal per direction rounded to 0.1 rad, the first face in the hull's
    # order: Qhull lists its facets in another order than cudahull, so the candidates (and the box, a
    # heuristic's) differ a little.  Within 1% of stock trimesh's volume.
    assert np.prod(extents) == pytest.approx(np.prod(stock_extents), rel=1e-2)
    mesh_hull = as_mesh(name, points).convex_hull  # a new mesh: trimesh caches its hull
    assert mesh_hull.is_convex and mesh_hull.is_watertight
    assert mesh_hull.volume == pytest.approx(stock_mesh_hull.volume, rel=1e-9)
