"""clraster.torch.texture against a float64 numpy transcription of
nvdiffrast's sampling rules (texel centres, wrap/clamp/zero boundaries,
2×2 mean mip levels, the footprint's major axis as level): the forward
within float32 rounding, and every backward (tex through every mip level,
uv, uv_da, mip_level_bias) against central differences of that reference,
for every filter and boundary mode."""
import numpy as np
import pytest
import torch

import clraster.torch as dr
from gradref import assert_close, central_differences

FILTERS = ["nearest", "linear", "linear-mipmap-nearest", "linear-mipmap-linear"]
BOUNDARIES = ["wrap", "clamp", "zero"]
# float32 kernels against float64: bilinear weights and level fractions
# in float32 carry ~1e-6 relative error, amplified by the texel scale (8)
# in uv's gradient; 1e-3 of the largest component bounds both.
REL = 1e-3


def ref_mips(tex, max_level):
    levels = [tex]
    while len(levels) - 1 < max_level:
        t = levels[-1]
        h, w = t.shape[1:3]
        if (h == 1 and w == 1) or (h > 1 and h % 2) or (w > 1 and w % 2):
            break
        if h == 1:
            t = 0.5 * (t[:, :, 0::2] + t[:, :, 1::2])
        elif w == 1:
            t = 0.5 * (t[:, 0::2] + t[:, 1::2])
        else:
            t = 0.25 * (t[:, 0::2, 0::2] + t[:, 0::2, 1::2] + t[:, 1::2, 0::2] + t[:, 1::2, 1::2])
        levels.append(t)
    return levels


def ref_bilinear(level, uv, boundary):
    """level [1, h, w, C], uv [N, 2]: [N, C]."""
    h, w = level.shape[1:3]
    u, v = uv[:, 0].copy(), uv[:, 1].copy()
    if boundary == "wrap":
        u, v = u - np.floor(u), v - np.floor(v)
    x, y = u * w - 0.5, v * h - 0.5
    cu = cv = np.zeros(len(u), bool)
    if boundary == "clamp":
        x, y = np.clip(x, 0, w - 1), np.clip(y, 0, h - 1)
        cu, cv = (x == 0) | (x == w - 1), (y == 0) | (y == h - 1)
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    x1, y1 = x0 + ~cu, y0 + ~cv
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]
    if boundary == "wrap":
        x0, y0, x1, y1 = x0 % w, y0 % h, x1 % w, y1 % h

    def fetch(i, j):
        ok = (i >= 0) & (i < w) & (j >= 0) & (j < h)
        return np.where(ok[:, None], level[0, np.clip(j, 0, h - 1), np.clip(i, 0, w - 1)], 0.0)

    top = fetch(x0, y0) * (1 - fx) + fetch(x1, y0) * fx
    bottom = fetch(x0, y1) * (1 - fx) + fetch(x1, y1) * fx
    return top * (1 - fy) + bottom * fy


def ref_texture(tex, uv, uv_da, bias, filter_mode, boundary, max_level=99):
    flat = uv.reshape(-1, 2)
    h, w = tex.shape[1:3]
    if filter_mode == "nearest":
        shifted = flat + np.array([0.5 / w, 0.5 / h])  # floor(u · w) is the bilinear x0 of u + 0.5 / w
        if boundary == "clamp":
            u = np.clip(np.floor((flat[:, 0]) * w), 0, w - 1).astype(int)
            v = np.clip(np.floor((flat[:, 1]) * h), 0, h - 1).astype(int)
            return tex[0, v, u].reshape(uv.shape[:3] + (-1,))
        lv = tex[:, :, :, :]
        x = shifted[:, 0] - (np.floor(shifted[:, 0]) if boundary == "wrap" else 0)
        y = shifted[:, 1] - (np.floor(shifted[:, 1]) if boundary == "wrap" else 0)
        i, j = np.floor(x * w - 0.5).astype(int), np.floor(y * h - 0.5).astype(int)
        if boundary == "wrap":
            i, j = i % w, j % h
        ok = (i >= 0) & (i < w) & (j >= 0) & (j < h)
        out = np.where(ok[:, None], lv[0, np.clip(j, 0, h - 1), np.clip(i, 0, w - 1)], 0.0)
        return out.reshape(uv.shape[:3] + (-1,))
    mips = ref_mips(tex, max_level if filter_mode.startswith("linear-mipmap") else 0)
    top = len(mips) - 1
    level = np.zeros(len(flat))
    if uv_da is not None:
        d = uv_da.reshape(-1, 4)
        dsdx, dsdy, dtdx, dtdy = d[:, 0] * w, d[:, 1] * w, d[:, 2] * h, d[:, 3] * h
        a, b, c = dsdx**2 + dtdx**2, dsdy**2 + dtdy**2, dsdx * dsdy + dtdx * dtdy
        l2b = 0.5 * (a + b)
        level = 0.5 * np.log2(l2b + np.sqrt(0.25 * (a - b) ** 2 + c**2))
    if bias is not None:
        level = level + bias.reshape(-1)
    level = np.clip(level, 0, top)
    l0 = np.floor(level).astype(int)
    frac = level - l0 if filter_mode == "linear-mipmap-linear" else np.zeros(len(flat))
    out = np.zeros((len(flat), tex.shape[3]))
    for k in range(top + 1):
        sel = l0 == k
        if sel.any():
            a = ref_bilinear(mips[k], flat[sel], boundary)
            if k < top:
                a = a * (1 - frac[sel, None]) + ref_bilinear(mips[k + 1], flat[sel], boundary) * frac[sel, None]
            out[sel] = a
    return out.reshape(uv.shape[:3] + (-1,))


def inputs(seed):
    rng = np.random.default_rng(seed)
    tex = rng.uniform(0, 1, (1, 8, 8, 2))
    uv = rng.uniform(-0.3, 1.3, (1, 5, 6, 2))
    # Footprints from a quarter texel to 16 texels: levels below 0, across 0..3 and above.
    scale = 2.0 ** rng.uniform(-2, 4, (1, 5, 6, 1)) / 8
    uv_da = rng.standard_normal((1, 5, 6, 4)) * scale
    bias = rng.uniform(-1, 1, (1, 5, 6))
    return tex, uv, uv_da, bias


@pytest.mark.parametrize("boundary", BOUNDARIES)
@pytest.mark.parametrize("filter_mode", FILTERS)
def test_forward_and_gradients(ctx, filter_mode, boundary):
    tex, uv, uv_da, bias = inputs(FILTERS.index(filter_mode) * 3 + BOUNDARIES.index(boundary))
    mip = filter_mode.startswith("linear-mipmap")
    t = [torch.tensor(x, dtype=torch.float32, requires_grad=True) for x in (tex, uv, uv_da, bias)]
    out = dr.texture(t[0], t[1], uv_da=t[2] if mip else None, mip_level_bias=t[3] if mip else None,
                     filter_mode=filter_mode, boundary_mode=boundary)
    f32 = [x.astype(np.float32).astype(np.float64) for x in (tex, uv, uv_da, bias)]
    want = ref_texture(f32[0], f32[1], f32[2] if mip else None, f32[3] if mip else None, filter_mode, boundary)
    assert out.shape == (1, 5, 6, 2)
    assert np.abs(out.detach().numpy() - want).max() < 1e-5
    wo = np.random.default_rng(1).standard_normal(out.shape)
    (out * torch.from_numpy(wo).float()).sum().backward()

    def loss(i):
        def f(x):
            args = list(f32)
            args[i] = x
            return (ref_texture(args[0], args[1], args[2] if mip else None, args[3] if mip else None, filter_mode,
                                boundary) * wo).sum()
        return f

    assert_close(t[0].grad.numpy(), central_differences(loss(0), f32[0].copy(), 1e-5), REL, "d loss / d tex")
    if filter_mode == "nearest":
        assert (t[1].grad.numpy() == 0).all()
        return
    assert_close(t[1].grad.numpy(), central_differences(loss(1), f32[1].copy(), 1e-6), REL, "d loss / d uv")
    if filter_mode == "linear-mipmap-linear":
        assert_close(t[2].grad.numpy(), central_differences(loss(2), f32[2].copy(), 1e-7), REL, "d loss / d uv_da")
        assert_close(t[3].grad.numpy(), central_differences(loss(3), f32[3].copy(), 1e-6), REL, "d loss / d bias")
    elif mip:
        assert (t[2].grad.numpy() == 0).all() and (t[3].grad.numpy() == 0).all()


def test_constructed_mip_matches_the_built_one(ctx):
    tex, uv, uv_da, _ = inputs(20)
    mip = dr.texture_construct_mip(torch.tensor(tex, dtype=torch.float32))
    a = dr.texture(tex.astype(np.float32), uv.astype(np.float32), uv_da=uv_da.astype(np.float32), mip=mip)
    b = dr.texture(tex.astype(np.float32), uv.astype(np.float32), uv_da=uv_da.astype(np.float32))
    assert torch.equal(a, b)
    levels = ref_mips(tex.astype(np.float32).astype(np.float64), 99)
    assert len(levels) == 4
    want = np.concatenate([lv.reshape(-1) for lv in levels[1:]])
    assert np.abs(mip.levels - want).max() < 1e-6
    with pytest.raises(ValueError, match="^mip: "):
        dr.texture(tex[:, :4, :4].astype(np.float32), uv.astype(np.float32), uv_da=uv_da.astype(np.float32), mip=mip)


def test_bad_modes_are_named(ctx):
    tex, uv, _, _ = inputs(21)
    with pytest.raises(ValueError, match="^filter_mode: "):
        dr.texture(tex, uv, filter_mode="cubic")
    with pytest.raises(ValueError, match="^filter_mode: "):
        dr.texture(tex, uv, filter_mode="linear-mipmap-linear")
    with pytest.raises(ValueError, match="^boundary_mode: "):
        dr.texture(tex, uv, boundary_mode="mirror")
    with pytest.raises(ValueError, match="^uv: "):
        dr.texture(tex, uv[..., :1])


@pytest.mark.parametrize("boundary", BOUNDARIES)
def test_non_finite_and_huge_uv_read_within_the_texture(ctx, boundary):
    tex = torch.rand(1, 4, 4, 1, requires_grad=True)
    uv = torch.tensor([[[[np.nan, 0.5], [np.inf, -np.inf], [1e30, -1e30], [0.5, 0.5]]]], dtype=torch.float32,
                      requires_grad=True)
    for mode in FILTERS:
        kwargs = dict(mip_level_bias=torch.zeros(1, 1, 4)) if mode.startswith("linear-mipmap") else {}
        out = dr.texture(tex, uv, filter_mode=mode, boundary_mode=boundary, **kwargs)
        assert out[0, 0, :2].abs().sum() == 0  # non-finite: zero
        assert torch.isfinite(out).all()
        out.sum().backward()
        assert torch.isfinite(tex.grad).all() and torch.isfinite(uv.grad[0, 0, 2:]).all()


def ref_cube_face(d):
    """Face and (s, t) of one direction, nvdiffrast's cube convention
    written out per face (face 0..5 = +x, -x, +y, -y, +z, -z)."""
    x, y, z = d
    if abs(z) > max(abs(x), abs(y)):
        return (4, x / (2 * z) + 0.5, -y / (2 * z) + 0.5) if z > 0 else (5, x / (2 * z) + 0.5, y / (2 * z) + 0.5)
    if abs(y) > abs(x):
        return (2, x / (2 * y) + 0.5, z / (2 * y) + 0.5) if y > 0 else (3, -x / (2 * y) + 0.5, z / (2 * y) + 0.5)
    return (0, -z / (2 * x) + 0.5, -y / (2 * x) + 0.5) if x > 0 else (1, -z / (2 * x) + 0.5, y / (2 * x) + 0.5)


def ref_cube_texel(tex, f, i, j):
    """Texel (row i, column j) of face f, continued across the face's edges
    onto the neighbouring face (through the texel centre's direction), a
    corner beyond both edges the mean of the other three of its quad."""
    n = tex.shape[1]
    out_i, out_j = not 0 <= i < n, not 0 <= j < n
    if not out_i and not out_j:
        return tex[f, i, j]
    if out_i and out_j:
        i1, j1 = min(max(i, 0), n - 1), min(max(j, 0), n - 1)
        return (ref_cube_texel(tex, f, i1, j1) + ref_cube_texel(tex, f, i, j1) + ref_cube_texel(tex, f, i1, j)) / 3
    a, b = 2 * (j + 0.5) / n - 1, 2 * (i + 0.5) / n - 1
    d = [(1, -b, -a), (-1, -b, a), (a, 1, b), (a, -1, -b), (a, -b, 1), (-a, -b, -1)][f]
    f2, s, t = ref_cube_face(d)
    return tex[f2, min(int(t * n), n - 1), min(int(s * n), n - 1)]


def ref_cube(tex, dirs, filter_mode):
    """tex [6, n, n, C], dirs [N, 3], float64: [N, C]."""
    n = tex.shape[1]
    out = np.zeros((len(dirs), tex.shape[3]))
    for k, d in enumerate(dirs):
        f, s, t = ref_cube_face(d)
        s, t = min(max(s, 0.0), 1.0), min(max(t, 0.0), 1.0)
        if filter_mode == "nearest":
            out[k] = tex[f, min(int(np.floor(t * n)), n - 1), min(int(np.floor(s * n)), n - 1)]
            continue
        u, v = s * n - 0.5, t * n - 0.5
        j, i = int(np.floor(u)), int(np.floor(v))
        fu, fv = u - j, v - i
        q = [ref_cube_texel(tex, f, i + di, j + dj) for di in (0, 1) for dj in (0, 1)]
        out[k] = (q[0] * (1 - fu) + q[1] * fu) * (1 - fv) + (q[2] * (1 - fu) + q[3] * fu) * fv
    return out


@pytest.mark.parametrize("filter_mode", ["nearest", "linear"])
def test_cube_map_forward_and_gradients(filter_mode):
    # Directions of every face, many within a texel of an edge or a corner (where the neighbouring faces' texels
    # are read); tex and uv gradients against central differences of the float64 reference.
    rng = np.random.default_rng(4)
    n, channels = 4, 2
    tex = rng.uniform(0, 1, (6, n, n, channels))
    dirs = rng.standard_normal((60, 3))
    near_edge = rng.standard_normal((60, 3))
    near_edge[:, 0] = np.sign(near_edge[:, 0]) * np.abs(near_edge).max(1) * rng.uniform(0.9, 0.999, 60)
    dirs = np.vstack([dirs, near_edge, [[1, 1, 0.999], [-1, 0.999, -1], [0.5, -0.5, 0.5]]])
    weights = rng.standard_normal((len(dirs), channels))
    t_tex = torch.tensor(tex[None].astype(np.float32), requires_grad=True)
    t_uv = torch.tensor(dirs.reshape(1, 1, -1, 3).astype(np.float32), requires_grad=True)
    out = dr.texture(t_tex, t_uv, filter_mode=filter_mode, boundary_mode="cube")
    (out[0, 0] * torch.from_numpy(weights).float()).sum().backward()
    dirs32 = dirs.astype(np.float32).astype(np.float64)
    want = ref_cube(tex, dirs32, filter_mode)
    assert np.abs(out.detach().numpy()[0, 0] - want).max() < 1e-5
    # tex: the loss is linear in tex; central differences of the reference.
    g_tex = central_differences(lambda t: (ref_cube(t, dirs32, filter_mode) * weights).sum(), tex.copy(), 1e-3)
    assert_close(t_tex.grad.numpy()[0], g_tex, REL, "tex")
    if filter_mode == "nearest":
        assert np.abs(t_uv.grad.numpy()).max() == 0  # piecewise constant
        return
    # uv: per direction and component (each output reads its own direction only).
    eps = 1e-6
    g_uv = np.zeros_like(dirs32)
    for c in range(3):
        up, down = dirs32.copy(), dirs32.copy()
        up[:, c] += eps
        down[:, c] -= eps
        g_uv[:, c] = ((ref_cube(tex, up, filter_mode) - ref_cube(tex, down, filter_mode)) * weights).sum(1) / (2 * eps)
    assert_close(t_uv.grad.numpy()[0, 0], g_uv, REL, "uv")


def test_cube_map_refuses_mipmaps_and_wrong_shapes():
    tex, uv = torch.zeros(1, 6, 4, 4, 3), torch.ones(1, 2, 2, 3)
    with pytest.raises(ValueError, match="filter_mode"):
        dr.texture(tex, uv, uv_da=torch.zeros(1, 2, 2, 6), boundary_mode="cube")
    with pytest.raises(ValueError, match="tex"):
        dr.texture(torch.zeros(1, 6, 4, 5, 3), uv, filter_mode="linear", boundary_mode="cube")
    with pytest.raises(ValueError, match="uv"):
        dr.texture(tex, torch.ones(1, 2, 2, 2), filter_mode="linear", boundary_mode="cube")
