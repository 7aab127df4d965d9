"""clraster: an exact OpenCL triangle rasterizer with nvdiffrast's calls.

    import clraster as dr            # was: import nvdiffrast.torch as dr
    ctx = dr.Context()               # was: dr.RasterizeCudaContext()
    rast, rast_db = dr.rasterize(ctx, pos, tri, resolution=(H, W))
    out, _ = dr.interpolate(attr, rast, tri)

Arrays are numpy: pos float32 [V, 4] or [B, V, 4] (clip space, OpenGL
conventions), tri int32 [T, 3], attr float32 [V, C] or [B, V, C]. Other
dtypes, and anything with __array__ or __dlpack__, are converted where
nothing is lost (else a ValueError naming the argument); out= takes the
caller's output arrays. rast is
float32 [B, H, W, 4] = (u, v, z/w, triangle_id + 1), row 0 at the bottom,
zero where nothing covers; u and v weigh the triangle's vertices 0 and 1.
triangle_ids(rast) gives the exact int32 triangle_id + 1 for any triangle
count. Coverage and ids are those of `clraster render` (fixed-point,
watertight, nearest z/w wins, ties to the lower triangle index, no culling;
triangles with a non-finite vertex are culled). Every bad argument raises
ValueError naming it; one of the wrong type raises ArgumentTypeError, both
a TypeError and a ValueError. Calls release the GIL while the device or
the host arithmetic works; calls on one Context take turns (its lock).
docs/python.md maps the rest of nvdiffrast.
"""

import numbers
import threading

import numpy as np

from . import _clraster
from ._clraster import Error

__all__ = ["Context", "Error", "ArgumentTypeError", "rasterize", "interpolate", "triangle_ids", "devices"]
__version__ = _clraster.__version__

_MAX_RESOLUTION = 16384


class ArgumentTypeError(TypeError, ValueError):
    """An argument of the wrong type: a TypeError, as Python's convention has
    it, and a ValueError, as every bad argument to clraster is."""


class Context:
    """One OpenCL device. device: None or "" (the first GPU, else the first
    CPU), a device index, or a substring of the device or platform name (see
    devices()). Kernels are built on the first rasterize call.
    memory_limit: None, or the most bytes one call may take (its outputs
    and device buffers); every call is checked against it, the device's
    memory and the host's (RLIMIT_AS too) before allocating, and refused
    with clraster.Error naming the size. release() frees the buffers kept
    between calls (garbage collection of the Context does too)."""

    def __init__(self, device=None, memory_limit=None):
        if device is None:
            device = ""
        if isinstance(device, bool) or not isinstance(device, (str, numbers.Integral)):
            raise ArgumentTypeError(f"device: expected None, an index or a name, got {type(device).__name__}")
        if isinstance(device, numbers.Integral):
            if device < 0:
                raise ValueError(f"device: index {device} is negative")
            device = str(int(device))
        if memory_limit is not None and (isinstance(memory_limit, bool)
                                         or not isinstance(memory_limit, numbers.Integral)):
            raise ArgumentTypeError(f"memory_limit: expected None or a number of bytes, got {memory_limit!r}")
        if memory_limit is not None and memory_limit <= 0:
            raise ValueError(f"memory_limit: expected a positive number of bytes, got {memory_limit}")
        self._ctx = _clraster.Context(device)
        if memory_limit is not None:
            self._ctx.memory_limit = int(memory_limit)
        self._lock = threading.Lock()

    def release(self):
        """Frees the device buffers kept between calls; kernels stay built."""
        with self._lock:
            self._ctx.release()

    @property
    def device_name(self):
        return self._ctx.device_name

    @property
    def device_type(self):
        return self._ctx.device_type

    def __repr__(self):
        return f"clraster.Context({self._ctx.device_name!r}, {self._ctx.device_type})"


def devices():
    """The OpenCL devices as dicts (index, name, platform, type)."""
    return _clraster.devices()


def _numpy(name, value):
    """value as a numpy array: an ndarray, or anything with __dlpack__ or
    __array__ (a torch tensor, a CuPy array on the host, ...)."""
    if isinstance(value, np.ndarray):
        return value
    if hasattr(value, "__dlpack__") or hasattr(value, "__array__"):
        try:
            return np.from_dlpack(value) if hasattr(value, "__dlpack__") else np.asarray(value)
        except (RuntimeError, TypeError, BufferError, ValueError):
            try:
                return np.asarray(value)
            except (RuntimeError, TypeError, ValueError) as e:
                raise ValueError(f"{name}: cannot read it as an array ({e})") from None
    raise ArgumentTypeError(f"{name}: expected a numpy array (or anything with __array__), got {type(value).__name__}")


def _convert(name, value, dtype):
    """value converted to dtype (float32 or int32), or a ValueError naming
    the argument where that would lose information: a finite float beyond
    float32's range, an integer beyond int32's (or, to float32, beyond
    2^24), or a kind that does not convert (bool, complex, floats to
    indices)."""
    kind, target = value.dtype.kind, np.dtype(dtype)
    if value.dtype.newbyteorder("=") == target:
        return value.astype(dtype)  # the values are right, maybe in the other byte order
    if kind not in "iuf" or (target.kind == "i" and kind == "f"):
        raise ValueError(f"{name}: expected dtype {target.name}, got {value.dtype.name}")
    with np.errstate(over="ignore", invalid="ignore"):
        out = value.astype(dtype)
    if value.size == 0:
        return out
    if target.kind == "f" and kind == "f":
        lost = (np.isfinite(value) & ~np.isfinite(out)).any()
    else:
        lost = not np.array_equal(out.astype(value.dtype), value) if kind != "f" else False
        if target.kind == "f":
            lost = lost or np.abs(value).max() > 2**24
    if lost:
        raise ValueError(f"{name}: {value.dtype.name} values that {target.name} cannot hold exactly")
    return out


def _array(name, value, dtype, ndims, last=None):
    """value as a C-contiguous array of dtype with one of ndims dimensions
    (and last extent `last`), converted where nothing is lost (_convert),
    or a ValueError naming the argument."""
    value = _numpy(name, value)
    if value.dtype != dtype:
        value = _convert(name, value, dtype)
    if value.ndim not in ndims:
        dims = " or ".join(str(n) for n in ndims)
        raise ValueError(f"{name}: expected {dims} dimensions, got shape {list(value.shape)}")
    if last is not None and value.shape[-1] != last:
        raise ValueError(f"{name}: the last dimension must be {last}, got shape {list(value.shape)}")
    return np.ascontiguousarray(value)


def _outputs(out, shapes):
    """The caller's output arrays (out: a tuple of len(shapes) arrays, each
    float32, C-contiguous, writeable, of its shape), or fresh ones."""
    if out is None:
        return [np.empty(shape, np.float32) for shape in shapes]
    if not isinstance(out, (tuple, list)) or len(out) != len(shapes):
        raise ArgumentTypeError(f"out: expected a tuple of {len(shapes)} arrays, got {type(out).__name__}")
    for a, shape in zip(out, shapes):
        if not isinstance(a, np.ndarray) or a.dtype != np.float32 or not a.flags.c_contiguous or not a.flags.writeable:
            raise ValueError("out: each array must be a writeable C-contiguous float32 numpy array")
        if a.shape != tuple(shape):
            raise ValueError(f"out: expected shape {list(shape)}, got {list(a.shape)}")
    return list(out)


def _check_tri(tri, num_vertices):
    tri = _array("tri", tri, np.int32, (2,), 3)
    if tri.size and (tri.min() < 0 or tri.max() >= num_vertices):
        bad = int(tri.min()) if tri.min() < 0 else int(tri.max())
        raise ValueError(f"tri: vertex index {bad} outside [0, {num_vertices})")
    return tri


def rasterize(glctx, pos, tri, resolution, ranges=None, grad_db=True, *, out=None):
    """nvdiffrast's rasterize: returns (rast, rast_db), both float32
    [B, H, W, 4]; rast_db = (du/dX, du/dY, dv/dX, dv/dY) per pixel, or
    [B, H, W, 0] with grad_db=False. pos [V, 4] gives B = 1; [B, V, 4] is
    instanced mode (one image per entry, the same tri). Range mode (ranges)
    is not supported. out: optional (rast, rast_db) arrays to write into
    instead (float32, C-contiguous, of the result's shapes)."""
    if not isinstance(glctx, Context):
        raise ArgumentTypeError(f"glctx: expected a clraster.Context, got {type(glctx).__name__}")
    if ranges is not None:
        raise ValueError("ranges: range mode is not supported (pass one pos array per image, or [B, V, 4])")
    if not isinstance(grad_db, (bool, np.bool_)):
        raise ArgumentTypeError(f"grad_db: expected True or False, got {type(grad_db).__name__} {grad_db!r}")
    grad_db = bool(grad_db)
    try:
        height, width = resolution
    except (TypeError, ValueError):
        raise ArgumentTypeError(f"resolution: expected (height, width), got {resolution!r}") from None
    for n in (height, width):
        if isinstance(n, bool) or not isinstance(n, numbers.Integral):
            raise ArgumentTypeError(f"resolution: expected two integers, got {resolution!r}")
        if not 1 <= n <= _MAX_RESOLUTION:
            raise ValueError(f"resolution: expected two integers in 1..{_MAX_RESOLUTION}, got {resolution!r}")
    height, width = int(height), int(width)
    pos = _array("pos", pos, np.float32, (2, 3), 4)
    batch = pos if pos.ndim == 3 else pos[None]
    tri = _check_tri(tri, batch.shape[1])
    with glctx._lock:  # before the outputs exist: refused with the size, not killed
        _clraster.check_rasterize_memory(glctx._ctx, width, height,
                                         batch.shape[0] * height * width * (32 if grad_db else 16))
    rast, db = _outputs(out, [(batch.shape[0], height, width, 4), (batch.shape[0], height, width, 4 if grad_db else 0)])
    with glctx._lock:  # one frame for the whole batch (images stacked)
        _clraster.rasterize_batch(glctx._ctx, batch, tri, None, rast, db if grad_db else None)
    return rast, db


def triangle_ids(rast):
    """The exact int32 triangle_id + 1 (0: background) of each pixel of a
    rast from rasterize(), [B, H, W], for any triangle count: channel 3 holds
    the id in nvdiffrast's encoding (the float itself up to 2^24, above that
    the float's bits biased by 0x4a800000)."""
    rast = _array("rast", rast, np.float32, (3, 4), 4)
    f = rast[..., 3]
    big = f > 16777216.0
    with np.errstate(invalid="ignore"):  # NaN and huge channels cast to garbage, which the where() drops
        ids = np.where(big, f.view(np.int32) - np.int32(0x4A800000), f.astype(np.int32))
    return np.where(f > 0, ids, 0).astype(np.int32)


def _diff_list(diff_attrs, num_attrs):
    """diff_attrs (None, 'all' or integer indices, negative from the end) as
    a list of indices in [0, num_attrs); ValueError naming diff_attrs."""
    if diff_attrs is None:
        return []
    if isinstance(diff_attrs, str):
        if diff_attrs != "all":
            raise ValueError(f"diff_attrs: expected a list of indices or 'all', got {diff_attrs!r}")
        return list(range(num_attrs))
    try:
        diff = [int(j) for j in diff_attrs if not isinstance(j, bool) and isinstance(j, numbers.Integral)]
        ok = len(diff) == len(diff_attrs)
    except TypeError:
        ok = False
    if not ok:
        raise ValueError(f"diff_attrs: expected a list of integer indices or 'all', got {diff_attrs!r}")
    for j in diff:
        if not -num_attrs <= j < num_attrs:
            raise ValueError(f"diff_attrs: attribute index {j} outside [-{num_attrs}, {num_attrs})")
    return [j % num_attrs for j in diff]


def _check_rast_ids(rast, num_triangles):
    """ValueError naming rast unless every channel 3 is 0 (background) or
    the encoding of an id in 1..num_triangles."""
    f = rast[..., 3]
    ids = triangle_ids(rast)
    with np.errstate(invalid="ignore"):
        exact = (f > 16777216.0) | (np.floor(f) == f)
    bad = ~((f == 0) | ((ids >= 1) & (ids <= num_triangles) & exact))
    if bad.any():
        where = tuple(int(k) for k in np.argwhere(bad)[0])
        raise ValueError(f"rast: pixel {list(where)} holds triangle id channel {float(f[where])!r}, "
                         f"not an id in 0..{num_triangles} (0: background)")


def interpolate(attr, rast, tri, rast_db=None, diff_attrs=None, *, out=None):
    """nvdiffrast's interpolate: out [B, H, W, C] = u·a0 + v·a1 + (1−u−v)·a2
    of the covering triangle (0 where none), and out_da [B, H, W, 2·len]
    = (dA/dX, dA/dY) per attribute of diff_attrs (a list of indices or
    'all', with rast_db), else [B, H, W, 0]. attr [V, C] is shared by every
    image; [B, V, C] gives each image its own (B matching rast, or 1).
    out: optional (out, out_da) arrays to write into instead."""
    attr = _array("attr", attr, np.float32, (2, 3))
    rast = _array("rast", rast, np.float32, (4,), 4)
    batch = rast.shape[0]
    attrs = attr if attr.ndim == 3 else attr[None]
    if attrs.shape[0] not in (1, batch):
        raise ValueError(f"attr: {attrs.shape[0]} attribute sets for {batch} images in rast")
    tri = _check_tri(tri, attrs.shape[1])
    num_attrs = attrs.shape[2]
    diff = _diff_list(diff_attrs, num_attrs)
    if diff:
        if rast_db is None:
            raise ValueError("rast_db: needed with diff_attrs (rasterize(..., grad_db=True))")
        rast_db = _array("rast_db", rast_db, np.float32, (4,), 4)
        if rast_db.shape != rast.shape:
            raise ValueError(f"rast_db: shape {list(rast_db.shape)} differs from rast's {list(rast.shape)}")
    _check_rast_ids(rast, tri.shape[0])
    out, out_da = _outputs(out, [rast.shape[:3] + (num_attrs,), rast.shape[:3] + (2 * len(diff),)])
    for b in range(batch):
        a = attrs[b if attrs.shape[0] == batch else 0]
        _clraster.interpolate_into(a, rast[b], tri, out[b], rast_db[b] if diff else None, diff,
                                   out_da[b] if diff else None)
    return out, out_da
