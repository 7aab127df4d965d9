"""pose.py — nvdiffrast's `pose` sample on clraster.torch: recover a cube's
rotation from a target image by gradient descent on a quaternion.

    PYTHONPATH=build/python /usr/bin/python3 examples/pose.py [--iterations N] [--resolution R]

A cube with a random colour per vertex (24 vertices, so faces differ) is
drawn at the target rotation; the optimisation starts 25° away and
minimises the mean squared image difference with Adam, through
rasterize, interpolate and antialias (the silhouette gradients). Prints
the loss and the angle to the target every 10 iterations, and the time per
iteration; run() returns the same as a list of (iteration, loss, degrees).
The only change from an nvdiffrast script is the import.
"""
import argparse
import time

import numpy as np
import torch

import clraster.torch as dr


def cube_mesh(seed=0):
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float32) * 0.5
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    pos = np.concatenate([corners[f] for f in faces])  # 4 own vertices per face: colours per face corner
    tri = np.array([[4 * i, 4 * i + 1, 4 * i + 2] for i in range(6)] + [[4 * i, 4 * i + 2, 4 * i + 3] for i in range(6)],
                   np.int32)
    colour = np.random.default_rng(seed).uniform(0, 1, (len(pos), 3)).astype(np.float32)
    return torch.from_numpy(pos), torch.from_numpy(tri), torch.from_numpy(colour)


def projection(fov_y=np.pi / 4, near=0.1, far=10.0):
    f = 1 / np.tan(fov_y / 2)
    return torch.tensor([[f, 0, 0, 0], [0, f, 0, 0], [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)],
                         [0, 0, -1, 0]], dtype=torch.float32)


def quat_to_matrix(q):
    q = q / q.norm()
    w, x, y, z = q
    return torch.stack([torch.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)]),
                        torch.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)]),
                        torch.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)])])


def angle_deg(q0, q1):
    d = abs(float((q0 / q0.norm()) @ (q1 / q1.norm())))
    return float(np.degrees(2 * np.arccos(min(1.0, d))))


def render(glctx, q, pos, tri, colour, resolution):
    world = pos @ quat_to_matrix(q).T + torch.tensor([0.0, 0.0, -3.0])
    clip = torch.cat([world, torch.ones(len(world), 1)], 1) @ projection().T
    rast, _ = dr.rasterize(glctx, clip[None], tri, resolution=[resolution, resolution])
    image, _ = dr.interpolate(colour[None], rast, tri)
    return dr.antialias(image, rast, clip[None], tri)


def random_quat(rng):
    q = rng.standard_normal(4)
    return torch.tensor(q / np.linalg.norm(q), dtype=torch.float32)


def offset_quat(q, degrees, rng):
    axis = rng.standard_normal(3)
    axis /= np.linalg.norm(axis)
    half = np.radians(degrees) / 2
    r = torch.tensor([np.cos(half), *(np.sin(half) * axis)], dtype=torch.float32)
    w0, x0, y0, z0 = r
    w1, x1, y1, z1 = q
    return torch.stack([w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1, w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
                        w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1, w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1])


def run(iterations=300, resolution=64, start_degrees=25.0, seed=1, log=print):
    rng = np.random.default_rng(seed)
    glctx = dr.RasterizeCudaContext()
    pos, tri, colour = cube_mesh()
    target_q = random_quat(rng)
    target = render(glctx, target_q, pos, tri, colour, resolution)
    q = offset_quat(target_q, start_degrees, rng).clone().requires_grad_(True)
    opt = torch.optim.Adam([q], lr=0.02)
    history = []
    start = time.perf_counter()
    for it in range(iterations + 1):
        image = render(glctx, q, pos, tri, colour, resolution)
        loss = torch.mean((image - target) ** 2)
        history.append((it, float(loss), angle_deg(q.detach(), target_q)))
        if it % 10 == 0:
            log(f"pose {it:4d}  loss {history[-1][1]:.6f}  angle {history[-1][2]:6.2f} deg")
        if it == iterations:
            break
        opt.zero_grad()
        loss.backward()
        opt.step()
        for g in opt.param_groups:  # nvdiffrast's sample decays its rate as well
            g["lr"] = 0.02 * 0.99 ** (it / 10)
    elapsed = time.perf_counter() - start
    log(f"pose: {elapsed / (iterations + 1) * 1000:.1f} ms per iteration at {resolution}x{resolution}")
    return history


def main(doc, run, iterations):
    """The examples' command line: --iterations, --resolution, and --curve
    FILE for the history, one tab-separated line per iteration."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--iterations", type=int, default=iterations)
    parser.add_argument("--resolution", type=int, default=64)
    parser.add_argument("--curve", help="write the history here, one tab-separated line per iteration")
    args = parser.parse_args()
    rows = run(args.iterations, args.resolution)
    if args.curve:
        with open(args.curve, "w") as f:
            f.writelines("\t".join(str(v) for v in row) + "\n" for row in rows)


if __name__ == "__main__":
    main(__doc__, run, 300)
