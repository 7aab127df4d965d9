"""clraster.rasterize on crafted triangles: ids exactly the scalar oracle's
(tests/reference_raster.cpp) and barycentrics, z/w and rast_db against the
perspective-correct formula evaluated in numpy (float64)."""
import os

import numpy as np

import clraster
from conftest import oracle_ids


def pixel_centres(height, width):
    y, x = np.mgrid[0:height, 0:width]
    return (2.0 * x + 1.0) / width - 1.0, (2.0 * y + 1.0) / height - 1.0


def perspective_weights(clip, xn, yn):
    """λ of the three clip vertices at NDC (xn, yn): λ ∝ adj(M)·(xn, yn, 1)
    with M's columns (x_i, y_i, w_i); also their derivatives per NDC unit."""
    p = [np.array([c[0], c[1], c[3]], np.float64) for c in clip]
    r = [np.cross(p[1], p[2]), np.cross(p[2], p[0]), np.cross(p[0], p[1])]
    k = [ri[0] * xn + ri[1] * yn + ri[2] for ri in r]
    s = k[0] + k[1] + k[2]
    lam = [ki / s for ki in k]
    sx, sy = sum(ri[0] for ri in r), sum(ri[1] for ri in r)
    dx = [(r[i][0] - lam[i] * sx) / s for i in range(3)]
    dy = [(r[i][1] - lam[i] * sy) / s for i in range(3)]
    return lam, dx, dy


def crafted_scene(seed, count=40):
    """Random triangles in clip space with w in [0.5, 3], some crossing the
    near plane (z < -w), some behind the eye (w < 0), some reaching far beyond
    the viewport (guard-band clipping), both windings."""
    rng = np.random.default_rng(seed)
    pos = np.empty((3 * count, 4), np.float32)
    w = rng.uniform(0.5, 3.0, 3 * count)
    pos[:, 0] = rng.uniform(-1.3, 1.3, 3 * count) * w
    pos[:, 1] = rng.uniform(-1.3, 1.3, 3 * count) * w
    pos[:, 2] = rng.uniform(-0.9, 0.9, 3 * count) * w
    pos[:, 3] = w
    pos[3:6, 2] = [-2.0 * pos[3, 3], 0.1, 0.2]  # one vertex before the near plane
    pos[6:9, 3] = [-0.5, 1.0, 1.0]  # one vertex behind the eye
    pos[9:12, 0] = [-5000.0, 4000.0, 0.0]  # beyond the guard band
    tri = np.arange(3 * count, dtype=np.int32).reshape(count, 3)
    return pos, tri


def test_ids_match_the_oracle_exactly(ctx, helper, tmp_path):
    for seed, (h, w) in zip(range(4), [(64, 64), (37, 91), (128, 40), (1, 1)]):
        pos, tri = crafted_scene(seed)
        rast, _ = clraster.rasterize(ctx, pos, tri, (h, w))
        ids = clraster.triangle_ids(rast)[0]
        expected = oracle_ids(helper, tmp_path, pos, tri, h, w)
        assert (ids == expected).all(), f"seed {seed}: {(ids != expected).sum()} pixels differ"
        assert (h, w) == (1, 1) or (expected > 0).sum() > h * w // 4  # the scene covers something


def test_shared_edges_are_watertight(ctx, helper, tmp_path):
    # A fan of 64 thin triangles around the centre: every pixel covered once.
    n = 64
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    ring = np.stack([3 * np.cos(angles), 3 * np.sin(angles), np.zeros(n), np.ones(n)], 1)
    pos = np.vstack([[0.013, -0.021, 0.0, 1.0], ring]).astype(np.float32)
    tri = np.array([[0, 1 + i, 1 + (i + 1) % n] for i in range(n)], np.int32)
    rast, _ = clraster.rasterize(ctx, pos, tri, (50, 70))
    ids = clraster.triangle_ids(rast)[0]
    assert (ids > 0).all()
    assert (ids == oracle_ids(helper, tmp_path, pos, tri, 50, 70)).all()


def test_barycentrics_depth_and_derivatives(ctx):
    # One perspective triangle (w from 1 to 4), fully inside the view.
    clip = np.array([[-0.8, -0.7, 0.2, 1.0], [3.0, -2.4, 1.0, 4.0], [0.3, 2.2, 0.5, 2.5]], np.float32)
    tri = np.array([[0, 1, 2]], np.int32)
    h, w = 48, 64
    rast, db = clraster.rasterize(ctx, clip, tri, (h, w))
    xn, yn = pixel_centres(h, w)
    lam, dx, dy = perspective_weights(clip, xn, yn)
    covered = rast[0, ..., 3] == 1.0
    assert covered.sum() > 300
    # Tolerances: the pipeline gets λ from fixed-point screen barycentrics
    # (positions snapped to 1/256 pixel) and float32 1/w; 2e-3 bounds that
    # on this triangle, whose extent is 40 pixels.
    assert np.abs(rast[0, ..., 0] - lam[0])[covered].max() < 2e-3
    assert np.abs(rast[0, ..., 1] - lam[1])[covered].max() < 2e-3
    zw = sum(lam[i] * clip[i, 2] for i in range(3)) / sum(lam[i] * clip[i, 3] for i in range(3))
    assert np.abs(rast[0, ..., 2] - zw)[covered].max() < 2e-3
    # rast_db is per pixel step: d/dX = d/dx_ndc · 2/W (float32 vs float64: 1e-4 relative).
    for channel, ref in enumerate([dx[0] * 2 / w, dy[0] * 2 / h, dx[1] * 2 / w, dy[1] * 2 / h]):
        err = np.abs(db[0, ..., channel] - ref)[covered]
        assert err.max() < 1e-4 * (np.abs(ref[covered]).max() + 1e-3)
    assert (rast[0][~covered] == 0).all() and (db[0][~covered] == 0).all()


def test_clipped_triangle_weights_are_of_the_input_vertices(ctx):
    # Vertex 0 lies behind the eye: clipping makes sub-triangles, whose
    # weights rast still gives for the input triangle's own vertices.
    clip = np.array([[0.2, 0.1, -1.5, -0.5], [-1.0, -0.8, 0.5, 1.0], [1.2, -0.6, 0.6, 1.2]], np.float32)
    tri = np.array([[0, 1, 2]], np.int32)
    rast, _ = clraster.rasterize(ctx, clip, tri, (40, 40))
    xn, yn = pixel_centres(40, 40)
    lam, _, _ = perspective_weights(clip, xn, yn)
    covered = rast[0, ..., 3] == 1.0
    assert covered.sum() > 100
    assert np.abs(rast[0, ..., 0] - lam[0])[covered].max() < 5e-3
    assert np.abs(rast[0, ..., 1] - lam[1])[covered].max() < 5e-3


def test_nearest_wins_and_ties_go_to_the_lower_index(ctx, helper, tmp_path):
    quad = np.array([[-1, -1, 0, 1], [1, -1, 0, 1], [-1, 1, 0, 1]], np.float32)
    for z_first, z_second, winner in [(0.5, 0.2, 2), (0.2, 0.5, 1), (0.3, 0.3, 1)]:
        pos = np.vstack([quad, quad]).copy()
        pos[:3, 2], pos[3:, 2] = z_first, z_second
        tri = np.array([[0, 1, 2], [3, 4, 5]], np.int32)
        rast, _ = clraster.rasterize(ctx, pos, tri, (16, 16))
        ids = clraster.triangle_ids(rast)[0]
        assert (ids[ids > 0] == winner).all()
        assert (ids == oracle_ids(helper, tmp_path, pos, tri, 16, 16)).all()


def test_non_finite_vertices_cull_their_triangles(ctx, helper, tmp_path):
    pos, tri = crafted_scene(7)
    pos[0, 0] = np.nan
    pos[4, 3] = np.inf
    pos[8, 1] = -np.inf
    rast, _ = clraster.rasterize(ctx, pos, tri, (64, 64))
    ids = clraster.triangle_ids(rast)[0]
    assert not np.isin(ids, [1, 2, 3]).any()
    assert (ids == oracle_ids(helper, tmp_path, pos, tri, 64, 64)).all()
    assert np.isfinite(rast).all()


def test_instanced_batch_is_one_image_per_entry(ctx):
    pos0, tri = crafted_scene(11)
    pos1, _ = crafted_scene(12)
    batch = np.stack([pos0, pos1, pos0])
    rast, db = clraster.rasterize(ctx, batch, tri, (32, 48))
    assert rast.shape == (3, 32, 48, 4) and db.shape == (3, 32, 48, 4)
    single0, _ = clraster.rasterize(ctx, pos0, tri, (32, 48))
    single1, _ = clraster.rasterize(ctx, pos1, tri, (32, 48))
    assert single0.shape == (1, 32, 48, 4)
    assert np.array_equal(rast[0], single0[0]) and np.array_equal(rast[2], single0[0])
    assert np.array_equal(rast[1], single1[0])
    _, no_db = clraster.rasterize(ctx, pos0, tri, (32, 48), grad_db=False)
    assert no_db.shape == (1, 32, 48, 0)


def test_empty_inputs_give_background(ctx):
    pos = np.zeros((0, 4), np.float32)
    tri = np.zeros((0, 3), np.int32)
    rast, db = clraster.rasterize(ctx, pos, tri, (5, 7))
    assert rast.shape == (1, 5, 7, 4) and not rast.any() and not db.any()
    rast, _ = clraster.rasterize(ctx, np.zeros((0, 3, 4), np.float32), np.zeros((1, 3), np.int32), (2, 2))
    assert rast.shape == (0, 2, 2, 4)


def test_triangle_ids_decode_nvdiffrast_encoding_exactly():
    ids = np.array([0, 1, 2, 16777215, 16777216, 16777217, 16777219, 123456789, 600000000], np.int64)
    enc = np.where(ids <= 0x01000000, ids.astype(np.float32), (ids + 0x4A800000).astype(np.int32).view(np.float32))
    rast = np.zeros((1, 1, len(ids), 4), np.float32)
    rast[0, 0, :, 3] = enc
    assert (clraster.triangle_ids(rast)[0, 0] == ids).all()


def test_threads_with_own_or_shared_contexts_agree(ctx):
    """The calls release the GIL: threads with their own Context run at once,
    threads sharing one take turns; every result is the single thread's."""
    import threading

    pos, tri = crafted_scene(11, count=200)
    want, want_db = clraster.rasterize(ctx, pos, tri, (64, 96))
    own = [clraster.Context(os.environ.get("CLRASTER_TEST_DEVICE")) for _ in range(2)]
    results = []

    def work(c):
        for _ in range(3):
            results.append(clraster.rasterize(c, pos, tri, (64, 96)))

    threads = [threading.Thread(target=work, args=(c,)) for c in own + [ctx, ctx]]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 12
    for rast, db in results:
        assert np.array_equal(rast, want) and np.array_equal(db, want_db)
