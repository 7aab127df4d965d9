// cli_support.h — running the clraster binary from the tests: its exit
// status, stdout and stderr, scratch files beside it, and the one-line error
// contract (exit 1, one line on stderr naming the problem).
#pragma once

#include <cstddef>
#include <string>

namespace test {

struct Run {
  int status = -1;
  std::string out, err;
};

// Runs `clraster ARGS` (ARGS as a shell would split them) with stdin from
// /dev/null and stderr to a file, so stderr is never a terminal.
Run run(const std::string& args);

// Runs a shell command whose stderr the command itself sends to errPath:
// its exit status, its stdout, and errPath's contents.
Run runShell(const std::string& command, const std::string& errPath);

// The whole contents of a file ("" when it cannot be read).
std::string slurp(const std::string& path);

// Writes content to tempDir()/name (atomically, by rename) and returns that path.
std::string writeFile(const std::string& name, const std::string& content);

// A failing run: exit 1, exactly one line on stderr containing `needle`.
Run expectError(const std::string& args, const std::string& needle);

// Temporary files left beside `target` (its name followed by ".tmp-").
size_t leftoverTemps(const std::string& target);

// Whether a file exists.
bool exists(const std::string& path);

}  // namespace test
