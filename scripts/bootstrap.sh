#!/usr/bin/env bash
# bootstrap.sh — the README's two commands, on a Debian 12 machine, as root.
#
#   bash scripts/bootstrap.sh render   install what is missing, build, and
#                                      render the built-in scene to out/default.png
#   bash scripts/bootstrap.sh test     install what is missing, build, and run
#                                      every test (what .ci/run calls)
#
# Packages are checked with dpkg and only the missing ones are installed, so a
# second run installs nothing. zlib1g-dev is listed because assimp's CMake
# package links libz.so but Debian's libassimp-dev does not depend on it, and libclang-rt-dev
# (libFuzzer, the sanitizer runtimes) because clang only recommends it;
# gnuplot-nox draws the benchmarks' charts (bench/*.sh only check for it).
#
# Both modes leave PoCL's kernel cache warm: a render of the built-in scene
# compiles the kernels a default frame runs into PoCL's default cache
# (~/.cache/pocl/kcache), where a later `build/clraster render` finds them;
# `test` also renders once into build/pocl-cache, the tests' cache, before
# the tests start.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

mode="${1:-}"
case "$mode" in
  render | test) ;;
  *) echo "usage: bash scripts/bootstrap.sh render|test" >&2; exit 2 ;;
esac

# Step 1: packages.
packages=(cmake g++ make pkg-config
  ocl-icd-opencl-dev pocl-opencl-icd opencl-clhpp-headers
  libglm-dev catch2 libassimp-dev zlib1g-dev libstb-dev libosmesa6-dev nlohmann-json3-dev libtinyexr-dev
  assimp-testmodels clang-format oclgrind clang libclang-rt-dev gnuplot-nox
  python3-dev pybind11-dev python3-numpy python3-pytest python3-torch libmeshoptimizer-dev libembree-dev libssl-dev
  libfast-float-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Step 2: build.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"

# Step 3: render (into PoCL's default kernel cache) and store the compiled
# programs (clraster cache), or warm PoCL's caches and test.
if [[ "$mode" == render ]]; then
  mkdir -p out
  ./build/clraster devices
  ./build/clraster render -o out/default.png --size 1280x720 --stats
  echo "bootstrap: wrote out/default.png"
  echo "bootstrap: storing the compiled kernels, so later starts skip the compiler (clraster cache)"
  ./build/clraster cache
else
  warm=$(mktemp -d)
  trap 'rm -rf "$warm"' EXIT
  echo "bootstrap: warm-up render (compiles the default frame's kernels into PoCL's caches)"
  ./build/clraster render -o "$warm/default.png"
  export POCL_CACHE_DIR="$PWD/build/pocl-cache"
  ./build/clraster render -o "$warm/default.png"
  ctest --test-dir build --output-on-failure -j "$(nproc)"
fi
