// aa.cpp — the anti-aliasing mode table and the standard sample positions
// (see aa.h). The positions are the Direct3D 11 standard multisample
// patterns (also Vulkan's standard sample locations), in 1/16 pixel.
#include "pipeline/aa.h"

#include "pipeline/cl.h"

namespace clr {

const std::vector<AaMode>& aaModes()
{
  static const std::vector<AaMode> modes = {{"none", 1, false},  {"msaa2", 2, false},   {"msaa4", 4, false},
                                            {"msaa8", 8, false}, {"msaa16", 16, false}, {"ssaa4", 4, true},
                                            {"ssaa16", 16, true}};
  return modes;
}

const AaMode& findAaMode(const std::string& name)
{
  std::string names;
  for (const AaMode& m : aaModes()) {
    if (name == m.name) return m;
    names += std::string(names.empty() ? "" : ", ") + m.name;
  }
  throw Error("--aa: unknown mode '" + userText(name) + "' (" + names + ", auto)");
}

std::string aaModeName(uint32_t samples, bool shadeEverySample)
{
  for (const AaMode& m : aaModes())
    if (m.samples == samples && (samples == 1 || m.shadeEverySample == shadeEverySample)) return m.name;
  return (shadeEverySample ? "ssaa" : "msaa") + std::to_string(samples);
}

const std::vector<SampleOffset>& samplePositions(uint32_t samples)
{
  static const std::vector<SampleOffset> one = {{0, 0}};
  static const std::vector<SampleOffset> two = {{4, 4}, {-4, -4}};
  static const std::vector<SampleOffset> four = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
  static const std::vector<SampleOffset> eight = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                                  {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
  static const std::vector<SampleOffset> sixteen = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                                    {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                                    {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};
  switch (samples) {
    case 1: return one;
    case 2: return two;
    case 4: return four;
    case 8: return eight;
    case 16: return sixteen;
    default: throw Error("unsupported sample count " + std::to_string(samples) + " (1, 2, 4, 8 or 16)");
  }
}

}  // namespace clr
