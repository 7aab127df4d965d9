"""clraster.torch.rasterize's backward (kernels/diff.cl) against central
differences, in float64, of the rasterize formulas (tests/python/gradref.py)
with coverage held fixed: random upstream gradients on u, v, z/w and
rast_db, on triangles clipped by the near plane, behind the eye, beyond the
guard band, degenerate, and meshes whose pixels lie on shared edges; in
one-image, instanced and range mode."""
import numpy as np
import pytest
import torch

import clraster
import clraster.torch as dr
from gradref import assert_close, central_differences, rast_formula
from test_rasterize import crafted_scene

# The kernels work in float32: a gradient is a sum over pixels of terms
# with cancellation (u − λ Σ), so 2e-3 of the largest component bounds it
# on these scenes; a wrong term is off by its whole size.
REL = 2e-3


@pytest.fixture(scope="module")
def glctx(ctx):
    return ctx


def mixed_scene():
    """Crafted triangles (clipped, behind the eye, far outside) and two
    degenerate ones: a repeated vertex and three collinear vertices."""
    pos, tri = crafted_scene(31, count=10)
    extra = np.array([[0.1, 0.1, 0.2, 1], [0.5, 0.4, 0.2, 1], [0.1, 0.1, 0.2, 1],  # repeated vertex
                      [-0.5, -0.5, 0, 1], [0, 0, 0, 1], [0.5, 0.5, 0, 1]], np.float32)  # collinear
    n = len(pos)
    tri = np.vstack([tri, [[n, n + 1, n + 2], [n + 3, n + 4, n + 5]]]).astype(np.int32)
    return np.vstack([pos, extra]), tri


def fan_scene():
    """A fan of 12 triangles around an off-centre vertex: every pixel is
    covered, many on or next to the shared edges."""
    n = 12
    a = np.linspace(0, 2 * np.pi, n, endpoint=False) + 0.1
    ring = np.stack([2 * np.cos(a), 2 * np.sin(a), 0.3 * np.cos(3 * a), 1.0 + 0.2 * np.sin(a)], 1)
    pos = np.vstack([[0.07, -0.05, 0.1, 1.1], ring]).astype(np.float32)
    tri = np.array([[0, 1 + i, 1 + (i + 1) % n] for i in range(n)], np.int32)
    return pos, tri


def check_rasterize_grad(glctx, pos, tri, h, w, seed, ranges=None):
    rng = np.random.default_rng(seed)
    p = torch.tensor(pos, requires_grad=True)
    rast, db = dr.rasterize(glctx, p, torch.from_numpy(tri), (h, w), ranges=ranges)
    wr = rng.standard_normal(rast.shape[:3] + (3,))
    wd = rng.standard_normal(db.shape)
    loss = (rast[..., :3] * torch.from_numpy(wr).float()).sum() + (db * torch.from_numpy(wd).float()).sum()
    loss.backward()
    ids = clraster.triangle_ids(rast.detach().numpy())
    images = pos if pos.ndim == 3 else np.broadcast_to(pos, (len(ids),) + pos.shape)

    def f(x):
        total = 0.0
        for b in range(len(ids)):
            ref = rast_formula(x if x.ndim == 2 else x[b], tri, ids[b], h, w)
            total += (ref[..., :3] * wr[b]).sum() + (ref[..., 3:] * wd[b]).sum()
        return total

    x = np.array(pos, np.float64)
    want = central_differences(f, x, 1e-6)
    assert_close(p.grad.numpy(), want, REL, "d loss / d pos")
    assert np.isfinite(p.grad.numpy()).all()
    return p.grad.numpy(), ids, images


def test_clipped_behind_eye_and_degenerate_triangles(glctx):
    pos, tri = mixed_scene()
    grad, ids, _ = check_rasterize_grad(glctx, pos, tri, 24, 32, 1)
    assert (ids > 0).sum() > 200
    # The degenerate triangles cover nothing, so their own vertices get no gradient.
    assert not np.isin(ids, [len(tri) - 1, len(tri)]).any()
    assert (grad[-6:] == 0).all()
    # The clipped (1), behind-the-eye (2) and far (3) triangles are seen and differentiated.
    for t in (1, 2, 3):
        assert (ids == t + 1).any(), f"triangle {t} covers nothing"
        assert np.abs(grad[3 * t:3 * t + 3]).max() > 0


def test_pixels_on_shared_edges(glctx):
    pos, tri = fan_scene()
    grad, ids, _ = check_rasterize_grad(glctx, pos, tri, 20, 20, 2)
    assert (ids > 0).all() and len(np.unique(ids)) == len(tri)
    assert np.abs(grad[0]).max() > 0  # the shared centre vertex sums every triangle's share


def test_instanced_mode_is_one_gradient_per_image(glctx):
    pos0, tri = fan_scene()
    rng = np.random.default_rng(4)
    batch = np.stack([pos0, pos0 * np.float32(1.1) + rng.uniform(-0.1, 0.1, pos0.shape).astype(np.float32)])
    check_rasterize_grad(glctx, batch, tri, 16, 12, 3)


def test_range_mode_shares_the_positions(glctx):
    pos, tri = mixed_scene()
    ranges = torch.tensor([[0, 5], [4, 6], [10, 2]], dtype=torch.int32)
    grad, ids, _ = check_rasterize_grad(glctx, pos, tri, 16, 16, 5, ranges=ranges)
    assert ids.shape == (3, 16, 16)
    assert ids[0].max() <= 5 and ids[1][ids[1] > 0].min() >= 5  # absolute triangle ids


def test_without_grad_db_only_rast_counts(glctx):
    pos, tri = fan_scene()
    p = torch.tensor(pos, requires_grad=True)
    rast, db = dr.rasterize(glctx, p, tri, (12, 12), grad_db=False)
    assert db.shape == (1, 12, 12, 0)
    rast[..., 0].sum().backward()
    ids = clraster.triangle_ids(rast.detach().numpy())[0]
    want = central_differences(lambda x: rast_formula(x, tri, ids, 12, 12)[..., 0].sum(), pos.astype(np.float64),
                               1e-6)
    assert_close(p.grad.numpy(), want, REL, "d sum(u) / d pos")


def test_float64_and_int64_inputs_convert(glctx):
    pos, tri = fan_scene()
    p = torch.tensor(pos, dtype=torch.float64, requires_grad=True)
    rast, _ = dr.rasterize(glctx, p, torch.tensor(tri, dtype=torch.int64), (8, 8))
    want, _ = dr.rasterize(glctx, pos, tri, (8, 8))
    assert torch.equal(rast, want)
    rast[..., 2].sum().backward()
    assert p.grad.dtype == torch.float64 and p.grad.abs().max() > 0
    with pytest.raises(ValueError, match="^pos: "):
        dr.rasterize(glctx, np.full((len(pos), 4), 1e300), tri, (8, 8))
    with pytest.raises(ValueError, match="^tri: "):
        dr.rasterize(glctx, pos, np.array([[0, 1, 2**40]], np.int64), (8, 8))
