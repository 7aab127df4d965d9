"""Every bad argument of the Python module raises ValueError naming it,
within bounded time; nothing reaches the C++ side unchecked. Extreme but
valid positions (huge, tiny, non-finite) rasterize without error."""
import numpy as np
import pytest

import clraster

POS = np.array([[-1, -1, 0, 1], [1, -1, 0, 1], [0, 1, 0, 1]], np.float32)
TRI = np.array([[0, 1, 2]], np.int32)


@pytest.fixture(scope="module")
def rast(ctx):
    return clraster.rasterize(ctx, POS, TRI, (8, 8))


@pytest.mark.parametrize(
    "name, kwargs",
    [
        ("glctx", dict(glctx=None)),
        ("glctx", dict(glctx="cpu")),
        ("pos", dict(pos=POS.tolist())),
        ("pos", dict(pos=np.full((3, 4), 1e300))),  # beyond float32
        ("pos", dict(pos=POS[:, :3].copy())),
        ("pos", dict(pos=POS[0])),
        ("pos", dict(pos=POS[None, None])),
        ("tri", dict(tri=np.array([[0, 1, 2**40]], np.int64))),  # beyond int32
        ("tri", dict(tri=np.array([[0, 1, 2**32 - 1]], np.uint32))),
        ("tri", dict(tri=TRI.astype(np.float32))),
        ("tri", dict(tri=TRI[:, :2].copy())),
        ("tri", dict(tri=TRI[0])),
        ("tri", dict(tri=np.array([[0, 1, 3]], np.int32))),
        ("tri", dict(tri=np.array([[0, -1, 2]], np.int32))),
        ("tri", dict(tri=np.array([[0, 1, 2**31 - 1]], np.int32))),
        ("resolution", dict(resolution=(0, 8))),
        ("resolution", dict(resolution=(8, -1))),
        ("resolution", dict(resolution=(8, 16385))),
        ("resolution", dict(resolution=(8,))),
        ("resolution", dict(resolution=8)),
        ("resolution", dict(resolution=(8.0, 8))),
        ("resolution", dict(resolution=(True, 8))),
        ("resolution", dict(resolution=None)),
        ("ranges", dict(ranges=np.zeros((1, 2), np.int32))),
        ("grad_db", dict(grad_db=1)),
    ],
)
def test_rasterize_rejects(ctx, name, kwargs):
    args = dict(glctx=ctx, pos=POS, tri=TRI, resolution=(8, 8))
    args.update(kwargs)
    with pytest.raises(ValueError, match=f"^{name}: "):
        clraster.rasterize(**args)


@pytest.mark.parametrize(
    "name, kwargs",
    [
        ("attr", dict(attr=POS.tolist())),
        ("attr", dict(attr=POS.astype(np.complex64))),
        ("attr", dict(attr=POS[0])),
        ("attr", dict(attr=np.zeros((2, 3, 3, 1), np.float32))),
        ("attr", dict(attr=np.zeros((3, 3, 4), np.float32))),  # 3 sets for 1 image
        ("rast", dict(rast="rast")),
        ("rast", dict(rast=np.zeros((8, 8, 4), np.float32))),
        ("rast", dict(rast=np.zeros((1, 8, 8, 3), np.float32))),
        ("rast", dict(rast=np.full((1, 8, 8, 4), -1e300))),
        ("tri", dict(tri=np.array([[0, 1, 5]], np.int32))),
        ("tri", dict(tri=TRI.astype(bool))),
        ("diff_attrs", dict(diff_attrs="some")),
        ("diff_attrs", dict(diff_attrs=[0, 4])),
        ("diff_attrs", dict(diff_attrs=[-5])),
        ("diff_attrs", dict(diff_attrs=[0.5])),
        ("diff_attrs", dict(diff_attrs=7)),
        ("rast_db", dict(diff_attrs=[0])),
        ("rast_db", dict(diff_attrs=[0], rast_db=np.zeros((1, 8, 4, 4), np.float32))),
        ("rast_db", dict(diff_attrs=[0], rast_db=np.full((1, 8, 8, 4), 1e300))),
    ],
)
def test_interpolate_rejects(rast, name, kwargs):
    args = dict(attr=POS, rast=rast[0], tri=TRI)
    args.update(kwargs)
    with pytest.raises(ValueError, match=f"^{name}: "):
        clraster.interpolate(**args)


def test_context_rejects_bad_devices():
    with pytest.raises(ValueError, match="^device: "):
        clraster.Context(-1)
    with pytest.raises(ValueError, match="^device: "):
        clraster.Context(3.5)
    with pytest.raises(clraster.Error, match="--device no-such-device-xyz: no device name matches"):
        clraster.Context("no-such-device-xyz")
    with pytest.raises(clraster.Error, match="no such device index"):
        clraster.Context(999)


def test_triangle_ids_rejects():
    with pytest.raises(ValueError, match="^rast: "):
        clraster.triangle_ids(np.zeros((2, 2, 3), np.float32))


@pytest.mark.parametrize("value", [2.0, 7.0, -3.0, np.nan, np.inf, 1e30, 0.5])
def test_rast_naming_no_triangle_is_refused(rast, value):
    bad = rast[0].copy()
    bad[0, 3, 5, 3] = value
    with pytest.raises(ValueError, match=r"^rast: pixel \[0, 3, 5\] .* not an id in 0\.\.1 "):
        clraster.interpolate(POS, bad, TRI)


def test_extreme_positions_do_not_fail(ctx):
    # Huge and tiny finite coordinates, inf and nan: culled or clipped as the
    # kernels do, never an error or a non-finite output.
    pos = np.array(
        [[-3e38, -3e38, 0, 1], [3e38, -3e38, 0, 1], [0, 3e38, 0, 1],
         [1e-30, 1e-30, 0, 1e-30], [2e-30, 1e-30, 0, 1e-30], [1e-30, 2e-30, 0, 1e-30],
         [np.inf, 0, 0, 1], [0, np.nan, 0, 1], [0, 0, 0, 0]], np.float32)
    tri = np.array([[0, 1, 2], [3, 4, 5], [6, 7, 8], [8, 8, 8]], np.int32)
    rast, db = clraster.rasterize(ctx, pos, tri, (16, 16))
    assert np.isfinite(rast[..., 3]).all()
    assert set(np.unique(clraster.triangle_ids(rast))) <= {0, 1, 2}


def test_non_contiguous_inputs_are_accepted(ctx):
    pos = np.asfortranarray(POS)
    tri = np.asfortranarray(TRI)
    a, _ = clraster.rasterize(ctx, pos, tri, (8, 8))
    b, _ = clraster.rasterize(ctx, POS, TRI, (8, 8))
    assert np.array_equal(a, b)


@pytest.mark.parametrize(
    "name, kwargs",
    [
        ("glctx", dict(glctx=None)),
        ("pos", dict(pos=POS.tolist())),
        ("pos", dict(pos=None)),
        ("resolution", dict(resolution=(8.0, 8))),
        ("resolution", dict(resolution=8)),
        ("grad_db", dict(grad_db=1)),
    ],
)
def test_wrong_types_are_type_errors_as_well(ctx, name, kwargs):
    args = dict(glctx=ctx, pos=POS, tri=TRI, resolution=(8, 8))
    args.update(kwargs)
    with pytest.raises(TypeError, match=f"^{name}: ") as caught:
        clraster.rasterize(**args)
    assert isinstance(caught.value, ValueError) and isinstance(caught.value, clraster.ArgumentTypeError)
    with pytest.raises(TypeError, match="^device: "):
        clraster.Context(3.5)


def test_other_byte_order_and_numpy_bools_are_accepted(ctx):
    want, want_db = clraster.rasterize(ctx, POS, TRI, (8, 8))
    got, got_db = clraster.rasterize(ctx, POS.astype(">f4"), TRI.astype(">i4"), (8, 8), grad_db=np.bool_(True))
    assert np.array_equal(got, want) and np.array_equal(got_db, want_db)
    out, _ = clraster.interpolate(POS.astype(">f4"), want, TRI)
    assert np.array_equal(out, clraster.interpolate(POS, want, TRI)[0])
