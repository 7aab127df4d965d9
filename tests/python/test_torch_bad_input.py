"""Every bad argument of clraster.torch raises ValueError (or
ArgumentTypeError, also a ValueError) whose message starts with the
argument's name, before anything reaches the device."""
import numpy as np
import pytest
import torch

import clraster.torch as dr

POS = torch.tensor([[-1, -1, 0, 1], [1, -1, 0, 1], [0, 1, 0, 1]], dtype=torch.float32)
TRI = torch.tensor([[0, 1, 2]], dtype=torch.int32)


@pytest.fixture(scope="module")
def glctx(ctx):
    return ctx


@pytest.fixture(scope="module")
def rast(glctx):
    return dr.rasterize(glctx, POS, TRI, (8, 8))[0]


@pytest.mark.parametrize("name, kwargs", [
    ("glctx", dict(glctx=None)),
    ("pos", dict(pos=POS[:, :3])),
    ("pos", dict(pos=POS.double() * 1e300)),
    ("pos", dict(pos="pos")),
    ("tri", dict(tri=TRI + 5)),
    ("tri", dict(tri=TRI.float())),
    ("tri", dict(tri=TRI.long() * 2**40)),
    ("resolution", dict(resolution=(8,))),
    ("resolution", dict(resolution=(0, 8))),
    ("ranges", dict(ranges=torch.tensor([[0, 2]], dtype=torch.int32))),
    ("ranges", dict(ranges=torch.tensor([0, 1], dtype=torch.int32))),
    ("grad_db", dict(grad_db=1)),
])
def test_rasterize_rejects(glctx, name, kwargs):
    args = dict(glctx=glctx, pos=POS, tri=TRI, resolution=(8, 8))
    args.update(kwargs)
    with pytest.raises(ValueError, match=f"^{name}: "):
        dr.rasterize(**args)


@pytest.mark.parametrize("name, kwargs", [
    ("attr", dict(attr=POS[0])),
    ("attr", dict(attr=POS[None].expand(3, 3, 4))),
    ("rast", dict(rast=torch.zeros(8, 8, 4))),
    ("tri", dict(tri=TRI + 1)),
    ("diff_attrs", dict(diff_attrs=[9])),
    ("diff_attrs", dict(diff_attrs="some")),
    ("rast_db", dict(diff_attrs=[0])),
    ("rast_db", dict(diff_attrs=[0], rast_db=torch.zeros(1, 4, 4, 4))),
])
def test_interpolate_rejects(rast, name, kwargs):
    args = dict(attr=POS, rast=rast, tri=TRI)
    args.update(kwargs)
    with pytest.raises(ValueError, match=f"^{name}: "):
        dr.interpolate(**args)


TEX = torch.zeros(1, 8, 8, 3)
UV = torch.zeros(1, 4, 4, 2)


@pytest.mark.parametrize("name, kwargs", [
    ("tex", dict(tex=TEX[0])),
    ("tex", dict(tex=TEX.expand(2, 8, 8, 3))),
    ("uv", dict(uv=UV[..., :1])),
    ("uv_da", dict(uv_da=torch.zeros(1, 4, 4, 3))),
    ("mip_level_bias", dict(mip_level_bias=torch.zeros(1, 4, 5))),
    ("max_mip_level", dict(uv_da=torch.zeros(1, 4, 4, 4), max_mip_level=-1)),
    ("filter_mode", dict(filter_mode="cubic")),
    ("boundary_mode", dict(boundary_mode="mirror")),
    ("tex", dict(boundary_mode="cube")),  # a 2D texture for cube mode
    ("mip", dict(uv_da=torch.zeros(1, 4, 4, 4), mip="mip")),
])
def test_texture_rejects(glctx, name, kwargs):
    args = dict(tex=TEX, uv=UV)
    args.update(kwargs)
    with pytest.raises(ValueError, match=f"^{name}: "):
        dr.texture(**args)


@pytest.mark.parametrize("name, kwargs", [
    ("color", dict(color=torch.zeros(1, 8, 7, 3))),
    ("rast", dict(rast=torch.zeros(1, 8, 8, 3))),
    ("pos", dict(pos=torch.zeros(2, 3, 4))),
    ("tri", dict(tri=TRI + 3)),
    ("topology_hash", dict(topology_hash="hash")),
    ("topology_hash", dict(topology_hash=dr.antialias_construct_topology_hash(torch.tensor([[0, 2, 1]])))),
    ("pos_gradient_boost", dict(pos_gradient_boost=float("nan"))),
])
def test_antialias_rejects(rast, name, kwargs):
    args = dict(color=torch.zeros(1, 8, 8, 3), rast=rast, pos=POS, tri=TRI)
    args.update(kwargs)
    with pytest.raises(ValueError, match=f"^{name}: "):
        dr.antialias(**args)


def test_cube_mip_pyramids_are_refused_by_name():
    with pytest.raises(ValueError, match="^cube_mode: "):
        dr.texture_construct_mip(TEX, cube_mode=True)
    assert np.isfinite(dr.texture(TEX, UV).numpy()).all()


@pytest.mark.parametrize("channel", [2.0, 7.0, -3.0, float("nan")])
def test_rast_naming_no_triangle_is_refused(rast, channel):
    """interpolate and antialias read the id channel: one naming no triangle
    of tri (7 with one triangle, -3, NaN) is refused, never read as 0."""
    bad = rast.clone()
    bad[0, 4, 4, 3] = channel
    attr = torch.ones(3, 2)
    with pytest.raises(ValueError, match="^rast"):
        dr.interpolate(attr, bad, TRI)
    with pytest.raises(ValueError, match="^rast"):
        dr.antialias(torch.zeros(1, 8, 8, 3), bad, POS, TRI)


def test_log_level_round_trips_and_refuses_bad_levels():
    assert dr.get_log_level() == 1  # nvdiffrast's default
    try:
        dr.set_log_level(np.int64(2))
        assert dr.get_log_level() == 2
        for bad in (-1, 4):
            with pytest.raises(ValueError, match=r"^level: "):
                dr.set_log_level(bad)
        for bad in (1.0, "1", True, None):
            with pytest.raises(dr.ArgumentTypeError, match=r"^level: "):
                dr.set_log_level(bad)
        assert dr.get_log_level() == 2  # a refused level changes nothing
    finally:
        dr.set_log_level(1)
