// test_frame_request.cpp — makeFrameSettings (frame_request.h), the one
// function that turns render arguments, a camera and a viewport into a
// frame's settings: each flag lands in its field, the camera's matrices and
// the depth choice agree, and the defaults are FrameSettings' own.
#include "render/frame_request.h"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace {

clr::RenderArgs parse(const std::vector<std::string>& flags)
{
  std::vector<std::string> args = {"-o", "out.png"};
  args.insert(args.end(), flags.begin(), flags.end());
  return clr::parseRenderArgs(args);
}

clr::Bounds unitBox()
{
  clr::Bounds b;
  b.min = glm::vec3(-1.0f, -2.0f, -2.0f);
  b.max = glm::vec3(1.0f, 2.0f, 2.0f);  // diagonal 6, so the point light's default range is 3
  b.empty = false;
  return b;
}

}  // namespace

TEST_CASE("frame settings: the defaults are FrameSettings' own, the camera's matrices and light", "[cli][settings]")
{
  const clr::RenderArgs args = parse({});
  const clr::Camera camera = clr::frameCamera(args.camera, unitBox());
  clr::DepthChoice depth;
  const clr::FrameSettings s = clr::makeFrameSettings(args, camera, 320, 200, unitBox(), &depth);
  const clr::FrameSettings d;
  CHECK(s.width == 320);
  CHECK(s.height == 200);
  CHECK(s.mvp == camera.viewProjection(320, 200));
  CHECK(s.lightDir == camera.lightDirection());
  CHECK(s.eye == camera.eye);
  CHECK(s.zNear == camera.zNear);
  CHECK(s.zFar == camera.zFar);
  CHECK(depth.mode == CLR_DEPTH_FLOAT32);
  CHECK(depth.reason == "--depth");
  CHECK(s.depthMode == d.depthMode);
  CHECK(s.shadeMode == d.shadeMode);
  CHECK(s.cullBack == d.cullBack);
  CHECK(s.samples == d.samples);
  CHECK(s.shadeEverySample == d.shadeEverySample);
  CHECK(s.edgeMode == d.edgeMode);
  CHECK(s.interpMode == d.interpMode);
  CHECK(s.traversal == d.traversal);
  CHECK(s.visibility == d.visibility);
  CHECK(s.pointLightOn == d.pointLightOn);
  CHECK(s.texFilter == d.texFilter);
  CHECK(s.wireframe == d.wireframe);
  CHECK(s.lineMethod == d.lineMethod);
  CHECK(s.lineWidth == d.lineWidth);
  CHECK(s.keepVisAttributes == d.keepVisAttributes);
  CHECK(s.pointLightRange == 3.0f);  // half the bounds' diagonal
}

TEST_CASE("frame settings: each flag lands in its field", "[cli][settings]")
{
  const clr::RenderArgs args =
      parse({"--shade",   "phong",        "--cull",        "back",        "--aa",         "ssaa4",        "--edges",
             "float",     "--interp",     "affine",        "--traversal", "hierarchical", "--visibility", "painter",
             "--filter",  "nearest",      "--light-point", "1,2,3",       "--wireframe",  "only",         "--line",
             "bresenham", "--line-width", "2.5",           "--aov",       "a.exr",        "--depth",      "unorm24"});
  const clr::Camera camera = clr::frameCamera(args.camera, unitBox());
  const clr::FrameSettings s = clr::makeFrameSettings(args, camera, 64, 48, unitBox());
  CHECK(s.shadeMode == CLR_SHADE_PHONG);
  CHECK(s.cullBack);
  CHECK(s.samples == 4);
  CHECK(s.shadeEverySample);
  CHECK(s.edgeMode == CLR_EDGES_FLOAT);
  CHECK(s.interpMode == CLR_INTERP_AFFINE);
  CHECK(s.traversal == CLR_TRAVERSAL_HIERARCHICAL);
  CHECK(s.visibility == CLR_VISIBILITY_PAINTER);
  CHECK(s.texFilter == CLR_FILTER_NEAREST);
  CHECK(s.pointLightOn);
  CHECK(s.pointLight == glm::vec3(1.0f, 2.0f, 3.0f));
  CHECK(s.pointLightRange == 3.0f);
  CHECK(s.wireframe == CLR_WIREFRAME_ONLY);
  CHECK(s.lineMethod == CLR_LINE_BRESENHAM);
  CHECK(s.lineWidth == 2.5f);
  CHECK(s.keepVisAttributes);  // the AOVs read the depth and barycentric planes
  CHECK(s.depthMode == CLR_DEPTH_UNORM24);

  const clr::FrameSettings ranged =
      clr::makeFrameSettings(parse({"--light-point", "1,2,3,7"}), camera, 64, 48, unitBox());
  CHECK(ranged.pointLightRange == 7.0f);
  const clr::FrameSettings msaa = clr::makeFrameSettings(parse({"--aa", "msaa8"}), camera, 64, 48, unitBox());
  CHECK(msaa.samples == 8);
  CHECK(!msaa.shadeEverySample);
}

TEST_CASE("frame settings: the depth format's auto rule, and the reversed projection it brings", "[cli][settings]")
{
  const clr::Bounds box = unitBox();
  SECTION("far over near beyond 1e4 goes reversed, with the reversed projection")
  {
    const clr::RenderArgs args = parse({"--depth", "auto", "--near", "0.001", "--far", "100"});
    const clr::Camera camera = clr::frameCamera(args.camera, box);
    clr::DepthChoice depth;
    const clr::FrameSettings s = clr::makeFrameSettings(args, camera, 64, 48, box, &depth);
    CHECK(depth.mode == CLR_DEPTH_REVERSED);
    CHECK(s.depthMode == CLR_DEPTH_REVERSED);
    CHECK(s.mvp == camera.viewProjection(64, 48, CLR_DEPTH_REVERSED));
    CHECK(s.mvp != camera.viewProjection(64, 48, CLR_DEPTH_FLOAT32));
  }
  SECTION("--quality auto applies the rule, unless --depth names a format")
  {
    const std::vector<std::string> camera = {"--near", "0.001", "--far", "100"};
    std::vector<std::string> quality = camera, named = camera;
    quality.insert(quality.end(), {"--quality", "auto"});
    named.insert(named.end(), {"--quality", "auto", "--depth", "float32"});
    const clr::RenderArgs a = parse(quality), b = parse(named);
    CHECK(clr::makeFrameSettings(a, clr::frameCamera(a.camera, box), 64, 48, box).depthMode == CLR_DEPTH_REVERSED);
    CHECK(clr::makeFrameSettings(b, clr::frameCamera(b.camera, box), 64, 48, box).depthMode == CLR_DEPTH_FLOAT32);
  }
  SECTION("--aa auto leaves one sample for the probe frame to change (quality.h)")
  {
    const clr::RenderArgs args = parse({"--aa", "auto"});
    CHECK(clr::makeFrameSettings(args, clr::frameCamera(args.camera, box), 64, 48, box).samples == 1);
  }
}
