// Running a program as a subprocess from a test: argv without a shell (no quoting
// problems), standard input from a file (/dev/null unless given), stdout and stderr
// captured through files, the exit code or the signal.
#pragma once
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "test_support.h"

extern char** environ;

namespace gridrt::test {

struct CommandResult {
  int exit_code = -1;  // -1 when it did not exit normally
  int signal = 0;      // the signal that ended it, if any
  std::string out, err;
};

inline std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline CommandResult runCommand(const std::vector<std::string>& argv,
                                const std::string& stdin_path = "/dev/null") {
  static int counter = 0;
  const std::string base = tempPath("cmd" + std::to_string(counter++));
  const std::string out_path = base + ".out", err_path = base + ".err";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, stdin_path.c_str(), O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  CommandResult r;
  pid_t pid = 0;
  int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    r.err = "posix_spawn failed: " + std::string(std::strerror(rc));
    return r;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = readWholeFile(out_path);
  r.err = readWholeFile(err_path);
  std::remove(out_path.c_str());
  std::remove(err_path.c_str());
  return r;
}

// "a b c" for failure messages.
inline std::string joinArgs(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

// Whether gridrt finds an OpenCL device (the CLI tests that render skip without one).
inline bool gridrtHasDevice() {
  return runCommand({gridrtBinary(), "--list-devices"}).exit_code == 0;
}

// gridrt on `scene` at width x height, quiet, then `flags`.
inline std::vector<std::string> gridrtCommand(const std::string& scene, int width, int height,
                                              const std::vector<std::string>& flags) {
  std::vector<std::string> argv{
      gridrtBinary(),        scene, "-q", "--width", std::to_string(width), "--height",
      std::to_string(height)};
  argv.insert(argv.end(), flags.begin(), flags.end());
  return argv;
}

}  // namespace gridrt::test
