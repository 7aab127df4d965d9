"""clraster.torch: nvdiffrast.torch's differentiable operations on CPU tensors.

    import clraster.torch as dr        # was: import nvdiffrast.torch as dr
    glctx = dr.RasterizeCudaContext()  # or dr.RasterizeGLContext(), dr.Context()
    rast, rast_db = dr.rasterize(glctx, pos, tri, resolution=[H, W])
    out, out_da = dr.interpolate(attr, rast, tri, rast_db=rast_db, diff_attrs='all')

Each operation is a torch.autograd.Function: the forward runs clraster's
rasterizer (the numpy module's calls), the backward runs OpenCL kernels
(kernels/diff.cl) on the same device. Gradients follow nvdiffrast: those of
the forward formulas at the pixel centres with coverage held fixed. Where
clraster differs (the rasterize gradient also flows through z/w; coverage
rules): docs/nvdiffrast.md.

Inputs may be torch tensors, numpy arrays, or anything with __array__ or
__dlpack__; float64 and int64 are converted, with a ValueError naming the
argument only where the conversion would lose information (a finite value
beyond float32's range, an index beyond int32's). Outputs are float32 CPU
tensors.
"""

import numbers

import numpy as np
import torch

from . import _clraster
from . import ArgumentTypeError, Context, Error  # noqa: F401  (re-exported)
from . import _MAX_RESOLUTION, _check_rast_ids, _diff_list, triangle_ids  # noqa: F401
from . import rasterize as np_rasterize

__all__ = ["Context", "RasterizeCudaContext", "RasterizeGLContext", "Error", "rasterize", "interpolate", "texture",
           "texture_construct_mip", "TextureMip", "DepthPeeler", "antialias", "antialias_construct_topology_hash", "TopologyHash",
           "triangle_ids", "set_default_context", "get_log_level", "set_log_level"]

_default = None
_log_level = 1  # nvdiffrast's levels: 0 info, 1 warning (its default), 2 error, 3 fatal


class RasterizeCudaContext(Context):
    """nvdiffrast's context classes map to a clraster Context on the default
    OpenCL device (the first GPU, else the first CPU). A torch device
    argument (tensors here live on the CPU) is ignored; a clraster device
    selector (an index or a name substring) picks that device."""

    def __init__(self, device=None, **_nvdiffrast_options):
        if isinstance(device, torch.device) or (isinstance(device, str) and device.split(":")[0] in ("cuda", "cpu")):
            device = None
        super().__init__(device)
        set_default_context(self)


RasterizeGLContext = RasterizeCudaContext


def set_default_context(glctx):
    """The Context that interpolate's backward (which takes none) runs on;
    set by every rasterize call and context construction."""
    global _default
    if not isinstance(glctx, Context):
        raise ArgumentTypeError(f"glctx: expected a clraster.Context, got {type(glctx).__name__}")
    _default = glctx


def get_log_level():
    """nvdiffrast's log level, 0 (info) to 3 (fatal); 1 until set."""
    return _log_level


def set_log_level(level):
    """Sets the level get_log_level returns. clraster.torch writes no log
    lines at any level (problems raise exceptions), so the level changes no
    output; it is kept so that scripts which set it run unchanged."""
    global _log_level
    if isinstance(level, bool) or not isinstance(level, (int, np.integer)):
        raise ArgumentTypeError(f"level: expected an int from 0 to 3, got {type(level).__name__}")
    if not 0 <= int(level) <= 3:
        raise ValueError(f"level: {int(level)} outside [0, 3] (0 info, 1 warning, 2 error, 3 fatal)")
    _log_level = int(level)


def _context():
    global _default
    if _default is None:
        _default = Context()
    return _default


def _to_tensor(name, value):
    """value as a torch tensor: itself, through DLPack, or through __array__."""
    if isinstance(value, torch.Tensor):
        return value
    if hasattr(value, "__dlpack__") and not isinstance(value, np.ndarray):
        return torch.utils.dlpack.from_dlpack(value)
    if isinstance(value, np.ndarray) or hasattr(value, "__array__"):
        return torch.as_tensor(np.asarray(value))
    raise ArgumentTypeError(f"{name}: expected a tensor or an array, got {type(value).__name__}")


def _floats(name, t):
    """t (a tensor) as a C-contiguous float32 numpy array."""
    if not (t.dtype.is_floating_point or t.dtype in (torch.int32, torch.int64, torch.int16, torch.uint8)):
        raise ValueError(f"{name}: expected a floating-point tensor, got {t.dtype}")
    a = t.detach().to("cpu").numpy()
    with np.errstate(over="ignore"):  # checked just below
        out = np.ascontiguousarray(a, np.float32)
    if a.dtype != np.float32 and a.size and (np.isfinite(a) & ~np.isfinite(out)).any():
        raise ValueError(f"{name}: a finite value beyond float32's range ({a.dtype.name} converts with loss)")
    if a.dtype.kind in "iu" and a.size and np.abs(a.astype(np.int64)).max() > 2**24:
        raise ValueError(f"{name}: an integer beyond 2^24, which float32 cannot hold exactly")
    return out


def _indices(name, t):
    """t as a C-contiguous int32 numpy array (integers only, within int32)."""
    if t.dtype.is_floating_point or t.dtype == torch.bool or t.is_complex():
        raise ValueError(f"{name}: expected an integer tensor, got {t.dtype}")
    a = t.detach().to("cpu").numpy()
    if a.dtype != np.int32 and a.size and (a.min() < -(2**31) or a.max() >= 2**31):
        raise ValueError(f"{name}: an index beyond int32's range ({a.dtype.name} converts with loss)")
    return np.ascontiguousarray(a, np.int32)


def _check_tri(tri, num_vertices):
    if tri.ndim != 2 or tri.shape[1] != 3:
        raise ValueError(f"tri: expected shape [T, 3], got {list(tri.shape)}")
    if tri.size and (tri.min() < 0 or tri.max() >= num_vertices):
        bad = int(tri.min()) if tri.min() < 0 else int(tri.max())
        raise ValueError(f"tri: vertex index {bad} outside [0, {num_vertices})")


def _resolution(resolution):
    try:
        height, width = resolution
    except (TypeError, ValueError):
        raise ArgumentTypeError(f"resolution: expected (height, width), got {resolution!r}") from None
    out = []
    for n in (height, width):
        if isinstance(n, torch.Tensor) and n.numel() == 1 and not n.dtype.is_floating_point:
            n = int(n)
        if isinstance(n, bool) or not isinstance(n, numbers.Integral):
            raise ArgumentTypeError(f"resolution: expected two integers, got {resolution!r}")
        if not 1 <= n <= _MAX_RESOLUTION:
            raise ValueError(f"resolution: expected two integers in 1..{_MAX_RESOLUTION}, got {resolution!r}")
        out.append(int(n))
    return out


def _encode_ids(ids):
    """nvdiffrast's float encoding of triangle id + 1 (rast channel 3)."""
    ids = ids.astype(np.int64)
    small = ids.astype(np.float32)
    big = (ids + 0x4A800000).astype(np.uint32).view(np.float32)
    return np.where(ids <= 0x01000000, small, big).astype(np.float32)


def _rasterize_forward(glctx, pos, tri, resolution, ranges, grad_db):
    """(rast, db) float32 numpy [B, H, W, 4] (db [B, H, W, 0] without grad_db);
    range mode in one frame for all ranges, as instanced mode."""
    height, width = resolution
    if ranges is None:
        return np_rasterize(glctx, pos, tri, (height, width), grad_db=grad_db)
    with glctx._lock:
        _clraster.check_rasterize_memory(glctx._ctx, width, height, len(ranges) * height * width * (32 if grad_db else 16))
    rast = np.empty((len(ranges), height, width, 4), np.float32)
    db = np.empty((len(ranges), height, width, 4 if grad_db else 0), np.float32)
    with glctx._lock:
        _clraster.rasterize_batch(glctx._ctx, pos[None], tri, np.ascontiguousarray(ranges, np.int32), rast,
                                  db if grad_db else None)
    return rast, db


class _Rasterize(torch.autograd.Function):
    @staticmethod
    def forward(ctx, glctx, pos, tri_np, resolution, ranges_np, grad_db, peeler=None):
        pos_np = _floats("pos", pos)
        if peeler is None:
            rast, db = _rasterize_forward(glctx, pos_np, tri_np, resolution, ranges_np, grad_db)
        else:
            rast, db = peeler._next(pos_np)
        ctx.glctx, ctx.pos_np, ctx.tri_np, ctx.rast_np, ctx.grad_db = glctx, pos_np, tri_np, rast, grad_db
        ctx.pos_dtype = pos.dtype
        out = torch.from_numpy(rast), torch.from_numpy(db)
        if not grad_db:
            ctx.mark_non_differentiable(out[1])
        return out

    @staticmethod
    def backward(ctx, dy, ddb):
        if not ctx.needs_input_grad[1]:
            return None, None, None, None, None, None, None
        pos = ctx.pos_np if ctx.pos_np.ndim == 3 else ctx.pos_np[None]
        dy = np.ascontiguousarray(dy.detach().numpy(), np.float32)
        ddb = np.ascontiguousarray(ddb.detach().numpy(), np.float32) if ctx.grad_db and ddb is not None else None
        with ctx.glctx._lock:
            g = _clraster.rasterize_grad(ctx.glctx._ctx, pos, ctx.tri_np, ctx.rast_np, dy, ddb)
        g = torch.from_numpy(g.reshape(ctx.pos_np.shape)).to(ctx.pos_dtype)
        return None, g, None, None, None, None, None


def rasterize(glctx, pos, tri, resolution, ranges=None, grad_db=True):
    """nvdiffrast's rasterize: (rast, rast_db), float32 [B, H, W, 4]; rast =
    (u, v, z/w, triangle_id + 1), rast_db = (du/dX, du/dY, dv/dX, dv/dY)
    ([B, H, W, 0] with grad_db=False). pos [B, V, 4] is instanced mode;
    pos [V, 4] with ranges ([N, 2] int32 (start, count) triangle ranges,
    one image each) is range mode, triangle ids absolute; pos [V, 4]
    alone gives one image. Differentiable in pos through u, v, z/w and
    rast_db."""
    glctx, pos, tri_np, resolution, ranges_np, grad_db = _rasterize_args(glctx, pos, tri, resolution, ranges, grad_db)
    return _Rasterize.apply(glctx, pos, tri_np, resolution, ranges_np, grad_db)


def _rasterize_args(glctx, pos, tri, resolution, ranges, grad_db):
    """rasterize's arguments checked and converted (DepthPeeler takes the same)."""
    if not isinstance(glctx, Context):
        raise ArgumentTypeError(f"glctx: expected a clraster.Context, got {type(glctx).__name__}")
    if not isinstance(grad_db, (bool, np.bool_)):
        raise ArgumentTypeError(f"grad_db: expected True or False, got {type(grad_db).__name__} {grad_db!r}")
    set_default_context(glctx)
    pos = _to_tensor("pos", pos)
    if pos.dim() not in (2, 3) or pos.shape[-1] != 4:
        raise ValueError(f"pos: expected shape [V, 4] or [B, V, 4], got {list(pos.shape)}")
    tri_np = _indices("tri", _to_tensor("tri", tri))
    _check_tri(tri_np, pos.shape[-2])
    ranges_np = None
    if ranges is not None:
        if pos.dim() != 2:
            raise ValueError(f"ranges: range mode takes pos [V, 4], got {list(pos.shape)}")
        ranges_np = _indices("ranges", _to_tensor("ranges", ranges))
        if ranges_np.ndim != 2 or ranges_np.shape[1] != 2:
            raise ValueError(f"ranges: expected shape [N, 2], got {list(ranges_np.shape)}")
        if ranges_np.size and (ranges_np.min() < 0 or (ranges_np[:, 0] + ranges_np[:, 1]).max() > len(tri_np)):
            raise ValueError(f"ranges: a range reaches outside the {len(tri_np)} triangles")
    return glctx, pos, tri_np, _resolution(resolution), ranges_np, bool(grad_db)


class DepthPeeler:
    """nvdiffrast's DepthPeeler: rasterize_next_layer() gives (rast, rast_db)
    of the first layer, then of what lies behind it pixel by pixel, as
    rasterize() takes its arguments (instanced and range mode too). Layer
    0 equals rasterize's result; each later one keeps, per pixel, the
    nearest fragment strictly behind the last layer's depth (empty once
    nothing is left). Differentiable in pos as rasterize is.

        with dr.DepthPeeler(glctx, pos, tri, resolution) as peeler:
            for i in range(layers):
                rast, rast_db = peeler.rasterize_next_layer()
    """

    def __init__(self, glctx, pos, tri, resolution, ranges=None, grad_db=True):
        (self._glctx, self._pos, self._tri, self._resolution, self._ranges,
         self._grad_db) = _rasterize_args(glctx, pos, tri, resolution, ranges, grad_db)
        self._floors = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._floors = None
        return False

    def rasterize_next_layer(self):
        return _Rasterize.apply(self._glctx, self._pos, self._tri, self._resolution, self._ranges, self._grad_db,
                                self)

    def _next(self, pos_np):
        """The next layer of every image, in one frame for the batch (as rasterize)."""
        height, width = self._resolution
        pos = pos_np if pos_np.ndim == 3 else pos_np[None]
        images = len(pos) if self._ranges is None else len(self._ranges)
        if self._floors is None:
            self._floors = np.full((images, height, width), -np.inf, np.float32)
        ranges = None if self._ranges is None else np.ascontiguousarray(self._ranges, np.int32)
        with self._glctx._lock:
            rast, db, self._floors = _clraster.rasterize_peel(self._glctx._ctx, np.ascontiguousarray(pos), self._tri,
                                                              ranges, self._floors, self._grad_db)
        return rast, db


class _Interpolate(torch.autograd.Function):
    @staticmethod
    def forward(ctx, attr, rast, rast_db, tri_np, diff):
        attr_np, rast_np = _floats("attr", attr), _floats("rast", rast)
        db_np = _floats("rast_db", rast_db) if diff else None
        attrs = attr_np if attr_np.ndim == 3 else attr_np[None]
        out = np.empty(rast_np.shape[:3] + (attrs.shape[2],), np.float32)
        out_da = np.empty(rast_np.shape[:3] + (2 * len(diff),), np.float32)
        for b in range(rast_np.shape[0]):
            a = attrs[b if attrs.shape[0] > 1 else 0]
            _clraster.interpolate_into(a, rast_np[b], tri_np, out[b], db_np[b] if diff else None, diff,
                                       out_da[b] if diff else None)
        ctx.attr_np, ctx.rast_np, ctx.db_np, ctx.tri_np, ctx.diff = attr_np, rast_np, db_np, tri_np, diff
        ctx.dtypes = attr.dtype, rast.dtype, rast_db.dtype if diff else None
        return torch.from_numpy(out), torch.from_numpy(out_da)

    @staticmethod
    def backward(ctx, dy, dda):
        attrs = ctx.attr_np if ctx.attr_np.ndim == 3 else ctx.attr_np[None]
        dy = np.ascontiguousarray(dy.detach().numpy(), np.float32)
        dda = np.ascontiguousarray(dda.detach().numpy(), np.float32) if ctx.diff else None
        glctx = _context()
        with glctx._lock:
            ga, gr, gdb = _clraster.interpolate_grad(glctx._ctx, attrs, ctx.rast_np, ctx.tri_np, dy, ctx.db_np,
                                                     ctx.diff, dda)
        ga = torch.from_numpy(ga.reshape(ctx.attr_np.shape)).to(ctx.dtypes[0])
        gr = torch.from_numpy(gr).to(ctx.dtypes[1])
        gdb = torch.from_numpy(gdb).to(ctx.dtypes[2]) if ctx.diff else None
        return ga, gr, gdb, None, None


def interpolate(attr, rast, tri, rast_db=None, diff_attrs=None):
    """nvdiffrast's interpolate: (out [B, H, W, C], out_da [B, H, W, 2·len])
    with out = u·a0 + v·a1 + (1 − u − v)·a2 of the pixel's triangle (0 where
    none) and out_da = (dA/dX, dA/dY) per attribute of diff_attrs (a list of
    indices or 'all'; needs rast_db). attr [V, C] or [B, V, C] (B 1
    broadcasts). Differentiable in attr, rast (u, v) and rast_db."""
    attr, rast = _to_tensor("attr", attr), _to_tensor("rast", rast)
    if attr.dim() not in (2, 3):
        raise ValueError(f"attr: expected shape [V, C] or [B, V, C], got {list(attr.shape)}")
    if rast.dim() != 4 or rast.shape[-1] != 4:
        raise ValueError(f"rast: expected shape [B, H, W, 4], got {list(rast.shape)}")
    if attr.dim() == 3 and attr.shape[0] not in (1, rast.shape[0]):
        raise ValueError(f"attr: {attr.shape[0]} attribute sets for {rast.shape[0]} images in rast")
    tri_np = _indices("tri", _to_tensor("tri", tri))
    _check_tri(tri_np, attr.shape[-2])
    _check_rast_ids(rast.detach().numpy(), tri_np.shape[0])
    diff = _diff_list(diff_attrs, attr.shape[-1])
    if diff:
        if rast_db is None:
            raise ValueError("rast_db: needed with diff_attrs (rasterize(..., grad_db=True))")
        rast_db = _to_tensor("rast_db", rast_db)
        if tuple(rast_db.shape) != tuple(rast.shape):
            raise ValueError(f"rast_db: shape {list(rast_db.shape)} differs from rast's {list(rast.shape)}")
    else:
        rast_db = torch.zeros(0)
    return _Interpolate.apply(attr, rast, rast_db, tri_np, diff)


_FILTERS = {"nearest": 0, "linear": 1, "linear-mipmap-nearest": 2, "linear-mipmap-linear": 3}
_BOUNDARIES = {"wrap": 0, "clamp": 1, "zero": 2}


class TextureMip:
    """A mip pyramid from texture_construct_mip (levels 1.., flat), for
    texture(..., mip=...). Built for one texture shape and max_mip_level."""

    def __init__(self, levels, shape, max_mip_level):
        self.levels, self.shape, self.max_mip_level = levels, shape, max_mip_level


def _max_level(max_mip_level):
    if max_mip_level is None:
        return -1
    if isinstance(max_mip_level, bool) or not isinstance(max_mip_level, numbers.Integral) or max_mip_level < 0:
        raise ValueError(f"max_mip_level: expected None or a non-negative integer, got {max_mip_level!r}")
    return int(max_mip_level)


def _tex_array(tex):
    tex_np = _floats("tex", tex)
    if tex_np.ndim != 4:
        raise ValueError(f"tex: expected shape [B, H, W, C], got {list(tex_np.shape)}")
    return tex_np


def texture_construct_mip(tex, max_mip_level=None, cube_mode=False):
    """nvdiffrast's texture_construct_mip: the mip levels of tex [B, H, W, C]
    (each texel the mean of its 2×2 children), for texture(..., mip=).
    Gradients do not flow into a pyramid built here (texture() then
    differentiates only level 0, tex itself)."""
    if cube_mode:
        raise ValueError("cube_mode: cube maps are not supported")
    tex_np = _tex_array(_to_tensor("tex", tex))
    level = _max_level(max_mip_level)
    glctx = _context()
    with glctx._lock:
        levels = _clraster.texture_mips(glctx._ctx, tex_np, level)
    return TextureMip(levels, tex_np.shape, level)


class _Texture(torch.autograd.Function):
    @staticmethod
    def forward(ctx, tex, uv, uv_da, bias, mip, filter_mode, boundary, max_level):
        arrays = [_tex_array(tex), _floats("uv", uv), _floats("uv_da", uv_da) if uv_da is not None else None,
                  _floats("mip_level_bias", bias) if bias is not None else None]
        mips = mip.levels if mip is not None else None
        glctx = _context()
        with glctx._lock:
            out = _clraster.texture_fwd(glctx._ctx, arrays[0], mips, arrays[1], arrays[2], arrays[3], filter_mode,
                                        boundary, max_level)
        ctx.arrays, ctx.mips, ctx.modes = arrays, mips, (filter_mode, boundary, max_level)
        ctx.dtypes = [t.dtype if t is not None else None for t in (tex, uv, uv_da, bias)]
        return torch.from_numpy(out)

    @staticmethod
    def backward(ctx, dy):
        tex, uv, uv_da, bias = ctx.arrays
        dy = np.ascontiguousarray(dy.detach().numpy(), np.float32)
        glctx = _context()
        with glctx._lock:
            grads = _clraster.texture_grad(glctx._ctx, tex, ctx.mips, uv, uv_da, bias, dy, *ctx.modes)
        out = [torch.from_numpy(g).to(d) if g is not None else None for g, d in zip(grads, ctx.dtypes)]
        return out[0], out[1], out[2], out[3], None, None, None, None


def _cube_face(d):
    """nvdiffrast's cube-map lookup of directions d [..., 3] (torch or numpy,
    float): (face 0..5 = +x, -x, +y, -y, +z, -z, s, t in [0, 1]); s, t are
    NaN where d picks no face (zero or non-finite)."""
    lib = torch if isinstance(d, torch.Tensor) else np
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    ax, ay, az = abs(x), abs(y), abs(z)
    zmaj = az > lib.maximum(ax, ay)
    ymaj = ~zmaj & (ay > ax)
    c = lib.where(zmaj, z, lib.where(ymaj, y, x))
    face = lib.where(zmaj, 4, lib.where(ymaj, 2, 0)) + (c < 0) * 1
    a = lib.where(zmaj | ymaj, x, z)  # the numerators of s and t
    b = lib.where(ymaj, z, y)
    valid = c != 0
    m = 0.5 / abs(lib.where(valid, c, 1.0 + 0.0 * c))
    s = a * lib.where((face == 0) | (face == 5), -m, m) + 0.5
    t = b * lib.where(face == 2, m, -m) + 0.5
    valid = valid & lib.isfinite(s) & lib.isfinite(t)
    nan = float("nan")
    s = lib.where(valid, lib.clip(s, 0.0, 1.0) if lib is np else s.clamp(0.0, 1.0), nan)
    t = lib.where(valid, lib.clip(t, 0.0, 1.0) if lib is np else t.clamp(0.0, 1.0), nan)
    return face, s, t


_CUBE_ATLAS = {}


def _cube_atlas_sources(n):
    """The cube atlas of faces n × n: 6 faces of (n + 2)², each face's
    texels framed by the neighbouring faces' edge texels (found by mapping
    the framing texel's centre direction back onto the cube), the corners by
    the mean of the other three texels of their 2×2 quad (nvdiffrast's rule).
    Returns (src [6 (n + 2)², 3] texel indices face·n² + row·n + column,
    weight [6 (n + 2)², 3])."""
    if n in _CUBE_ATLAS:
        return _CUBE_ATLAS[n]
    face, row, col = np.meshgrid(np.arange(6), np.arange(-1, n + 1), np.arange(-1, n + 1), indexing="ij")
    a, b = 2 * (col + 0.5) / n - 1, 2 * (row + 0.5) / n - 1  # s and t at the texel centres, as -1..1
    one = np.ones_like(a)
    axes = [(one, -b, -a), (-one, -b, a), (a, one, b), (a, -one, -b), (a, -b, one), (-a, -b, -one)]
    d = np.zeros(face.shape + (3,))
    for f, (x, y, z) in enumerate(axes):
        d[face == f] = np.stack([x, y, z], -1)[face == f]
    f2, s2, t2 = _cube_face(d)
    nearest = f2 * n * n + np.minimum((t2 * n).astype(np.int64), n - 1) * n + np.minimum((s2 * n).astype(np.int64),
                                                                                         n - 1)
    src = np.repeat(nearest.reshape(-1, 1), 3, 1)
    weight = np.tile([1.0, 0.0, 0.0], (src.shape[0], 1))
    p = n + 2
    for r, c in [(0, 0), (0, p - 1), (p - 1, 0), (p - 1, p - 1)]:  # corners: the other three of the quad
        dr_, dc = (1 if r == 0 else -1), (1 if c == 0 else -1)
        for f in range(6):
            k = (f * p + r) * p + c
            src[k] = [nearest[f, r + dr_, c + dc], nearest[f, r, c + dc], nearest[f, r + dr_, c]]
            weight[k] = 1.0 / 3.0
    _CUBE_ATLAS[n] = (torch.from_numpy(src), torch.from_numpy(weight.astype(np.float32)))
    return _CUBE_ATLAS[n]


def _texture_cube(tex, uv, filter_mode):
    """Cube-map texture(): tex [B or 1, 6, n, n, C] sampled at directions uv
    [B, h, w, 3], as a 2D texture() of the framed faces stacked (clamp
    boundary: a sample never leaves its face's frame); torch autograd carries
    the gradients through the framing and the face coordinates."""
    if tex.dim() != 5 or tex.shape[1] != 6 or tex.shape[2] != tex.shape[3]:
        raise ValueError(f"tex: cube maps take shape [B, 6, n, n, C], got {list(tex.shape)}")
    if uv.dim() != 4 or uv.shape[-1] != 3:
        raise ValueError(f"uv: cube maps take directions of shape [B, H, W, 3], got {list(uv.shape)}")
    if tex.shape[0] not in (1, uv.shape[0]):
        raise ValueError(f"tex: {tex.shape[0]} textures for {uv.shape[0]} images in uv")
    n, p = tex.shape[2], tex.shape[2] + 2
    src, weight = _cube_atlas_sources(n)
    flat = tex.reshape(tex.shape[0], 6 * n * n, tex.shape[4]).float()
    atlas = (flat[:, src] * weight[None, :, :, None]).sum(2).reshape(tex.shape[0], 6 * p, p, tex.shape[4])
    face, s, t = _cube_face(uv.float())
    if filter_mode == "nearest":  # s = 1 reads the face's last texel, not its frame
        s, t = s.clamp(max=(n - 0.5) / n), t.clamp(max=(n - 0.5) / n)
    uv2 = torch.stack([(s * n + 1) / p, (face * p + t * n + 1) / (6 * p)], -1)
    return _Texture.apply(atlas, uv2.contiguous(), None, None, None, _FILTERS[filter_mode], _BOUNDARIES["clamp"], 0)


def texture(tex, uv, uv_da=None, mip_level_bias=None, mip=None, filter_mode="auto", boundary_mode="wrap",
            max_mip_level=None):
    """nvdiffrast's texture: tex [B or 1, H, W, C] sampled at uv [B, h, w, 2]
    (u along W, v along H, texel centres at (i + 0.5) / size) into
    [B, h, w, C]. filter_mode 'nearest', 'linear', 'linear-mipmap-nearest',
    'linear-mipmap-linear' or 'auto' (the last with uv_da or
    mip_level_bias, else 'linear'); boundary_mode 'wrap', 'clamp', 'zero' or
    'cube' (tex [B, 6, n, n, C], uv directions [B, h, w, 3]; 'nearest' and
    'linear' filters only). uv_da [B, h, w, 4] = (du/dX, du/dY, dv/dX, dv/dY) and
    mip_level_bias [B, h, w] pick the mip level. Differentiable in tex, uv,
    uv_da and mip_level_bias."""
    if filter_mode == "auto":
        filter_mode = "linear-mipmap-linear" if uv_da is not None or mip_level_bias is not None else "linear"
    if filter_mode not in _FILTERS:
        raise ValueError(f"filter_mode: expected one of {', '.join(['auto'] + list(_FILTERS))}, got {filter_mode!r}")
    if boundary_mode == "cube":
        if filter_mode not in ("nearest", "linear"):
            raise ValueError(f"filter_mode: cube maps take 'nearest' or 'linear' here, got {filter_mode!r}")
        return _texture_cube(_to_tensor("tex", tex), _to_tensor("uv", uv), filter_mode)
    if boundary_mode not in _BOUNDARIES:
        raise ValueError(f"boundary_mode: expected one of {', '.join(_BOUNDARIES)}, got {boundary_mode!r}")
    level = _max_level(max_mip_level)
    tex, uv = _to_tensor("tex", tex), _to_tensor("uv", uv)
    if tex.dim() != 4:
        raise ValueError(f"tex: expected shape [B, H, W, C], got {list(tex.shape)}")
    if uv.dim() != 4 or uv.shape[-1] != 2:
        raise ValueError(f"uv: expected shape [B, H, W, 2], got {list(uv.shape)}")
    if tex.shape[0] not in (1, uv.shape[0]):
        raise ValueError(f"tex: {tex.shape[0]} textures for {uv.shape[0]} images in uv")
    mipmapped = filter_mode.startswith("linear-mipmap")
    if mipmapped and uv_da is None and mip_level_bias is None:
        raise ValueError(f"filter_mode: {filter_mode!r} needs uv_da or mip_level_bias")
    if not mipmapped:
        uv_da = mip_level_bias = mip = None
    if uv_da is not None:
        uv_da = _to_tensor("uv_da", uv_da)
        if tuple(uv_da.shape) != tuple(uv.shape[:3]) + (4,):
            raise ValueError(f"uv_da: expected shape {list(uv.shape[:3]) + [4]}, got {list(uv_da.shape)}")
    if mip_level_bias is not None:
        mip_level_bias = _to_tensor("mip_level_bias", mip_level_bias)
        if tuple(mip_level_bias.shape) != tuple(uv.shape[:3]):
            raise ValueError(f"mip_level_bias: expected shape {list(uv.shape[:3])}, got {list(mip_level_bias.shape)}")
    if mip is not None:
        if not isinstance(mip, TextureMip):
            raise ArgumentTypeError(f"mip: expected texture_construct_mip's result, got {type(mip).__name__}")
        if tuple(mip.shape) != tuple(tex.shape) or mip.max_mip_level != level:
            raise ValueError("mip: built for another texture shape or max_mip_level")
    return _Texture.apply(tex, uv, uv_da, mip_level_bias, mip, _FILTERS[filter_mode], _BOUNDARIES[boundary_mode],
                          level)


class TopologyHash:
    """antialias_construct_topology_hash's result: per triangle, the vertex
    across each edge (−1 on a boundary), for one tri array."""

    def __init__(self, opp, tri):
        self.opp, self.tri = opp, tri


def antialias_construct_topology_hash(tri):
    """nvdiffrast's antialias_construct_topology_hash: the mesh's edge
    neighbours, for antialias(..., topology_hash=)."""
    tri_np = _indices("tri", _to_tensor("tri", tri))
    if tri_np.ndim != 2 or tri_np.shape[1] != 3:
        raise ValueError(f"tri: expected shape [T, 3], got {list(tri_np.shape)}")
    if tri_np.size and tri_np.min() < 0:
        raise ValueError(f"tri: vertex index {int(tri_np.min())} is negative")
    num_vertices = int(tri_np.max()) + 1 if tri_np.size else 0
    return TopologyHash(_clraster.antialias_topology(tri_np, num_vertices), tri_np)


class _Antialias(torch.autograd.Function):
    @staticmethod
    def forward(ctx, color, rast, pos, tri_np, opp, boost):
        color_np, rast_np, pos_np = _floats("color", color), _floats("rast", rast), _floats("pos", pos)
        pos3 = pos_np if pos_np.ndim == 3 else pos_np[None]
        glctx = _context()
        with glctx._lock:
            out = _clraster.antialias_fwd(glctx._ctx, color_np, rast_np, pos3, tri_np, opp)
        ctx.arrays = color_np, rast_np, pos_np, pos3, tri_np, opp
        ctx.boost, ctx.dtypes = boost, (color.dtype, pos.dtype)
        return torch.from_numpy(out)

    @staticmethod
    def backward(ctx, dy):
        color_np, rast_np, pos_np, pos3, tri_np, opp = ctx.arrays
        dy = np.ascontiguousarray(dy.detach().numpy(), np.float32)
        glctx = _context()
        with glctx._lock:
            gc, gp = _clraster.antialias_grad(glctx._ctx, color_np, rast_np, pos3, tri_np, opp, dy, ctx.boost)
        return (torch.from_numpy(gc).to(ctx.dtypes[0]), None,
                torch.from_numpy(gp.reshape(pos_np.shape)).to(ctx.dtypes[1]), None, None, None)


def antialias(color, rast, pos, tri, topology_hash=None, pos_gradient_boost=1.0):
    """nvdiffrast's antialias: color [B, H, W, C] blended across the
    silhouette edges of the mesh (pos [B, V, 4] or [V, 4], tri) that
    rasterize drew into rast, by the edge's crossing between each pair of
    neighbouring pixels (Laine et al. 2020). Differentiable in color and,
    through the crossings, in pos (times pos_gradient_boost)."""
    color, rast, pos = _to_tensor("color", color), _to_tensor("rast", rast), _to_tensor("pos", pos)
    if rast.dim() != 4 or rast.shape[-1] != 4:
        raise ValueError(f"rast: expected shape [B, H, W, 4], got {list(rast.shape)}")
    if color.dim() != 4 or tuple(color.shape[:3]) != tuple(rast.shape[:3]):
        raise ValueError(f"color: expected shape {list(rast.shape[:3]) + ['C']}, got {list(color.shape)}")
    if pos.dim() not in (2, 3) or pos.shape[-1] != 4 or (pos.dim() == 3 and pos.shape[0] != rast.shape[0]):
        raise ValueError(f"pos: expected shape [V, 4] or [{rast.shape[0]}, V, 4], got {list(pos.shape)}")
    tri_np = _indices("tri", _to_tensor("tri", tri))
    _check_tri(tri_np, pos.shape[-2])
    _check_rast_ids(rast.detach().numpy(), tri_np.shape[0])
    if topology_hash is None:
        topology_hash = antialias_construct_topology_hash(tri_np)
    if not isinstance(topology_hash, TopologyHash):
        raise ArgumentTypeError(f"topology_hash: expected antialias_construct_topology_hash's result, "
                                f"got {type(topology_hash).__name__}")
    if not np.array_equal(topology_hash.tri, tri_np):
        raise ValueError("topology_hash: built for another tri")
    if not isinstance(pos_gradient_boost, numbers.Real) or not np.isfinite(pos_gradient_boost):
        raise ValueError(f"pos_gradient_boost: expected a finite number, got {pos_gradient_boost!r}")
    return _Antialias.apply(color, rast, pos, tri_np, topology_hash.opp, float(pos_gradient_boost))
