"""clraster.torch.interpolate's backward (kernels/diff.cl) against central
differences, in float64, of nvdiffrast's interpolate formula
(tests/python/gradref.py): gradients to attr (shared, broadcast and per
image), to rast's u and v, to rast_db through diff_attrs; and the whole
chain pos -> rasterize -> interpolate -> loss against differences of the
composed formulas."""
import numpy as np
import pytest
import torch

import clraster
import clraster.torch as dr
from gradref import assert_close, central_differences, interpolate_formula, rast_formula
from test_grad_rasterize import fan_scene, mixed_scene

# float32 kernels against float64: interpolate is linear in attr, so its
# gradients differ from the reference by float32 sums of a few hundred
# terms (1e-5 relative); through rasterize see test_grad_rasterize.REL.
REL_LINEAR = 1e-5
REL_CHAIN = 2e-3


@pytest.fixture(scope="module")
def scene(ctx):
    pos, tri = mixed_scene()
    rast, db = dr.rasterize(ctx, pos, tri, (20, 24))
    return pos, tri, rast.numpy(), db.numpy()


@pytest.mark.parametrize("attr_shape", ["shared", "broadcast", "per_image"])
def test_gradients_to_attr_rast_and_rast_db(ctx, attr_shape):
    pos, tri = mixed_scene()
    batch = np.stack([pos, pos * np.float32(0.9)])
    rast_np, db_np = (x.numpy() for x in dr.rasterize(ctx, batch, tri, (20, 24)))
    rng = np.random.default_rng(7)
    shape = {"shared": (len(pos), 3), "broadcast": (1, len(pos), 3), "per_image": (2, len(pos), 3)}[attr_shape]
    attr_np = rng.standard_normal(shape).astype(np.float32)
    diff = [2, 0]
    attr = torch.tensor(attr_np, requires_grad=True)
    rast = torch.tensor(rast_np, requires_grad=True)
    db = torch.tensor(db_np, requires_grad=True)
    out, out_da = dr.interpolate(attr, rast, tri, rast_db=db, diff_attrs=diff)
    wo = rng.standard_normal(out.shape)
    wda = rng.standard_normal(out_da.shape)
    ((out * torch.from_numpy(wo).float()).sum() + (out_da * torch.from_numpy(wda).float()).sum()).backward()
    ids = clraster.triangle_ids(rast_np)

    def loss(a, r, d):
        total = 0.0
        for b in range(2):
            ab = a if a.ndim == 2 else a[b if len(a) == 2 else 0]
            o, oda = interpolate_formula(ab, r[b], d[b], tri, ids[b], diff)
            total += (o * wo[b]).sum() + (oda * wda[b]).sum()
        return total

    a64, r64, d64 = (np.array(x, np.float64) for x in (attr_np, rast_np, db_np))
    want_attr = central_differences(lambda a: loss(a, r64, d64), a64, 1e-4)
    assert_close(attr.grad.numpy(), want_attr, REL_LINEAR, "d loss / d attr")
    # rast: only u and v carry gradients (z/w and the id do not enter the formula).
    uv = r64[..., :2].copy()

    def with_uv(x):
        r = r64.copy()
        r[..., :2] = x
        return loss(a64, r, d64)

    want_uv = central_differences(with_uv, uv, 1e-4)
    assert_close(rast.grad.numpy()[..., :2], want_uv, REL_LINEAR, "d loss / d (u, v)")
    assert (rast.grad.numpy()[..., 2:] == 0).all()
    want_db = central_differences(lambda d: loss(a64, r64, d), d64, 1e-4)
    assert_close(db.grad.numpy(), want_db, REL_LINEAR, "d loss / d rast_db")


def test_background_pixels_get_no_gradient(ctx, scene):
    pos, tri, rast_np, _ = scene
    rast = torch.tensor(rast_np, requires_grad=True)
    attr = torch.ones((len(pos), 2), requires_grad=True)
    out, _ = dr.interpolate(attr, rast, tri)
    out.sum().backward()
    empty = clraster.triangle_ids(rast_np) == 0
    assert empty.any() and (rast.grad.numpy()[empty] == 0).all()
    # Each covered pixel adds u + v + (1 − u − v) = 1 to its three vertices' sum.
    assert abs(attr.grad[:, 0].sum().item() - (~empty).sum()) < 1e-3


def test_chain_from_positions_through_interpolate(ctx):
    pos, tri = fan_scene()
    rng = np.random.default_rng(9)
    colour = rng.standard_normal((len(pos), 2))
    p = torch.tensor(pos, requires_grad=True)
    rast, db = dr.rasterize(ctx, p, tri, (16, 16))
    out, out_da = dr.interpolate(torch.tensor(colour, dtype=torch.float32), rast, tri, rast_db=db, diff_attrs="all")
    wo, wda = rng.standard_normal(out.shape), rng.standard_normal(out_da.shape)
    ((out * torch.from_numpy(wo).float()).sum() + (out_da * torch.from_numpy(wda).float()).sum()).backward()
    ids = clraster.triangle_ids(rast.detach().numpy())[0]

    def loss(x):
        f = rast_formula(x, tri, ids, 16, 16)
        o, oda = interpolate_formula(colour, f[..., :2], f[..., 3:], tri, ids, [0, 1])
        return (o * wo[0]).sum() + (oda * wda[0]).sum()

    want = central_differences(loss, pos.astype(np.float64), 1e-6)
    assert_close(p.grad.numpy(), want, REL_CHAIN, "d loss / d pos through interpolate")
