// asset_root.cpp — the rule for files a model names (see asset_root.h).
#include "io/asset_root.h"

#include "base/error.h"

#include <climits>
#include <cstdlib>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace clr {

namespace {

// The canonical form of an existing path (every link and ".." resolved),
// or "" when it cannot be resolved.
std::string canonical(const std::string& path)
{
  char* real = realpath(path.c_str(), nullptr);
  if (!real) return "";
  std::string out(real);
  std::free(real);
  return out;
}

std::string asFolder(std::string dir)
{
  if (dir.empty() || dir.back() != '/') dir += '/';
  return dir;
}

// The path of what an open descriptor names, as the kernel resolved it; ""
// where /proc is not mounted.
std::string openedPath(int fd)
{
  char link[PATH_MAX];
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  const ssize_t n = readlink(proc.c_str(), link, sizeof link - 1);
  return n > 0 ? std::string(link, size_t(n)) : "";
}

}  // namespace

AssetRoot::AssetRoot(const std::string& modelPath, const std::string& assets)
{
  if (assets == kAnyAssets) return;
  confined_ = true;
  const size_t slash = modelPath.rfind('/');
  const std::string folder = canonical(slash == std::string::npos ? "." : modelPath.substr(0, slash + 1));
  if (!folder.empty()) roots_.push_back(asFolder(folder));
  if (!assets.empty()) {
    struct stat st;
    const std::string dir = canonical(assets);
    if (dir.empty() || stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      throw Error("--assets: '" + userText(assets) + "' is not a directory (or 'any')");
    roots_.push_back(asFolder(dir));
  }
}

bool AssetRoot::inside(const std::string& path) const
{
  for (const std::string& root : roots_)
    if (path.compare(0, root.size(), root) == 0) return true;
  return false;
}

std::string AssetRoot::refusal(const std::string& reference)
{
  return "cannot use '" + userText(reference, 100) +
         "': missing, unreadable, malformed or outside the model's folder (see --assets)";
}

std::unique_ptr<InputFile> AssetRoot::open(const std::string& path, const std::string& reference,
                                           const InputKind& kind) const
{
  if (!confined()) return std::make_unique<InputFile>(path, kind);
  // Step 1: where the path leads, before anything is opened.
  const std::string real = canonical(path);
  if (real.empty() || !inside(real)) throw Error(refusal(reference));
  // Step 2: open that file under the file rule; every failure reads alike.
  std::unique_ptr<InputFile> file;
  try {
    file = std::make_unique<InputFile>(real, kind);
  } catch (const InputOverLimit&) {
    throw;  // a limit names itself: the file is inside the root, so saying so tells nothing new
  } catch (const Error&) {
    throw Error(refusal(reference));
  }
  // Step 3: what was opened is still inside (a link swapped in after step 1).
  const std::string opened = openedPath(file->descriptor());
  if (!opened.empty() && !inside(opened)) throw Error(refusal(reference));
  return file;
}

}  // namespace clr
