// cli_support.cpp — see cli_support.h.
#include "cli_support.h"

#include "test_support.h"

#include <catch2/catch.hpp>

#include <dirent.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace test {

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Run run(const std::string& args)
{
  // One stderr file per test process: CTest runs test cases in parallel.
  const std::string errPath = tempDir() + "/stderr-" + std::to_string(getpid()) + ".txt";
  return runShell(std::string("'") + CLRASTER_BIN + "' " + args + " 2>'" + errPath + "' </dev/null", errPath);
}

Run runShell(const std::string& command, const std::string& errPath)
{
  Run r;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe);
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = slurp(errPath);
  return r;
}

std::string writeFile(const std::string& name, const std::string& content)
{
  // Written aside and renamed into place: CTest runs test cases in parallel
  // processes, and several write the same scene file (views-cube.obj); a
  // reader must never see it truncated.
  const std::string path = tempDir() + "/" + name;
  const std::string aside = path + ".writing-" + std::to_string(getpid());
  std::ofstream(aside, std::ios::binary) << content;
  std::rename(aside.c_str(), path.c_str());
  return path;
}

Run expectError(const std::string& args, const std::string& needle)
{
  const Run r = run(args);
  INFO("clraster " << args << "\nstderr: " << r.err);
  CHECK(r.status == 1);
  CHECK(r.err.find(needle) != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  return r;
}

size_t leftoverTemps(const std::string& target)
{
  const std::string dirPath = target.substr(0, target.rfind('/'));
  const std::string prefix = target.substr(target.rfind('/') + 1) + ".tmp-";
  size_t n = 0;
  DIR* dir = opendir(dirPath.c_str());
  if (!dir) return 0;
  while (dirent* e = readdir(dir)) n += std::string(e->d_name).rfind(prefix, 0) == 0;
  closedir(dir);
  return n;
}

bool exists(const std::string& path)
{
  struct stat st;
  return stat(path.c_str(), &st) == 0;
}

}  // namespace test
