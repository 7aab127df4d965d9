"""The numpy module's inputs convert from other dtypes and array types
where nothing is lost (float64, int64, float16, torch tensors through
DLPack or __array__), and its outputs go into the caller's arrays with
out=; results are those of the float32/int32 call."""
import numpy as np
import pytest

import clraster
from test_rasterize import crafted_scene


def test_wider_dtypes_give_the_float32_result(ctx):
    pos, tri = crafted_scene(41, count=20)
    want, want_db = clraster.rasterize(ctx, pos, tri, (24, 32))
    rast, db = clraster.rasterize(ctx, pos.astype(np.float64), tri.astype(np.int64), (24, 32))
    assert np.array_equal(rast, want) and np.array_equal(db, want_db)
    attr = np.random.default_rng(1).standard_normal((len(pos), 3)).astype(np.float32)
    out, _ = clraster.interpolate(attr, want, tri)
    for converted in (attr.astype(np.float64), attr.astype(np.float16).astype(np.float64)):
        got, _ = clraster.interpolate(converted, want.astype(np.float64), tri.astype(np.uint16))
        ref, _ = clraster.interpolate(converted.astype(np.float32), want, tri)
        assert np.array_equal(got, ref)
    assert np.array_equal(clraster.interpolate(attr, want, tri.astype(np.int16))[0], out)


def test_torch_tensors_and_dlpack(ctx):
    torch = pytest.importorskip("torch")
    pos, tri = crafted_scene(42, count=20)
    want, _ = clraster.rasterize(ctx, pos, tri, (16, 16))
    got, _ = clraster.rasterize(ctx, torch.from_numpy(pos).double(), torch.from_numpy(tri).long(), (16, 16))
    assert np.array_equal(got, want)

    class OnlyDlpack:
        def __init__(self, a):
            self.a = a

        def __dlpack__(self, stream=None):
            return self.a.__dlpack__()

        def __dlpack_device__(self):
            return self.a.__dlpack_device__()

    got, _ = clraster.rasterize(ctx, OnlyDlpack(pos), OnlyDlpack(tri), (16, 16))
    assert np.array_equal(got, want)


def test_outputs_into_caller_arrays(ctx):
    pos, tri = crafted_scene(43, count=20)
    want, want_db = clraster.rasterize(ctx, pos, tri, (16, 20))
    rast, db = np.full((1, 16, 20, 4), 7, np.float32), np.full((1, 16, 20, 4), 7, np.float32)
    result = clraster.rasterize(ctx, pos, tri, (16, 20), out=(rast, db))
    assert result[0] is rast and result[1] is db
    assert np.array_equal(rast, want) and np.array_equal(db, want_db)
    attr = np.ones((len(pos), 2), np.float32)
    out, out_da = np.empty((1, 16, 20, 2), np.float32), np.empty((1, 16, 20, 4), np.float32)
    got = clraster.interpolate(attr, rast, tri, rast_db=db, diff_attrs="all", out=(out, out_da))
    assert got[0] is out and np.array_equal(out, clraster.interpolate(attr, rast, tri)[0])
    with pytest.raises(ValueError, match="^out: "):
        clraster.rasterize(ctx, pos, tri, (16, 20), out=(rast[..., :2], db))
    with pytest.raises(ValueError, match="^out: "):
        clraster.rasterize(ctx, pos, tri, (16, 20), out=(rast.astype(np.float64), db))
