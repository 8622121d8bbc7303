"""cudahull.dask.convex_hull on a LocalCluster (two worker processes) against the one-shot hull."""

import dask.array as dask_array
import distributed
import numpy as np
import pytest
import scipy.spatial

import cudahull
import cudahull.dask


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        yield client


def test_chunked_hull_equals_one_shot(client):
    rng = np.random.default_rng(33)
    points = rng.normal(size=(20000, 3))
    points[15000:15010] = points[100:110]  # duplicates across chunks: the lower index stays the vertex
    array = dask_array.from_array(points, chunks=(2500, 3))
    with distributed.get_task_stream(client) as stream:
        result = cudahull.dask.convex_hull(array, backend="cpu")
    # Every chunk's hull ran as a task on the cluster.
    chunk_tasks = [t for t in stream.data if "_chunk_vertices" in str(t["key"])]
    assert len(chunk_tasks) == 8
    one_shot = cudahull.ConvexHull(points, backend="cpu")
    assert np.array_equal(result["vertices"], one_shot.vertices)
    assert np.array_equal(result["vertices"], scipy.spatial.ConvexHull(points).vertices)
    assert {tuple(t) for t in result["simplices"].tolist()} == {tuple(t) for t in one_shot.simplices.tolist()}
    assert result["volume"] == pytest.approx(one_shot.volume, rel=1e-14)
    assert np.array_equal(result["vertex_points"], points[result["vertices"]])
    assert len(one_shot.vertices) <= result["candidates"] < len(points)


def test_float32_chunks_stay_float(client):
    points = np.random.default_rng(34).uniform(-1, 1, size=(6000, 3)).astype(np.float32)
    result = cudahull.dask.convex_hull(dask_array.from_array(points, chunks=(1000, 3)), backend="cpu")
    assert result["precision"] == "float"
    assert np.array_equal(result["vertices"], cudahull.ConvexHull(points, backend="cpu").vertices)


@pytest.mark.parametrize("row", [0, 177, 777, 999])
def test_bad_point_is_named_by_its_row_in_the_whole_array(client, row):
    points = np.random.default_rng(35).normal(size=(1000, 3))
    points[row, 1] = np.nan
    with pytest.raises(ValueError) as error:
        cudahull.dask.convex_hull(dask_array.from_array(points, chunks=(200, 3)), backend="cpu")
    assert str(error.value).startswith(f"point {row}: y coordinate nan is not finite (row {row % 200} of the chunk "
                                       f"that starts at row {row - row % 200})"), str(error.value)
    # The same words as the one-shot hull's, which names the row itself.
    with pytest.raises(ValueError, match=f"^point {row}: y coordinate nan is not finite$"):
        cudahull.ConvexHull(points, backend="cpu")
