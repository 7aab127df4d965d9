// info.h — `clraster info MESH [--fov DEG] [--json]`: what a newcomer needs
// to know about a model before rendering it.
//
// Loads the file as `render` does (no device work) and prints its counts
// (triangles, vertices, lines, points), bounds (min, max, centre, radius:
// half the box diagonal), materials and textures (missing ones named),
// whether normals and texture coordinates came from the file or were
// computed or repaired, and the default framing's camera as render flags.
// Those flags print every float with %.9g, which round-trips a float
// exactly, so pasted into `clraster render` with the same --fov they give
// the default picture byte for byte. Human-readable text, or one JSON
// object with --json.
#pragma once

#include <string>
#include <vector>

namespace clr {

// args: everything after "info". Returns the exit status.
int infoCommand(const std::vector<std::string>& args);

}  // namespace clr
