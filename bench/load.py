#!/usr/bin/env python3
"""load.py: time to picture, the driver of bench/load.sh (see there).

For each size and format: `clraster render FILE -o PNG --size 1920x1080
--stats`, best of REPEATS by total_ms, with its split and the process's peak
memory; Open3D's o3d.io.read_triangle_mesh of the same file, best of
REPEATS, timed inside a Python process that has already imported Open3D;
and, given --llvmpipe, llvmpipe's picture of the same file, command to PNG
(clraster_llvmpipe_picture: assimp's read, one lambert frame, the PNG),
best of REPEATS by the process's wall time. Prints a Markdown table;
--update-docs writes it into docs/benchmarks.md and the 1M rows into
README.md, between the "load-table" markers.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

FORMATS = ["ply", "off", "stl", "obj", "glb"]
NAMES = {"ply": "binary PLY", "off": "OFF", "stl": "binary STL", "obj": "OBJ", "glb": "GLB"}
O3D_READER = r"""
import sys, time
import open3d as o3d
o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
best = None
for _ in range(int(sys.argv[2])):
    t = time.perf_counter()
    mesh = o3d.io.read_triangle_mesh(sys.argv[1])
    ms = (time.perf_counter() - t) * 1000.0
    best = ms if best is None else min(best, ms)
print("%.3f %d" % (best, len(mesh.triangles)))
"""


def clraster_run(binary, path, png):
    """One render: its --stats JSON, with the wall time added."""
    start = time.perf_counter()
    proc = subprocess.Popen([binary, "render", path, "-o", png, "--size", "1920x1080", "--stats"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out, err = proc.communicate()
    wall = (time.perf_counter() - start) * 1000.0
    if proc.returncode != 0:
        sys.exit("load.py: %s failed: %s" % (path, err.decode(errors="replace").strip()))
    stats = json.loads(out.decode())
    stats["wall_ms"] = wall
    return stats


def peak_rss_kb(binary, path, png):
    """The peak resident memory of one render, in kB (GNU time)."""
    res = subprocess.run(["/usr/bin/time", "-f", "%M", binary, "render", path, "-o", png, "--size", "1920x1080"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, check=True)
    return int(res.stderr.decode().strip().splitlines()[-1])


def open3d_read(path, repeats):
    res = subprocess.run(["/usr/bin/python3", "-c", O3D_READER, path, str(repeats)], capture_output=True, text=True)
    if res.returncode != 0:
        return None, 0
    ms, tris = res.stdout.split()
    return float(ms), int(tris)


def llvmpipe_picture(binary, path, png, repeats):
    """llvmpipe's picture of the file: the best wall time of REPEATS runs, in ms (None without the tool)."""
    if not binary:
        return None
    best = None
    for _ in range(repeats):
        start = time.perf_counter()
        res = subprocess.run([binary, path, png, "--size", "1920x1080"], capture_output=True, text=True)
        wall = (time.perf_counter() - start) * 1000.0
        if res.returncode != 0:
            print("load.py: llvmpipe: %s" % res.stderr.strip(), file=sys.stderr)
            return None
        best = wall if best is None else min(best, wall)
    return best


def ms(value):
    return "%.0f ms" % value if value is not None else "n/a"


def ratio(a, b):
    return "%.2f×" % (a / b) if b else "n/a"


def table(rows):
    head = ("| file | triangles | MB | read | parse | build | prepare | frame | encode | total (command to PNG) "
            "| wall | peak RSS | Open3D read | total / Open3D | llvmpipe, command to PNG | wall / llvmpipe |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    lines = []
    for r in rows:
        lines.append("| %s | %s | %.1f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f ms | %.0f ms | %.0f MB | %s | %s "
                     "| %s | %s |"
                     % (NAMES[r["format"]], "{:,}".format(r["triangles"]), r["mb"], r["read_ms"], r["parse_ms"],
                        r["build_ms"], r["prepare_ms"], r["frame_ms"], r["encode_ms"], r["total_ms"], r["wall_ms"],
                        r["rss_kb"] / 1024.0, ms(r["o3d_ms"]), ratio(r["total_ms"], r["o3d_ms"]),
                        ms(r["llvmpipe_ms"]), ratio(r["wall_ms"], r["llvmpipe_ms"])))
    return head + "\n".join(lines) + "\n"


def readme_table(rows):
    out = ("| 1M triangles | MB | parse ms | total, command to PNG | peak RSS | Open3D's read alone "
           "| llvmpipe's picture, command to PNG |\n|---|---|---|---|---|---|---|\n")
    for r in rows:
        out += "| %s | %.1f | %.0f | %.0f ms | %.0f MB | %s | %s |\n" % (
            NAMES[r["format"]], r["mb"], r["parse_ms"], r["total_ms"], r["rss_kb"] / 1024.0, ms(r["o3d_ms"]),
            ms(r["llvmpipe_ms"]))
    return out


def replace_between(path, body):
    text = open(path).read()
    begin, end = "<!-- load-table begin -->", "<!-- load-table end -->"
    if begin in text:
        text = re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda _: begin + "\n" + body + end, text, flags=re.S)
    else:
        text = text.rstrip("\n") + "\n\n" + begin + "\n" + body + end + "\n"
    open(path, "w").write(text)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("meshes")
    ap.add_argument("--sizes", default="100000,1000000,10000000")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--update-docs", metavar="REPO")
    ap.add_argument("--llvmpipe", metavar="BINARY", help="clraster_llvmpipe_picture, for llvmpipe's column")
    a = ap.parse_args()
    rows = []
    for size in [int(s) for s in a.sizes.split(",")]:
        for fmt in FORMATS:
            path = os.path.join(a.meshes, "load_%d.%s" % (size, fmt))
            png = os.path.join(a.meshes, "out.png")
            runs = [clraster_run(a.binary, path, png) for _ in range(a.repeats)]
            best = min(runs, key=lambda s: s["total_ms"])
            best.update(format=fmt, triangles=best["triangles_in"], mb=os.path.getsize(path) / 1e6,
                        wall_ms=min(s["wall_ms"] for s in runs), rss_kb=peak_rss_kb(a.binary, path, png))
            best["o3d_ms"], _ = open3d_read(path, a.repeats)
            best["llvmpipe_ms"] = llvmpipe_picture(a.llvmpipe, path, os.path.join(a.meshes, "llvmpipe.png"), a.repeats)
            rows.append(best)
            print("load.py: %s done" % path, file=sys.stderr)
    out = table(rows)
    sys.stdout.write(out)
    if a.update_docs:
        note = ("Best of %d, 1920×1080, `bash bench/load.sh`, sizes %s, on a 2-core machine shared with other work: "
                "figures vary by up to about 2× between runs.\n\n" % (a.repeats, a.sizes))
        replace_between(os.path.join(a.update_docs, "docs/benchmarks.md"), note + out)
        small = [r for r in rows if r["triangles"] >= 900000 and r["triangles"] <= 1100000] or rows
        replace_between(os.path.join(a.update_docs, "README.md"), readme_table(small))


if __name__ == "__main__":
    main()
