// program_cache.cpp — the compiled-program cache (program_cache.h for the
// contract). A file is an 80-byte header, then the driver's binary:
//   magic "CLRBIN02" | key (32) | payload bytes (u64 LE) | tag (32)
// where key is SHA-256 of the sources, options, device and driver, and tag
// is HMAC-SHA-256, under the directory's secret, of key and payload.
#include "pipeline/program_cache.h"

#include "pipeline/device.h"
#include "pipeline/embedded_kernels.h"
#include "io/file_rule.h"
#include "io/image_io.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace clr {

namespace {

constexpr char kMagic[8] = {'C', 'L', 'R', 'B', 'I', 'N', '0', '2'};
constexpr size_t kDigestBytes = 32;
constexpr size_t kHeaderBytes = 8 + kDigestBytes + 8 + kDigestBytes;
constexpr char kSecretName[] = "secret";
using Digest = std::array<unsigned char, kDigestBytes>;

// SHA-256 of the fields, each followed by a NUL (so that ("ab","c") and ("a","bc") differ).
Digest sha256(const std::vector<std::string>& fields)
{
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  Digest d{};
  unsigned n = 0;
  bool ok = ctx && EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr);
  for (const std::string& f : fields)
    ok = ok && EVP_DigestUpdate(ctx, f.data(), f.size()) && EVP_DigestUpdate(ctx, "", 1);
  ok = ok && EVP_DigestFinal_ex(ctx, d.data(), &n);
  EVP_MD_CTX_free(ctx);
  if (!ok || n != kDigestBytes) throw Error("kernel cache: SHA-256 failed");
  return d;
}

// HMAC-SHA-256 of key and payload under secret.
Digest tag(const std::string& secret, const Digest& key, const unsigned char* payload, size_t n)
{
  std::vector<unsigned char> message(key.begin(), key.end());
  message.insert(message.end(), payload, payload + n);
  Digest d{};
  unsigned length = 0;
  if (!HMAC(EVP_sha256(), secret.data(), int(secret.size()), message.data(), message.size(), d.data(), &length) ||
      length != kDigestBytes)
    throw Error("kernel cache: HMAC-SHA-256 failed");
  return d;
}

void putU64(std::vector<unsigned char>& out, uint64_t v)
{
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

uint64_t getU64(const std::string& s, size_t at)
{
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(s[at + size_t(i)]);
  return v;
}

std::string hex(const Digest& d)
{
  std::string out;
  char two[3];
  for (unsigned char c : d) {
    std::snprintf(two, sizeof two, "%02x", c);
    out += two;
  }
  return out;
}

// Whether path is, without following a link, a directory (or a regular file)
// of this user that no other user can write.
bool privateEntry(const std::string& path, bool directory)
{
  struct stat st;
  if (lstat(path.c_str(), &st) != 0) return false;
  if (directory ? !S_ISDIR(st.st_mode) : !S_ISREG(st.st_mode)) return false;
  return st.st_uid == geteuid() && (st.st_mode & (S_IWGRP | S_IWOTH)) == 0;
}

// The directory's secret, or "" when the directory or the secret is not private.
std::string readSecret(const std::string& dir)
{
  const std::string path = dir + "/" + kSecretName;
  if (!privateEntry(dir, true) || !privateEntry(path, false)) return "";
  const std::string secret = readInputFile(path, kProgramCacheInput);
  return secret.size() == kDigestBytes ? secret : "";
}

// The private cache directory, made 0700 when missing, and its secret, made
// when missing; an Error when either is not private.
std::string makePrivateDir(const std::string& dir)
{
  std::error_code failed;
  std::filesystem::create_directories(std::filesystem::path(dir).parent_path(), failed);
  if (mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw Error(userText(dir) + ": cannot create the kernel cache directory (" + std::strerror(errno) + ")");
  if (!privateEntry(dir, true))
    throw Error(userText(dir) +
                ": the kernel cache directory must be a folder of this user that no other user can write");
  std::string secret = readSecret(dir);
  if (secret.empty()) {
    std::vector<unsigned char> bytes(kDigestBytes);
    if (RAND_bytes(bytes.data(), int(bytes.size())) != 1) throw Error("kernel cache: no random bytes for the secret");
    writeFileAtomic(dir + "/" + kSecretName, bytes, 0600);
    secret = readSecret(dir);
    if (secret.empty()) throw Error(userText(dir) + ": cannot keep the kernel cache's secret private");
  }
  return secret;
}

}  // namespace

std::string programCacheDir()
{
  if (const char* dir = std::getenv("CLRASTER_CACHE_DIR")) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/') return std::string(xdg) + "/clraster";
  if (const char* home = std::getenv("HOME"); home && *home == '/') return std::string(home) + "/.cache/clraster";
  return "";
}

std::string programCacheKey(const cl::Device& device, const std::string& options)
{
  std::vector<std::string> fields{std::string(kMagic, sizeof kMagic)};
  for (size_t i = 0; i < kEmbeddedKernelCount; ++i) fields.push_back(kEmbeddedKernels[i].text);
  const cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>());
  fields.insert(fields.end(), {options, platform.getInfo<CL_PLATFORM_NAME>(), platform.getInfo<CL_PLATFORM_VERSION>(),
                               device.getInfo<CL_DEVICE_NAME>(), device.getInfo<CL_DEVICE_VERSION>(),
                               device.getInfo<CL_DRIVER_VERSION>()});
  const Digest d = sha256(fields);
  return std::string(d.begin(), d.end());
}

cl::Program loadCachedProgram(const cl::Context& context, const cl::Device& device, const std::string& options)
{
  const std::string dir = programCacheDir();
  if (dir.empty()) return cl::Program();
  try {  // any doubt (a missing or foreign file, a link, a group-writable folder, a bad tag) is a miss
    const std::string secret = readSecret(dir);
    if (secret.empty()) return cl::Program();
    Digest key;
    const std::string keyBytes = programCacheKey(device, options);
    std::memcpy(key.data(), keyBytes.data(), kDigestBytes);
    const std::string path = dir + "/" + hex(key) + ".bin";
    if (!privateEntry(path, false)) return cl::Program();
    const std::string file = readInputFile(path, kProgramCacheInput);
    if (file.size() <= kHeaderBytes || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0) return cl::Program();
    if (file.compare(8, kDigestBytes, keyBytes) != 0) return cl::Program();
    if (getU64(file, 8 + kDigestBytes) != file.size() - kHeaderBytes) return cl::Program();
    const auto* payload = reinterpret_cast<const unsigned char*>(file.data()) + kHeaderBytes;
    const Digest expected = tag(secret, key, payload, file.size() - kHeaderBytes);
    if (CRYPTO_memcmp(expected.data(), file.data() + 8 + kDigestBytes + 8, kDigestBytes) != 0) return cl::Program();
    const cl::Program::Binaries binaries{std::vector<unsigned char>(payload, payload + file.size() - kHeaderBytes)};
    cl::Program program(context, {device}, binaries);
    program.build({device}, options.c_str());
    std::vector<cl::Kernel> kernels;  // every kernel must create, or the source build is used
    program.createKernels(&kernels);
    if (kernels.empty()) return cl::Program();
    return program;
  } catch (const std::exception&) {  // cl::Error or clr::Error: build from source instead
    return cl::Program();
  }
}

std::string storeProgramBinary(const cl::Program& program, const cl::Device& device, const std::string& options)
{
  const std::string dir = programCacheDir();
  if (dir.empty()) throw Error("no kernel cache directory (CLRASTER_CACHE_DIR is empty, HOME unset)");
  const std::string secret = makePrivateDir(dir);
  Digest key;
  const std::string keyBytes = programCacheKey(device, options);
  std::memcpy(key.data(), keyBytes.data(), kDigestBytes);
  const cl::Program::Binaries binaries = program.getInfo<CL_PROGRAM_BINARIES>();
  if (binaries.size() != 1 || binaries[0].empty()) throw Error("the OpenCL driver gave no program binary to cache");
  const std::vector<unsigned char>& payload = binaries[0];
  std::vector<unsigned char> file;
  file.reserve(kHeaderBytes + payload.size());
  file.insert(file.end(), kMagic, kMagic + sizeof kMagic);
  file.insert(file.end(), key.begin(), key.end());
  putU64(file, payload.size());
  const Digest t = tag(secret, key, payload.data(), payload.size());
  file.insert(file.end(), t.begin(), t.end());
  file.insert(file.end(), payload.begin(), payload.end());
  const std::string path = dir + "/" + hex(key) + ".bin";
  writeFileAtomic(path, std::move(file), 0600);
  return path;
}

int cacheCommand(const std::vector<std::string>& args)
{
  std::string selector;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--device" && i + 1 < args.size())
      selector = args[++i];
    else
      throw Error("cache: unexpected argument '" + userText(args[i]) + "' (cache [--device SEL])");
  }
  for (const bool clipInput : {false, true}) {
    ClContext ctx(selector, 0, clipInput);
    for (const bool extras : {false, true}) {
      const cl::Program& program = extras ? ctx.extras() : ctx.program;
      std::printf("%s\n",
                  storeProgramBinary(program, ctx.info.device, programOptions(ctx.buildOptions(), extras)).c_str());
    }
  }
  return 0;
}

}  // namespace clr
