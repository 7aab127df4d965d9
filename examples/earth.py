"""earth.py — nvdiffrast's `earth` sample on clraster.torch: recover a
sphere's texture, mip-mapped, from images of it under random views.

    PYTHONPATH=build/python /usr/bin/python3 examples/earth.py [--iterations N] [--resolution R]

A UV sphere carries a procedural 64×64 "planet" texture; the optimised
texture starts grey. Each iteration renders the target and the estimate
from a new random rotation through rasterize, interpolate (uv and its
pixel derivatives, diff_attrs='all') and texture in linear-mipmap-linear
mode, so the loss reaches every mip level, and steps Adam on the texture.
Prints the loss and the mean texel error every 50 iterations, and the time
per iteration; run() returns (iteration, loss, texel error) tuples.
"""
import time

import numpy as np
import torch

import clraster.torch as dr
from pose import main, projection, quat_to_matrix, random_quat


def uv_sphere(rows=12, cols=24):
    """Positions, triangles and uv of a unit sphere (a seam column of its own vertices)."""
    theta = np.linspace(0, np.pi, rows + 1)
    phi = np.linspace(0, 2 * np.pi, cols + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    pos = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    uv = np.stack([p / (2 * np.pi), 1 - t / np.pi], -1).reshape(-1, 2)
    tri = []
    for r in range(rows):
        for c in range(cols):
            a, b = r * (cols + 1) + c, (r + 1) * (cols + 1) + c
            tri += [[a, b, a + 1], [a + 1, b, b + 1]]
    return [torch.tensor(x, dtype=dt) for x, dt in ((pos, torch.float32), (tri, torch.int32), (uv, torch.float32))]


def planet(size=64):
    v, u = np.mgrid[0:size, 0:size] / size
    land = (np.sin(12 * u) * np.cos(7 * v) + np.sin(5 * u + 3 * v) > 0.3).astype(np.float32)
    tex = np.stack([0.1 + 0.5 * land, 0.3 + 0.4 * land, 0.8 - 0.6 * land], -1) * (0.6 + 0.4 * np.sin(np.pi * v))[..., None]
    return torch.from_numpy(tex[None].astype(np.float32))


def render(glctx, q, pos, tri, uv, tex, resolution):
    world = pos @ quat_to_matrix(q).T + torch.tensor([0.0, 0.0, -3.0])
    clip = torch.cat([world, torch.ones(len(world), 1)], 1) @ projection().T
    rast, rast_db = dr.rasterize(glctx, clip[None], tri, resolution=[resolution, resolution])
    texc, texd = dr.interpolate(uv[None], rast, tri, rast_db=rast_db, diff_attrs="all")
    color = dr.texture(tex, texc, texd, filter_mode="linear-mipmap-linear", max_mip_level=4)
    return color * (rast[..., 3:] > 0).float()


def run(iterations=400, resolution=64, seed=3, log=print):
    rng = np.random.default_rng(seed)
    glctx = dr.RasterizeCudaContext()
    pos, tri, uv = uv_sphere()
    target_tex = planet()
    tex = torch.full_like(target_tex, 0.5).requires_grad_(True)
    opt = torch.optim.Adam([tex], lr=0.02)
    history = []
    start = time.perf_counter()
    for it in range(iterations + 1):
        q = random_quat(rng)
        with torch.no_grad():
            target = render(glctx, q, pos, tri, uv, target_tex, resolution)
        image = render(glctx, q, pos, tri, uv, tex, resolution)
        loss = torch.mean((image - target) ** 2)
        err = float((tex.detach() - target_tex).abs().mean())
        history.append((it, float(loss), err))
        if it % 50 == 0:
            log(f"earth {it:4d}  loss {history[-1][1]:.6f}  texel error {err:.4f}")
        if it == iterations:
            break
        opt.zero_grad()
        loss.backward()
        opt.step()
    elapsed = time.perf_counter() - start
    log(f"earth: {elapsed / (iterations + 1) * 1000:.1f} ms per iteration (two renders) at {resolution}x{resolution}")
    return history


if __name__ == "__main__":
    main(__doc__, run, 400)
