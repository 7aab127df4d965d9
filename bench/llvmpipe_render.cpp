// llvmpipe_render.cpp — OSMesa rendering and ID comparison (see
// llvmpipe_render.h for the contract).
#define GL_GLEXT_PROTOTYPES
#include "llvmpipe_render.h"

#include "pipeline/cl.h"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <malloc.h>

namespace clr::bench {

namespace {

// An OSMesa RGBA8 context with a 24-bit depth buffer, current for its
// lifetime, drawing into its own buffer of width x height pixels.
class OsMesaContext {
 public:
  OsMesaContext(uint32_t width, uint32_t height) : width_(width), height_(height), buffer_(size_t(width) * height)
  {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
    if (!context_) throw Error("OSMesaCreateContextExt failed");
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, GLsizei(width), GLsizei(height))) {
      OSMesaDestroyContext(context_);
      throw Error("OSMesaMakeCurrent failed for " + std::to_string(width) + "x" + std::to_string(height));
    }
  }
  ~OsMesaContext() { OSMesaDestroyContext(context_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  // The common state: the mvp as projection, identity modelview (so eye
  // space is world space for lighting), depth LESS against 1, no blending,
  // dithering, culling or multisampling.
  void setCommonState(const glm::mat4& mvp) const
  {
    glViewport(0, 0, GLsizei(width_), GLsizei(height_));
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(glm::value_ptr(mvp));
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DITHER);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
  }

  // Reads the colour buffer into `image`, flipped to top row first.
  void readImage(std::vector<uint32_t>& rows, std::vector<uint32_t>& image) const
  {
    rows.resize(size_t(width_) * height_);
    glReadPixels(0, 0, GLsizei(width_), GLsizei(height_), GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    image.resize(rows.size());
    for (uint32_t y = 0; y < height_; ++y)
      std::copy_n(&rows[size_t(height_ - 1 - y) * width_], width_, &image[size_t(y) * width_]);
  }

  void checkError(const char* what) const
  {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) throw Error("GL error " + std::to_string(error) + " while " + what);
  }

 private:
  uint32_t width_, height_;
  std::vector<uint32_t> buffer_;
  OSMesaContext context_ = nullptr;
};

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void fixHeapTrimThreshold()
{
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

namespace {

// clraster's lambert shade per pixel (resolve.cl, shade.h), in GLSL 1.20:
// the normal interpolated with the 1/w rule (GL's smooth varyings), made
// unit (the eye-facing one when zero) and flipped on back faces, then
// albedo · (0.12 + 0.88 · max(n·l, 0)).
const char* const kLambertVertexShader = R"(#version 120
varying vec3 normal;
void main()
{
  normal = gl_Normal;
  gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
)";
const char* const kLambertFragmentShader = R"(#version 120
varying vec3 normal;
uniform vec3 lightDir;
uniform vec3 albedo;
void main()
{
  float len = sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
  float facing = gl_FrontFacing ? 1.0 : -1.0;
  vec3 n = len > 0.0 ? normal * (facing / len) : vec3(0.0, 0.0, facing);
  float diffuse = max(dot(n, lightDir), 0.0);
  gl_FragColor = vec4(albedo * (0.12 + 0.88 * diffuse), 1.0);
}
)";

GLuint compileShader(GLenum kind, const char* text)
{
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  char log[2048] = "";
  glGetShaderInfoLog(shader, sizeof log, nullptr, log);
  glDeleteShader(shader);
  throw Error(std::string("llvmpipe: the lambert shader does not compile: ") + log);
}

// Links the per-pixel lambert program and makes it current.
GLuint useLambertProgram(const glm::vec3& light, const GLfloat* albedo)
{
  const GLuint program = glCreateProgram();
  const GLuint vertex = compileShader(GL_VERTEX_SHADER, kLambertVertexShader);
  const GLuint fragment = compileShader(GL_FRAGMENT_SHADER, kLambertFragmentShader);
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = "";
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw Error(std::string("llvmpipe: the lambert program does not link: ") + log);
  }
  glUseProgram(program);
  glUniform3f(glGetUniformLocation(program, "lightDir"), light.x, light.y, light.z);
  glUniform3f(glGetUniformLocation(program, "albedo"), albedo[0], albedo[1], albedo[2]);
  return program;
}

}  // namespace

LlvmpipeFrames renderLlvmpipeLambert(const Mesh& mesh, uint32_t width, uint32_t height, const glm::mat4& mvp,
                                     const glm::vec3& lightDir, LambertShading shading, uint32_t warmupFrames,
                                     uint32_t timedFrames)
{
  // Step 1: context and state; lighting equal to clraster's lambert shade.
  OsMesaContext gl(width, height);
  gl.setCommonState(mvp);
  const glm::vec3 light = glm::normalize(lightDir);
  const GLfloat position[4] = {light.x, light.y, light.z, 0.0f};  // directional
  const GLfloat ambient[4] = {0.12f, 0.12f, 0.12f, 1.0f}, diffuse[4] = {0.88f, 0.88f, 0.88f, 1.0f};
  const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 1.0f}, albedo[4] = {0.80f, 0.78f, 0.74f, 1.0f};
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glLightfv(GL_LIGHT0, GL_POSITION, position);
  glLightfv(GL_LIGHT0, GL_AMBIENT, ambient);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, black);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, black);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, albedo);
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, black);
  glEnable(GL_NORMALIZE);  // clraster normalises the interpolated normal; file normals may not be unit
  glShadeModel(GL_SMOOTH);
  glFrontFace(GL_CCW);
  glClearColor(0x1A / 255.0f, 0x1F / 255.0f, 0x26 / 255.0f, 1.0f);  // clraster's lambert background
  const GLuint program = shading == LambertShading::perPixel ? useLambertProgram(light, albedo) : 0;
  gl.checkError("setting up the lambert shading");

  // Step 2: positions, normals and indices in buffer objects, uploaded once.
  GLuint buffers[3];
  glGenBuffers(3, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.positions.size() * sizeof(float)), mesh.positions.data(),
               GL_STATIC_DRAW);
  glVertexPointer(3, GL_FLOAT, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[1]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.normals.size() * sizeof(float)), mesh.normals.data(), GL_STATIC_DRAW);
  glNormalPointer(GL_FLOAT, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[2]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
               GL_STATIC_DRAW);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  gl.checkError("uploading the mesh");

  // Step 3: frames, timed from the clear to glFinish, when the image lies in
  // the host memory OSMesa renders into (clraster's frames end with its
  // image mapped, likewise without a copy); then one read for the caller.
  LlvmpipeFrames out;
  out.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  out.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  for (uint32_t f = 0; f < warmupFrames + timedFrames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
    glFinish();
    if (f >= warmupFrames) out.frameMs.push_back(msSince(start));
  }
  std::vector<uint32_t> rows;
  gl.readImage(rows, out.image);
  gl.checkError("drawing");
  glDeleteBuffers(3, buffers);
  if (program) {
    glUseProgram(0);
    glDeleteProgram(program);
  }
  return out;
}

LlvmpipeFrames renderLlvmpipeIds(const Mesh& mesh, uint32_t width, uint32_t height, const glm::mat4& mvp,
                                 uint32_t frames)
{
  // Step 1: unlit, flat, black background.
  OsMesaContext gl(width, height);
  gl.setCommonState(mvp);
  glDisable(GL_LIGHTING);
  glShadeModel(GL_FLAT);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);

  // Step 2: un-shared vertices in index order, each triangle's three
  // carrying its id (index + 1) as R (low byte), G, B (high byte).
  const size_t numTris = mesh.numTris();
  std::vector<float> positions(numTris * 9);
  std::vector<uint8_t> colours(numTris * 12);
  for (size_t t = 0; t < numTris; ++t) {
    const uint32_t id = uint32_t(t + 1) & kIdMask;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + k];
      std::copy_n(&mesh.positions[3 * size_t(v)], 3, &positions[9 * t + 3 * k]);
      uint8_t* c = &colours[12 * t + 4 * k];
      c[0] = uint8_t(id), c[1] = uint8_t(id >> 8), c[2] = uint8_t(id >> 16), c[3] = 255;
    }
  }
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, positions.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours.data());

  // Step 3: the frames, timed from the clear to glFinish; ids masked to 24 bits.
  LlvmpipeFrames out;
  for (uint32_t f = 0; f < std::max(frames, 1u); ++f) {
    const auto start = std::chrono::steady_clock::now();
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(numTris * 3));
    glFinish();
    out.frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::vector<uint32_t> rows;
  gl.readImage(rows, out.image);
  gl.checkError("drawing ids");
  out.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  for (uint32_t& p : out.image) p &= kIdMask;
  return out;
}

namespace {

// True when the 3x3 neighbourhood of (x, y), clipped to the image, holds one id.
bool uniformNeighbourhood(const std::vector<uint32_t>& image, uint32_t w, uint32_t h, uint32_t x, uint32_t y)
{
  const uint32_t id = image[size_t(y) * w + x];
  for (uint32_t ny = y ? y - 1 : 0; ny <= std::min(y + 1, h - 1); ++ny)
    for (uint32_t nx = x ? x - 1 : 0; nx <= std::min(x + 1, w - 1); ++nx)
      if (image[size_t(ny) * w + nx] != id) return false;
  return true;
}

}  // namespace

IdComparison compareIds(const std::vector<uint32_t>& ours, const std::vector<uint32_t>& theirs, uint32_t width,
                        uint32_t height)
{
  IdComparison c;
  c.diffImage.assign(ours.size(), 0xFF000000u);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      c.coveredOurs += ours[i] != 0;
      c.coveredTheirs += theirs[i] != 0;
      c.coveredUnion += ours[i] != 0 || theirs[i] != 0;
      if (ours[i] == theirs[i]) continue;
      ++c.differing;
      c.diffImage[i] = 0xFF0000FFu;
      if (uniformNeighbourhood(ours, width, height, x, y) && uniformNeighbourhood(theirs, width, height, x, y) &&
          c.differingNotNearEdge++ == 0)
        c.firstNotNearEdge = "(" + std::to_string(x) + ", " + std::to_string(y) + "): clraster id " +
                             std::to_string(ours[i]) + ", llvmpipe id " + std::to_string(theirs[i]);
    }
  return c;
}

double meanShadeDifference(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, uint32_t background)
{
  const uint32_t rgb = 0xFFFFFFu;
  uint64_t pixels = 0, sum = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if ((a[i] & rgb) == (background & rgb) && (b[i] & rgb) == (background & rgb)) continue;
    ++pixels;
    for (int shift = 0; shift < 24; shift += 8)
      sum += uint64_t(std::abs(int((a[i] >> shift) & 0xFF) - int((b[i] >> shift) & 0xFF)));
  }
  return pixels ? double(sum) / (3.0 * double(pixels)) : 0.0;
}

}  // namespace clr::bench
