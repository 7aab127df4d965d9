#!/usr/bin/env bash
# gallery.sh — renders the README's shading and texture gallery into
# docs/gallery/ from Debian's assimp-testmodels and docs/gallery/scene/.
#
#   bash scripts/gallery.sh [BUILD_DIR]     (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${1:-$root/build}/clraster"
models=/usr/share/assimp/models
out="$root/docs/gallery"
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$root/build/pocl-cache}"
render() { "$bin" render "$@" --size 256x192 --aa msaa4; }

render "$models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb" -o "$out/box_phong.png" --shade phong --eye 1.6,1.3,2.2
render "$models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf" -o "$out/truck_phong.png" --shade phong --eye 6,3.5,7 --target 0,1,0
render "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" -o "$out/engine_phong.png" --shade phong
render "$models/OBJ/spider.obj" -o "$out/spider_phong.png" --shade phong
for mode in flat gouraud phong; do
  render "$models/OBJ/WusonOBJ.obj" -o "$out/wuson_$mode.png" --shade "$mode" --eye 3.2,1.5,2.4 --light-point 1.5,2.5,2
done
render "$models/OBJ/cube_with_vertexcolors.obj" -o "$out/cube_color.png" --shade color --eye 2.5,2,3 --target 0,0,0
for filter in nearest trilinear; do
  render "$root/docs/gallery/scene/plane.obj" -o "$out/plane_$filter.png" --shade texture --filter "$filter" \
    --eye 0,1.2,18 --target 0,0,0 --fov 60
done
echo "gallery written to $out"
