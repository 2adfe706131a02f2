// The test binary loads the example plugin (examples/plugin) before any test runs, so every
// test that iterates the registry (contact law, bar, block) checks the plugged scheme too.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "core/plugin.hpp"

int main(int argc, char** argv) {
  nsb::load_plugin(NSBENCH_EXAMPLE_PLUGIN);
  return Catch::Session().run(argc, argv);
}
