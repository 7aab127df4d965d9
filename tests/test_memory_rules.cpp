// test_memory_rules.cpp — a pipeline's device buffers are checked before
// they are allocated: past the caller's limit or the device's global memory
// a frame is a clr::Error naming the sizes, and the pipeline renders again
// once the limit allows it.
#include "io/scene.h"
#include "pipeline/pipeline.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("memory: buffers past the caller's limit or the device's memory are an error naming the size", "[memory]")
{
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(clr::defaultScene());
  const clr::FrameSettings settings = test::idSettings(512, 512);
  const std::vector<uint32_t> expected = test::renderTriIds(pipeline, settings);
  for (const bool device : {false, true}) {
    clr::Pipeline limited(test::context());
    (device ? limited.memory().globalMemBytes : limited.memory().limitBytes) = 1 << 20;
    limited.uploadScene(clr::defaultScene());
    try {
      test::renderTriIds(limited, settings);
      FAIL("a 512x512 frame fit in 1 MiB of buffers");
    } catch (const clr::Error& e) {
      const std::string message = e.what();
      CHECK(message.rfind("the frame needs ", 0) == 0);
      CHECK(message.find(device ? "more than the device's 1,048,576 bytes"
                                : "more than the memory limit of 1,048,576") != std::string::npos);
    }
    (device ? limited.memory().globalMemBytes : limited.memory().limitBytes) = UINT64_MAX;
    CHECK(test::renderTriIds(limited, settings) == expected);
  }
}
