"""The merged path's QbB shortcut (trimesh's "QbB Pp Qt" on host double points): its volume and area are the
general scaled path's (_scaled_measures with qhull_options' map over the exact hull's vertices), bit for bit."""
import numpy as np
import pytest

import cudahull
from cudahull import _hull
from cudahull import qhull_options
from cudahull._errors import qhull_error


def clouds():
    rng = np.random.default_rng(7)
    for n in (8, 40, 300, 3000):
        yield rng.normal(size=(n, 3)) * rng.uniform(0.01, 100, size=3) + rng.uniform(-50, 50, size=3)
    # A rotated box's faces with noise of the order of Qhull's roundoff: merging sets points aside, and some
    # of them attain the box's bounds.
    box = rng.uniform(-1, 1, size=(4000, 3))
    box[np.arange(4000), np.arange(4000) % 3] = np.where(np.arange(4000) % 2, 1.0, -1.0)
    rotation = np.array([[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]])
    yield box @ rotation.T + rng.normal(scale=1e-16, size=box.shape)


@pytest.mark.parametrize("points", list(clouds()))
def test_qbb_measures_equal_the_general_path(points):
    hull = cudahull.ConvexHull(points, qhull_options="QbB Pp Qt", backend="cpu")
    plain = cudahull.ConvexHull(points, tolerance="qhull", backend="cpu")
    assert np.array_equal(hull.vertices, plain.vertices)
    assert np.array_equal(hull.simplices, plain.simplices)
    extreme = np.unique(np.concatenate([plain.vertices, plain.coplanar[:, 0]]))
    corners = points[extreme]
    scaling = qhull_options.parse("QbB", qhull_error).scaling(corners)
    volume, area = _hull._scaled_measures(corners, np.searchsorted(extreme, plain.simplices), scaling,
                                          float(plain.volume))
    assert hull.volume == volume
    assert hull.area == area
