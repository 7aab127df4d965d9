// quality.cpp — the automatic method choice (see quality.h).
#include "render/quality.h"

#include "render/flags.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace clr {

namespace {

// Largest per-channel difference of two RGBA8 colours, in [0, 1].
double channelDelta(uint32_t a, uint32_t b, int channel)
{
  const int shift = 8 * channel;
  return std::abs(int((a >> shift) & 0xFF) - int((b >> shift) & 0xFF)) / 255.0;
}

}  // namespace

EdgeContrast measureEdgeContrast(const std::vector<uint32_t>& rgba, const std::vector<VisSample>& vis, uint32_t width,
                                 uint32_t height, Window window)
{
  EdgeContrast c;
  const uint32_t x1 = std::min(width, window.x0 + std::min(window.w, width));
  const uint32_t y1 = std::min(height, window.y0 + std::min(window.h, height));
  for (uint32_t y = window.y0; y < y1; ++y)
    for (uint32_t x = window.x0; x < x1; ++x) {
      ++c.pixels;
      // Step 1: an edge pixel shows another triangle than its right or upper neighbour.
      const size_t p = size_t(y) * width + x;
      const uint32_t colour = rgba[size_t(height - 1 - y) * width + x];
      double delta[3] = {0, 0, 0};
      bool edge = false;
      for (int n = 0; n < 2; ++n) {
        const uint32_t nx = x + (n == 0), ny = y + (n == 1);
        if (nx >= width || ny >= height) continue;
        const size_t q = size_t(ny) * width + nx;
        if (vis[q].setupIndex == vis[p].setupIndex) continue;
        edge = true;
        // Step 2: its contrast, per channel.
        const uint32_t other = rgba[size_t(height - 1 - ny) * width + nx];
        for (int ch = 0; ch < 3; ++ch) delta[ch] = std::max(delta[ch], channelDelta(colour, other, ch));
      }
      if (!edge) continue;
      ++c.edgePixels;
      c.sumSquared += delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2];
    }
  return c;
}

double edgeCoverageError(const AaMode& mode)
{
  // RMS coverage error per edge pixel (0 < exact area < 1), measured by
  // `clraster_accuracy` on its coverage scene (2304 disjoint random
  // triangles at 1280x720, one per 20-pixel cell) against the exact area:
  // docs/bench/accuracy.csv, column edge_rmse. Deterministic (no timing).
  // SSAA's coverage is MSAA's at the same count.
  switch (mode.samples) {
    case 1: return 0.2594;
    case 2: return 0.1703;
    case 4: return 0.0970;
    case 8: return 0.0606;
    default: return 0.0444;
  }
}

double predictRmse(const AaMode& mode, const EdgeContrast& contrast)
{
  if (contrast.pixels == 0) return 0.0;
  return edgeCoverageError(mode) * std::sqrt(contrast.sumSquared / (3.0 * double(contrast.pixels)));
}

AutoChoice chooseAutomatically(Pipeline& pipeline, FrameSettings& settings, bool chooseAa, bool chooseTraversal)
{
  // Step 1: the probe frame, one sample per pixel.
  FrameSettings probe = settings;
  probe.samples = 1;
  probe.shadeEverySample = false;
  std::vector<uint32_t> rgba;
  const FrameStats stats = pipeline.render(probe, rgba);
  AutoChoice choice;
  choice.contrast = measureEdgeContrast(rgba, pipeline.readVis(), settings.width, settings.height);
  // Step 2: the cheapest mode meeting the target (modes are listed cheapest
  // first; SSAA never lowers the edge error below MSAA's at the same count).
  const std::vector<AaMode>& modes = aaModes();
  const AaMode* chosen = nullptr;
  for (const AaMode& m : modes) {
    if (m.shadeEverySample) continue;
    const double predicted = predictRmse(m, choice.contrast);
    if (predicted <= choice.targetRmse) {
      chosen = &m;
      choice.predictedRmse = predicted;
      break;
    }
  }
  if (chosen) {
    choice.reason = "cheapest mode predicted within the target";
  } else {
    chosen = &findAaMode("msaa16");
    choice.predictedRmse = predictRmse(*chosen, choice.contrast);
    choice.reason = "no mode meets the target; the most accurate MSAA";
  }
  if (chooseAa) {
    choice.aa = chosen->name;
    settings.samples = chosen->samples;
    settings.shadeEverySample = chosen->shadeEverySample;
  } else {
    choice.aa = aaModeName(settings.samples, settings.shadeEverySample);
    choice.predictedRmse = predictRmse(findAaMode(choice.aa), choice.contrast);
    choice.reason = "anti-aliasing given by --aa";
  }
  // Step 3: traversal, from the probe's bin entries per triangle; then
  // exact spans where they measure faster (quality.h), never the float walk.
  choice.tilesPerTriangle = stats.setupTriangles ? double(stats.binEntries) / double(stats.setupTriangles) : 0.0;
  choice.traversal = settings.traversal;
  if (!chooseTraversal) return choice;
  const uint32_t rule =
      choice.tilesPerTriangle > kHierarchicalTilesPerTriangle ? CLR_TRAVERSAL_HIERARCHICAL : CLR_TRAVERSAL_BBOX;
  choice.traversal = rule;
  if (settings.edgeMode == CLR_EDGES_FIXED) {
    choice.ruleMs = choice.spansMs = std::numeric_limits<double>::infinity();
    for (int round = 0; round < kSpansProbeRounds; ++round)
      for (uint32_t traversal : {rule, CLR_TRAVERSAL_SPANS}) {
        probe.traversal = traversal;
        const FrameStats timed = pipeline.render(probe, rgba);
        double ms = 0.0;
        for (const auto& [stage, stageMs] : timed.stageMs) ms += stageMs;
        double& least = traversal == rule ? choice.ruleMs : choice.spansMs;
        least = std::min(least, ms);
      }
    if (choice.spansMs < kSpansMargin * choice.ruleMs) choice.traversal = CLR_TRAVERSAL_SPANS;
  }
  settings.traversal = choice.traversal;
  return choice;
}

std::string AutoChoice::json() const
{
  char buffer[640];
  std::snprintf(buffer, sizeof buffer,
                "{\"aa\":\"%s\",\"predicted_rmse\":%.5f,\"target_rmse\":%.5f,\"edge_pixels\":%llu,"
                "\"pixels\":%llu,\"tiles_per_triangle\":%.2f,\"traversal\":\"%s\",\"probe_ms\":%.3f,"
                "\"probe_spans_ms\":%.3f,\"reason\":\"%s\"}",
                aa.c_str(), predictedRmse, targetRmse, (unsigned long long)contrast.edgePixels,
                (unsigned long long)contrast.pixels, tilesPerTriangle, traversalName(traversal), ruleMs, spansMs,
                reason.c_str());
  return buffer;
}

}  // namespace clr
