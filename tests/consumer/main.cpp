// main.cpp — the consumer project: rasterizes two triangles and checks ids
// and barycentrics the test states by hand, interpolates, renders the
// built-in scene to the PNG named by its argument, and checks that a bad
// argument is a clraster::Error. Exit status 0 only if all of that holds.
#include <clraster/clraster.hpp>

#include <cmath>
#include <cstdio>

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer OUT.png\n");
    return 2;
  }
  try {
    clraster::Context ctx{""};
    // A full-view quad split along its diagonal y = x: triangle 0 below it,
    // triangle 1 above; pixels whose centre lies on it are not checked.
    const float pos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 1, 1, 0, 1, -1, 1, 0, 1};
    const int32_t tri[] = {0, 1, 2, 0, 2, 3};
    const clraster::Raster r = clraster::rasterize(ctx, pos, 4, tri, 2, 4, 4);
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x) {
        const uint32_t expected = y < x ? 1u : 2u;
        if (x != y && r.ids[y * 4 + x] != expected) {
          std::fprintf(stderr, "consumer: pixel (%u, %u) id %u, expected %u\n", x, y, r.ids[y * 4 + x], expected);
          return 1;
        }
      }
    // One attribute, the vertex's index: at pixel (3, 0), in triangle 0,
    // 0·u + 1·v + 2·(1 − u − v).
    const float attr[] = {0, 1, 2, 3};
    const std::vector<float> out = clraster::interpolate(ctx, attr, 4, 1, r, tri);
    const float u = r.rast[4 * 3], v = r.rast[4 * 3 + 1], expected = v + 2.0f * (1.0f - u - v);
    if (std::fabs(out[3] - expected) > 1e-6f) {
      std::fprintf(stderr, "consumer: interpolate %g, expected %g\n", out[3], expected);
      return 1;
    }
    const clraster::Image image =
        clraster::render(ctx, clraster::RenderOptions::parse({"--size", "64x48", "-o", argv[1]}));
    if (image.width != 64 || image.height != 48 || image.rgba.size() != 64 * 48) return 1;
    try {
      clraster::rasterize(ctx, pos, 6, tri, 2, 0, 4);
      std::fprintf(stderr, "consumer: a zero width was accepted\n");
      return 1;
    } catch (const clraster::Error& e) {
      std::printf("consumer: expected error: %s\n", e.what());
    }
    std::printf("consumer: ok on %s\n", ctx.device().name.c_str());
    return 0;
  } catch (const clraster::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
