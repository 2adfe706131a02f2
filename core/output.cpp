#include "core/output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include <cstdint>
#include <fstream>
#include <system_error>
#include <thread>
#include <tuple>

#include "core/parameters.hpp"

namespace nsb {

void write_file_atomic(const std::filesystem::path& path, const std::string& content) {
  const auto tmp = path.parent_path() /
                   fmt::format(".{}.tmp.{}", path.filename().string(), static_cast<long>(::getpid()));
  {
    errno = 0;  // the failing call's reason, not an earlier one's (a full disk: ENOSPC)
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      const int reason = errno;
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw InputError(fmt::format("cannot write '{}': {}", path.string(), reason ? std::strerror(reason) : "the write failed"));
    }
  }
  std::error_code ec, ignored;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ignored);  // not into ec: the message says why the rename failed
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

// What a directory entry is, for the refusal: "a FIFO", ...; empty for a regular file or a
// directory (what the suite writes).
std::string foreign_kind(std::filesystem::file_type type) {
  using std::filesystem::file_type;
  switch (type) {
    case file_type::regular:
    case file_type::directory: return "";
    case file_type::symlink: return "a symbolic link";
    case file_type::fifo: return "a FIFO";
    case file_type::socket: return "a socket";
    case file_type::block:
    case file_type::character: return "a device file";
    default: return "a special file";
  }
}

// Throws unless `dir` (an existing directory) is empty, or the suite's own output holding
// only regular files and directories.
void check_own_output(const std::filesystem::path& dir, const std::string& option) {
  namespace fs = std::filesystem;
  try {
    if (fs::is_empty(dir)) return;
    if (!fs::is_regular_file(fs::symlink_status(dir / kOutputMarker)))
      throw InputError(fmt::format("{} '{}': not empty and not an nsbench output directory (no {} file); the suite "
                                   "replaces its output directory whole and writes only into a new or empty directory "
                                   "or one it wrote; valid: a new directory",
                                   option, dir.string(), kOutputMarker));
    for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
      const std::string kind = foreign_kind(it->symlink_status().type());
      if (!kind.empty())
        throw InputError(fmt::format("{} '{}': holds '{}', {} the suite never writes; its output directory is replaced "
                                     "whole, so it would be deleted; move it away or choose another directory",
                                     option, dir.string(), it->path().string(), kind));
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(fmt::format("{} '{}': cannot be read: {}", option, dir.string(), e.code().message()));
  }
}

// Created in place, not through a temporary and a rename: the marker is the first entry of a
// new output directory, so a run claiming it at the same time (the shards of one study on a
// cluster) finds it empty or marked, never holding another run's temporary and unmarked.
// Only its existence counts, so a reader may see it before its line is written.
void mark_output(const std::filesystem::path& dir) {
  const std::filesystem::path marker = dir / kOutputMarker;
  const int fd = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return;  // another run marked it first
    throw InputError(fmt::format("cannot write '{}': {}", marker.string(), std::strerror(errno)));
  }
  static constexpr char kText[] = "nsbench output: replaced whole by the suite's next run into it\n";
  const bool written = ::write(fd, kText, sizeof kText - 1) == static_cast<ssize_t>(sizeof kText - 1);
  ::close(fd);
  if (!written) throw InputError(fmt::format("cannot write '{}'", marker.string()));
}

}  // namespace

void claim_output_directory(const std::filesystem::path& dir, const std::string& option) {
  ensure_directory(dir, option);  // leaves an existing directory as it was
  check_own_output(dir, option);
  if (!std::filesystem::exists(dir / kOutputMarker))
    mark_output(dir);
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
// cannot be made); returns the directories' modes, by their path under `to`. `from` holds
// only regular files and directories (check_own_output): nothing is followed out of it.
std::vector<std::pair<std::filesystem::path, std::filesystem::perms>> link_tree(const std::filesystem::path& from,
                                                                                 const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  std::vector<std::pair<fs::path, fs::perms>> modes{{to, fs::status(from).permissions()}};
  for (auto it = fs::recursive_directory_iterator(from); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path dest = to / it->path().lexically_relative(from);
    if (it->is_directory()) {
      fs::create_directories(dest);
      modes.emplace_back(dest, it->symlink_status().permissions());
    } else if (it->is_regular_file()) {
      std::error_code ec;
      fs::create_hard_link(it->path(), dest, ec);
      if (ec) fs::copy_file(it->path(), dest);
    }
  }
  return modes;
}

}  // namespace

void TargetLock::acquire(const std::filesystem::path& file, const std::string& what) {
  for (;;) {
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(fmt::format("{}: cannot create its lock '{}': {}", what, file.string(), std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      char holder[24] = {};
      const ssize_t n = ::pread(fd, holder, sizeof holder - 1, 0);
      fmt::print(stderr, "nsbench: {}: being written by process {}; waiting for it to finish\n", what,
                 n > 0 ? std::string(holder, static_cast<std::size_t>(n)) : std::string("?"));
      int locked;
      while ((locked = ::flock(fd, LOCK_EX)) != 0 && errno == EINTR) {
      }
      if (locked != 0) {
        const int err = errno;
        ::close(fd);
        throw InputError(fmt::format("{}: cannot lock '{}': {}", what, file.string(), std::strerror(err)));
      }
    }
    // The holder removes the file at its end: a lock on a file no longer at `file` guards nothing.
    struct stat held {}, named {};
    if (::fstat(fd, &held) == 0 && ::stat(file.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      const std::string pid = std::to_string(static_cast<long>(::getpid()));
      // The pid only names the holder in a waiting line: a failed write costs nothing else.
      std::ignore = ::ftruncate(fd, 0) == 0 && ::pwrite(fd, pid.data(), pid.size(), 0) > 0;
      file_ = file;
      fd_ = fd;
      return;
    }
    ::close(fd);
  }
}

TargetLock::~TargetLock() {
  if (fd_ < 0) return;
  ::unlink(file_.c_str());  // before the unlock: a waiter then finds its file gone and takes the new one
  ::close(fd_);
}

ReportDirectory::ReportDirectory(const std::filesystem::path& target, const std::string& option) : option_(option) {
  namespace fs = std::filesystem;
  ensure_directory(target, option);
  check_own_output(target, option);
  std::error_code ec;
  target_ = fs::canonical(target);  // "out/", ".": a name and a parent to stage beside
  const fs::path parent = target_.parent_path();
  const std::string name = target_.filename().string();
  if (name.empty()) throw InputError(fmt::format("{} '{}': the root directory cannot be a report", option, target.string()));
  lock_.acquire(parent / fmt::format(".{}.lock", name), fmt::format("{} '{}'", option, target_.string()));
  for (const auto& e : fs::directory_iterator(parent, ec)) {  // earlier runs' leftovers
    const std::string entry = e.path().filename().string();
    const long pid = entry.rfind("." + name + ".staging.", 0) == 0 ? temporary_owner(entry, ".staging.") : 0;
    if (pid > 0 && process_gone(pid)) fs::remove_all(e.path(), ec);
  }
  staging_ = parent / fmt::format(".{}.staging.{}", name, static_cast<long>(::getpid()));
  fs::remove_all(staging_, ec);
  try {
    fs::create_directory(staging_);
    modes_ = link_tree(target_, staging_);
    ensure_directory(staging_, option);
    mark_output(staging_);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(staging_, ec);
    throw InputError(fmt::format("{} '{}': cannot stage the report beside it: {}", option, target_.string(), e.what()));
  } catch (const InputError&) {  // no destructor runs for a constructor that throws
    fs::remove_all(staging_, ec);
    throw;
  }
}

ReportDirectory::~ReportDirectory() {
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);  // after commit(): the old report
}

void ReportDirectory::remove_on_signals() const {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  if (pthread_sigmask(SIG_BLOCK, &signals, nullptr) != 0) return;  // the signals then act as before
  std::thread([signals, staging = staging_, lock = lock_.file()] {
    int taken = 0;
    if (sigwait(&signals, &taken) != 0) return;
    std::error_code ignored;
    std::filesystem::remove_all(staging, ignored);
    std::filesystem::remove(lock, ignored);
    std::signal(taken, SIG_DFL);  // the process ends by the signal, as it would have
    pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
    std::raise(taken);
  }).detach();
}

void ReportDirectory::commit() {
  if (committed_) return;
  for (const auto& [dir, mode] : modes_) std::filesystem::permissions(dir, mode);  // set last: a 0500 one still took files
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
