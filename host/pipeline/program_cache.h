// program_cache.h — compiled kernel programs kept between runs, so a warm
// start skips the compiler front end (PoCL preprocesses the whole source,
// opencl-c.h included, just to find its own cache entry).
//
// A cache file holds one program's device binary (CL_PROGRAM_BINARIES) for
// one key: SHA-256 of the embedded sources, the build options, the device
// and its driver. Files are written only by storeProgramBinary (`clraster
// cache`, which the bootstrap runs): on PoCL, asking for a binary compiles
// every kernel of the program, far too slow for a render's path. A render
// only loads.
//
// Trust: the directory is created 0700, and is used only while it is a
// folder (not a link) of this user that no other user can write; each file
// likewise (written 0600). The directory holds a random secret ("secret",
// 0600), and every entry carries HMAC-SHA-256 of its key and binary under
// it, so a binary swapped in from elsewhere, even with its key and a
// checksum recomputed, fails the check. Any doubt (a missing, truncated,
// foreign or unchecked file, a folder others can write, a driver refusing
// the binary or a kernel that fails to create) is a miss and the program
// is built from source: the cache can make a start faster, never make a
// render fail or differ.
//
// The directory: CLRASTER_CACHE_DIR when set (empty: no cache), else
// $XDG_CACHE_HOME/clraster, else $HOME/.cache/clraster.
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
