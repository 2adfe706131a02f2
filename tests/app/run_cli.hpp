#pragma once
// Runs a command line as a user would and returns its exit code and output (stderr merged).
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

namespace nsb::test {

struct Outcome {
  int code;
  std::string output;
};

inline Outcome run_command(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// The test build's `nsbench` program with these arguments, as a command line.
inline std::string nsbench_command(const std::string& args) { return std::string(NSBENCH_CLI) + " " + args; }

// The path of one of the test plugins (tests/plugins/NAME.cpp, built beside not_a_plugin).
inline std::string test_plugin(const std::string& name) { return std::string(NSBENCH_TEST_PLUGIN_DIR) + "/" + name + ".so"; }

}  // namespace nsb::test
