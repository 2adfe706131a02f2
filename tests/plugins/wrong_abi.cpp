// A plugin built against another plugin ABI: its marker and its registration carry ABI 999.
// The registration must be refused without reading the entry, and the load fail cleanly.
#undef NSBENCH_PLUGIN  // keeps the header's marker out: this file defines its own
#include "integrators/registry.hpp"

extern "C" __attribute__((visibility("default"))) const int nsbench_plugin_abi_version = 999;

[[maybe_unused]] static const bool registered = nsb::register_integrator(
    nsb::IntegratorEntry{"wrong-abi", "never listed", nullptr, nullptr, false}, 999);
