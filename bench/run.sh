#!/usr/bin/env bash
# run.sh — clraster's benchmark suite against Mesa llvmpipe, on a Debian 12
# machine with the packages of scripts/bootstrap.sh (gnuplot-nox among them).
#
#   bash bench/run.sh [--out DIR | --update-docs] [MESH ...]
#
# Builds clraster, clraster_bench and clraster_peak in build/ (configuring it
# when there is none), then runs, each case as one clraster_bench process:
#   peaks        clraster_peak: fp32 GFLOP/s, 64-bit multiply-adds/s, copy GB/s
#   real meshes  the four largest assimp test models that load (below), far
#                view (the whole model, as the CLI frames it) at 1280x720,
#                1920x1080 and 3840x2160, and the fill view (the model
#                filling the screen) at 1920x1080
#   scale series a displaced cube-sphere of ~10k, 100k, 1M and 10M triangles,
#                and a 16x16 grid of instanced Wuson.off copies (955k
#                triangles), each with the far (whole object, small
#                triangles) and the near (camera close, large triangles)
#                view, at 1920x1080
#   grid5-fill   a 5x5 grid of Wuson.off copies (93k triangles) filling
#                the 1920x1080 screen
#   grid16-away  the 16x16 grid loaded and nothing in view (the far camera
#                turned round)
#   MESH ...     any further mesh files, like the real meshes
#   input order  every case of a real mesh (the meshes, the Wuson grids,
#                MESH ...) runs twice: in the file's triangle order, and
#                with its faces shuffled (clraster_bench --shuffle 1, a
#                fixed seed), the same camera; the shuffled rows are named
#                shuffled-CASE, and the report sets both orders side by side
#   cold start   wall time of a whole `clraster render` process (built-in
#                scene, 1920x1080, one frame) with empty caches (median
#                and range of three, each cache new), then with PoCL's
#                cache warm, then also with `clraster cache`'s programs
#                (medians of three)
# and writes into build/bench, or DIR, or docs/bench with --update-docs
# (bench/common.sh; BENCH_OUT is the default DIR), replacing earlier results:
#   results.csv            one row per case (columns: bench/bench_suite.cpp)
#   results.md             the tables, peaks, cold start and definitions
#   scaling_triangles.png  frame time vs triangles, log-log (sphere series)
#   scaling_pixels.png     frame time vs pixels, log-log (real meshes)
#
# Environment: WARMUP (default 3) and FRAMES (default 20) per case; the 10M
# cases use 1 and 5. LP_NUM_THREADS (llvmpipe threads) defaults to the core
# count, POCL_AFFINITY to 1 (below). DEVICE picks clraster's OpenCL device
# (as --device: an index or a name substring; default: the first GPU, else
# the first CPU).
# BENCH_BIN names a folder of already built clraster, clraster_bench and
# clraster_peak and skips the build, for a machine without the build tools
# (a GPU machine the binaries were copied to); there, BENCH_CHARTS=0 skips the
# charts, which `bash bench/charts.sh RESULTS.csv DIR` draws later elsewhere.
# Each case times
# llvmpipe twice: lighting per pixel as clraster does (the ratio), and per
# vertex, the three renderers taking turns in four rounds (bench_suite.cpp).
# It stays well under the suite's 15-minute budget; do not run it beside
# other heavy jobs if the numbers matter. Any
# failure stops the suite with a message and a non-zero exit, leaving
# earlier results in place.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/common.sh
bench_args bench/run.sh "$@"
set -- ${bench_rest[@]+"${bench_rest[@]}"}

models=/usr/share/assimp/models
# The largest test models assimp loads, by triangle count (PLY/pond.0.ply is
# larger but has no faces; the draco glTF copy of the engine is skipped).
real_meshes=(
  "$models/BLEND/SuzanneSubdiv_252.blend"                         # 251,904 triangles
  "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" # 121,496
  "$models/BLEND/yxa_1.blend"                                     # 115,712
  "$models/IFC/AC14-FZK-Haus.ifc"                                 # 35,906
)
grid_mesh="$models/OFF/Wuson.off"
warmup="${WARMUP:-3}"
frames="${FRAMES:-20}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-$(nproc)}"
# PoCL's worker threads pinned one per core (POCL_AFFINITY, unless set):
# unpinned, the scheduler can leave both workers on one core for the first
# frames, and a case's median then comes out at one core's speed. Mesa has no
# such setting for llvmpipe's threads.
export POCL_AFFINITY="${POCL_AFFINITY:-1}"
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
out_dir="$bench_out"
device_args=()
[[ -n "${DEVICE:-}" ]] && device_args=(--device "$DEVICE")
suite_start=$(date +%s.%N)

fail() { echo "bench/run.sh: $*" >&2; exit 1; }

# Step 1: arguments and packages.
for mesh in "${real_meshes[@]}" "$grid_mesh" "$@"; do
  [[ -r "$mesh" ]] || fail "cannot read mesh '$mesh' (real meshes need assimp-testmodels)"
done
[[ "${BENCH_CHARTS:-1}" == 0 ]] || need_gnuplot bench/run.sh

# Step 2: build (unless BENCH_BIN names built binaries).
built="${BENCH_BIN:-build}"
if [[ -z "${BENCH_BIN:-}" ]]; then
  [[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j "$(nproc)" --target clraster clraster_bench clraster_peak clraster_embree >/dev/null ||
    fail "build failed (run: cmake --build build --target clraster_bench clraster_embree)"
fi
for program in clraster clraster_bench clraster_peak clraster_embree; do
  [[ -x "$built/$program" ]] || fail "no $built/$program (clraster_bench is built only with libosmesa6-dev)"
done
# The suite runs private copies, so that a rebuild in build/ meanwhile (kernels
# are embedded in the binaries) cannot change or break the code it measures.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin"
cp "$built/clraster" "$built/clraster_bench" "$built/clraster_peak" "$built/clraster_embree" "$work/bin/"
bin="$work/bin"
csv="$work/results.csv"

# Step 3: the device's peaks, best of 50 runs each.
echo "bench/run.sh: peaks"
peak_json=$("$bin/clraster_peak" ${device_args[@]+"${device_args[@]}"} --repeats 50)
peak() { sed -n "s/.*\"$1\":\([0-9.]*\).*/\1/p" <<<"$peak_json"; }
peak_text() { sed -n "s/.*\"$1\":\"\([^\"]*\)\".*/\1/p" <<<"$peak_json"; }
peak_fp32=$(peak fp32_gflops)
peak_mad=$(peak int64_mad_gops)
peak_wmad=$(peak int64_wmad_gops)
peak_copy=$(peak copy_gbs)
peak_lanes=$(awk -v f="$peak_fp32" 'BEGIN { printf "%.2f", f / 2 }')  # 32-bit lane operations: one FMA is 2 FLOPs
echo "  $peak_json"

# Step 4: the cases, one process each, never two at a time.
bench_case() {  # NAME ARGS...
  local name=$1
  shift
  echo "bench/run.sh: $name $*"
  "$bin/clraster_bench" "$@" ${device_args[@]+"${device_args[@]}"} --name "$name" --csv "$csv" \
    --peak-lane-gops "$peak_lanes" --peak-copy-gbs "$peak_copy" >/dev/null ||
    fail "case $name failed"
}
both_orders() {  # NAME ARGS...: the case in the file's order, then shuffled
  local name=$1
  shift
  bench_case "$name" "$@"
  bench_case "shuffled-$name" "$@" --shuffle 1
}
for mesh in "${real_meshes[@]}" "$@"; do
  for size in 1280x720 1920x1080 3840x2160; do
    both_orders "mesh-$(basename "$mesh")" "$mesh" --size "$size" --warmup "$warmup" --frames "$frames"
  done
  both_orders "fill-$(basename "$mesh")" "$mesh" --view fill --size 1920x1080 --warmup "$warmup" --frames "$frames"
done
both_orders "grid5-fill" "$grid_mesh" --grid 5 --view fill --size 1920x1080 --warmup "$warmup" --frames "$frames"
for view in far near; do
  for tris in 10000 100000 1000000; do
    bench_case "sphere-$view" --sphere "$tris" --view "$view" --size 1920x1080 --warmup "$warmup" --frames "$frames"
  done
  bench_case "sphere-$view" --sphere 10000000 --view "$view" --size 1920x1080 --warmup 1 --frames 5
  both_orders "grid16-$view" "$grid_mesh" --grid 16 --view "$view" --size 1920x1080 --warmup "$warmup" \
    --frames "$frames"
done
# Nothing in view with the ~1M-triangle scene loaded (the far camera turned round).
both_orders "grid16-away" "$grid_mesh" --grid 16 --view away --size 1920x1080 --warmup "$warmup" --frames "$frames"

# The second anchor: visibility alone (--shade id) against Embree's primary rays (clraster_embree), the ~93k and
# ~1M real scenes in both orders; Embree's BVH build is timed apart and shown beside its frame.
embree_csv="$work/embree.csv"
echo "name,triangles,width,height,threads,clraster_id_ms,embree_ms,ratio,embree_build_ms,covered,differing" >"$embree_csv"
embree_case() {  # NAME ARGS...
  local name=$1
  shift
  echo "bench/run.sh: embree $name"
  "$bin/clraster_embree" "$@" ${device_args[@]+"${device_args[@]}"} --name "$name" --csv "$embree_csv" \
    --warmup "$warmup" --frames "$frames" >/dev/null || fail "embree case $name failed"
}
for order in "" "--shuffle 1"; do
  prefix=${order:+shuffled-}
  embree_case "${prefix}grid5-fill" "$grid_mesh" --grid 5 --view fill --size 1920x1080 $order
  embree_case "${prefix}grid16-far" "$grid_mesh" --grid 16 --view far --size 1920x1080 $order
done

# Step 5: start-up, the whole process: empty caches, PoCL's cache warm, and
# PoCL's cache warm with the programs stored by `clraster cache`.
wall() {  # seconds taken by a clraster render with its kernel caches in $1
  local start end
  start=$(date +%s.%N)
  # PoCL's cache, NVIDIA's (its OpenCL driver caches built programs there too) and clraster's program cache.
  POCL_CACHE_DIR="$1" CUDA_CACHE_PATH="$1" CLRASTER_CACHE_DIR="$1/clraster" "$bin/clraster" render \
    ${device_args[@]+"${device_args[@]}"} -o "$work/cold.png" --size 1920x1080 >/dev/null ||
    fail "clraster render failed"
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }'
}
median3() { for i in 1 2 3; do wall "$1"; echo; done | sort -n | sed -n 2p; }
echo "bench/run.sh: cold start"
for i in 1 2 3; do
  mkdir "$work/pocl-cold$i"
  wall "$work/pocl-cold$i" >>"$work/colds"
  echo >>"$work/colds"
done
colds=$(sort -n "$work/colds")
cold_s=$(sed -n 2p <<<"$colds")
cold_min=$(sed -n 1p <<<"$colds")
cold_max=$(sed -n 3p <<<"$colds")
warm_s=$(median3 "$work/pocl-cold1")
POCL_CACHE_DIR="$work/pocl-cold1" CUDA_CACHE_PATH="$work/pocl-cold1" CLRASTER_CACHE_DIR="$work/pocl-cold1/clraster" \
  "$bin/clraster" cache ${device_args[@]+"${device_args[@]}"} >/dev/null || fail "clraster cache failed"
stored_s=$(median3 "$work/pocl-cold1")

# Step 6: the Markdown report; awk programs address CSV columns by name.
columns='NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } '
md="$work/results.md"
clr_device=$(awk -F, "$columns"'NR == 2 { print $c["device"] }' "$csv")
# The Mesa release as the bench's GL_VERSION reported it (the library that ran);
# the package list's version where it named none.
mesa=$(awk -F, "$columns"'NR == 2 { print $c["mesa"] }' "$csv")
[[ -n "$mesa" ]] || mesa="$(dpkg-query -W -f='${Version}' libosmesa6 2>/dev/null || echo '?') (package)"
clr_driver="$(peak_text platform), driver $(peak_text driver)"
{
  echo "# clraster vs llvmpipe: benchmark results"
  echo
  echo "Generated by \`bash bench/run.sh\` on $(date -u '+%Y-%m-%d %H:%M UTC')."
  echo "CPU: $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) cores." \
    "clraster device: $clr_device ($clr_driver)." \
    "llvmpipe: $(awk -F, "$columns"'NR == 2 { print $c["llvmpipe"] }' "$csv"), Mesa $mesa, LP_NUM_THREADS=$LP_NUM_THREADS; POCL_AFFINITY=$POCL_AFFINITY."
  echo "Frames: $frames timed per case and renderer (10M-triangle cases: 5), in four rounds that take turns between the renderers, each round after $warmup warm-up frames (10M: 1); times are medians with (min–max)."
  echo
  echo "## Device peaks (clraster_peak, best of 50)"
  echo
  echo "| fp32 FMA | 64-bit multiply-add (64x64) | 64-bit widening multiply-add (32x32→64) | copy (read + write) |"
  echo "|---|---|---|---|"
  echo "| $peak_fp32 GFLOP/s | $peak_mad G/s | $peak_wmad G/s | $peak_copy GB/s |"
  echo
  echo "## Targets"
  echo
  echo "The performance targets at 1920x1080 against llvmpipe in this run: the ~93k-triangle real mesh (grid5-fill, 5x5"
  echo "copies of Wuson.off filling the screen), the ~1M-triangle real scene (grid16, 16x16 copies, far and near), both"
  echo "in the file's order and shuffled; nothing in view with grid16 loaded (grid16-away); the added cost per triangle"
  echo "over the sphere series from 100k to 10M (largest over smallest); and device memory over its minimum in every case."
  echo
  echo "| target | case | measured | goal | met |"
  echo "|---|---|---|---|---|"
  awk -F, "$columns"'NR > 1 { ratio[$c["name"]] = $c["ratio"]; ms[$c["name"]] = $c["clr_ms"]
      if ($c["mem_ratio"] > mem) { mem = $c["mem_ratio"]; memCase = $c["name"] }
      if ($c["name"] ~ /^sphere-/) { n[$c["name"]]++; t[$c["name"], n[$c["name"]]] = $c["triangles"]; f[$c["name"], n[$c["name"]]] = $c["clr_ms"] } }
    function row(what, name, value, goal, ok) { printf "| %s | %s | %s | %s | %s |\n", what, name, value, goal, ok ? "yes" : "no" }
    END {
      split("grid5-fill shuffled-grid5-fill grid16-far shuffled-grid16-far grid16-near shuffled-grid16-near", cases, " ")
      for (i = 1; i <= 6; i++) if (cases[i] in ratio)
        row(i <= 2 ? "frame, ~93k-triangle real mesh" : "frame, ~1M-triangle real scene", cases[i],
            sprintf("%.3fx llvmpipe", ratio[cases[i]]), "<= 0.20x", ratio[cases[i]] <= 0.20)
      split("grid16-away shuffled-grid16-away", away, " ")
      for (i = 1; i <= 2; i++) if (away[i] in ms)
        row("empty view, 1M triangles loaded", away[i], ms[away[i]] " ms", "< 0.5 ms", ms[away[i]] < 0.5)
      split("sphere-far sphere-near", series, " ")
      for (j = 1; j <= 2; j++) {
        s = series[j]; lo = hi = 0
        for (i = 2; i <= n[s]; i++) if (t[s, i - 1] >= 90000) {
          a = (f[s, i] - f[s, i - 1]) / (t[s, i] - t[s, i - 1]); if (!lo || a < lo) lo = a; if (a > hi) hi = a }
        if (lo > 0) row("added cost per triangle, 100k to 10M", s, sprintf("%.2fx", hi / lo), "within 2x", hi / lo <= 2)
      }
      row("device memory over the minimum", "largest: " memCase, sprintf("%.2fx", mem), "<= 2x", mem <= 2)
    }' "$csv"
  echo
  echo "Against the physical limit: the least a frame moves is its scene's minimum (positions, normals and indices"
  echo "read, the image written; the minimum of **device MB** below). At the device's copy bandwidth ($peak_copy GB/s,"
  echo "read + write) that takes the **stream bound**. **bound / llvmpipe** is the ratio no renderer can beat on this"
  echo "machine; **bound / clraster** is the share of that limit clraster's frame reaches."
  echo
  echo "| case | minimum MB | stream bound ms | bound / llvmpipe | bound / clraster |"
  echo "|---|---|---|---|---|"
  awk -F, -v copy="$peak_copy" "$columns"'NR > 1 { row[$c["name"]] = NR; minb[NR] = $c["min_bytes"]; clr[NR] = $c["clr_ms"]
      llvm[NR] = $c["llvm_ms"] }
    END {
      split("grid5-fill shuffled-grid5-fill grid16-far shuffled-grid16-far grid16-near shuffled-grid16-near", cases, " ")
      for (i = 1; i <= 6; i++) if (cases[i] in row) {
        r = row[cases[i]]; bound = minb[r] / (copy * 1e6)
        printf "| %s | %.1f | %.3f | %.4fx | %.1f%% |\n", cases[i], minb[r] / 1e6, bound, bound / llvm[r], 100 * bound / clr[r]
      }
    }' "$csv"
  echo
  echo "## Cases"
  echo
  echo "| case | size | triangles | covered | clraster ms | llvmpipe ms | clraster / llvmpipe (rounds) | llvmpipe lit per vertex ms (clraster / it) |" \
    "raster / resolve / other kernels ms | Mtri/s (clraster / llvmpipe) | Mpix/s (clraster / llvmpipe) | device MB (minimum, ratio) |" \
    "ID differing fraction (pixels; not near an edge) | shade MAD (per pixel; per vertex) | edge Geval/s (% peak) | raster+resolve GB/s (% peak) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, "$columns"'NR > 1 {
    name = $c["name"]; sub(/^mesh-/, "", name)
    printf "| %s | %sx%s | %d | %.1f%% | %s (%s–%s) | %s (%s–%s) | %s (%s–%s) | %s (%s) |",
      name, $c["width"], $c["height"], $c["triangles"], 100 * $c["covered_pixels"] / $c["pixels"], $c["clr_ms"], $c["clr_ms_min"], $c["clr_ms_max"],
      $c["llvm_ms"], $c["llvm_ms_min"], $c["llvm_ms_max"], $c["ratio"], $c["ratio_round_min"], $c["ratio_round_max"],
      $c["llvm_vertex_ms"], $c["ratio_vertex"]
    printf " %s / %s / %s | %.2f / %.2f | %.1f / %.1f | %.1f (%.1f, %.2fx) | %s (%s px; %s) | %s; %s |",
      $c["raster_ms"], $c["resolve_ms"], $c["other_stages_ms"], $c["clr_mtris_s"], $c["llvm_mtris_s"], $c["clr_mpix_s"],
      $c["llvm_mpix_s"], $c["device_bytes"] / 1e6, $c["min_bytes"] / 1e6, $c["mem_ratio"], $c["differing_fraction"],
      $c["differing_pixels"], $c["differing_not_near_edge"], $c["shade_mad"], $c["shade_mad_vertex"]
    printf " %.2f (%.1f%%) | %.2f (%.1f%%) |\n", $c["edge_gevals_s"], 100 * $c["edge_frac_lane_ops"], $c["rr_gbs"],
      100 * $c["rr_frac_copy"]
  }' "$csv"
  echo
  echo "## Input order: the file's and shuffled faces"
  echo
  echo "Each real-mesh case in its file's triangle order and with its faces shuffled (\`--shuffle 1\`), the same camera."
  echo "clraster lays every scene out at upload (docs/architecture.md, \"Scene layout and locality\"); **prepare ms** is"
  echo "that upload (layout, cluster bounds, buffers), once per scene and outside the frame times."
  echo
  echo "| case | size | triangles | file: clraster ms | file: llvmpipe ms | file: ratio | shuffled: clraster ms | shuffled: llvmpipe ms | shuffled: ratio | clraster shuffled / file | prepare ms (file; shuffled) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, "$columns"'NR > 1 {
    key = $c["name"] "@" $c["width"] "x" $c["height"]
    if ($c["name"] ~ /^shuffled-/) { sub(/^shuffled-/, "", key); shuf[key] = NR; row[NR] = $0; next }
    keys[++n] = key; file[key] = NR; row[NR] = $0
  }
  END {
    for (i = 1; i <= n; i++) {
      k = keys[i]; if (!(k in shuf)) continue
      split(row[file[k]], f, ","); split(row[shuf[k]], s, ",")
      name = k; sub(/@.*/, "", name); sub(/^mesh-/, "", name)
      printf "| %s | %sx%s | %d | %s | %s | %s | %s | %s | %s | %.2f | %s; %s |\n", name, f[c["width"]], f[c["height"]],
        f[c["triangles"]], f[c["clr_ms"]], f[c["llvm_ms"]], f[c["ratio"]], s[c["clr_ms"]], s[c["llvm_ms"]], s[c["ratio"]],
        s[c["clr_ms"]] / f[c["clr_ms"]], f[c["prepare_ms"]], s[c["prepare_ms"]]
    }
  }' "$csv"
  echo
  echo "## Per-stage kernel times (clraster, median ms, OpenCL profiling)"
  echo
  echo "| case | size | triangles | setup triangles | bin entries | stages | device idle between kernels |"
  echo "|---|---|---|---|---|---|---|"
  awk -F, "$columns"'NR > 1 {
    s = $c["stage_ms"]; gsub(/;/, ", ", s); gsub(/=/, " ", s)
    printf "| %s | %sx%s | %d | %d | %d | %s | %s |\n", $c["name"], $c["width"], $c["height"], $c["triangles"],
      $c["setup_triangles"], $c["bin_entries"], s, $c["device_idle_ms"]
  }' "$csv"
  echo
  echo "## Scale series: time per triangle"
  echo
  echo "Each renderer's frame time over the series' triangle count (**per triangle**), and the cost of the triangles"
  echo "each step adds (**added**: the frame's growth over the triangles' growth since the previous size). The issue's"
  echo "target is per triangle within 2x from 100k to 10M; a frame's fixed costs (clearing, the pixels every size"
  echo "covers) weigh on the small sizes per triangle, not on the added cost. **spread**: the largest value over the"
  echo "smallest from 100k triangles on."
  echo
  echo "| series | triangles | clraster ns per triangle (added) | llvmpipe ns per triangle (added) |"
  echo "|---|---|---|---|"
  for series in sphere-far sphere-near; do
    awk -F, -v series="$series" "$columns"'NR > 1 && $c["name"] == series {
      n++; tris[n] = $c["triangles"]; clr[n] = $c["clr_ms"]; llvm[n] = $c["llvm_ms"]
    }
    function spread(lo, hi) { return lo > 0 ? sprintf("%.2fx", hi / lo) : "-" }
    END {
      for (i = 1; i <= n; i++) {
        pc = 1e6 * clr[i] / tris[i]; pl = 1e6 * llvm[i] / tris[i]; ac = al = "-"
        if (i > 1) {
          ac = sprintf("%.1f", 1e6 * (clr[i] - clr[i - 1]) / (tris[i] - tris[i - 1]))
          al = sprintf("%.1f", 1e6 * (llvm[i] - llvm[i - 1]) / (tris[i] - tris[i - 1]))
        }
        printf "| %s | %d | %.1f (%s) | %.1f (%s) |\n", series, tris[i], pc, ac, pl, al
        if (tris[i] < 90000) continue
        if (!m || pc < pcLo) pcLo = pc; if (!m || pc > pcHi) pcHi = pc
        if (!m || pl < plLo) plLo = pl; if (!m || pl > plHi) plHi = pl
        if (m && (m == 1 || ac + 0 < acLo)) acLo = ac + 0; if (m && (m == 1 || ac + 0 > acHi)) acHi = ac + 0
        if (m && (m == 1 || al + 0 < alLo)) alLo = al + 0; if (m && (m == 1 || al + 0 > alHi)) alHi = al + 0
        m++
      }
      if (m) printf "| %s spread | | %s (%s) | %s (%s) |\n", series, spread(pcLo, pcHi),
        (m > 1 ? spread(acLo, acHi) : "-"), spread(plLo, plHi), (m > 1 ? spread(alLo, alHi) : "-")
    }' "$csv"
  done
  echo
  echo "## Cold start"
  echo
  echo "Whole \`build/clraster render -o OUT.png --size 1920x1080\` process (built-in scene, one frame), wall time;"
  echo "caches: PoCL's (POCL_CACHE_DIR), NVIDIA's (CUDA_CACHE_PATH) and the programs \`clraster cache\` stores (CLRASTER_CACHE_DIR):"
  echo
  echo "| empty caches (kernels compiled; median of 3, range) | warm driver cache (median of 3) | warm, programs stored (median of 3) |"
  echo "|---|---|---|"
  awk -v c="$cold_s" -v lo="$cold_min" -v hi="$cold_max" -v w="$warm_s" -v st="$stored_s" \
    'BEGIN { printf "| %.3f s (%.3f–%.3f) | %.3f s | %.3f s |\n", c, lo, hi, w, st }'
  echo
  echo "## Definitions"
  echo
  echo "- **clraster ms**: wall time of \`Pipeline::render\` into an \`ImageView\`: parameter upload through all kernels"
  echo "  to the RGBA8 image mapped for the host (on a CPU device, no copy). **llvmpipe ms**: \`glClear\` +"
  echo "  \`glDrawElements\` (positions, normals and indices in buffer objects) + \`glFinish\` through OSMesa, into its host"
  echo "  buffer (no copy either). Both shade lambert per pixel, the same image: one directional light, ambient"
  echo "  0.12 + diffuse 0.88 times the built-in grey albedo (the file's materials set aside on both sides), the"
  echo "  interpolated normal made unit, two-sided; llvmpipe through a GLSL program written to clraster's formula."
  echo "  **llvmpipe lit per vertex**: llvmpipe's fixed-function lighting instead (GL_SMOOTH: lit at the vertices,"
  echo "  colours interpolated), a cheaper and different image, timed in the same process. The process fixes"
  echo "  glibc's heap trim threshold at 256 MB, which keeps llvmpipe at its faster mode (it otherwise gives its"
  echo "  per-frame memory back to the system and faults it in again: 26 against 18 ms on \`yxa_1\` filling 1080p)."
  echo "- **clraster / llvmpipe**: the ratio of the two medians over all timed frames; in brackets the least and"
  echo "  greatest of the four rounds' own ratios (each round's clraster median over llvmpipe's in the same round),"
  echo "  which shows how far the host's slower and faster spells move the ratio."
  echo "- **far / fill / near**: the whole object framed as by \`clraster render\` (mostly small triangles; an elongated"
  echo "  model covers a few percent of the screen); the same camera moved closer until the model reaches 90% of the way"
  echo "  to the nearest border (rows named \`fill-\`); or the eye at 0.75 bounding radii from the object's centre (mostly"
  echo "  large triangles; the grid's near view looks at the centre copy). **covered** is the share of pixels either renderer covers."
  echo "- **device MB**: every clraster device buffer (\`Pipeline::deviceBytes()\`). **minimum** = 24 B per vertex"
  echo "  (position + normal) + 12 B per triangle (indices) + 4 B per pixel (the RGBA8 image)."
  echo "- **ID differing**: triangle-ID images of both renderers compared as \`clraster_vs_llvmpipe\` does: pixels whose"
  echo "  ids differ, as a fraction of the pixels either covers; \"not near an edge\" counts those whose 3x3"
  echo "  neighbourhood is a single id in both images. **shade MAD**: mean absolute RGB difference (0–255) of"
  echo "  clraster's lambert image and llvmpipe's, per pixel (the same formula: rounding only) and per vertex,"
  echo "  over the pixels either covers."
  echo "- **edge Geval/s** = bin entries × 16² samples × 3 edges / raster time: the nominal edge-function evaluations"
  echo "  of the raster kernel. Raster steps each edge function from row to row with one add per lane (32-bit lanes"
  echo "  for triangles within 64 pixels), so **% peak** is relative to the 32-bit lane-operation rate, half the fp32"
  echo "  FLOP peak. It can exceed 100 %: the kernel skips rows and row segments a triangle's bounds miss, and bin"
  echo "  entries wholly behind the depths their tile keeps, so fewer evaluations run than counted."
  echo "- **raster+resolve GB/s** = (12 B per pixel: the visible triangle's 4-B index written by raster and read"
  echo "  by resolve, the 4-B image written; plus 36 B of triangle setup read per bin entry) / (raster + resolve time);"
  echo "  **% peak** is relative to the copy bandwidth (bytes read + written)."
  echo "- **device idle between kernels**: median over the timed frames of the time from the first kernel's start to"
  echo "  the last one's end that no kernel ran (profiling events): launches, buffer fills, reads, and the host's wait"
  echo "  for the totals that size the buffers. The image's read-back after the last kernel is not in it."
  echo "- Other engineers' jobs may share the host's cores; treat single runs as noisy."
  echo
  echo "## Visibility alone against Embree"
  echo
  echo "clraster's triangle-ID frame (\`--shade id\`, camera upload to mapped image) against Embree $(dpkg-query -W -f='${Version}' libembree3-3 2>/dev/null || echo '?')"
  echo "primary rays (one per pixel centre, 16-ray packets, as many threads as cores; the BVH built once, its build"
  echo "timed apart), medians of $frames frames in turns. **differing** counts pixels whose IDs differ, over those either"
  echo "covers (edges: float rays against 1/256-pixel snapping). Goal: clraster <= 0.15x Embree."
  echo
  echo "| case | triangles | clraster id ms | Embree ms | ratio | met | Embree BVH build ms | differing / covered |"
  echo "|---|---|---|---|---|---|---|---|"
  awk -F, "$columns"'NR > 1 { printf "| %s | %d | %s | %s | %.3fx | %s | %s | %d / %d |\n", $c["name"], $c["triangles"],
      $c["clraster_id_ms"], $c["embree_ms"], $c["ratio"], $c["ratio"] <= 0.15 ? "yes" : "no", $c["embree_build_ms"],
      $c["differing"], $c["covered"] }' "$embree_csv"
} >"$md"

# Step 7: the charts (bench/charts.sh), unless BENCH_CHARTS=0.
charts=()
if [[ "${BENCH_CHARTS:-1}" != 0 ]]; then
  bash bench/charts.sh "$csv" "$work" || fail "charts failed"
  charts=("$work/scaling_triangles.png" "$work/scaling_pixels.png")
fi

# Step 8: replace the results in the output folder.
mkdir -p "$out_dir"
cp "$csv" "$embree_csv" "$md" ${charts[@]+"${charts[@]}"} "$out_dir/"
elapsed=$(awk -v a="$suite_start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.0f", b - a }')
echo "bench/run.sh: wrote $out_dir/results.csv, results.md${charts[*]:+, scaling_triangles.png, scaling_pixels.png} in ${elapsed} s"
