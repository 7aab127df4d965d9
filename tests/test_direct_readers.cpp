// test_direct_readers.cpp — the oracle for the direct model readers
// (io/fast_off.h, io/fast_stl.h, io/fast_ply.h): wherever one accepts a
// file, its mesh must equal, byte for byte, the mesh of the assimp path
// (ModelFile::direct off), and the outcome (mesh or error) must be the same
// either way. Files: every OFF, STL and PLY of assimp's test models, and
// generated ones whose numbers stress rounding (7 to 9 significant digits,
// exponents, -0, '+'), with CRLF line ends, comments, blanks and polygons,
// plus variants a direct reader must leave to assimp. Each format must have
// files the direct reader accepted, so the test cannot compare nothing.
#include "cli_support.h"
#include "test_support.h"
#include "io/fast_off.h"
#include "io/fast_ply.h"
#include "io/fast_stl.h"
#include "io/scene.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Outcome {
  clr::Mesh mesh;
  std::string error;
};

Outcome load(const std::string& path, bool direct)
{
  Outcome o;
  try {
    clr::ModelFile file = clr::checkSceneFile(path);
    file.direct = direct;
    o.mesh = clr::importScene(file);
  } catch (const clr::Error& e) {
    o.error = e.what();
  }
  return o;
}

std::string readAll(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Which direct reader takes the file, if any: "off", "stl-binary", "stl-ascii", "ply-binary", "ply-ascii" or "".
std::string directKind(const std::string& path)
{
  const std::string bytes = readAll(path);
  std::string ext = path.substr(path.rfind('.') + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  clr::Mesh m;
  if (ext == "off") return clr::readPlainOff(bytes, m) ? "off" : "";
  if (ext == "ply")
    return clr::readPlainBinaryPly(bytes, m) ? "ply-binary" : clr::readPlainAsciiPly(bytes, m) ? "ply-ascii" : "";
  if (ext == "stl" && clr::readPlainStl(bytes, m))
    return bytes.compare(0, 5, "solid") == 0 && m.numVerts() * 50 / 3 + 84 != bytes.size() ? "stl-ascii" : "stl-binary";
  return "";
}

// Loads `path` both ways and requires the same outcome; returns the direct kind.
std::string compareBothWays(const std::string& path)
{
  INFO(path);
  const Outcome viaAssimp = load(path, false), direct = load(path, true);
  CHECK(viaAssimp.error == direct.error);
  CHECK(test::meshDifference(viaAssimp.mesh, direct.mesh) == "");
  return directKind(path);
}

void listModels(const std::string& dir, std::vector<std::string>& out)
{
  DIR* d = opendir(dir.c_str());
  if (!d) return;
  while (const dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    const std::string path = dir + "/" + name;
    if (e->d_type == DT_DIR) {
      listModels(path, out);
      continue;
    }
    std::string ext = name.substr(name.rfind('.') + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (name.find('.') != std::string::npos && (ext == "off" || ext == "stl" || ext == "ply")) out.push_back(path);
  }
  closedir(d);
}

// A coordinate as text in one of the forms files use, rounding-hard ones first.
std::string number(std::mt19937& rng)
{
  const double v = std::ldexp(double(rng()) / 4294967296.0 - 0.5, int(rng() % 24) - 8);
  char buf[64];
  switch (rng() % 10) {
    case 0: return "-0";
    case 1: std::snprintf(buf, sizeof buf, "%.8e", v); break;
    case 2: std::snprintf(buf, sizeof buf, "%+.7g", v); break;
    case 3: std::snprintf(buf, sizeof buf, "%d", int(rng() % 2001) - 1000); break;
    case 4: std::snprintf(buf, sizeof buf, "%.9f", v); break;
    case 5: std::snprintf(buf, sizeof buf, "%.6E", v); break;
    default: std::snprintf(buf, sizeof buf, "%.*g", 7 + int(rng() % 3), v); break;
  }
  return buf;
}

std::string blanks(std::mt19937& rng)
{
  static const char* const kinds[] = {" ", " ", " ", "  ", "\t", " \t "};
  return kinds[rng() % 6];
}

// A random OFF: `vertices` lines of three coordinates, polygons of 3 to `maxCorners` corners.
std::string offFile(uint32_t seed, int vertices, int faces, const std::string& eol, int maxCorners = 9)
{
  std::mt19937 rng(seed);
  std::string s = "OFF" + eol;
  if (seed % 2) s += "# made by a test" + eol + eol;
  s += std::to_string(vertices) + " " + std::to_string(faces) + " 0" + eol;
  if (seed % 3 == 0) s += "  # the vertices" + eol;
  for (int v = 0; v < vertices; ++v)
    s += (v % 7 == 0 ? " " : "") + number(rng) + blanks(rng) + number(rng) + blanks(rng) + number(rng) +
         (v % 5 == 0 ? " " : "") + eol;
  for (int f = 0; f < faces; ++f) {
    const int k = 3 + int(rng() % uint32_t(maxCorners - 2));
    s += std::to_string(k);
    for (int j = 0; j < k; ++j) s += blanks(rng) + std::to_string(rng() % uint32_t(vertices));
    s += eol;
  }
  return s;
}

// A random ASCII PLY: OFF's body under a PLY header (the header's lines end in '\n').
std::string asciiPly(uint32_t seed, int vertices, int faces, const std::string& eol, int maxCorners = 12)
{
  const std::string off = offFile(seed, vertices, faces, eol, maxCorners);
  size_t body = off.find(eol, off.find(" 0" + eol)) + eol.size();
  if (off.compare(body, 3, "  #") == 0) body = off.find(eol, body) + eol.size();  // offFile's comment
  return "ply\nformat ascii 1.0\ncomment made by a test\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
         "\nproperty list uchar int vertex_indices\nend_header\n" + off.substr(body);
}

// A random ASCII STL of `solids` solids of `facets` facets each.
std::string asciiStl(uint32_t seed, int solids, int facets, const std::string& eol)
{
  std::mt19937 rng(seed);
  std::string s;
  for (int k = 0; k < solids; ++k) {
    s += (k ? "  " : "") + std::string("solid") + (k % 2 ? "" : " part" + std::to_string(k)) + eol;
    for (int f = 0; f < facets; ++f) {
      const bool zero = rng() % 9 == 0;  // a normal left (0, 0, 0), repaired with a warning
      s += "  facet normal " + (zero ? "0 0 0" : number(rng) + " " + number(rng) + " " + number(rng)) + eol;
      s += "\touter loop" + eol;
      for (int v = 0; v < 3; ++v)
        s += "      vertex" + blanks(rng) + number(rng) + blanks(rng) + number(rng) + " " + number(rng) + eol;
      s += "    endloop" + eol + "  endfacet" + eol;
    }
    s += "endsolid" + std::string(k % 2 ? "" : " part" + std::to_string(k)) + eol;
  }
  return s;
}

// A random binary STL: normals random, zero or NaN; positions random floats, some -0.
std::string binaryStl(uint32_t seed, uint32_t facets)
{
  std::mt19937 rng(seed);
  std::string s = "binary STL made by a test";
  s.resize(80, ' ');
  s.append(reinterpret_cast<const char*>(&facets), 4);
  for (uint32_t f = 0; f < facets; ++f) {
    float v[12];
    for (float& c : v) c = std::ldexp(float(rng()) / 4294967296.0f - 0.5f, int(rng() % 20) - 6);
    if (f % 7 == 0) v[0] = v[1] = v[2] = 0.0f;
    if (f % 11 == 0) v[1] = NAN;
    if (f % 5 == 0) v[3 + rng() % 9] = -0.0f;
    s.append(reinterpret_cast<const char*>(v), sizeof v);
    const uint16_t attribute = uint16_t(rng() & 0x7FFF);
    s.append(reinterpret_cast<const char*>(&attribute), 2);
  }
  return s;
}

}  // namespace

TEST_CASE("direct readers: assimp's test models read the same both ways", "[io][models][direct]")
{
  std::vector<std::string> paths;
  listModels("/usr/share/assimp/models", paths);
  REQUIRE(paths.size() > 10);
  std::map<std::string, int> accepted;
  for (const std::string& path : paths) ++accepted[compareBothWays(path)];
  INFO("files " << paths.size());
  CHECK(accepted["off"] > 0);
  CHECK(accepted["stl-binary"] > 0);
  CHECK(accepted["stl-ascii"] > 0);
  CHECK(accepted["ply-binary"] > 0);
}

TEST_CASE("direct readers: generated OFF files read the same both ways", "[io][models][direct]")
{
  int accepted = 0;
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    const std::string eol = seed % 2 ? "\n" : "\r\n";
    std::string text = offFile(seed, 40 + int(seed) * 13, 30 + int(seed) * 7, eol);
    if (seed % 4 == 0) text += eol + "  " + eol;               // white space after the faces
    if (seed % 4 == 1) text.resize(text.size() - eol.size());  // no line end after the last face
    const std::string path = test::writeFile("direct" + std::to_string(seed) + ".off", text);
    accepted += compareBothWays(path) == "off";
  }
  // Large enough to be parsed in several parts.
  const std::string big = test::writeFile("direct-big.off", offFile(99, 40000, 60000, "\n"));
  accepted += compareBothWays(big) == "off";
  CHECK(accepted == 13);
  // Left to assimp: each is refused or read by it, the same either way.
  const std::string base = offFile(5, 30, 20, "\n");
  const std::vector<std::pair<std::string, std::string>> unusual = {
      {"decagon", offFile(5, 30, 20, "\n", 12)},
      {"face-colour", base.substr(0, base.size() - 1) + " 255 0 0\n"},
      {"blank-line",
       [&] {
         std::string t = base;
         t.insert(t.find('\n', t.find("0\n") + 2) + 1, "\n");
         return t;
       }()},
      {"index-range", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"},
      {"too-few-faces", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"huge", "OFF\n3 1 0\n0 0 0\n1e30 0 0\n0 1 0\n3 0 1 2\n"},
      {"nan", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"},
      {"comma", "OFF\n3 1 0\n0 0 0\n1,5 0 0\n0 1 0\n3 0 1 2\n"},
      {"two-corners", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n"},
      {"coff", "COFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n"},
      {"counts-on-header", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"cr-only", "OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 0\r3 0 1 2\r"},
      {"truncated", base.substr(0, base.size() / 2)},
  };
  for (const auto& [name, text] : unusual) {
    const std::string path = test::writeFile("unusual-" + name + ".off", text);
    CHECK(compareBothWays(path) == "");
  }
}

TEST_CASE("direct readers: generated STL files read the same both ways", "[io][models][direct]")
{
  int ascii = 0, binary = 0;
  for (uint32_t seed = 1; seed <= 8; ++seed) {
    const std::string eol = seed % 2 ? "\n" : "\r\n";
    std::string text = asciiStl(seed, 1 + int(seed % 3), 20 + int(seed) * 5, eol);
    if (seed % 3 == 0) text += eol + " " + eol;
    ascii += compareBothWays(test::writeFile("direct" + std::to_string(seed) + ".stl", text)) == "stl-ascii";
    binary += compareBothWays(test::writeFile("direct-bin" + std::to_string(seed) + ".stl",
                                              binaryStl(seed, 30 + seed * 11))) == "stl-binary";
  }
  ascii += compareBothWays(test::writeFile("direct-big.stl", asciiStl(77, 2, 9000, "\n"))) == "stl-ascii";
  CHECK(ascii == 9);
  CHECK(binary == 8);
  const std::string plain = asciiStl(3, 1, 4, "\n");
  std::string coloured = binaryStl(4, 10);
  coloured[84 + 48 + 1] = char(0x80);  // a facet colour
  std::string empty = binaryStl(4, 1);
  std::memset(&empty[80], 0, 4);
  const std::vector<std::pair<std::string, std::string>> unusual = {
      {"no-normal",
       "solid a\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
       "endsolid a\n"},
      {"four-vertices",
       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       "vertex 1 1 0\nendloop\nendfacet\nendsolid a\n"},
      {"no-endsolid", plain.substr(0, plain.rfind("endsolid"))},
      {"empty-solid", "solid a\nendsolid a\n"},
      {"trailing-text", plain + "some words\n"},
      {"huge",
       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e30 0 0\nvertex 0 1 0\nendloop\n"
       "endfacet\nendsolid a\n"},
      {"normal-comma",
       "solid a\nfacet normal 0 0,5 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       "endloop\nendfacet\nendsolid a\n"},
      {"bom", "\xEF\xBB\xBF" + plain},
      {"coloured", coloured},
      {"no-facets", empty},
      {"truncated", coloured.substr(0, coloured.size() - 7)},
  };
  for (const auto& [name, text] : unusual) {
    const std::string path = test::writeFile("unusual-" + name + ".stl", text);
    const std::string kind = compareBothWays(path);
    CHECK((kind == "" || name == "normal-comma"));
  }
}

TEST_CASE("direct readers: generated ASCII PLY files read the same both ways", "[io][models][direct]")
{
  int accepted = 0;
  for (uint32_t seed = 1; seed <= 8; ++seed) {
    const std::string eol = seed % 2 ? "\n" : "\r\n";
    const std::string path = test::writeFile("direct" + std::to_string(seed) + ".ply",
                                             asciiPly(seed, 30 + int(seed) * 9, 20 + int(seed) * 5, eol));
    accepted += compareBothWays(path) == "ply-ascii";
  }
  accepted += compareBothWays(test::writeFile("direct-big.ply", asciiPly(98, 40000, 60000, "\n"))) == "ply-ascii";
  CHECK(accepted == 9);
  const std::string plain =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::vector<std::pair<std::string, std::string>> unusual = {
      {"two-corners", plain + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"},
      {"index-range", plain + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"},
      {"short", plain + "0 0 0\n1 0 0\n0 1 0\n"},
      {"long", plain + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"},
      {"huge", plain + "0 0 0\n1e30 0 0\n0 1 0\n3 0 1 2\n"},
      {"blank-line", plain + "0 0 0\n\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"crlf-header",
       [&] {
         std::string t;
         for (char c : plain + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
           t += c == '\n' ? std::string("\r\n") : std::string(1, c);
         return t;
       }()},
      {"extra-value", plain + "0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"integer-x",
       [&] {
         std::string t = plain + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
         t.replace(t.find("float x"), 7, "int x");
         return t;
       }()},
  };
  for (const auto& [name, text] : unusual) {
    const std::string path = test::writeFile("unusual-" + name + ".ply", text);
    CHECK(compareBothWays(path) == "");
  }
}

TEST_CASE("direct readers: the fuzz seeds of OFF, STL and PLY read the same both ways", "[io][models][direct]")
{
  // The seeds lie beside the corpus list: one selector byte, then the file (fuzz_load.cpp).
  const std::string list = CLRASTER_CORPUS_LIST;
  const std::string dir = list.substr(0, list.rfind('/')) + "/fuzz_corpus";
  DIR* d = opendir(dir.c_str());
  REQUIRE(d);
  std::map<std::string, int> accepted;
  while (const dirent* e = readdir(d)) {
    const std::string bytes = readAll(dir + "/" + e->d_name);
    const char* ext = bytes.empty()     ? nullptr
                      : bytes[0] == 'f' ? "off"
                      : bytes[0] == 's' ? "stl"
                      : bytes[0] == 'p' ? "ply"
                                        : nullptr;
    if (!ext || e->d_type != DT_REG) continue;
    ++accepted[compareBothWays(test::writeFile(std::string("seed-") + e->d_name + "." + ext, bytes.substr(1)))];
  }
  closedir(d);
  CHECK(accepted["off"] > 0);
  CHECK(accepted["stl-ascii"] > 0);
  CHECK(accepted["stl-binary"] > 0);
  CHECK(accepted["ply-ascii"] > 0);
  CHECK(accepted["ply-binary"] > 0);
}

TEST_CASE("direct readers: OFF face lines that assimp skips are refused", "[io][models][direct]")
{
  // assimp's OFF reader skips a face line of count 0 or above 9 but counts the faces down: the last
  // face was dropped silently, and more such lines than faces crashed it (found by fuzzing). Skipped
  // lines that leave every face read stay as before (assimp's OFF/invalid.off).
  const std::string head = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  for (const std::string& faces : {std::string("x\n3 0 2 1\n"), std::string("x\na\nb\nc\n"),
                                   std::string("10 0 1 2 0 1 2 0 1 2 0\n3 0 2 1\n"), std::string("0\n3 0 2 1\n")}) {
    const std::string path = test::writeFile("skipped-face.off", head + faces);
    INFO(faces);
    CHECK(load(path, true).error == path +
                                        ": OFF line 7: face lines whose vertex count is not 1 to 9 would drop "
                                        "later faces (positions are read exactly, not guessed)");
  }
  CHECK(load(test::writeFile("two-faces.off", head + "3 0 2 1\n"), false).mesh.numTris() == 2);
  CHECK(
      load(test::writeFile("skipped-at-end.off", "OFF\n3 4 0\n0 0 0\n1 0 0\n0 1 0\n0\n3 0 1 2\n20\n4 0 1 2 0\n"), true)
          .mesh.numTris() == 3);
}
