// The test binary loads the example plugin (examples/plugin) before any test runs, so every
// test that iterates the registry (contact law, bar, block) checks the plugged scheme too.
// Loaded while the binary starts (a static initialiser, after libnsbench's own registrations,
// before main), since the runner is Catch2's prebuilt main (Debian's libCatch2WithMain.a,
// tests/CMakeLists.txt says why). A plugin that fails to load ends the binary there, as an
// exception out of main did.
#include "core/plugin.hpp"

namespace {
const bool kExamplePluginLoaded = (nsb::load_plugin(NSBENCH_EXAMPLE_PLUGIN), true);
}  // namespace
