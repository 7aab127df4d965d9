#!/usr/bin/env python3
"""make_load_meshes.py: the meshes of bench/load.sh, from a real mesh.

A grid of copies of one OBJ (default: assimp's WusonOBJ), enough for at
least TRIANGLES triangles, its faces shuffled with a fixed seed (a scan's
file order is not the render order), written as binary PLY, OFF, binary
STL, OBJ and GLB: OUT/load_N.{ply,off,stl,obj,glb}.

usage: make_load_meshes.py OUT TRIANGLES [--source OBJ]
"""
import argparse
import json
import os
import struct

import numpy as np


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append([float(x) for x in w[1:4]])
            elif w[0] == "f":
                idx = [int(c.split("/")[0]) - 1 for c in w[1:]]
                for k in range(1, len(idx) - 1):
                    tris.append([idx[0], idx[k], idx[k + 1]])
    return np.array(verts, np.float32), np.array(tris, np.uint32)


def grid(verts, tris, want):
    copies = -(-want // len(tris))
    side = int(np.ceil(np.sqrt(copies)))
    extent = verts.max(0) - verts.min(0)
    pos, idx = [], []
    for c in range(copies):
        offset = np.array([(c % side) * extent[0] * 1.1, 0.0, (c // side) * extent[2] * 1.1], np.float32)
        pos.append(verts + offset)
        idx.append(tris + c * len(verts))
    pos = np.concatenate(pos).astype(np.float32)
    idx = np.concatenate(idx)[:want]
    np.random.default_rng(46).shuffle(idx)
    return pos, idx


def write_ply(path, pos, idx):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                 "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(pos), len(idx))).encode())
        f.write(pos.astype("<f4").tobytes())
        faces = np.zeros(len(idx), dtype=[("n", "u1"), ("i", "<i4", 3)])
        faces["n"] = 3
        faces["i"] = idx
        f.write(faces.tobytes())


def text_rows(fmt, rows):
    return "".join(fmt % tuple(r) for r in rows.tolist())


def write_off(path, pos, idx):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(pos), len(idx)))
        f.write(text_rows("%.6f %.6f %.6f\n", pos))
        f.write(text_rows("3 %d %d %d\n", idx))


def write_obj(path, pos, idx):
    with open(path, "w") as f:
        f.write(text_rows("v %.6f %.6f %.6f\n", pos))
        f.write(text_rows("f %d %d %d\n", idx + 1))


def write_stl(path, pos, idx):
    tri = pos[idx]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-30)
    rec = np.zeros(len(idx), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"] = normal
    rec["v"] = tri
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(idx)))
        f.write(rec.tobytes())


def write_glb(path, pos, idx):
    body = pos.astype("<f4").tobytes() + idx.astype("<u4").tobytes()
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(body)}],
        "bufferViews": [{"buffer": 0, "byteLength": pos.nbytes},
                        {"buffer": 0, "byteOffset": pos.nbytes, "byteLength": idx.nbytes}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
                       "min": pos.min(0).tolist(), "max": pos.max(0).tolist()},
                      {"bufferView": 1, "componentType": 5125, "count": idx.size, "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
    }
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    body += b"\0" * (-len(body) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(body)))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(body), 0x004E4942) + body)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("triangles", type=int)
    ap.add_argument("--source", default="/usr/share/assimp/models/OBJ/WusonOBJ.obj")
    a = ap.parse_args()
    verts, tris = read_obj(a.source)
    pos, idx = grid(verts, tris, a.triangles)
    os.makedirs(a.out, exist_ok=True)
    base = os.path.join(a.out, "load_%d" % a.triangles)
    for ext, write in (("ply", write_ply), ("off", write_off), ("stl", write_stl), ("obj", write_obj),
                       ("glb", write_glb)):
        if not os.path.exists(base + "." + ext):
            write(base + "." + ext, pos, idx)


if __name__ == "__main__":
    main()
