"""cube.py — nvdiffrast's `cube` sample on clraster.torch: recover a cube's
vertex positions and colours from images of it under random views.

    PYTHONPATH=build/python /usr/bin/python3 examples/cube.py [--iterations N] [--resolution R]

The target is a cube (8 shared corner positions, a colour per face corner
through its own index array, as the sample's pos_idx and col_idx); the
optimisation starts from jittered corners and random colours and
minimises the mean squared difference between antialiased renders and
target images from a new random rotation each iteration (Adam). Prints the
loss, the mean corner error and the mean colour error every 50
iterations, and the time per iteration; run() returns (iteration, loss,
corner error, colour error) tuples. The only change from an nvdiffrast
script is the import.
"""
import time

import numpy as np
import torch

import clraster.torch as dr
from pose import main, projection, quat_to_matrix, random_quat


def cube_target(seed=0):
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float32) * 0.5
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    pos_idx = np.array([[a, b, c] for a, b, c, d in faces] + [[a, c, d] for a, b, c, d in faces], np.int32)
    col_idx = np.array([[4 * i, 4 * i + 1, 4 * i + 2] for i in range(6)] + [[4 * i, 4 * i + 2, 4 * i + 3]
                                                                             for i in range(6)], np.int32)
    colour = np.random.default_rng(seed).uniform(0, 1, (24, 3)).astype(np.float32)
    return [torch.from_numpy(x) for x in (corners, pos_idx, colour, col_idx)]


def render(glctx, q, pos, pos_idx, colour, col_idx, resolution):
    world = pos @ quat_to_matrix(q).T + torch.tensor([0.0, 0.0, -3.5])
    clip = torch.cat([world, torch.ones(len(world), 1)], 1) @ projection().T
    rast, _ = dr.rasterize(glctx, clip[None], pos_idx, resolution=[resolution, resolution])
    image, _ = dr.interpolate(colour[None], rast, col_idx)
    return dr.antialias(image, rast, clip[None], pos_idx)


def run(iterations=500, resolution=64, seed=2, log=print):
    rng = np.random.default_rng(seed)
    torch.manual_seed(seed)
    glctx = dr.RasterizeCudaContext()
    pos_t, pos_idx, col_t, col_idx = cube_target()
    pos = (pos_t + torch.from_numpy(rng.normal(0, 0.15, pos_t.shape).astype(np.float32))).requires_grad_(True)
    col = torch.from_numpy(rng.uniform(0, 1, col_t.shape).astype(np.float32)).requires_grad_(True)
    opt = torch.optim.Adam([pos, col], lr=0.01)
    history = []
    start = time.perf_counter()
    for it in range(iterations + 1):
        q = random_quat(rng)
        target = render(glctx, q, pos_t, pos_idx, col_t, col_idx, resolution)
        image = render(glctx, q, pos, pos_idx, col, col_idx, resolution)
        loss = torch.mean((image - target) ** 2)
        pos_err = float((pos.detach() - pos_t).norm(dim=1).mean())
        col_err = float((col.detach() - col_t).abs().mean())
        history.append((it, float(loss), pos_err, col_err))
        if it % 50 == 0:
            log(f"cube {it:4d}  loss {history[-1][1]:.6f}  corner error {pos_err:.4f}  colour error {col_err:.4f}")
        if it == iterations:
            break
        opt.zero_grad()
        loss.backward()
        opt.step()
        for g in opt.param_groups:  # a decaying rate, as the sample's
            g["lr"] = 0.01 * 0.5 ** (it / 150)
    elapsed = time.perf_counter() - start
    log(f"cube: {elapsed / (iterations + 1) * 1000:.1f} ms per iteration (two renders) at {resolution}x{resolution}")
    return history


if __name__ == "__main__":
    main(__doc__, run, 500)
