// test_messages.cpp — the one-line rule for every message that quotes a
// user's string: a path holding a newline, or one of about 4 KB, still gives
// one line under 300 bytes, from every model check (GLB, OFF, PLY), the
// normals warning and `info --fov`; and the warning sink keeps every
// stream of warnings (a render's, a views run's, the library's list) within
// about 4 KB whatever the input, each repeating kind once with its count.
#include "base/warnings.h"
#include "cli_support.h"
#include "io/scene.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <string>
#include <vector>

namespace {

// The lines of a message stream.
std::vector<std::string> lines(const std::string& text)
{
  std::vector<std::string> out;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    out.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    start = end == std::string::npos ? text.size() : end + 1;
  }
  return out;
}

// A folder under the scratch directory whose path is about `bytes` long.
std::string longFolder(const std::string& name, size_t bytes)
{
  std::string dir = test::tempDir() + "/" + name;
  mkdir(dir.c_str(), 0755);
  while (dir.size() + 260 < bytes) {
    dir += "/" + std::string(250, 'd');
    mkdir(dir.c_str(), 0755);
  }
  return dir;
}

}  // namespace

TEST_CASE("messages: a path with a newline or of 4 KB stays one line under 300 bytes", "[messages]")
{
  const std::string plain = test::tempDir() + "/msg-inj";
  mkdir(plain.c_str(), 0755);
  const std::vector<std::string> folders = {plain, longFolder("msg-long", 4000)};
  REQUIRE(folders[1].size() > 3700);
  // Each file: its contents, and what its message says.
  struct Case {
    const char* ext;
    std::string content;
    const char* needle;
    bool fails;
  };
  const std::vector<Case> cases = {
      {".glb", std::string("glTF\x02\0\0\0", 8), "GLB header truncated", true},
      {".off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "OFF header vertex count", true},
      {".ply", "ply junk\nformat ascii 1.0\nend_header\n", "text after the magic", true},
      {".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n", "vertex normals were zero", false},
  };
  for (const std::string& folder : folders)
    for (const Case& c : cases) {
      const std::string path = folder + "/inj\nclraster: forged line" + c.ext;
      test::writeFile(path.substr(test::tempDir().size() + 1), c.content);
      const test::Run r = test::run("render '" + path + "' -o '" + plain + "/out.png' --size 8x8");
      INFO(c.ext << " in a folder of " << folder.size() << " bytes; stderr: " << r.err);
      CHECK(r.status == (c.fails ? 1 : 0));
      CHECK(r.err.find(c.needle) != std::string::npos);
      for (const std::string& line : lines(r.err)) {
        CHECK(line.rfind("clraster: ", 0) == 0);
        CHECK(line.rfind("clraster: forged", 0) != 0);
        CHECK(line.size() < 300);
      }
    }
}

TEST_CASE("messages: info --fov quotes a long or multi-line value in one short line", "[messages]")
{
  for (const std::string& value : {std::string(100000, '7'), std::string("1\nclraster: forged")}) {
    const test::Run r = test::run("info --fov '" + value + "' no-such.obj");
    INFO("stderr: " << r.err.substr(0, 400));
    CHECK(r.status == 1);
    CHECK(r.err.find("--fov: '") != std::string::npos);
    REQUIRE(lines(r.err).size() == 1);
    CHECK(r.err.size() < 300);
  }
}

TEST_CASE("messages: the warning sink keeps each kind once and stays within its bound", "[messages]")
{
  clr::Warnings w;
  CHECK(w.add("lib", "a.obj: material library 'x0.mtl' not found"));
  size_t newLines = 0;
  for (int i = 1; i < 100000; ++i) newLines += w.add("lib", "a.obj: material library 'x" + std::to_string(i) + "'");
  CHECK(newLines == 0);
  REQUIRE(w.lines().size() == 1);
  CHECK(w.lines()[0] == "a.obj: material library 'x0.mtl' not found (and 99,999 more like it)");
  for (int i = 0; i < 100000; ++i) w.add("distinct " + std::to_string(i) + std::string(100, '.'));
  size_t bytes = 0;
  for (const std::string& line : w.lines()) bytes += line.size() + 1;
  CHECK(bytes <= clr::Warnings::kMaxBytes + 200);
  CHECK(w.lines().back().rfind("and ", 0) == 0);
  CHECK(w.lines().back().find(" more warnings") != std::string::npos);
  CHECK(clr::Warnings::grouped(1234567) == "1,234,567");
}

TEST_CASE("messages: floods of warnings from a model print at most about 4 KB", "[messages]")
{
  // 20,000 missing material libraries; 3,000 materials naming missing textures.
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (int i = 0; i < 20000; ++i) obj += "mtllib missing" + std::to_string(i) + ".mtl\n";
  const std::string libs = test::writeFile("flood-libs.obj", obj);
  std::string mtl;
  obj = "mtllib flood-tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  for (int i = 0; i < 3000; ++i) {
    mtl += "newmtl m" + std::to_string(i) + "\nmap_Kd no-such-" + std::to_string(i) + ".png\n";
    obj += "usemtl m" + std::to_string(i) + "\nf 1/1 2/2 3/3\n";
  }
  test::writeFile("flood-tex.mtl", mtl);
  const std::string textures = test::writeFile("flood-tex.obj", obj);
  const std::string out = test::tempDir() + "/flood.png";
  std::string views = "{\"views\": [{}";
  for (int i = 1; i < 3; ++i) views += ", {\"eye\": [" + std::to_string(i) + ", 2, 3]}";
  const std::string viewsPath = test::writeFile("flood-views.json", views + "]}");
  for (const std::string& scene : {libs, textures}) {
    for (const std::string& mode :
         {std::string("-o '") + out + "'", "--views '" + viewsPath + "' -o '" + test::tempDir() + "/flood_%d.png'"}) {
      const test::Run r = test::run("render '" + scene + "' " + mode + " --size 16x16");
      INFO(scene << " " << mode << "\nstderr: " << r.err.substr(0, 600));
      CHECK(r.status == 0);
      CHECK(r.err.size() <= clr::Warnings::kMaxBytes + 200);
      CHECK(r.err.find(" more like it)") != std::string::npos);
      for (const std::string& line : lines(r.err)) CHECK(line.size() < 400);
    }
    // info's report: its warnings and missing textures within the same bound.
    for (const char* json : {"", "--json "}) {
      const test::Run info = test::run(std::string("info ") + json + "'" + scene + "'");
      CHECK(info.status == 0);
      CHECK(info.out.size() < 2 * clr::Warnings::kMaxBytes);
    }
    // The library's list (Scene::warnings) is the same bounded list.
    const clr::Mesh mesh = clr::loadScene(scene);
    size_t bytes = 0;
    for (const std::string& line : mesh.warnings.lines()) bytes += line.size();
    CHECK(bytes <= clr::Warnings::kMaxBytes + 200);
    CHECK(!mesh.warnings.empty());
  }
}
