#include "core/plugin.hpp"

#include <dlfcn.h>
#include <elf.h>
#include <fmt/format.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>

#include "core/output.hpp"
#include "core/parameters.hpp"

namespace nsb {

namespace {

namespace fs = std::filesystem;

struct Loader {
  const std::string* loading = nullptr;  // set while a plugin's static registrations run
  std::vector<std::string> errors;       // of the plugin being loaded
  std::vector<std::function<void()>> undo;  // its entries registered so far (detail::registered)
  std::map<std::string, std::string> refused;  // canonical path -> why: dlopen runs no registration twice
  std::vector<PluginInfo> loaded;
};

// Takes back the entries of the plugin being loaded, newest first.
void undo_registrations(Loader& l) {
  for (auto it = l.undo.rbegin(); it != l.undo.rend(); ++it) (*it)();
  l.undo.clear();
}

Loader& loader() {
  static Loader l;
  return l;
}

// Why `bytes` is no ELF shared object this process can map; empty when it is. dlopen maps the
// file's segments and reads its headers without checking them against the file's size: a
// truncated file faults (SIGBUS) instead of failing, so every table and segment is checked
// to lie within the file first.
std::string elf_damage(const std::string& bytes) {
  const auto within = [&](std::uint64_t offset, std::uint64_t size) {
    return offset <= bytes.size() && size <= bytes.size() - offset;
  };
  Elf64_Ehdr header;
  if (bytes.size() < sizeof header || bytes.compare(0, SELFMAG, ELFMAG) != 0) return "not an ELF file";
  std::memcpy(&header, bytes.data(), sizeof header);
  if (header.e_ident[EI_CLASS] != ELFCLASS64) return "not a 64-bit ELF file";
  if (header.e_type != ET_DYN) return "not an ELF shared object";
  if (header.e_phentsize != sizeof(Elf64_Phdr) || !within(header.e_phoff, std::uint64_t{header.e_phnum} * sizeof(Elf64_Phdr)))
    return fmt::format("its program header table lies beyond its {} bytes (truncated?)", bytes.size());
  if (header.e_shnum != 0 &&
      (header.e_shentsize != sizeof(Elf64_Shdr) || !within(header.e_shoff, std::uint64_t{header.e_shnum} * sizeof(Elf64_Shdr))))
    return fmt::format("its section header table lies beyond its {} bytes (truncated?)", bytes.size());
  for (std::size_t i = 0; i < header.e_phnum; ++i) {
    Elf64_Phdr segment;
    std::memcpy(&segment, bytes.data() + header.e_phoff + i * sizeof segment, sizeof segment);
    if (!within(segment.p_offset, segment.p_filesz))
      return fmt::format("segment {} lies beyond its {} bytes (truncated?)", i, bytes.size());
  }
  for (std::size_t i = 0; i < header.e_shnum; ++i) {
    Elf64_Shdr section;
    std::memcpy(&section, bytes.data() + header.e_shoff + i * sizeof section, sizeof section);
    if (section.sh_type != SHT_NOBITS && !within(section.sh_offset, section.sh_size))
      return fmt::format("section {} lies beyond its {} bytes (truncated?)", i, bytes.size());
  }
  return {};
}

// Far above any plugin (the example is tens of kB).
constexpr std::size_t kMaxPluginBytes = std::size_t{1} << 30;

}  // namespace

namespace detail {
const std::string* loading_plugin() { return loader().loading; }
void registration_error(std::string message) { loader().errors.push_back(std::move(message)); }
void registered(std::function<void()> undo) { loader().undo.push_back(std::move(undo)); }
}  // namespace detail

void load_plugin(const std::string& path) {
  const auto fail = [&](const std::string& why) { throw InputError(fmt::format("plugin {}: {}", path, why)); };
  std::error_code ec;
  if (!fs::exists(path, ec)) fail("no such file");
  if (!fs::is_regular_file(path, ec)) fail("not a regular file");
  const fs::path canonical = fs::canonical(path, ec);
  if (ec) fail(fmt::format("cannot resolve its path ({})", ec.message()));
  Loader& l = loader();
  for (const auto& p : l.loaded)
    if (p.path == canonical.string()) return;  // named twice (flag and environment)
  if (const auto it = l.refused.find(canonical.string()); it != l.refused.end()) fail(it->second);
  // Refused once its registrations ran: none of its entries stays, and a second call says so again.
  const auto refuse = [&](const std::string& why) {
    undo_registrations(l);
    l.refused[canonical.string()] = why;
    fail(why);
  };
  const std::string bytes = read_file_bounded(canonical, kMaxPluginBytes, "plugin");
  const std::string hash = "fnv1a64:" + fnv1a64(bytes);  // identifies the file a table came from
  const std::string damage = elf_damage(bytes);
  if (!damage.empty()) fail(fmt::format("not a loadable shared library ({})", damage));

  // The plugin's registrations run inside dlopen (static initialisation).
  l.loading = &path;
  l.errors.clear();
  l.undo.clear();
  void* handle = dlopen(canonical.c_str(), RTLD_NOW | RTLD_LOCAL);
  l.loading = nullptr;
  if (!handle) {
    const char* why = dlerror();
    fail(fmt::format("not a loadable shared library ({})", why ? why : "dlopen failed"));
  }
  // Never dlclose'd: the registry keeps pointers to its functions.
  const auto* abi = static_cast<const int*>(dlsym(handle, "nsbench_plugin_abi_version"));
  if (!abi)
    refuse("not an nsbench plugin (no nsbench_plugin_abi_version symbol: it registers nothing with "
         "NSBENCH_INTEGRATOR or NSBENCH_PROBLEM)");
  if (*abi != NSBENCH_PLUGIN_ABI)
    refuse(fmt::format("built for plugin ABI {}, this nsbench has ABI {}: rebuild it against this nsbench "
                       "(CHANGELOG.md, 'Plugin API: what to change', says what its source must change)",
                       *abi, NSBENCH_PLUGIN_ABI));
  if (!l.errors.empty()) refuse(l.errors.front());
  l.undo.clear();
  PluginInfo info;
  info.path = canonical.string();
  info.file = canonical.filename().string();
  info.hash = hash;
  const auto* optimized = static_cast<const int*>(dlsym(handle, "nsbench_plugin_optimized"));
  const auto* build_type = static_cast<const char*>(dlsym(handle, "nsbench_plugin_build_type"));
  const auto* flags = static_cast<const char*>(dlsym(handle, "nsbench_plugin_compile_flags"));
  if (optimized && build_type && flags) {
    info.build_known = true;
    info.optimized = *optimized != 0;
    info.build_type = build_type;
    info.compile_flags = flags;
  }
  l.loaded.push_back(std::move(info));
}

std::string PluginInfo::build_text() const {
  if (!build_known) return "build unknown (built before nsbench recorded it)";
  return fmt::format("{}, {}, flags {}", build_type.empty() ? "build type unknown" : build_type,
                     optimized ? "optimised" : "UNOPTIMISED (-O0)", compile_flags.empty() ? "unknown" : compile_flags);
}

void load_plugins(const std::vector<std::string>& paths) {
  if (const char* env = std::getenv("NSBENCH_PLUGINS")) {
    const std::string list = env;
    std::size_t begin = 0;
    while (begin <= list.size()) {
      const std::size_t end = std::min(list.find(':', begin), list.size());
      if (end > begin) load_plugin(list.substr(begin, end - begin));
      begin = end + 1;
    }
  }
  for (const auto& p : paths) load_plugin(p);
}

const std::vector<PluginInfo>& loaded_plugins() { return loader().loaded; }

void register_as_plugin(const std::string& source, const std::function<void()>& registrations) {
  Loader& l = loader();
  l.loading = &source;
  l.errors.clear();
  l.undo.clear();
  try {
    registrations();
  } catch (...) {
    l.loading = nullptr;
    undo_registrations(l);
    throw;
  }
  l.loading = nullptr;
  if (!l.errors.empty()) {
    undo_registrations(l);
    throw InputError(fmt::format("{}: {}", source, l.errors.front()));
  }
  l.undo.clear();
}

std::string plugins_stamp() {
  std::vector<std::string> parts;
  for (const auto& p : loaded_plugins()) parts.push_back(fmt::format("{} ({}; {})", p.file, p.hash, p.build_text()));
  return fmt::format("{}", fmt::join(parts, ", "));
}

std::string missing_plugin_hint(const std::string& kind) {
  std::vector<std::string> files;
  for (const auto& p : loaded_plugins()) files.push_back(p.file);
  return fmt::format("a plugin's {}? load its file with --plugin FILE or NSBENCH_PLUGINS (plugins loaded: {})", kind,
                     files.empty() ? std::string("none") : fmt::format("{}", fmt::join(files, ", ")));
}

std::string unoptimized_plugins_warning() {
  std::vector<std::string> slow;
  for (const auto& p : loaded_plugins())
    if (p.build_known && !p.optimized) slow.push_back(fmt::format("{} ({})", p.file, p.build_text()));
  if (slow.empty()) return "";
  return fmt::format("warning: plugin {} compiled without optimisation: its CPU times are those of unoptimised code "
                     "(rebuild it with -DCMAKE_BUILD_TYPE=Release, nsbench_add_plugin's default)",
                     fmt::join(slow, ", "));
}

}  // namespace nsb
