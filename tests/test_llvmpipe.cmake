# test_llvmpipe.cmake — clraster against Mesa llvmpipe (bench/llvmpipe_ids.cpp) as triangle-ID images,
# registered only where bench/ built the tool (OSMesa found); include it after add_subdirectory(bench).
#
# Why the bound is 5e-4 of the covered pixels. Both rasterizers snap vertices to the same 1/256-pixel grid
# with the same fill rule, so coverage agreed at every pixel in every scene measured; the few differing pixels
# (1 of 21914 for Wuson at 640x480, 1 of 104527 for the default scene at 1280x720) are depth-order decisions
# where the two triangles' depth planes meet within 0.006 px of the pixel centre: the shared edge of a
# silhouette fold (the pixel centre within 1e-3 px of it) or an interpenetration. There the two depths differ
# by under 1e-5, and the nearer one depends on whether depth is the plane through the unsnapped float vertices
# (llvmpipe) or interpolated with the snapped triangle's barycentrics (clraster). The bound leaves 10x (Wuson)
# and 50x (default scene) headroom over that, yet fails on a systematic convention error: moving llvmpipe's
# viewport by 0.001 px (a quarter of one snapping step) already gives 5.9e-4 (Wuson) and 8.1e-4 (default
# scene), a half-pixel centre error about 0.2, a y flip far more. Any differing pixel whose 3x3 neighbourhood
# is a single id in both images fails regardless.
if(TARGET clraster_vs_llvmpipe)
  add_test(NAME llvmpipe_coverage_wuson
           COMMAND clraster_vs_llvmpipe /usr/share/assimp/models/OFF/Wuson.off
                   --size 640x480 --max-diff-fraction 5e-4)
  add_test(NAME llvmpipe_coverage_default_scene
           COMMAND clraster_vs_llvmpipe --size 1280x720 --max-diff-fraction 5e-4)
  set_tests_properties(llvmpipe_coverage_wuson llvmpipe_coverage_default_scene
                       PROPERTIES ENVIRONMENT "POCL_CACHE_DIR=${CMAKE_BINARY_DIR}/pocl-cache")
endif()

# The bench's lambert peer (bench/llvmpipe_render.cpp): llvmpipe's GLSL
# program must draw clraster's lambert image, or the suite's ratios compare
# different work. Why the bound is 0.05 of 255 (mean absolute RGB difference
# over the covered pixels): both sides evaluate the same formula in floats,
# and differ only where the rounding of the interpolation or of the 8-bit
# conversion moves a channel by one, or where a depth tie at a silhouette
# shows another triangle, well under the bound on the bench scenes (whose
# file materials the bench sets aside on both sides), while an ambient of
# 0.11 instead of 0.12 in the program, or an unnormalised normal, exceeds it
# by far. (These runs time nothing: one
# frame each, and only the images are checked.)
if(TARGET clraster_bench)
  add_test(NAME llvmpipe_lambert_default_scene
           COMMAND clraster_bench --size 640x480 --warmup 0 --frames 1 --no-ids --max-shade-mad 0.05)
  add_test(NAME llvmpipe_lambert_yxa_1
           COMMAND clraster_bench /usr/share/assimp/models/BLEND/yxa_1.blend --view fill --size 640x480
                   --warmup 0 --frames 1 --no-ids --max-shade-mad 0.05)
  # The results' header names the Mesa release from the bench's own
  # GL_VERSION (the library that ran), not from the package list, which on
  # a machine running a copied libOSMesa names none.
  add_test(NAME bench_reports_mesa_release COMMAND clraster_bench --size 64x48 --warmup 0 --frames 1 --no-ids)
  set_tests_properties(bench_reports_mesa_release PROPERTIES PASS_REGULAR_EXPRESSION
                                                             "\"mesa\":\"[0-9]+\\.[0-9]+\\.[0-9]+\"")
  # Each round's own ratio, least and greatest, beside the ratio of all frames.
  add_test(NAME bench_reports_round_ratios COMMAND clraster_bench --size 64x48 --warmup 0 --frames 2 --rounds 2 --no-ids)
  set_tests_properties(bench_reports_round_ratios PROPERTIES PASS_REGULAR_EXPRESSION
                                                             "\"ratio_round_min\":[0-9.]+,\"ratio_round_max\":[0-9.]+,")
  # bench/ab.sh, the A/B tool, on two pairs of turns of the same build: both builds' medians and the pairs'
  # counts; and a case the servers cannot load, which must end the script with the server's error, not hang it.
  add_test(NAME bench_ab_script COMMAND bash ${CMAKE_SOURCE_DIR}/bench/ab.sh -n 2 ${CMAKE_BINARY_DIR}
                                        ${CMAKE_BINARY_DIR} --size 64x48 --warmup 0 --frames 1)
  set_tests_properties(bench_ab_script PROPERTIES PASS_REGULAR_EXPRESSION
                                                  "A frame [0-9.]+ ms, .*raster [0-9.]+.*\nB frame [0-9.]+ ms, .*\nB lower: frame [012], .*raster [012].* of 2 pairs")
  add_test(NAME bench_ab_script_server_fails
           COMMAND bash -c "bash \"$0\" -n 2 \"$1\" \"$1\" \"$1/no-such-scene.obj\" 2>&1 || echo \"exit status $?\""
                   ${CMAKE_SOURCE_DIR}/bench/ab.sh ${CMAKE_BINARY_DIR})
  set_tests_properties(bench_ab_script_server_fails PROPERTIES TIMEOUT 60 PASS_REGULAR_EXPRESSION
                                                               "no-such-scene.obj: cannot open.*\n.*--serve stopped\nexit status 1")
  # --serve with an output it does not write: a clear error before any rendering.
  add_test(NAME bench_serve_rejects_outputs COMMAND bash -c "\"$0\" --serve --csv \"$1\" 2>&1 || echo \"exit status $?\""
                                                    $<TARGET_FILE:clraster_bench> ${CMAKE_BINARY_DIR}/serve.csv)
  set_tests_properties(bench_serve_rejects_outputs PROPERTIES PASS_REGULAR_EXPRESSION
                                                              "--serve writes only its turns' lines.*\nexit status 1")
  # --shade: clraster's other modes in ab.sh's turns (the general resolve kernel), and only there, since the
  # comparison with llvmpipe is of the lambert image.
  add_test(NAME bench_ab_script_shade COMMAND bash ${CMAKE_SOURCE_DIR}/bench/ab.sh -n 1 ${CMAKE_BINARY_DIR}
                                              ${CMAKE_BINARY_DIR} --size 64x48 --warmup 0 --frames 1 --shade phong)
  set_tests_properties(bench_ab_script_shade PROPERTIES PASS_REGULAR_EXPRESSION
                                                        "A frame [0-9.]+ ms, .*resolve [0-9.]+.*\nB frame [0-9.]+ ms")
  add_test(NAME bench_shade_needs_serve COMMAND bash -c "\"$0\" --shade phong 2>&1 || echo \"exit status $?\""
                                                $<TARGET_FILE:clraster_bench>)
  set_tests_properties(bench_shade_needs_serve PROPERTIES PASS_REGULAR_EXPRESSION
                                                          "--shade applies only with --serve.*\nexit status 1")
  set_tests_properties(llvmpipe_lambert_default_scene llvmpipe_lambert_yxa_1 bench_reports_mesa_release
                       bench_reports_round_ratios PROPERTIES ENVIRONMENT "POCL_CACHE_DIR=${CMAKE_BINARY_DIR}/pocl-cache")
endif()

# The bench's second anchor, Embree's primary rays (bench/embree_bench.cpp): both sides must see the same scene
# through the same camera, their ID images differing only where a float ray and 1/256-pixel snapping split an edge
# (under 1% of the covered pixels on these scenes; a camera or winding mistake differs on most of them). One frame
# each; nothing is timed.
if(TARGET clraster_embree)
  add_test(NAME embree_ids_default_scene COMMAND clraster_embree --size 320x240 --warmup 0 --frames 1
                                                 --max-differing 0.01)
  add_test(NAME embree_ids_wuson_grid COMMAND clraster_embree /usr/share/assimp/models/OFF/Wuson.off --grid 3
                                              --shuffle 1 --view fill --size 320x240 --warmup 0 --frames 1
                                              --max-differing 0.01)
  set_tests_properties(embree_ids_default_scene embree_ids_wuson_grid PROPERTIES LABELS slow
                       ENVIRONMENT "POCL_CACHE_DIR=${CMAKE_BINARY_DIR}/pocl-cache")
endif()

# bench/load.sh's llvmpipe column (bench/llvmpipe_picture.cpp): a file becomes a PNG and one JSON line with the
# split; a file it cannot import is one line on stderr and exit status 1. (Times nothing: the figures are only
# printed.)
if(TARGET clraster_llvmpipe_picture)
  add_test(NAME llvmpipe_picture_writes_png
           COMMAND bash -c "\"$0\" /usr/share/assimp/models/OFF/Wuson.off \"$1\" --size 64x48 && head -c 4 \"$1\" | tail -c 3"
                   $<TARGET_FILE:clraster_llvmpipe_picture> ${CMAKE_BINARY_DIR}/llvmpipe_picture.png)
  set_tests_properties(llvmpipe_picture_writes_png PROPERTIES PASS_REGULAR_EXPRESSION
                                                               "\"triangles\":[1-9][0-9]*,.*\"total_ms\":[0-9.]+}\nPNG")
  add_test(NAME llvmpipe_picture_refuses_bad_file
           COMMAND bash -c "\"$0\" /nonexistent.off \"$1\" 2>&1; echo \"exit status $?\""
                   $<TARGET_FILE:clraster_llvmpipe_picture> ${CMAKE_BINARY_DIR}/llvmpipe_picture_bad.png)
  set_tests_properties(llvmpipe_picture_refuses_bad_file PROPERTIES PASS_REGULAR_EXPRESSION
                                                                     "^clraster_llvmpipe_picture: [^\n]*nonexistent.off[^\n]*\nexit status 1\n$")
endif()
