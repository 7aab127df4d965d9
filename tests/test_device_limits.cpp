// test_device_limits.cpp — deviceNeeds and checkDeviceLimits (device.h): what
// a tile size asks of a device's work-group size and local memory, and the
// clr::Error a device too small for it gets, on fake device limits.
#include "pipeline/device.h"
#include "kernels/shared.h"

#include <catch2/catch.hpp>

#include <string>

TEST_CASE("the tile size's work-group and local memory needs", "[device]")
{
  // GPU shape: raster's group is the tile, its batch 64 bytes a record (raster.cl): 16 KB at tile 16.
  const clr::DeviceNeeds gpu16 = clr::deviceNeeds(1, 16);
  CHECK(gpu16.workGroupSize == 256);
  CHECK(gpu16.localMemBytes == 16384);
  const clr::DeviceNeeds gpu32 = clr::deviceNeeds(1, 32);
  CHECK(gpu32.workGroupSize == 1024);
  CHECK(gpu32.localMemBytes == 65536);
  // CPU shape: groups of one but the linear kernels' CLR_LINEAR_GROUP; resolve takes rows of 16 lanes at tile 32.
  CHECK(clr::deviceNeeds(16, 16).workGroupSize == CLR_LINEAR_GROUP);
  CHECK(clr::deviceNeeds(16, 32).workGroupSize == CLR_LINEAR_GROUP);
  CHECK(clr::deviceNeeds(16, 64).workGroupSize == 256);
}

TEST_CASE("a device that cannot run the tile size is refused by name", "[device]")
{
  const clr::DeviceLimits typicalGpu{1024, 49152};
  CHECK_NOTHROW(clr::checkDeviceLimits("gpu", typicalGpu, 1, 16));
  CHECK_NOTHROW(clr::checkDeviceLimits("cpu", {4096, 32768}, 16, 16));
  try {
    clr::checkDeviceLimits("small gpu", {128, 49152}, 1, 16);
    FAIL("a 256-item tile group passed a 128-item device");
  } catch (const clr::Error& e) {
    const std::string message = e.what();
    CHECK(message.find("small gpu") != std::string::npos);
    CHECK(message.find("tile size 16") != std::string::npos);
    CHECK(message.find("CL_DEVICE_MAX_WORK_GROUP_SIZE") != std::string::npos);
  }
  try {
    clr::checkDeviceLimits("gpu", typicalGpu, 1, 32);  // 1024 items fit, 64 KB of local memory do not
    FAIL("a 64 KB batch passed a 48 KB device");
  } catch (const clr::Error& e) {
    CHECK(std::string(e.what()).find("CL_DEVICE_LOCAL_MEM_SIZE") != std::string::npos);
  }
  CHECK_THROWS_AS(clr::checkDeviceLimits("cpu", {4096, 32768}, 16, 24), clr::Error);  // lanes must divide the tile
}
