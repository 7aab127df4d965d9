// test_main.cpp — Catch2's main for clraster_tests and api_tests. Every test
// builds its kernels from source, whatever program cache the user has:
// CLRASTER_CACHE_DIR is set empty for this process and the CLI runs it
// starts (test_program_cache.cpp sets its own directory where it needs one).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>

int main(int argc, char** argv)
{
  setenv("CLRASTER_CACHE_DIR", "", 1);
  return Catch::Session().run(argc, argv);
}
