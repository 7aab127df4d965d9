#!/usr/bin/env python3
"""comment_files.py — every file a comment names exists.

    tests/comment_files.py SOURCE_DIR
    tests/comment_files.py --plant SOURCE_DIR   the check must fail on a copy
                                                whose comment names no file

Reads the comments of kernels/, host/, tests/, bench/, include/ and python/
(// and /* */ in C, C++ and OpenCL; # in shell, Python and CMake files, and
Python's docstrings) and takes every token that names a source file: NAME.EXT
or DIR/NAME.EXT with EXT one of cpp, hpp, h, cl, sh, py, cmake. A name with a
folder must exist from the repository root, from the commenting file's folder,
or from host/ or kernels/ (as includes name them); a bare name must be the
name of some file of the repository. Names in capitals (NAME.h) are
placeholders, and EXTERNAL lists the headers of other projects that comments
cite. Exit 1 with one line per unknown name; 0 when every name exists.
"""
import os
import re
import shutil
import sys
import tempfile

SCANNED = ("kernels", "host", "tests", "bench", "include", "python")
SKIPPED = {".git", "__pycache__"}
EXTERNAL = {"CL/opencl.hpp", "opencl-c.h"}  # the OpenCL C++ bindings, clang's OpenCL builtins
TOKEN = re.compile(r"(?<![\w./$-])((?:[\w.-]+/)*[\w-]+\.(?:cpp|hpp|h|cl|sh|py|cmake))(?![\w/])")
C_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
PY_DOCSTRING = re.compile(r'"""(.*?)"""', re.S)


def repo_files(src):
    """Every file's path relative to src, leaving out build folders (any top-level
    folder with a CMakeCache.txt) and version control."""
    out = []
    for root, dirs, names in os.walk(src):
        rel = os.path.relpath(root, src)
        dirs[:] = [d for d in dirs if d not in SKIPPED and
                   not (rel == "." and os.path.exists(os.path.join(root, d, "CMakeCache.txt")))]
        out += [os.path.normpath(os.path.join(rel, n)) for n in names]
    return out


def comments(path, text):
    """(line, comment text) of each comment of a file, by its language."""
    line_of = lambda pos: text.count("\n", 0, pos) + 1
    if path.endswith((".cpp", ".h", ".hpp", ".cl")):
        return [(line_of(m.start()), m.group()) for m in C_COMMENT.finditer(text)]
    if path.endswith((".sh", ".py", ".cmake", "CMakeLists.txt")):
        found = [(i + 1, l[l.index("#"):]) for i, l in enumerate(text.split("\n")) if "#" in l]
        if path.endswith(".py"):
            found += [(line_of(m.start()), m.group(1)) for m in PY_DOCSTRING.finditer(text)]
        return found
    return []


def check(src):
    files = repo_files(src)
    paths, names = set(files), {os.path.basename(f) for f in files}
    bad = []
    for f in sorted(files):
        if f.split(os.sep)[0] not in SCANNED:
            continue
        with open(os.path.join(src, f), encoding="utf-8", errors="replace") as h:
            text = h.read()
        for line, comment in comments(f, text):
            for m in TOKEN.finditer(comment):
                name = m.group(1)
                stem = os.path.splitext(os.path.basename(name))[0]
                if name in EXTERNAL or stem.isupper():
                    continue
                if "/" in name:
                    bases = ("", os.path.dirname(f), "host", "kernels")
                    ok = any(os.path.normpath(os.path.join(b, name)) in paths for b in bases)
                else:
                    ok = name in names
                if not ok:
                    bad.append(f"FAIL {f}:{line}: the comment names '{name}', which is no file of the repository")
    return len(files), bad


def plant(src):
    """Copies the repository without its build folders, adds a comment naming a
    file that does not exist, and requires the check to report exactly it."""
    with tempfile.TemporaryDirectory() as tmp:
        copy = os.path.join(tmp, "src")
        build_dirs = {d for d in os.listdir(src) if os.path.exists(os.path.join(src, d, "CMakeCache.txt"))}
        shutil.copytree(src, copy, ignore=lambda d, n: [x for x in n if x in SKIPPED or
                                                      (os.path.samefile(d, src) and x in build_dirs)])
        with open(os.path.join(copy, "host", "io", "scene.h"), "a", encoding="utf-8") as h:
            h.write("// The planted name: see no_such_stage.cpp.\n")
        _, bad = check(copy)
    if len(bad) != 1 or "host/io/scene.h" not in bad[0] or "no_such_stage.cpp" not in bad[0]:
        print("comment_files: the planted name was not reported alone:", *bad, sep="\n", file=sys.stderr)
        return 1
    print("comment_files: the planted name is caught:", bad[0])
    return 0


def main(argv):
    if len(argv) == 3 and argv[1] == "--plant":
        return plant(argv[2])
    if len(argv) != 2:
        print("usage: comment_files.py [--plant] SOURCE_DIR", file=sys.stderr)
        return 2
    count, bad = check(argv[1])
    for b in bad:
        print(b, file=sys.stderr)
    if not bad:
        print(f"comment_files: every file named in a comment exists ({count} files)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
