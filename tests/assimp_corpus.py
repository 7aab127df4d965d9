#!/usr/bin/env python3
"""assimp_corpus.py: every model file of Debian's assimp-testmodels, rendered.

Walks MODELS (default /usr/share/assimp/models) for files with an extension
the linked assimp imports (printed by the assimp_extensions tool), renders
each with `clraster render FILE -o OUT.png --size 64x48` under a per-file
timeout, and classifies the result:
  ok              exit 0 and a PNG
  refused:REASON  exit 1, one line on stderr matching a policy reason
                  (POLICY below; docs/limits.md, "Model files: policy reasons")
Anything else (a crash, a timeout, several lines, an exit 0 without an image,
a message matching no reason) is a failure whatever the expected file says.
The outcomes are compared with EXPECTED (one "PATH<TAB>OUTCOME" a line, PATH
relative to MODELS, sorted); any difference fails. --update rewrites EXPECTED.

usage: assimp_corpus.py CLRASTER EXTENSIONS_TOOL EXPECTED [--models DIR]
                        [--jobs N] [--timeout S] [--update]
"""
import argparse
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile

# Policy reasons: what clraster refuses on purpose, each a pattern of its
# one-line message. Order matters: the first match names the reason.
POLICY = [
    ("empty-file", r": file is empty( or unreadable)?$"),
    ("assimp-cannot-import", r": cannot import \("),
    ("no-geometry", r": no meshes in file$|: no triangles, lines or points in file$"),
    ("bad-position", r"non-finite position|beyond the supported 1e18|no vertex has finite coordinates"),
    ("index-out-of-range", r"(?i)invalid (vertex |face )?index|out.of.range"),
    ("missing-file", r"could not open referenced file|names missing embedded texture|: cannot open \(|cannot use '"),
    ("hostile-file-guard", r": (PLY|OFF|glTF|GLB)\b|nested deeper than"),
    ("inexact-number", r"is not a decimal number \(positions are read exactly"),
]

# Lines a library prints on stderr by itself before clraster's one line
# (assimp's OpenDDL parser, under the OpenGEX reader, writes to std::cerr).
LIBRARY_NOISE = {"nullptr returned by creating DDLNode."}


def classify(status, out_png, stderr):
    lines = [l for l in stderr.strip("\n").split("\n") if l not in LIBRARY_NOISE] if stderr.strip() else []
    if status == 0:
        with open(out_png, "rb") as f:
            ok = f.read(8) == b"\x89PNG\r\n\x1a\n"
        # Warnings (a missing texture, repaired normals) may precede success.
        return "ok" if ok else "FAIL:exit 0 without a PNG"
    if status != 1 or len(lines) != 1:
        return "FAIL:exit %d, %d stderr lines: %s" % (status, len(lines), " | ".join(lines)[:200])
    for reason, pattern in POLICY:
        if re.search(pattern, lines[0]):
            return "refused:" + reason
    return "FAIL:unexplained: " + lines[0][:200]


def render(args, tmp, index, path):
    out_png = os.path.join(tmp, "%d.png" % index)
    cmd = [args.clraster, "render", path, "-o", out_png, "--size", "64x48"]
    device = os.environ.get("CLRASTER_TEST_DEVICE")
    if device:
        cmd += ["--device", device]
    try:
        r = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True, errors="replace",
                           timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return "FAIL:timeout after %g s" % args.timeout
    return classify(r.returncode, out_png, r.stderr)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("clraster")
    p.add_argument("extensions_tool")
    p.add_argument("expected")
    p.add_argument("--models", default="/usr/share/assimp/models")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    p.add_argument("--timeout", type=float, default=120.0)
    p.add_argument("--update", action="store_true")
    args = p.parse_args()
    if not os.path.isdir(args.models):
        print("assimp_corpus: %s is missing (Debian package assimp-testmodels)" % args.models, file=sys.stderr)
        return 1
    exts = set(subprocess.run([args.extensions_tool], capture_output=True, text=True, check=True).stdout.split())
    files = []
    for root, _, names in os.walk(args.models):
        for name in names:
            lower = name.lower()
            if any(lower.endswith("." + e) for e in exts):
                files.append(os.path.relpath(os.path.join(root, name), args.models))
    files.sort()
    if not files:
        print("assimp_corpus: no model files under %s" % args.models, file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        outcomes = list(pool.map(lambda item: render(args, tmp, item[0], os.path.join(args.models, item[1])),
                                 enumerate(files)))
    got = ["%s\t%s" % (f, o) for f, o in zip(files, outcomes)]
    failures = [g for g in got if "\tFAIL:" in g]
    counts = {}
    for o in outcomes:
        key = o.split(":")[0] if o.startswith("FAIL") else o
        counts[key] = counts.get(key, 0) + 1
    print("assimp_corpus: %d files: %s" % (len(files), ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    for f in failures:
        print("FAILED " + f)
    if args.update:
        with open(args.expected, "w") as f:
            f.write("# Expected outcome of every model file of /usr/share/assimp/models (Debian assimp-testmodels)\n"
                    "# under `clraster render FILE -o OUT.png --size 64x48`: ok, or refused:REASON (docs/limits.md,\n"
                    "# \"Model files: policy reasons\"). Checked by the CTest test assimp_corpus; rewritten by\n"
                    "# python3 tests/assimp_corpus.py build/clraster build/tests/assimp_extensions THIS_FILE --update\n")
            f.write("\n".join(got) + "\n")
        print("assimp_corpus: wrote " + args.expected)
        return 1 if failures else 0
    with open(args.expected) as f:
        expected = [line.rstrip("\n") for line in f if line.strip() and not line.startswith("#")]
    if expected != got:
        exp, now = dict(x.split("\t", 1) for x in expected), dict(x.split("\t", 1) for x in got)
        for path in sorted(set(exp) | set(now)):
            if exp.get(path) != now.get(path):
                print("CHANGED %s: expected %s, got %s" % (path, exp.get(path, "(not listed)"), now.get(path, "(absent)")))
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
