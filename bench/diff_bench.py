"""diff_bench.py — forward and backward time per iteration of the
clraster.torch examples (examples/pose.py, cube.py, earth.py) at given
resolutions, split per operation, and rasterize of 8 views (instanced
and range mode) against one (bench/diff.sh runs it).

Each case builds one iteration's graph (the example's render and its
mean squared loss against a fixed target) `--iterations` times after one
warm-up; the operations' forward calls and their autograd backward
methods are wrapped with wall-clock timers, and each time printed is the
median over the iterations. Times are host wall clock on whatever else
the machine runs: compare them within one run.
"""
import argparse
import collections
import functools
import os
import sys
import time

import numpy as np
import torch

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "examples"))
import clraster.torch as dr  # noqa: E402
import cube  # noqa: E402
import earth  # noqa: E402
import pose  # noqa: E402

SPENT = collections.defaultdict(float)


def timed(key, fn):
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        start = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            SPENT[key] += time.perf_counter() - start
    return wrapper


for op, function in [("rasterize", dr._Rasterize), ("interpolate", dr._Interpolate), ("texture", dr._Texture),
                     ("antialias", dr._Antialias)]:
    function.forward = staticmethod(timed((op, "forward"), function.forward))
    function.backward = staticmethod(timed((op, "backward"), function.backward))


def cases(resolution):
    glctx = dr.RasterizeCudaContext()
    rng = np.random.default_rng(0)
    q = pose.random_quat(rng)
    p_pos, p_tri, p_col = pose.cube_mesh()
    qv = q.clone().requires_grad_(True)
    c_pos, c_idx, c_col, c_cidx = cube.cube_target()
    cp, cc = c_pos.clone().requires_grad_(True), c_col.clone().requires_grad_(True)
    e_pos, e_tri, e_uv = earth.uv_sphere()
    tex = earth.planet().requires_grad_(True)
    return {
        "pose": (lambda: pose.render(glctx, qv, p_pos, p_tri, p_col, resolution), [qv]),
        "cube": (lambda: cube.render(glctx, q, cp, c_idx, cc, c_cidx, resolution), [cp, cc]),
        "earth": (lambda: earth.render(glctx, q, e_pos, e_tri, e_uv, tex, resolution), [tex]),
    }


def bench(name, render, params, iterations):
    """Medians over the iterations (after a warm-up): a shared machine's
    other work lands in a few iterations, which a median leaves out."""
    target = render().detach() * 0.9
    rows = []
    for it in range(iterations + 1):
        for p in params:
            p.grad = None
        SPENT.clear()
        t0 = time.perf_counter()
        loss = torch.mean((render() - target) ** 2)
        t1 = time.perf_counter()
        loss.backward()
        t2 = time.perf_counter()
        if it > 0:  # the first is a warm-up (kernel builds, buffer growth)
            rows.append(dict(SPENT, total=(t1 - t0, t2 - t1)))
    med = lambda values: float(np.median(values)) * 1000  # noqa: E731
    ops = sorted({op for op in rows[0] if op != "total" for op in [op[0]]})
    parts = []
    for op in ops:
        f = med([r.get((op, "forward"), 0.0) for r in rows])
        if not any((op, "backward") in r for r in rows):  # no parameter upstream: autograd skips its backward
            parts.append(f"{op} {f:.2f}/-")
            continue
        b = med([r.get((op, "backward"), 0.0) for r in rows])
        parts.append(f"{op} {f:.2f}/{b:.2f} (x{b / max(f, 1e-9):.2f})")
    print(f"{name:6s} forward {med([r['total'][0] for r in rows]):7.2f} ms  backward "
          f"{med([r['total'][1] for r in rows]):7.2f} ms  per op fwd/bwd ms (median): {'  '.join(parts)}")


def instanced(resolution, iterations):
    """Rasterize of 8 views (instanced, and range mode over 8 copies of the
    mesh) against one view, per image: medians of single calls."""
    glctx = dr.RasterizeCudaContext()
    pos, tri, _ = pose.cube_mesh()
    rng = np.random.default_rng(1)
    clips = []
    for _ in range(8):
        world = pos @ pose.quat_to_matrix(pose.random_quat(rng)).T + torch.tensor([0.0, 0.0, -3.0])
        clips.append(torch.cat([world, torch.ones(len(world), 1)], 1) @ pose.projection().T)
    views = torch.stack(clips)
    n_v, n_t = views.shape[1], len(tri)
    flat = views.reshape(-1, 4)  # range mode: image k draws copy k of the mesh
    tris = torch.cat([tri + k * n_v for k in range(8)])
    ranges = torch.tensor([[k * n_t, n_t] for k in range(8)], dtype=torch.int32)
    calls = {"1 view": lambda: dr.rasterize(glctx, views[:1], tri, [resolution, resolution]),
             "8 instanced": lambda: dr.rasterize(glctx, views, tri, [resolution, resolution]),
             "8 ranges": lambda: dr.rasterize(glctx, flat, tris, [resolution, resolution], ranges=ranges)}
    per_image = {}
    for name, call in calls.items():
        call()
        times = []
        for _ in range(max(iterations, 20)):
            start = time.perf_counter()
            call()
            times.append(time.perf_counter() - start)
        per_image[name] = float(np.median(times)) * 1000 / (1 if name == "1 view" else 8)
    one = per_image["1 view"]
    print(f"rasterize per image (median ms): 1 view {one:.3f}, 8 instanced {per_image['8 instanced']:.3f} "
          f"(x{per_image['8 instanced'] / one:.2f}), 8 ranges {per_image['8 ranges']:.3f} "
          f"(x{per_image['8 ranges'] / one:.2f})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--resolutions", type=int, nargs="+", default=[256, 512])
    parser.add_argument("--iterations", type=int, default=10)
    parser.add_argument("--batch-only", action="store_true", help="only the 8-views-against-one rasterize line")
    args = parser.parse_args()
    for r in args.resolutions:
        print(f"-- {r}x{r}, {args.iterations} iterations")
        for name, (render, params) in ([] if args.batch_only else cases(r).items()):
            bench(name, render, params, args.iterations)
        instanced(r, args.iterations)


if __name__ == "__main__":
    main()
