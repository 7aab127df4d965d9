"""clraster.torch.antialias (nvdiffrast's analytic silhouette antialias,
kernels/diff_antialias.cl) against differences of its own forward: the
colour gradient by the adjoint identity (the operation is linear in the
colour), the position gradient by central differences with rast held
fixed; and the forward's own contract: pixels change only next to a
change of triangle id, never away from silhouettes, each by a blend toward
its neighbour."""
import numpy as np
import pytest
import torch

import clraster
import clraster.torch as dr
from gradref import assert_close, central_differences


def cube_clip(angle, size=0.6):
    """A closed cube (8 vertices, 12 triangles) turned by `angle` about y
    and x, 3 units before a 60° perspective camera, in clip space."""
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float64) * size
    c, s = np.cos(angle), np.sin(angle)
    v = v @ np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]) @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    v[:, 2] -= 3.0
    f = 1 / np.tan(np.pi / 6)
    near, far = 0.1, 10.0
    z = (far + near) / (near - far) * v[:, 2] + 2 * far * near / (near - far)
    clip = np.stack([f * v[:, 0], f * v[:, 1], z, -v[:, 2]], 1)
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    tri = np.array([[a, b, c] for a, b, c, d in faces] + [[a, c, d] for a, b, c, d in faces], np.int32)
    return clip.astype(np.float32), tri


@pytest.fixture(scope="module")
def scene(ctx):
    pos, tri = cube_clip(0.5)
    rast, _ = dr.rasterize(ctx, pos, tri, (24, 24))
    colour = np.random.default_rng(3).uniform(0, 1, (len(pos), 3)).astype(np.float32)
    color, _ = dr.interpolate(colour, rast, tri)
    return pos, tri, rast, color.numpy()


def test_topology_finds_every_neighbour_of_a_closed_mesh():
    _, tri = cube_clip(0.0)
    opp = dr.antialias_construct_topology_hash(tri).opp
    assert (opp >= 0).all()  # closed: every edge has a triangle on each side
    single = dr.antialias_construct_topology_hash(tri[:1]).opp
    assert (single == -1).all()


def test_only_silhouette_pixels_change(ctx, scene):
    pos, tri, rast, color = scene
    out = dr.antialias(torch.from_numpy(color), rast, pos, tri).numpy()
    ids = clraster.triangle_ids(rast.numpy())[0]
    changed = np.abs(out[0] - color[0]).max(-1) > 0
    assert changed.sum() > 10
    # Each changed pixel has a neighbour of another id, and it borders the background (a
    # closed convex mesh's only silhouette is its outline).
    pad = np.pad(ids, 1, constant_values=-1)
    neighbours = np.stack([pad[1:-1, :-2], pad[1:-1, 2:], pad[:-2, 1:-1], pad[2:, 1:-1]])
    assert ((neighbours != ids) & (neighbours >= 0)).any(0)[changed].all()
    assert (neighbours == 0).any(0)[changed].all() or (ids[changed] == 0).all()
    # A blend: each output lies within the range of the pixel and its four neighbours.
    cpad = np.pad(color[0], ((1, 1), (1, 1), (0, 0)), mode="edge")
    stack = np.stack([color[0], cpad[1:-1, :-2], cpad[1:-1, 2:], cpad[:-2, 1:-1], cpad[2:, 1:-1]])
    assert (out[0] >= stack.min(0) - 1e-6).all() and (out[0] <= stack.max(0) + 1e-6).all()


def test_colour_gradient_is_the_adjoint(ctx, scene):
    pos, tri, rast, color = scene
    rng = np.random.default_rng(4)
    c = torch.tensor(color, requires_grad=True)
    out = dr.antialias(c, rast, pos, tri)
    w = rng.standard_normal(out.shape).astype(np.float32)
    (out * torch.from_numpy(w)).sum().backward()
    delta = rng.standard_normal(color.shape).astype(np.float32)
    moved = dr.antialias(torch.from_numpy(color + delta), rast, pos, tri).numpy()
    # Linear in colour: <grad, delta> = <w, out(c + delta) − out(c)> up to float32 sums.
    lhs = float((c.grad.numpy().astype(np.float64) * delta).sum())
    rhs = float((w.astype(np.float64) * (moved - out.detach().numpy())).sum())
    assert abs(lhs - rhs) < 1e-3 * (abs(lhs) + 1)


@pytest.mark.parametrize("boost", [1.0, 3.0])
def test_position_gradient_against_its_forward(ctx, scene, boost):
    pos, tri, rast, color = scene
    w = np.random.default_rng(5).standard_normal(color.shape)
    p = torch.tensor(pos, requires_grad=True)
    out = dr.antialias(torch.from_numpy(color), rast, p, tri, pos_gradient_boost=boost)
    (out * torch.from_numpy(w).float()).sum().backward()

    def loss(x):
        o = dr.antialias(color, rast, x.astype(np.float32), tri).numpy()
        return float((o.astype(np.float64) * w).sum())

    want = central_differences(loss, pos.astype(np.float64), 2e-4)
    # Differences of a float32 forward, 2e-4 clip units (~1/400 pixel): 2% of
    # the largest component covers their rounding.
    assert_close(p.grad.numpy() / boost, want, 2e-2, "d loss / d pos")
    assert (p.grad.numpy()[:, 2] == 0).all()  # depth never enters the crossing


def test_instanced_positions(ctx):
    pos0, tri = cube_clip(0.5)
    pos1, _ = cube_clip(0.9)
    batch = np.stack([pos0, pos1])
    rast, _ = dr.rasterize(ctx, batch, tri, (16, 16))
    color = np.random.default_rng(6).uniform(0, 1, (2, 16, 16, 2)).astype(np.float32)
    both = dr.antialias(color, rast, batch, tri).numpy()
    for b, p in enumerate([pos0, pos1]):
        one = dr.antialias(color[b:b + 1], rast[b:b + 1], p, tri).numpy()
        assert np.array_equal(both[b], one[0])
