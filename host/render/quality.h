// quality.h — `--aa auto` and `--quality auto`: the cheapest method whose
// predicted error stays within a stated target, per scene.
//
// The prediction is a model fitted to the figures bench/accuracy measures
// (docs/accuracy.md). A probe frame without anti-aliasing is rendered first;
// every pixel whose right or upper neighbour shows another triangle (or
// background) is an edge pixel, and its contrast Δ is the largest colour
// difference, per channel in [0, 1], to those neighbours. With c(mode) the
// RMS coverage error of an edge pixel that the mode leaves, measured on a
// scene of disjoint triangles against the exact area, the image's RMSE
// against a converged reference is predicted as
//     RMSE(mode) ≈ c(mode) · sqrt(Σ_edge pixels Σ_channels Δ² / (3 · pixels)).
// The model covers geometric edges only: aliasing inside triangles (a fine
// texture) is what SSAA addresses and is not predicted.
#pragma once

#include "pipeline/aa.h"
#include "pipeline/pipeline.h"

#include <cstdint>
#include <string>
#include <vector>

namespace clr {

// Image RMSE target of --aa auto: 0.005 of full scale over the whole image
// (PSNR 46 dB); at 0.01 a scene on a dark background often passed without
// anti-aliasing although its silhouettes were visibly stepped.
constexpr double kAutoTargetRmse = 0.005;

// Tiles per setup triangle (bounding-box binning) above which --quality auto
// takes hierarchical traversal: below it hierarchical's tile tests cost more than
// they save, far above it they save most of bin + raster; the threshold sits in the
// gap (compare `clraster render --stats --traversal bbox|hierarchical`, docs/methods.md).
constexpr double kHierarchicalTilesPerTriangle = 100.0;

// --quality auto then takes exact spans (the same coverage, raster.cl) where
// they measure faster on the scene itself: kSpansProbeRounds alternated
// probe frames of each, the least kernel time of each, spans taken when
// below kSpansMargin of the other's (bench/traversal.sh: they win on few
// scenes, so the margin keeps load noise from flipping the choice).
constexpr int kSpansProbeRounds = 3;
constexpr double kSpansMargin = 0.95;

struct EdgeContrast {
  uint64_t pixels = 0, edgePixels = 0;
  double sumSquared = 0;  // Σ over edge pixels and channels of Δ²
};

// rgba: an RGBA8 image, top row first (as Pipeline::readImage); vis: the
// visible setup triangle per pixel, bottom row first (Pipeline::readVis).
// Measured over the window [x0, x0 + w) × [y0, y0 + h), the whole image by default.
struct Window {
  uint32_t x0 = 0, y0 = 0, w = UINT32_MAX, h = UINT32_MAX;
};
EdgeContrast measureEdgeContrast(const std::vector<uint32_t>& rgba, const std::vector<VisSample>& vis, uint32_t width,
                                 uint32_t height, Window window = {});

// The measured RMS coverage error per edge pixel of a mode (see above).
double edgeCoverageError(const AaMode& mode);

double predictRmse(const AaMode& mode, const EdgeContrast& contrast);

struct AutoChoice {
  std::string aa;  // the chosen aa.h mode
  double predictedRmse = 0;
  double targetRmse = kAutoTargetRmse;
  EdgeContrast contrast;
  uint32_t traversal = CLR_TRAVERSAL_BBOX;  // chosen traversal (when chosen)
  double tilesPerTriangle = 0;
  double ruleMs = 0, spansMs = 0;  // probe kernel times: bbox or hierarchical by the rule, and spans (0: not timed)
  std::string reason;
  std::string json() const;  // for --stats
};

// Renders the probe frame with `settings` (anti-aliasing off) and sets, with
// chooseAa, the cheapest anti-aliasing mode whose predicted error meets the
// target and, with chooseTraversal, the traversal (more probe frames).
AutoChoice chooseAutomatically(Pipeline& pipeline, FrameSettings& settings, bool chooseAa, bool chooseTraversal);

}  // namespace clr
