"""clraster.interpolate against numpy evaluating nvdiffrast's formula
u·a0 + v·a1 + (1 − u − v)·a2 on rasterize's own u, v; its batch shapes;
and its pixel derivatives against the chain rule on rast_db."""
import numpy as np
import pytest

import clraster
from test_rasterize import crafted_scene


def numpy_interpolate(attr, rast, tri):
    ids = clraster.triangle_ids(rast)
    out = np.zeros(rast.shape[:3] + (attr.shape[-1],), np.float32)
    for b in range(rast.shape[0]):
        a = attr[b] if attr.ndim == 3 else attr
        covered = ids[b] > 0
        t = tri[ids[b][covered] - 1]
        u, v = rast[b][covered][:, 0:1], rast[b][covered][:, 1:2]
        # The same float32 operations in the same order as the C++ loop.
        out[b][covered] = (u * a[t[:, 0]] + v * a[t[:, 1]]) + (np.float32(1) - u - v) * a[t[:, 2]]
    return out


@pytest.fixture(scope="module")
def scene(ctx):
    pos, tri = crafted_scene(21)
    rast, db = clraster.rasterize(ctx, pos, tri, (40, 56))
    return pos, tri, rast, db


def test_matches_the_barycentric_formula(scene):
    pos, tri, rast, _ = scene
    attr = np.random.default_rng(3).standard_normal((len(pos), 5)).astype(np.float32)
    out, out_da = clraster.interpolate(attr, rast, tri)
    assert out.shape == (1, 40, 56, 5) and out_da.shape == (1, 40, 56, 0)
    # float32 sums: a few ulp of the largest term.
    assert np.allclose(out, numpy_interpolate(attr, rast, tri), rtol=0, atol=1e-5)
    ids = clraster.triangle_ids(rast)
    assert (out[ids == 0] == 0).all() and (ids > 0).sum() > 500


def test_reproduces_positions_in_screen_space(ctx):
    # Interpolating x/w, y/w perspective-correctly is wrong; interpolating
    # clip x, y, w and dividing gives the pixel centre back.
    pos, tri = crafted_scene(22)
    h, w = 32, 32
    rast, _ = clraster.rasterize(ctx, pos, tri, (h, w))
    out, _ = clraster.interpolate(pos, rast, tri)
    covered = clraster.triangle_ids(rast)[0] > 0
    y, x = np.mgrid[0:h, 0:w]
    # 5e-3 NDC: a pixel is 2/32 = 6e-2 wide; λ carries the fixed-point snap.
    assert np.abs(out[0, ..., 0] / out[0, ..., 3] - ((2 * x + 1) / w - 1))[covered].max() < 5e-3
    assert np.abs(out[0, ..., 1] / out[0, ..., 3] - ((2 * y + 1) / h - 1))[covered].max() < 5e-3


def test_batched_attributes_and_broadcast(ctx):
    pos0, tri = crafted_scene(23)
    pos1, _ = crafted_scene(24)
    rast, _ = clraster.rasterize(ctx, np.stack([pos0, pos1]), tri, (24, 24))
    attr = np.random.default_rng(5).standard_normal((2, len(pos0), 3)).astype(np.float32)
    out, _ = clraster.interpolate(attr, rast, tri)
    assert out.shape == (2, 24, 24, 3)
    assert np.allclose(out, numpy_interpolate(attr, rast, tri), atol=1e-5)
    shared, _ = clraster.interpolate(attr[0], rast, tri)
    one, _ = clraster.interpolate(attr[:1], rast, tri)
    assert np.array_equal(shared, one)
    assert np.allclose(shared, numpy_interpolate(attr[0], rast, tri), atol=1e-5)


def test_pixel_derivatives_follow_rast_db(scene):
    pos, tri, rast, db = scene
    attr = np.random.default_rng(6).standard_normal((len(pos), 3)).astype(np.float32)
    _, out_da = clraster.interpolate(attr, rast, tri, rast_db=db, diff_attrs=[2, 0])
    assert out_da.shape == (1, 40, 56, 4)
    ids = clraster.triangle_ids(rast)[0]
    covered = ids > 0
    t = tri[ids[covered] - 1]
    d = db[0][covered]
    for k, c in enumerate([2, 0]):
        dsdu = attr[t[:, 0], c] - attr[t[:, 2], c]
        dsdv = attr[t[:, 1], c] - attr[t[:, 2], c]
        assert np.allclose(out_da[0][covered][:, 2 * k], d[:, 0] * dsdu + d[:, 2] * dsdv, atol=1e-6)
        assert np.allclose(out_da[0][covered][:, 2 * k + 1], d[:, 1] * dsdu + d[:, 3] * dsdv, atol=1e-6)
    _, everything = clraster.interpolate(attr, rast, tri, rast_db=db, diff_attrs="all")
    assert everything.shape == (1, 40, 56, 6)
    assert np.array_equal(everything[..., 4:6], out_da[..., 0:2])
