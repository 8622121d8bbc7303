"""Batched hulls from a PyTorch tensor already on the GPU (issue 27).

Times ``cudahull.convex_hull_batch`` on B clouds of M points (a padded (B, M, 3) float32 tensor), against a
loop of ``scipy.spatial.ConvexHull`` and a loop of single ``cudahull.convex_hull`` calls on the same clouds.
The loops run on the first ``--loop`` clouds and are scaled to B (stated in the output).  Every one of
those clouds' vertex sets is checked against scipy's (general position: scipy is exact there).

    python3 python/bench/bench_batch.py --batch 10000 --n 1000 [--dist ball] [--repeat 5] [--loop 300]
        [--json FILE] [--profile]
"""
import argparse
import json
import statistics
import time

import numpy as np
import scipy.spatial
import torch

import cudahull


def clouds(dist, batch, n, seed):
    g = torch.Generator(device="cuda").manual_seed(seed)
    if dist == "cube":
        return torch.rand((batch, n, 3), generator=g, device="cuda") * 2 - 1
    d = torch.randn((batch, n, 3), generator=g, device="cuda")
    d = d / d.norm(dim=2, keepdim=True)
    if dist == "sphere":
        return d
    r = torch.rand((batch, n, 1), generator=g, device="cuda") ** (1 / 3)
    return d * r  # ball


def timed(fn, repeat):
    times = []
    out = None
    for _ in range(repeat):
        torch.cuda.synchronize()
        t0 = time.perf_counter()
        out = fn()
        torch.cuda.synchronize()
        times.append(1000 * (time.perf_counter() - t0))
    return out, times


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--batch", type=int, required=True)
    ap.add_argument("--n", type=int, required=True)
    ap.add_argument("--dist", default="ball", choices=["ball", "cube", "sphere"])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--loop", type=int, default=300, help="clouds the loops run on (scaled to --batch)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json")
    ap.add_argument("--profile", action="store_true", help="print where one batch call spends its time")
    a = ap.parse_args()

    points = clouds(a.dist, a.batch, a.n, a.seed)
    cudahull.convex_hull_batch(points[: min(a.batch, 64)])  # warm: the module, the CUDA context, the pools
    torch.cuda.reset_peak_memory_stats()
    hulls, batch_ms = timed(lambda: cudahull.convex_hull_batch(points), a.repeat)
    if a.profile:
        import cProfile
        import pstats
        profile = cProfile.Profile()
        profile.runcall(cudahull.convex_hull_batch, points)
        pstats.Stats(profile).sort_stats("cumulative").print_stats(12)

    k = min(a.loop, a.batch)
    host = points[:k].cpu().numpy().astype(np.float64)
    vertex_offsets = hulls.vertex_offsets.cpu().numpy()
    vertices = hulls.vertices.cpu().numpy()
    t0 = time.perf_counter()
    scipy_vertices = [np.sort(scipy.spatial.ConvexHull(host[c]).vertices) for c in range(k)]
    scipy_ms = 1000 * (time.perf_counter() - t0) * a.batch / k
    single = points[:k].contiguous()
    cudahull.convex_hull(single[0])
    torch.cuda.synchronize()
    t0 = time.perf_counter()
    for c in range(k):
        cudahull.convex_hull(single[c])
    torch.cuda.synchronize()
    loop_ms = 1000 * (time.perf_counter() - t0) * a.batch / k
    differ = sum(not np.array_equal(vertices[vertex_offsets[c]:vertex_offsets[c + 1]], scipy_vertices[c])
                 for c in range(k))

    best = min(batch_ms)
    row = {
        "input": f"{a.dist} {a.batch}x{a.n}", "device": torch.cuda.get_device_name(),
        "batch_ms_min": best, "batch_ms_median": statistics.median(batch_ms), "repeat": a.repeat,
        "scipy_loop_ms": scipy_ms, "single_call_loop_ms": loop_ms, "loops_timed_on": k,
        "vs_scipy": scipy_ms / best, "vs_single_calls": loop_ms / best,
        "hull_vertices": int(vertices.size), "differ_from_scipy": int(differ),
        "torch_peak_bytes": torch.cuda.max_memory_allocated(), **hulls.report,
    }
    print(f"{row['input']}: batch {best:.2f} ms (median {row['batch_ms_median']:.2f}); scipy loop "
          f"{scipy_ms:.0f} ms ({row['vs_scipy']:.0f}x); single calls {loop_ms:.0f} ms ({row['vs_single_calls']:.0f}x)"
          f" [loops on {k} clouds, scaled]; {differ} of {k} clouds differ from scipy; kernel "
          f"{row['kernel_ms']:.2f} ms, describe {row['describe_ms']:.2f} ms, device peak "
          f"{row['device_bytes_peak'] / 2**20:.0f} MiB")
    if a.json:
        with open(a.json, "a") as f:
            f.write(json.dumps(row) + "\n")
    return 1 if differ else 0


if __name__ == "__main__":
    raise SystemExit(main())
