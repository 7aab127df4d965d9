"""clraster.torch.DepthPeeler: layer 0 is rasterize's result bit for bit;
every later layer holds, per pixel, the triangle of the next distinct depth
behind the last layer (ties to the lower index), against a reference built
from each triangle rasterized alone (coverage and depth of a triangle do
not depend on the others); instanced and range mode peel each image as a
single call would; and a layer's gradient to pos matches central
differences of the rasterize formulas for its own ids."""
import numpy as np
import torch

import clraster
import clraster.torch as dr
from gradref import assert_close, central_differences, rast_formula
from test_rasterize import crafted_scene


def reference_layers(ctx, pos, tri, h, w):
    """Per layer, the expected triangle id + 1 of every pixel [layers, H, W]."""
    depth = np.full((len(tri), h, w), np.inf)
    for t in range(len(tri)):
        rast, _ = clraster.rasterize(ctx, pos, tri[t:t + 1], (h, w))
        covered = rast[0, ..., 3] > 0
        depth[t][covered] = rast[0, ..., 2][covered]
    layers = []
    floor = np.full((h, w), -np.inf)
    while True:
        behind = np.where(depth > floor, depth, np.inf)
        nearest = behind.min(0)
        if np.isinf(nearest).all():
            return np.array(layers)
        ids = np.where(np.isinf(nearest), 0, np.argmax(behind == nearest, 0) + 1)
        layers.append(ids)
        floor = nearest


def test_layers_follow_depth_order(ctx):
    pos, tri = crafted_scene(51, count=30)
    want = reference_layers(ctx, pos, tri, 40, 48)
    assert len(want) >= 4
    first, first_db = dr.rasterize(ctx, pos, tri, (40, 48))
    with dr.DepthPeeler(ctx, pos, tri, (40, 48)) as peeler:
        for k in range(len(want) + 1):
            rast, db = peeler.rasterize_next_layer()
            if k == 0:
                assert torch.equal(rast, first) and torch.equal(db, first_db)
            ids = clraster.triangle_ids(rast.numpy())[0]
            expected = want[k] if k < len(want) else np.zeros_like(ids)
            assert (ids == expected).all(), f"layer {k}: {(ids != expected).sum()} pixels differ"


def test_instanced_and_range_mode_peel_each_image(ctx):
    pos0, tri = crafted_scene(52, count=20)
    pos1, _ = crafted_scene(53, count=20)
    with dr.DepthPeeler(ctx, np.stack([pos0, pos1]), tri, (24, 24)) as both, \
            dr.DepthPeeler(ctx, pos1, tri, (24, 24)) as single:
        for _ in range(3):
            assert torch.equal(both.rasterize_next_layer()[0][1], single.rasterize_next_layer()[0][0])
    ranges = torch.tensor([[0, 10], [10, 10]], dtype=torch.int32)
    with dr.DepthPeeler(ctx, pos0, tri, (24, 24), ranges=ranges) as ranged, \
            dr.DepthPeeler(ctx, pos0, tri[10:], (24, 24)) as tail:
        for _ in range(3):
            got = clraster.triangle_ids(ranged.rasterize_next_layer()[0].numpy())[1]
            want = clraster.triangle_ids(tail.rasterize_next_layer()[0].numpy())[0]
            assert (got == np.where(want > 0, want + 10, 0)).all()


def test_second_layer_gradient(ctx):
    pos, tri = crafted_scene(54, count=12)
    p = torch.tensor(pos, requires_grad=True)
    with dr.DepthPeeler(ctx, p, tri, (20, 20)) as peeler:
        peeler.rasterize_next_layer()
        rast, db = peeler.rasterize_next_layer()
    w = np.random.default_rng(2).standard_normal(rast.shape[:3] + (3,))
    (rast[..., :3] * torch.from_numpy(w).float()).sum().backward()
    ids = clraster.triangle_ids(rast.detach().numpy())[0]
    assert (ids > 0).sum() > 20
    want = central_differences(lambda x: (rast_formula(x, tri, ids, 20, 20)[..., :3] * w[0]).sum(),
                               pos.astype(np.float64), 1e-6)
    assert_close(p.grad.numpy(), want, 2e-3, "d loss / d pos of layer 1")
