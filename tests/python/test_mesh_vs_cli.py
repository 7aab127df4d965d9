"""A real mesh (assimp's Wuson.off, parsed here in numpy) rasterized through
clraster.rasterize with clip-space positions computed in numpy, against
`clraster render --shade id` of the same camera: ids agree on at least
99.99% of the covered pixels (the rest: numpy's float64 transform against
the kernels' float32 one), and are identical given the CLI's own clip
positions (its loaded mesh and mvp from tests/api_helper.cpp, transformed
in numpy in the kernels' float32 order, transform.cl)."""
import os
import struct
import subprocess
import zlib

import numpy as np
import pytest

import clraster

MESH = "/usr/share/assimp/models/OFF/Wuson.off"
H, W = 384, 512
EYE, TARGET, UP = np.array([0.9, 0.7, 1.6]), np.array([0.0, 0.3, 0.0]), np.array([0.0, 1.0, 0.0])
FOV, NEAR, FAR = 40.0, 0.1, 10.0
FLAGS = ["--size", f"{W}x{H}", "--eye", "0.9,0.7,1.6", "--target", "0,0.3,0", "--up", "0,1,0",
         "--fov", "40", "--near", "0.1", "--far", "10"]


def load_off(path):
    """Vertices and fan-triangulated faces of an OFF file, in file order."""
    with open(path) as f:
        words = f.read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = np.array(words[at:at + 3 * nv], np.float64).reshape(nv, 3)
    at += 3 * nv
    tris = []
    for _ in range(nf):
        n = int(words[at])
        face = [int(x) for x in words[at + 1:at + 1 + n]]
        at += 1 + n
        tris += [[face[0], face[k], face[k + 1]] for k in range(1, n - 1)]
    return verts, np.array(tris, np.int32)


def view_projection():
    """glm::perspective(fov, W/H, near, far) · glm::lookAt(eye, target, up), float64."""
    f = 1.0 / np.tan(np.radians(FOV) / 2)
    proj = np.array([[f / (W / H), 0, 0, 0], [0, f, 0, 0],
                     [0, 0, -(FAR + NEAR) / (FAR - NEAR), -2 * FAR * NEAR / (FAR - NEAR)], [0, 0, -1, 0]])
    fwd = (TARGET - EYE) / np.linalg.norm(TARGET - EYE)
    side = np.cross(fwd, UP)
    side /= np.linalg.norm(side)
    up = np.cross(side, fwd)
    view = np.eye(4)
    view[0, :3], view[1, :3], view[2, :3] = side, up, -fwd
    view[:3, 3] = [-side @ EYE, -up @ EYE, fwd @ EYE]
    return proj @ view


def read_png_rgb(path):
    """An 8-bit RGB or RGBA PNG as uint8 [H, W, 3], top row first (filters 0-4)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat = 8, b""
    while at < len(data):
        (length,), kind = struct.unpack(">I", data[at:at + 4]), data[at + 4:at + 8]
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    bpp = 3 if colour == 2 else 4
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(h, 1 + w * bpp)
    out = np.zeros((h, w * bpp), np.int32)
    prev = np.zeros(w * bpp, np.int32)
    for y in range(h):
        kind, row = raw[y, 0], raw[y, 1:].astype(np.int32)
        if kind == 0:
            cur = row
        elif kind == 1:
            cur = np.cumsum(row.reshape(w, bpp), axis=0).reshape(-1) % 256
        elif kind == 2:
            cur = (row + prev) % 256
        else:
            cur = np.zeros_like(row)
            for x in range(w * bpp):
                a = cur[x - bpp] if x >= bpp else 0
                b, c = prev[x], prev[x - bpp] if x >= bpp else 0
                if kind == 3:
                    pred = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (row[x] + pred) % 256
        out[y], prev = cur, cur
    return out.reshape(h, w, bpp)[..., :3].astype(np.uint8)


@pytest.fixture(scope="module")
def cli_ids(tmp_path_factory):
    png = tmp_path_factory.mktemp("cli") / "ids.png"
    subprocess.run([os.environ["CLRASTER_BIN"], "render", MESH, "-o", str(png), "--shade", "id"] + FLAGS, check=True)
    rgb = read_png_rgb(png).astype(np.uint32)
    ids = rgb[..., 0] | rgb[..., 1] << 8 | rgb[..., 2] << 16
    return ids[::-1]  # bottom row first, as rast


def test_numpy_camera_agrees_with_the_cli(ctx, cli_ids):
    verts, tri = load_off(MESH)
    clip = (np.hstack([verts, np.ones((len(verts), 1))]) @ view_projection().T).astype(np.float32)
    rast, _ = clraster.rasterize(ctx, clip, tri, (H, W))
    ids = clraster.triangle_ids(rast)[0]
    covered = (ids > 0) | (cli_ids > 0)
    agree = (ids == cli_ids)[covered].mean()
    print(f"covered {covered.sum()}, agreement {agree:.6f}, differing {(ids != cli_ids).sum()}")
    assert covered.sum() > 0.1 * H * W
    assert agree >= 0.9999


def test_identical_clip_positions_give_identical_ids(ctx, cli_ids, helper, tmp_path):
    dump = tmp_path / "scene.bin"
    subprocess.run([helper, "scene-dump", str(dump), MESH, "-o", "unused.png"] + FLAGS, check=True)
    raw = open(dump, "rb").read()
    nv, nt = np.frombuffer(raw[:8], np.uint32)
    positions = np.frombuffer(raw, np.float32, 3 * nv, 8).reshape(nv, 3)
    indices = np.frombuffer(raw, np.uint32, 3 * nt, 8 + 12 * nv).reshape(nt, 3).astype(np.int32)
    m = np.frombuffer(raw, np.float32, 16, 8 + 12 * nv + 12 * nt)  # column-major
    x, y, z = positions[:, 0], positions[:, 1], positions[:, 2]
    # CLR_TRANSFORM_ROW (shared.h): float32, left to right, no FMA.
    clip = np.stack([((m[r] * x + m[4 + r] * y) + m[8 + r] * z) + m[12 + r] for r in range(4)], 1)
    rast, _ = clraster.rasterize(ctx, clip.astype(np.float32), indices, (H, W))
    ids = clraster.triangle_ids(rast)[0]
    assert (cli_ids > 0).sum() > 0.1 * H * W
    assert np.array_equal(ids, cli_ids)
