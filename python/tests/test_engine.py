"""cudahull.Engine: the iteration records and meshes it gives, checked against each other, scipy and the
one-call hull."""

import numpy as np
import pytest
import scipy.spatial

import cudahull


def assert_closed_mesh(mesh):
    """The mesh's faces form a closed, consistently oriented 2-manifold whose neighbours are opposite
    their corners."""
    faces, neighbors = mesh["faces"], mesh["neighbors"]
    assert faces.shape == neighbors.shape and faces.shape[1] == 3
    assert np.array_equal(np.unique(faces), mesh["vertices"])
    directed = {}
    for f, (a, b, c) in enumerate(faces.tolist()):
        for edge in ((a, b), (b, c), (c, a)):
            assert edge not in directed
            directed[edge] = f
    for f, tri in enumerate(faces.tolist()):
        for k in range(3):
            # The edge opposite corner k, reversed, is in the neighbour.
            edge = (tri[(k + 2) % 3], tri[(k + 1) % 3])
            assert directed.get(edge) == neighbors[f, k]


def test_stepping_records_and_result():
    points = np.random.default_rng(21).normal(size=(3000, 3))
    engine = cudahull.Engine(points, backend="cpu")
    assert engine.precision == "double" and not engine.done
    records = []
    while not engine.done:
        record = engine.step()
        records.append(record)
        if engine.dimension == 3:
            assert_closed_mesh(engine.mesh())
    assert [r["iteration"] for r in records] == list(range(len(records)))
    assert len(records[0]["refined_apexes"]) == 4  # section 3.1: the initial tetrahedron's corners
    assert records[-1]["external_after"] == 0
    for r in records[1:]:
        assert len(r["refined_apexes"]) == r["faces_refined"] == len(r["refined_faces"])
        kinds = r["swap_kind"]
        assert len(kinds) == r["swaps_regular"] + r["swaps_complementary"] + r["swaps_rejected"]
        assert (kinds == cudahull.SWAP_KINDS.index("regular")).sum() == r["swaps_regular"]
        assert (kinds == cudahull.SWAP_KINDS.index("complementary")).sum() == r["swaps_complementary"]
        # Every performed swap or removal has its entry in the decision array, of its kind.
        performed = r["swap_decision_index"][r["swap_decision_index"] >= 0]
        assert np.all(r["decision_kind"][performed] == 0)
        removed = r["removal_decision_index"][~r["removal_rejected"]]
        assert len(removed) == r["vertices_removed"]
        assert np.all(r["decision_kind"][removed] == 1)
        assert len(performed) + len(removed) == len(r["decision_kind"])
    assert sum(r["swaps_regular"] for r in records) > 0  # the records are not all empty

    result = engine.result()
    theirs = scipy.spatial.ConvexHull(points)
    assert np.array_equal(result["vertices"], theirs.vertices)
    assert result["volume"] == pytest.approx(theirs.volume, rel=1e-12)
    if sum(r["repairs"] for r in records) == 0:
        # The last mesh is the hull.
        mesh_faces = {tuple(sorted(t)) for t in engine.mesh()["faces"].tolist()}
        assert mesh_faces == {tuple(sorted(t)) for t in result["simplices"].tolist()}

    # restart(): the same steps again.
    engine.restart()
    again = engine.step()
    assert np.array_equal(again["refined_apexes"], records[0]["refined_apexes"])
    assert again["external_after"] == records[0]["external_after"]


def test_engine_errors_and_precision():
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float32)
    engine = cudahull.Engine(cube, backend="cpu")
    assert engine.precision == "float"
    with pytest.raises(RuntimeError, match="not done"):
        engine.result()
    engine.run()
    assert engine.result()["volume"] == 1.0
    with pytest.raises(RuntimeError, match="done"):
        engine.step()
    with pytest.raises(ValueError, match="not finite"):
        cudahull.Engine(np.array([[0, 0, np.inf]] + cube.tolist()))


def test_flat_input_in_one_step():
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    engine = cudahull.Engine(square, backend="cpu")
    record = engine.step()
    assert engine.done and engine.dimension == 2 and "dimension 2" in record["note"]
    assert engine.result()["vertices"].tolist() == [0, 1, 2, 3]
