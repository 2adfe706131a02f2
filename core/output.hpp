#pragma once
// Output files are written whole or not at all: content goes to a temporary file in the
// target directory, which is then renamed over the target (atomic on POSIX).
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace nsb {

void write_file_atomic(const std::filesystem::path& path, const std::string& content);

// FNV-1a 64 of the bytes as 16 hex digits: identifies content (not a security hash).
std::string fnv1a64(std::string_view bytes);

// The whole of a regular file, at most `max_bytes` of it; throws InputError naming `what`
// and the file when it cannot be read, is not a regular file (/dev/zero, a FIFO) or is larger.
std::string read_file_bounded(const std::filesystem::path& path, std::size_t max_bytes, const std::string& what);

// Creates the directory (and parents) and checks that a file can be created in it; throws
// InputError naming `option` when either fails (a read-only --out is reported before any
// computation).
void ensure_directory(const std::filesystem::path& dir, const std::string& option = "--out");

// How the suite recognises its own output: every output directory it writes (ReportDirectory,
// claim_output_directory) holds this file. The suite writes into a directory that is new,
// empty, or holds the marker and nothing but regular files and directories; anything else
// (a user's directory, a FIFO, a socket, a symbolic link) is refused before any work, since
// replacing a directory whole would delete or re-permission what the suite did not write.
inline constexpr const char* kOutputMarker = ".nsbench-output";

// Checks that `dir` is the suite's to write (kOutputMarker), creates it, checks that it takes
// files (ensure_directory) and marks it; throws InputError naming `option` otherwise.
void claim_output_directory(const std::filesystem::path& dir, const std::string& option);

// Removes what write_file_atomic leaves behind when its process is killed: hidden
// ".NAME.tmp.PID" files in `dir` whose process is gone.
void remove_stale_temporaries(const std::filesystem::path& dir);

// A report directory replaced whole (a directory the suite may write: kOutputMarker): its files are written into a staging sibling
// (".NAME.staging.PID", holding hard links to the directory's current files, so that a
// report of some studies keeps the others' files), then commit() swaps the two directories
// in one rename (renameat2 RENAME_EXCHANGE) and removes the old one. A reader sees the old
// report or the new one, never a mix; a process killed before commit() leaves the old
// report as it was (and a staging directory, removed by the next ReportDirectory of that
// target once its process is gone). Destroyed without commit(): the staging is removed.
// The directories keep their modes (a 1777 --out stays 1777); the staging holds the marker.
// Two writers of one target take turns: each holds a lock on ".NAME.lock" beside it from
// before staging to its end, so the second stages from the first's committed report (both
// studies stay listed) instead of both staging from the old one and the last commit dropping
// the other's files; the second says on stderr which process it waits for.
// The lock a ReportDirectory holds on its target: taken by acquire() (waiting for its holder),
// released and its file removed when destroyed.
class TargetLock {
 public:
  TargetLock() = default;
  ~TargetLock();
  TargetLock(const TargetLock&) = delete;
  TargetLock& operator=(const TargetLock&) = delete;
  // `what` names the target in the waiting line ("--out 'DIR'").
  void acquire(const std::filesystem::path& file, const std::string& what);
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

class ReportDirectory {
 public:
  // Errors name `option`, the command-line option that gave `target`.
  explicit ReportDirectory(const std::filesystem::path& target, const std::string& option = "--out");
  ~ReportDirectory();
  ReportDirectory(const ReportDirectory&) = delete;
  ReportDirectory& operator=(const ReportDirectory&) = delete;
  const std::filesystem::path& path() const { return staging_; }  // write here
  void commit();
  // From now on SIGINT and SIGTERM end the process after removing the staging and the lock's
  // file, which were left beside the target until the next run. Call it before the process
  // starts other threads: the signals are blocked in every thread and taken by one that waits
  // for them.
  void remove_on_signals() const;

 private:
  std::filesystem::path target_, staging_;
  std::string option_;
  TargetLock lock_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::perms>> modes_;  // of target_'s directories
  bool committed_ = false;
};

}  // namespace nsb
