// mtl.h — a strict reader for the plain OBJ material library (MTL), for the
// direct OBJ reader (fast_obj.h).
//
// It reads what assimp 5.2's ObjFileMtlImporter reads and the scene keeps
// of it: each material's name (newmtl), diffuse colour (Kd, parsed with
// assimp's own fast_atof so the floats are the same) and diffuse texture
// (map_Kd without options). Lines assimp reads but the scene ignores (Ka,
// Ks, Ke, Ns, Ni, d, Tr, Tf, illum, other texture maps) are checked to be
// well formed, so that assimp could not fail on them; lines assimp skips
// are skipped. Anything else (an option such as -clamp, a property before
// the first newmtl, a repeated name, a number assimp would refuse) returns
// false, and the caller lets assimp read the whole model instead.
#pragma once

#include <string>
#include <vector>

namespace clr {

struct MtlMaterial {
  std::string name;
  float diffuse[3] = {0.6f, 0.6f, 0.6f};  // assimp's default for an OBJ material
  std::string texture;                    // map_Kd as written, "" without one
};

// Whether [b, e) is a plain decimal number: an optional sign, 1 to 18
// digits, an optional fraction of 1 to 40 digits, an optional exponent of 1
// to 3 digits; no '.' first or last, nothing else.
bool plainDecimal(const char* b, const char* e);

// The word [b, e) as assimp's OBJ and MTL readers read it (fast_atof), if
// it is a plain decimal; false for any other word.
bool assimpNumber(const char* b, const char* e, float& value);

// Appends the materials of `text`, one library, in file order; false: not
// plain (the contents of `out` are then unspecified).
bool readPlainMtl(const std::string& text, std::vector<MtlMaterial>& out);

// false when assimp 5.2's MTL reader would write to a material that does
// not exist, and crash: a texture statement (map_*, bump, refl, norm, disp)
// or an anisotropy one before the library's first newmtl. Such a library is
// refused before assimp reads it (model_io.h).
bool mtlReadableByAssimp(const std::string& text);

}  // namespace clr
