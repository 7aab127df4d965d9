"""Instanced and range mode rasterize as one frame over all images
(rasterizeBatch, host/api/api_diff.cpp): each image's rast and rast_db
equal, bit for bit, the one-image path (rasterize_into, no batching) on
that image alone, and every backward's gradients equal the per-image
calls'. The scenes hold triangles far beyond the image's top and bottom
(reaching the neighbours' rows if setup's clamp to the image were gone),
clipped by the near plane and the guard band (binned by bin_pixel_bounds),
behind the eye, heights that are not a tile multiple, and ranges that
overlap, differ in length or are empty. DepthPeeler's batches the same."""
import numpy as np
import pytest
import torch

import clraster
import clraster.torch as dr
from clraster import _clraster
from test_rasterize import crafted_scene

# Gradients summed by float atomics (kernels/diff.cl) in an unspecified
# order: the batched and per-image sums of the same terms differ only in
# rounding, far below a wrong term's size.
REL = 1e-5


def stacked_scene(seed, images, count=40):
    """pos [images, V, 4]: crafted_scene's triangles moved per image, with
    a tall triangle per image reaching y = ±6 (far into the neighbours'
    rows) and in front of everything (z/w near -1)."""
    pos, tri = crafted_scene(seed, count)
    rng = np.random.default_rng(seed + 100)
    batch = np.repeat(pos[None], images, 0)
    batch[:, :, 0] += rng.uniform(-0.4, 0.4, (images, 1)) * batch[:, :, 3]
    batch[:, :, 1] += rng.uniform(-0.4, 0.4, (images, 1)) * batch[:, :, 3]
    n = len(pos)
    tall = np.array([[-0.3, -6.0, -0.95, 1.0], [0.2, 6.0, -0.95, 1.0], [0.4, -5.0, -0.95, 1.0]], np.float32)
    tall = np.repeat(tall[None], images, 0)
    tall[:, :, 0] += np.linspace(-0.6, 0.6, images)[:, None]  # a different column per image
    batch = np.concatenate([batch, tall], 1).astype(np.float32)
    tri = np.vstack([tri, [[n, n + 1, n + 2]]]).astype(np.int32)
    return np.ascontiguousarray(batch), tri


def one_image(ctx, pos, tri, h, w):
    rast = np.empty((h, w, 4), np.float32)
    db = np.empty((h, w, 4), np.float32)
    _clraster.rasterize_into(ctx._ctx, np.ascontiguousarray(pos), np.ascontiguousarray(tri), rast, db)
    return rast, db


def assert_bits(a, b, what):
    same = a.view(np.uint32) == b.view(np.uint32)
    assert same.all(), f"{what}: {(~same).sum()} values differ, first at {np.argwhere(~same)[0]}"


@pytest.mark.parametrize("h,w", [(21, 19), (32, 16), (1, 5), (47, 33)])
def test_instanced_equals_each_image_alone(ctx, h, w):
    pos, tri = stacked_scene(h + w, 6)
    rast, db = clraster.rasterize(ctx, pos, tri, (h, w))
    covered = 0
    for b in range(len(pos)):
        r1, d1 = one_image(ctx, pos[b], tri, h, w)
        assert_bits(rast[b], r1, f"image {b} rast")
        assert_bits(db[b], d1, f"image {b} rast_db")
        covered += (r1[..., 3] == len(tri)).sum()
    assert covered > 0  # the tall triangles show


def test_range_mode_equals_each_range_alone(ctx):
    pos, tri = stacked_scene(7, 1, count=30)
    pos = pos[0]
    ranges = np.array([[0, 31], [25, 6], [10, 2], [3, 0], [30, 1], [0, 31]], np.int32)
    rast, db = dr.rasterize(ctx, torch.from_numpy(pos), torch.from_numpy(tri), (29, 23), ranges=ranges)
    rast, db = rast.numpy(), db.numpy()
    for k, (start, count) in enumerate(ranges):
        r1, d1 = one_image(ctx, pos, tri[start:start + count], 29, 23)
        ids = clraster.triangle_ids(r1[None])[0]
        r1[..., 3] = np.where(ids > 0, dr._encode_ids(ids + start), 0)
        assert_bits(rast[k], r1, f"range {k} rast")
        assert_bits(db[k], d1, f"range {k} rast_db")
    assert (clraster.triangle_ids(rast[4:5]) == 31).any()  # the tall triangle, alone in range 4


@pytest.mark.parametrize("images,h,w,checked", [
    (345, 40, 8, (0, 340, 341, 344)),  # 48 rows an image: 16384 / 48 = 341 images a frame, so two frames
    (3, 300, 600, (0, 1, 2)),  # 304 · 600 pixels an image: one a frame (kBatchFramePixels, 2^19)
])
def test_batches_beyond_one_frame_split(ctx, images, h, w, checked):
    pos, tri = stacked_scene(3, images, count=4)
    rast, db = clraster.rasterize(ctx, pos, tri, (h, w))
    for b in checked:
        r1, d1 = one_image(ctx, pos[b], tri, h, w)
        assert_bits(rast[b], r1, f"image {b} rast")
        assert_bits(db[b], d1, f"image {b} rast_db")


def test_batches_beyond_the_memory_limit_split():
    # 8 images at 64x64: outputs 1,048,576 bytes plus one image's frame fit 1,260,000 bytes; the whole 8-image
    # frame (1,310,720 device bytes) does not, so the batch runs as frames of 4 (one frame would be refused).
    ctx = clraster.Context(memory_limit=1_260_000)
    pos, tri = stacked_scene(5, 8, count=10)
    rast, db = clraster.rasterize(ctx, pos, tri, (64, 64))
    for b in range(8):
        r1, d1 = one_image(ctx, pos[b], tri, 64, 64)
        assert_bits(rast[b], r1, f"image {b} rast")
        assert_bits(db[b], d1, f"image {b} rast_db")


@pytest.mark.parametrize("ranged", [False, True])
def test_depth_peeler_batches_equal_each_image_alone(ctx, ranged):
    # Every layer of the batch equals the image peeled alone (a batch of one); layer 0 equals rasterize_into.
    h, w = 21, 19
    pos, tri = stacked_scene(9, 1 if ranged else 4, count=20)
    ranges = np.array([[0, 21], [5, 10], [20, 1], [2, 0]], np.int32) if ranged else None
    batch = torch.from_numpy(pos[0] if ranged else pos)
    images = len(ranges) if ranged else len(pos)
    alone = [dr.DepthPeeler(ctx, batch if ranged else batch[b:b + 1], torch.from_numpy(tri), (h, w),
                            ranges=ranges[b:b + 1] if ranged else None) for b in range(images)]
    with dr.DepthPeeler(ctx, batch, torch.from_numpy(tri), (h, w), ranges=ranges) as peeler:
        for layer in range(3):
            rast, db = peeler.rasterize_next_layer()
            for b in range(images):
                r1, d1 = alone[b].rasterize_next_layer()
                assert_bits(rast[b].numpy(), r1[0].numpy(), f"layer {layer} image {b} rast")
                assert_bits(db[b].numpy(), d1[0].numpy(), f"layer {layer} image {b} rast_db")
                if layer == 0:
                    start, count = ranges[b] if ranged else (0, len(tri))
                    r0, _ = one_image(ctx, pos[0 if ranged else b], tri[start:start + count], h, w)
                    ids = clraster.triangle_ids(r0[None])[0]
                    r0[..., 3] = np.where(ids > 0, dr._encode_ids(ids + start), 0)
                    assert_bits(rast[b].numpy(), r0, f"layer 0 image {b} against rasterize_into")
            assert layer == 0 or (rast[..., 3] > 0).any()  # later layers hold fragments too


def chain(ctx, pos, tri, attr, tex, h, w, weights, ranges=None):
    """Every operation's forward on one rasterize, and a loss weighting
    antialias's, interpolate's out_da and rast's values by `weights`."""
    rast, db = dr.rasterize(ctx, pos, tri, (h, w), ranges=ranges)
    out, out_da = dr.interpolate(attr, rast, tri, rast_db=db, diff_attrs="all")
    color = dr.texture(tex, out[..., :2].contiguous(), uv_da=out_da[..., :4].contiguous(),
                       filter_mode="linear-mipmap-linear")
    aa = dr.antialias(color, rast, pos, tri)
    return (aa * weights[0]).sum() + (out_da * weights[1]).sum() + (rast[..., :3] * weights[2]).sum()


def upstream(images, h, w, seed):
    g = torch.Generator().manual_seed(seed)
    return [torch.randn((images, h, w, c), generator=g) for c in (3, 6, 3)]


def assert_close_rel(a, b, what):
    scale = max(float(np.abs(b).max()), 1e-30)
    assert np.abs(a - b).max() <= REL * scale, f"{what}: off by {np.abs(a - b).max()} of {scale}"
    assert scale > 1e-30 or what == "none", f"{what}: no gradient at all"


def leaves(*arrays):
    return [torch.tensor(a, requires_grad=True) for a in arrays]


def scene_for_gradients(images):
    pos, tri = stacked_scene(11, images, count=20)
    rng = np.random.default_rng(5)
    attr = rng.uniform(0, 1, (pos.shape[1], 3)).astype(np.float32)
    tex = rng.uniform(0, 1, (1, 16, 16, 3)).astype(np.float32)
    return pos, tri, attr, tex


def test_instanced_gradients_equal_per_image_calls(ctx):
    # pos's gradient of image b is image b's alone; attr's and tex's are the sum over the images.
    h, w, images = 21, 19, 4
    pos, tri, attr, tex = scene_for_gradients(images)
    weights = upstream(images, h, w, 1)
    batch = leaves(pos, attr, tex)
    chain(ctx, batch[0], torch.from_numpy(tri), batch[1], batch[2], h, w, weights).backward()
    sums = [np.zeros_like(pos), np.zeros_like(attr), np.zeros_like(tex)]
    for b in range(images):
        one = leaves(pos[b:b + 1], attr, tex)
        chain(ctx, one[0], torch.from_numpy(tri), one[1], one[2], h, w, [x[b:b + 1] for x in weights]).backward()
        sums[0][b] = one[0].grad.numpy()[0]
        sums[1] += one[1].grad.numpy()
        sums[2] += one[2].grad.numpy()
    for name, leaf, expected in zip(("pos", "attr", "tex"), batch, sums):
        assert_close_rel(leaf.grad.numpy(), expected, name)


def test_range_gradients_equal_per_range_calls(ctx):
    # Ranges share pos: every gradient is the sum over the ranges, each range's ids counted from its start.
    h, w = 29, 23
    pos, tri, attr, tex = scene_for_gradients(1)
    pos = pos[0]
    ranges = np.array([[0, 21], [15, 6], [3, 0], [20, 1]], np.int32)
    weights = upstream(len(ranges), h, w, 2)
    batch = leaves(pos, attr, tex)
    chain(ctx, batch[0], torch.from_numpy(tri), batch[1], batch[2], h, w, weights, ranges=ranges).backward()
    sums = [np.zeros_like(pos), np.zeros_like(attr), np.zeros_like(tex)]
    for k, (start, count) in enumerate(ranges):
        one = leaves(pos, attr, tex)
        sub = torch.from_numpy(np.ascontiguousarray(tri[start:start + count]))
        chain(ctx, one[0], sub, one[1], one[2], h, w, [x[k:k + 1] for x in weights]).backward()
        for s, leaf in zip(sums, one):
            s += leaf.grad.numpy()
    for name, leaf, expected in zip(("pos", "attr", "tex"), batch, sums):
        assert_close_rel(leaf.grad.numpy(), expected, name)
