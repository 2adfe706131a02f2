#pragma once
// The registry shared by problems and integrators: an entry has a `name`, its
// `parameters()` and a `make(Params)` factory. Entries are added by the registration macros
// (NSBENCH_INTEGRATOR, NSBENCH_PROBLEM) from the built-ins' and the plugins' sources, in
// whatever order static initialisation and plugin loading run; the listing is kept sorted
// (Registry's `Before`), so studies that iterate it are deterministic.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "core/plugin.hpp"

namespace nsb {

// What a registry of `Base` checks of a class T when a source registers it, at compile time:
// overrides of an older plugin API, warned about and adapted (integrators/plugin_compat.hpp,
// problems/plugin_compat.hpp). The default checks nothing.
template <class Base, class T>
struct PluginCompat {
  static void adapt(T& /*made*/) {}
};

// Factory of a registry entry: builds T from its validated parameters.
template <class Base, class T>
std::unique_ptr<Base> make_from_params(const Params& p) {
  auto made = std::make_unique<T>(p);
  PluginCompat<Base, T>::adapt(*made);
  return made;
}

// Throws InputError naming the option, the nearest name and the valid names when `name` is
// unknown, and that a plugin may be missing.
template <class Entry>
const Entry& find_entry(const std::vector<Entry>& entries, const std::string& name, const std::string& option,
                        const std::string& kind) {
  std::vector<std::string> names;
  for (const auto& e : entries) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw InputError(fmt::format("{} '{}': unknown {} (nearest: {}; valid: {}); {}", option, name, kind,
                               nearest_name(name, names), fmt::join(names, ", "), missing_plugin_hint(kind)));
}

template <class Entry>
auto make_entry(const Entry& entry, const std::map<std::string, std::string>& overrides) {
  return entry.make(Params(entry.parameters(), overrides));
}

template <class Entry, class Before>
class Registry {
 public:
  // `abi`: the NSBENCH_PLUGIN_ABI the caller was compiled with; on a mismatch `e` is not
  // read (its layout may differ). A refused plugin entry is reported through the loader; two
  // built-ins of one name are a bug of nsbench itself, stopped at start-up.
  bool add(const Entry& e, int abi, const char* kind) {
    const std::string* plugin = detail::loading_plugin();
    if (abi != NSBENCH_PLUGIN_ABI) {
      detail::registration_error(fmt::format("built for plugin ABI {}, this nsbench has ABI {}", abi, NSBENCH_PLUGIN_ABI));
      return false;
    }
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (entries_[i].name != e.name) continue;
      const std::string msg = fmt::format("{} '{}' is already registered by {}", kind, e.name,
                                          origins_[i].empty() ? "nsbench (built-in)" : "plugin " + origins_[i]);
      if (!plugin) {
        std::fprintf(stderr, "nsbench: internal error: built-in %s\n", msg.c_str());
        std::abort();
      }
      detail::registration_error(msg);
      return false;
    }
    const auto pos = std::upper_bound(entries_.begin(), entries_.end(), e, Before{});
    origins_.insert(origins_.begin() + (pos - entries_.begin()), plugin ? *plugin : std::string());
    entries_.insert(pos, e);
    if (plugin) detail::registered([this, name = e.name] { remove(name); });
    return true;
  }
  const std::vector<Entry>& entries() const { return entries_; }
  // Where the entry named `name` came from: "" (built in, or no such entry), else the source
  // it was registered under (a plugin's file, register_as_plugin's source).
  std::string origin(const std::string& name) const {
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (entries_[i].name == name) return origins_[i];
    return {};
  }

 private:
  void remove(const std::string& name) {
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (entries_[i].name == name) {
        entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(i));
        origins_.erase(origins_.begin() + static_cast<std::ptrdiff_t>(i));
        return;
      }
  }
  std::vector<Entry> entries_;
  std::vector<std::string> origins_;  // plugin file of each entry; empty: built-in
};

}  // namespace nsb
