"""The Python module's speed (issue 16, deliverable 5): cudahull.ConvexHull of N points from NumPy and from
CuPy/PyTorch (read in place), against the command line's `cudahull bench` on the same points (its total
plus its upload), and scipy.spatial.ConvexHull (Qhull).

    python3 python/bench/bench_module.py CUDAHULL_CLI POINTS.ply [--repeat 5] [--json OUT.jsonl]

POINTS.ply is a binary float PLY as `cudahull gen` writes it.  Each Python time is the median of --repeat
calls after one warm-up, wall clock around the call (the results as NumPy arrays included).  One JSON line
per measurement, then a table.
"""

import argparse
import json
import statistics
import subprocess
import sys
import time

import numpy as np

import cudahull


def read_ply(path):
    with open(path, "rb") as f:
        count = None
        while True:
            line = f.readline().decode("ascii").strip()
            if line.startswith("element vertex"):
                count = int(line.split()[2])
            if line == "end_header":
                break
        return np.fromfile(f, dtype="<f4", count=3 * count).reshape(count, 3)


def timed(call, repeat):
    call()  # warm-up: module load, the device's context, the engine's pool
    times = []
    result = None
    for _ in range(repeat):
        start = time.perf_counter()
        result = call()
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times), times, result


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cli")
    parser.add_argument("points")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json")
    parser.add_argument("--no-scipy", action="store_true")
    args = parser.parse_args()

    points = read_ply(args.points)
    rows = []

    def record(row):
        rows.append(row)
        print(json.dumps(row), flush=True)

    reference = None
    for engine in ("resident", "stepping"):
        cli = json.loads(subprocess.run(
            [args.cli, "bench", args.points, "--backend", "cuda", "--engine", engine, "--repeat",
             str(args.repeat), "--json"], check=True, capture_output=True, text=True).stdout)
        record({"what": f"cli {engine}", "total_ms": cli["total_ms"], "upload_ms": cli["upload_ms"],
                "total_plus_upload_ms": cli["total_ms"] + cli["upload_ms"], "hull_vertices": cli["hull_vertices"],
                "backend": cli["backend"]})
        median, times, hull = timed(lambda: cudahull.ConvexHull(points, backend="cuda", engine=engine), args.repeat)
        reference = hull if reference is None else reference
        assert np.array_equal(hull.vertices, reference.vertices)
        assert len(hull.vertices) == cli["hull_vertices"]
        record({"what": f"numpy {engine}", "ms": median, "times_ms": times, "backend": hull.backend,
                "vs_cli_total_plus_upload": median / (cli["total_ms"] + cli["upload_ms"]),
                "bytes_from_device": (hull.stats or {}).get("bytes_from_device"),
                "engine_ms": (hull.stats or {}).get("engine_ms"), "describe_ms": (hull.stats or {}).get("describe_ms")})

    for library in ("cupy", "torch"):
        try:
            module = __import__(library)
        except ImportError:
            record({"what": library, "skipped": "not installed"})
            continue
        if library == "cupy":
            device_points = module.asarray(points)
            sync = module.cuda.Device().synchronize
        else:
            device_points = module.from_numpy(points).cuda()
            sync = module.cuda.synchronize
        sync()
        median, times, hull = timed(lambda: cudahull.ConvexHull(device_points), args.repeat)
        assert np.array_equal(hull.vertices, reference.vertices)
        record({"what": f"{library} resident (in place)", "ms": median, "times_ms": times, "backend": hull.backend,
                "bytes_from_device": hull.stats["bytes_from_device"], "host_syncs": hull.stats["host_syncs"],
                "points_read_back": hull.stats["points_read_back"], "point_bytes": points.nbytes,
                "engine_ms": hull.stats["engine_ms"], "describe_ms": hull.stats["describe_ms"]})

    if not args.no_scipy:
        import scipy
        import scipy.spatial

        start = time.perf_counter()
        qhull = scipy.spatial.ConvexHull(points.astype(np.float64))
        ms = (time.perf_counter() - start) * 1e3
        record({"what": f"scipy {scipy.__version__} ConvexHull (Qhull)", "ms": ms, "runs": 1,
                "same_vertices": bool(np.array_equal(qhull.vertices, reference.vertices))})

    if args.json:
        with open(args.json, "w") as f:
            for row in rows:
                f.write(json.dumps(row) + "\n")
    print(f"\n{args.points}: {len(points)} points")
    for row in rows:
        value = row.get("ms", row.get("total_plus_upload_ms"))
        extra = {k: v for k, v in row.items() if k not in ("what", "times_ms")}
        print(f"{row['what']:36s} {value if value is None else round(value, 3)!s:>10} ms  {extra}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
