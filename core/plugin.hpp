#pragma once
// Plugins: shared modules loaded at run time (`--plugin FILE`, NSBENCH_PLUGINS) that register
// integrators and problems with the same macros as the built-ins (NSBENCH_INTEGRATOR in
// integrators/registry.hpp, NSBENCH_PROBLEM in problems/registry.hpp). Their registrations
// run while the loader holds the plugin's file name, so a clash or a wrong ABI is reported
// against that file; the loader then checks the marker every plugin exports.
#include <functional>
#include <string>
#include <vector>

// Bumped whenever an installed header changes what a plugin compiled against it sees
// (the layout of Problem, Integrator, Params, the registry entries).
#define NSBENCH_PLUGIN_ABI 12

#define NSBENCH_CONCAT_(a, b) a##b
#define NSBENCH_CONCAT(a, b) NSBENCH_CONCAT_(a, b)
#define NSBENCH_UNIQUE(prefix) NSBENCH_CONCAT(prefix, __COUNTER__)

// The marker the loader looks for (dlsym): defined, weak, in every translation unit of a
// plugin that includes a registry header. nsbench's own code (NSBENCH_BUILTIN, set for the
// library and, in the build tree, for its users) does not define it, so a library merely
// linked against nsbench is not taken for a plugin; nsbench_add_plugin sets NSBENCH_PLUGIN.
#if defined(NSBENCH_PLUGIN) || !defined(NSBENCH_BUILTIN)
extern "C" __attribute__((weak, visibility("default"))) const int nsbench_plugin_abi_version = NSBENCH_PLUGIN_ABI;
// How the plugin was compiled, stamped at its compile time so that the reports show the
// code that was measured. Optimised or not comes from the compiler itself (__OPTIMIZE__:
// GCC and Clang define it at -O1 and above), whatever built the plugin; the build type and
// the flags from nsbench_add_plugin (cmake/nsbenchPlugin.cmake), empty when it is not used.
#ifndef NSBENCH_PLUGIN_BUILD_TYPE
#define NSBENCH_PLUGIN_BUILD_TYPE ""
#endif
#ifndef NSBENCH_PLUGIN_COMPILE_FLAGS
#define NSBENCH_PLUGIN_COMPILE_FLAGS ""
#endif
#ifdef __OPTIMIZE__
extern "C" __attribute__((weak, visibility("default"))) const int nsbench_plugin_optimized = 1;
#else
extern "C" __attribute__((weak, visibility("default"))) const int nsbench_plugin_optimized = 0;
#endif
extern "C" __attribute__((weak, visibility("default"))) const char nsbench_plugin_build_type[] = NSBENCH_PLUGIN_BUILD_TYPE;
extern "C" __attribute__((weak, visibility("default"))) const char nsbench_plugin_compile_flags[] =
    NSBENCH_PLUGIN_COMPILE_FLAGS;
#endif

namespace nsb {

struct PluginInfo {
  std::string path;  // canonical path of the file loaded
  std::string file;  // its file name, as the reports print it
  std::string hash;  // "fnv1a64:<16 hex digits>" of the file's bytes
  // How it was compiled (the symbols above); `build_known` false for a plugin built before
  // nsbench recorded it.
  bool build_known = false;
  bool optimized = false;
  std::string build_type;     // empty: not built by nsbench_add_plugin
  std::string compile_flags;  // idem
  // "Release, optimised, flags -O3 -DNDEBUG" or "Debug, UNOPTIMISED (-O0), flags -g".
  std::string build_text() const;
};

// Loads one plugin. Throws InputError "plugin FILE: reason" when the file is missing, is
// not a shared library (checked before dlopen: an ELF shared object whose headers, sections
// and segments lie within the file, so that a truncated one is refused, not mapped), is not an nsbench plugin, was built for another ABI, or registers
// a name already taken (by a built-in or another plugin). A file already loaded is skipped.
void load_plugin(const std::string& path);
// The plugins named in NSBENCH_PLUGINS (colon-separated), then `paths` (the --plugin flags).
void load_plugins(const std::vector<std::string>& paths);
const std::vector<PluginInfo>& loaded_plugins();
// Runs `registrations` (register_integrator, register_problem calls made at run time, e.g. by
// the Python module for a class written in Python) as a plugin's run while it loads, under the
// name `source`: a name already taken or a wrong ABI is an InputError "source: reason", and the
// registry records `source` as the entry's origin. Not a file: loaded_plugins() does not list it.
void register_as_plugin(const std::string& source, const std::function<void()>& registrations);
// "file (hash; build), ..." of the loaded plugins, for the reports' stamps; empty when none.
std::string plugins_stamp();
// For an unknown integrator or problem name ("integrator", "problem"): that a plugin may be
// missing, and which plugins are loaded.
std::string missing_plugin_hint(const std::string& kind);
// One line naming the loaded plugins compiled without optimisation (their CPU times are
// not those of the code a user would run); empty when there is none.
std::string unoptimized_plugins_warning();

namespace detail {
// The plugin whose registrations are running (nullptr: a built-in one).
const std::string* loading_plugin();
// A registration refused while a plugin loads; the loader reports the first.
void registration_error(std::string message);
// How to take back an entry a plugin registered: run, newest first, when the plugin is refused
// after it (a clash on its second entry), so that a plugin registers all its entries or none.
void registered(std::function<void()> undo);
}  // namespace detail

}  // namespace nsb
