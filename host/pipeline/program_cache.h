// program_cache.h — compiled kernel programs kept between runs, so a warm
// start skips the compiler front end.
//
// A file holds one program's device binary for one key (SHA-256 of the
// sources, options, device and driver) and HMAC-SHA-256 of both under the
// folder's random secret. Only storeProgramBinary (`clraster cache`) writes
// (on PoCL asking for a binary compiles every kernel); a render only loads.
// The folder (0700) and its files (0600) are used only while no other user
// can write them; any doubt is a miss and the program is built from source,
// so the cache never fails a render or changes it (docs/limits.md, "The
// kernel cache"). The folder: CLRASTER_CACHE_DIR when set (empty: no
// cache), else $XDG_CACHE_HOME/clraster, else $HOME/.cache/clraster.
#pragma once

#include "pipeline/cl.h"

#include <string>
#include <vector>

namespace clr {

std::string programCacheDir();

// The key of a program: SHA-256 (32 bytes) of its sources, full options,
// device and driver.
std::string programCacheKey(const cl::Device& device, const std::string& options);

// The cached program for the key, built, or a null program when there is
// none usable.
cl::Program loadCachedProgram(const cl::Context& context, const cl::Device& device, const std::string& options);

// Writes a built program's binary under its key; returns the file written.
// Throws clr::Error when the directory cannot be made or written.
std::string storeProgramBinary(const cl::Program& program, const cl::Device& device, const std::string& options);

// `clraster cache [--device SEL]`: stores the programs a render and the
// library's rasterize build on the device (the frame and extras programs,
// both position inputs), printing each file; the exit status.
int cacheCommand(const std::vector<std::string>& args);

}  // namespace clr
