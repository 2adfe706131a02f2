#include "core/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <cstdint>
#include <fstream>
#include <system_error>

#include "core/parameters.hpp"

namespace nsb {

void write_file_atomic(const std::filesystem::path& path, const std::string& content) {
  const auto tmp = path.parent_path() /
                   fmt::format(".{}.tmp.{}", path.filename().string(), static_cast<long>(::getpid()));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw InputError(fmt::format("cannot write '{}'", path.string()));
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(fmt::format("cannot write '{}': {}", path.string(), ec.message()));
  }
}

std::string fnv1a64(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return fmt::format("{:016x}", h);
}

std::string read_file_bounded(const std::filesystem::path& path, std::size_t max_bytes, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("{} '{}': {}", what, path.string(),
                                 std::filesystem::exists(path, ec) ? "not a regular file" : "no such file"));
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(fmt::format("{} '{}': cannot be read: {}", what, path.string(), ec.message()));
  if (size > max_bytes)
    throw InputError(fmt::format("{} '{}': {} bytes, larger than the limit of {} bytes", what, path.string(), size, max_bytes));
  std::ifstream in(path, std::ios::binary);
  std::string text(size, '\0');
  if (!in || !in.read(text.data(), static_cast<std::streamsize>(size)))
    throw InputError(fmt::format("{} '{}': cannot be read", what, path.string()));
  return text;
}

void ensure_directory(const std::filesystem::path& dir, const std::string& option) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError(fmt::format("{} '{}': cannot create directory{}", option, dir.string(),
                                 ec ? ": " + ec.message() : ""));
  const auto probe = dir / fmt::format(".nsbench.probe.tmp.{}", static_cast<long>(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
    throw InputError(fmt::format("{} '{}': cannot write files there: {}", option, dir.string(), std::strerror(errno)));
  ::close(fd);
  std::filesystem::remove(probe, ec);
}

namespace {

// The pid of a ".NAME.tmp.PID" or ".NAME.staging.PID" entry; 0 for anything else.
long temporary_owner(const std::string& name, const char* kind) {
  const auto at = name.rfind(kind);
  if (name.empty() || name[0] != '.' || at == std::string::npos) return 0;
  const std::string digits = name.substr(at + std::strlen(kind));
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stol(digits);
}

bool process_gone(long pid) { return pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

}  // namespace

void remove_stale_temporaries(const std::filesystem::path& dir) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const long pid = temporary_owner(e.path().filename().string(), ".tmp.");
    if (pid > 0 && process_gone(pid)) std::filesystem::remove(e.path(), ec);
  }
}

namespace {

// Hard links to every file under `from`, in the same tree under `to` (copies where a link
// cannot be made).
void link_tree(const std::filesystem::path& from, const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  for (auto it = fs::recursive_directory_iterator(from); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path rel = fs::relative(it->path(), from), dest = to / rel;
    if (it->is_directory()) {
      fs::create_directories(dest);
    } else if (it->is_regular_file()) {
      std::error_code ec;
      fs::create_hard_link(it->path(), dest, ec);
      if (ec) fs::copy_file(it->path(), dest);
    }
  }
}

}  // namespace

ReportDirectory::ReportDirectory(const std::filesystem::path& target, const std::string& option) : option_(option) {
  namespace fs = std::filesystem;
  ensure_directory(target, option);
  target_ = fs::canonical(target);  // "out/", ".": a name and a parent to stage beside
  const fs::path parent = target_.parent_path();
  const std::string name = target_.filename().string();
  if (name.empty()) throw InputError(fmt::format("{} '{}': the root directory cannot be a report", option, target.string()));
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(parent, ec)) {  // earlier runs' leftovers
    const std::string entry = e.path().filename().string();
    const long pid = entry.rfind("." + name + ".staging.", 0) == 0 ? temporary_owner(entry, ".staging.") : 0;
    if (pid > 0 && process_gone(pid)) fs::remove_all(e.path(), ec);
  }
  staging_ = parent / fmt::format(".{}.staging.{}", name, static_cast<long>(::getpid()));
  fs::remove_all(staging_, ec);
  try {
    fs::create_directory(staging_);
    link_tree(target_, staging_);
    ensure_directory(staging_, option);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(staging_, ec);
    throw InputError(fmt::format("{} '{}': cannot stage the report beside it: {}", option, target_.string(), e.what()));
  }
}

ReportDirectory::~ReportDirectory() {
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);  // after commit(): the old report
}

void ReportDirectory::commit() {
  if (committed_) return;
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
    // A file system without the exchange (EINVAL): two renames, the report absent between them.
    const std::filesystem::path old = staging_.string() + ".old";
    if (errno != EINVAL || ::rename(target_.c_str(), old.c_str()) != 0 || ::rename(staging_.c_str(), target_.c_str()) != 0)
      throw InputError(fmt::format("{} '{}': cannot replace the report: {}", option_, target_.string(), std::strerror(errno)));
    staging_ = old;
  }
  committed_ = true;
}

}  // namespace nsb
