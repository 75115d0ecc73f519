#pragma once
// Runs the `rts` binary (RTS_BINARY, set by CMake) with arguments through the shell and
// collects its exit status and output, for end-to-end tests.

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace warpath::testing {

struct RtsResult {
  int status = -1;
  std::string out;  // stdout and stderr
};

// `command` run by the shell (which may set variables before the program: "PATH=/x prog").
inline RtsResult shell(const std::string& command) {
  RtsResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr)
    r.out += buffer;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

inline RtsResult rts(const std::string& args) {
  return shell(std::string(RTS_BINARY) + " " + args);
}

}  // namespace warpath::testing
