#!/usr/bin/env bash
# load.sh — time to picture: one 1920×1080 PNG of a mesh file, command to
# PNG, for binary PLY, OFF, binary STL, OBJ and GLB at 100k, 1M and 10M
# triangles (a shuffled grid of copies of assimp's WusonOBJ, made by
# make_load_meshes.py), split as --stats splits it (read, parse, build,
# prepare, frame, encode, total), best of 3, with each run's peak memory,
# Open3D's read of the same file (Debian python3-open3d) and llvmpipe's
# picture of it, command to PNG (clraster_llvmpipe_picture, built with
# OSMesa), in the same run.
#
# usage: bash bench/load.sh [--quick] [--update-docs] [BUILD_DIR]
#   --quick        skip the 10M-triangle files
#   --update-docs  write the table into docs/benchmarks.md and README.md
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(dirname "$here")
sizes=100000,1000000,10000000
update=()
build=$repo/build
for arg in "$@"; do
  case $arg in
    --quick) sizes=100000,1000000 ;;
    --update-docs) update=(--update-docs "$repo") ;;
    -*) echo "load.sh: unknown flag $arg" >&2; exit 2 ;;
    *) build=$arg ;;
  esac
done
/usr/bin/python3 -c "import open3d" 2>/dev/null ||
  { echo "load.sh: Open3D is the peer this table measures against: apt-get install python3-open3d" >&2; exit 1; }
export POCL_CACHE_DIR=${POCL_CACHE_DIR:-$build/pocl-cache}
meshes=$build/load-meshes
for n in ${sizes//,/ }; do /usr/bin/python3 "$here/make_load_meshes.py" "$meshes" "$n"; done
# One untimed render first: the program cache is warm for every timed run.
"$build/clraster" render "$meshes/load_100000.ply" -o "$meshes/out.png" --size 1920x1080 >/dev/null
llvmpipe=()
if [ -x "$build/clraster_llvmpipe_picture" ]; then
  llvmpipe=(--llvmpipe "$build/clraster_llvmpipe_picture")
else
  echo "load.sh: no $build/clraster_llvmpipe_picture (install libosmesa6-dev and rebuild): no llvmpipe column" >&2
fi
/usr/bin/python3 "$here/load.py" "$build/clraster" "$meshes" --sizes "$sizes" "${llvmpipe[@]}" "${update[@]}"
