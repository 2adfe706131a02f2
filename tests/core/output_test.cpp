// Reports replaced whole (issue 20): the staging directory, its swap, leftovers of killed
// processes.
#include "core/output.hpp"

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/parameters.hpp"
#include "tests/support/files.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> names(const fs::path& dir) {
  std::vector<std::string> v;
  for (const auto& e : fs::directory_iterator(dir)) v.push_back(e.path().filename().string());
  std::sort(v.begin(), v.end());
  return v;
}

// Marks `dir` as the suite's own output, as a ReportDirectory leaves it.
void mark_own(const fs::path& dir) { std::ofstream(dir / nsb::kOutputMarker) << "nsbench output\n"; }

fs::perms mode(const fs::path& p) { return fs::symlink_status(p).permissions(); }

// Above any pid_max (2^22): no such process.
constexpr const char* kDeadPid = "4194305";

}  // namespace

TEST_CASE("report directory: staged beside, swapped in whole, others' files kept", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "report";
  fs::create_directories(out / "figures");
  mark_own(out);
  std::ofstream(out / "other_study.md") << "kept";
  std::ofstream(out / "table.md") << "old";
  std::ofstream(out / "figures" / "f.png") << "png";
  {
    nsb::ReportDirectory report(out);
    nsb::write_file_atomic(report.path() / "table.md", "new");
    nsb::write_file_atomic(report.path() / "index.md", "index");
    // Before the swap nothing of the new report is visible, and the old files are untouched
    // (the staging holds links to them, replaced, not written through).
    CHECK(nsb::test::read_text(out / "table.md") == "old");
    CHECK_FALSE(fs::exists(out / "index.md"));
    report.commit();
    CHECK(nsb::test::read_text(out / "table.md") == "new");
    CHECK(nsb::test::read_text(out / "index.md") == "index");
    CHECK(nsb::test::read_text(out / "other_study.md") == "kept");
    CHECK(nsb::test::read_text(out / "figures" / "f.png") == "png");
  }
  CHECK(names(tmp.path) == std::vector<std::string>{"report"});  // the old report removed
}

TEST_CASE("report directory: abandoned without commit, the old report stays; a killed run's staging goes", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "report";
  fs::create_directories(out);
  mark_own(out);
  std::ofstream(out / "table.md") << "old";
  fs::create_directories(tmp.path / (std::string(".report.staging.") + kDeadPid));
  {
    nsb::ReportDirectory report(out);
    nsb::write_file_atomic(report.path() / "table.md", "half");
    // an exception, a signal: no commit
  }
  CHECK(nsb::test::read_text(out / "table.md") == "old");
  CHECK(names(tmp.path) == std::vector<std::string>{"report"});
}

TEST_CASE("report directory: only our own staging of a dead process goes; a live one's and other names stay", "[core][output]") {
  // A killed study (SIGKILL) leaves ".report.staging.PID"; the next ReportDirectory of
  // "report" removes it once kill(PID, 0) says ESRCH. The parent's (alive), another
  // report's, a name without the leading dot and a non-numeric pid are not ours to remove.
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "report";
  const std::string dead = std::string(".report.staging.") + kDeadPid, live = ".report.staging." + std::to_string(::getppid());
  const std::vector<std::string> kept = {std::string(".other.staging.") + kDeadPid, live,
                                         std::string(".report.staging.") + kDeadPid + "x", std::string("report.staging.") + kDeadPid};
  for (const std::string& d : kept) fs::create_directories(tmp.path / d);
  fs::create_directories(tmp.path / dead / "sub");
  std::ofstream(tmp.path / dead / "sub" / "table.md") << "half";
  { nsb::ReportDirectory report(out); }
  std::vector<std::string> expected = kept;
  expected.push_back("report");
  std::sort(expected.begin(), expected.end());
  CHECK(names(tmp.path) == expected);
}

TEST_CASE("report directory: a directory the suite did not write is refused whole, untouched", "[core][output]") {
  // Issue 30, finding 1: a 1777 --out with a 0700 subdirectory, a FIFO and a dangling
  // symlink came back 0755 with the FIFO and the symlink deleted, exit 0.
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "d";
  fs::create_directories(out / "private");
  fs::permissions(out, fs::perms(01777));
  fs::permissions(out / "private", fs::perms(0700));
  REQUIRE(::mkfifo((out / "fifo").c_str(), 0600) == 0);
  fs::create_symlink("nowhere", out / "dg");
  CHECK_THROWS_WITH(nsb::ReportDirectory(out), Catch::StartsWith("--out '" + out.string() + "': not empty and not an nsbench output"));
  CHECK_THROWS_WITH(nsb::claim_output_directory(out, "--fields"), Catch::StartsWith("--fields '" + out.string() + "': not empty"));
  CHECK(mode(out) == fs::perms(01777));
  CHECK(mode(out / "private") == fs::perms(0700));
  CHECK(fs::is_fifo(fs::symlink_status(out / "fifo")));
  CHECK(fs::is_symlink(fs::symlink_status(out / "dg")));
  CHECK(names(tmp.path) == std::vector<std::string>{"d"});  // no staging left
}

TEST_CASE("report directory: in the suite's own output, an entry it never writes is refused by name", "[core][output]") {
  // A symlink to an absolute file made the staging write through "staging/../file"; a FIFO,
  // a socket or a symlink would be deleted by the swap. The suite writes none of them.
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "report", outside = tmp.path / "outside.md";
  std::ofstream(outside) << "someone else's";
  const auto refused = [&](const fs::path& entry, const std::string& kind) {
    fs::create_directories(out / "figures");
    mark_own(out);
    std::ofstream(out / "table.md") << "old";
    CHECK_THROWS_WITH(nsb::ReportDirectory(out), "--out '" + out.string() + "': holds '" + entry.string() + "', " + kind +
                                                     " the suite never writes; its output directory is replaced whole, so "
                                                     "it would be deleted; move it away or choose another directory");
    CHECK(fs::exists(fs::symlink_status(entry)));
    CHECK(names(tmp.path) == std::vector<std::string>{"outside.md", "report"});
    fs::remove_all(out);
  };
  fs::create_directories(out / "figures");
  fs::create_symlink(outside, out / "figures" / "outside.md");
  refused(out / "figures" / "outside.md", "a symbolic link");
  CHECK(!fs::exists(tmp.path / "figures" / "outside.md"));
  fs::create_directories(out);
  REQUIRE(::mkfifo((out / "fifo").c_str(), 0600) == 0);
  refused(out / "fifo", "a FIFO");
  fs::create_directories(out);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string sock = (out / "sock").string();
  REQUIRE(sock.size() < sizeof addr.sun_path);
  std::copy(sock.begin(), sock.end(), addr.sun_path);
  REQUIRE(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0);
  ::close(fd);
  refused(out / "sock", "a socket");
}

TEST_CASE("report directory: new, empty and own directories are written, their modes kept", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path fresh = tmp.path / "new" / "report", empty = tmp.path / "empty";
  fs::create_directories(empty);
  fs::permissions(empty, fs::perms(01777));
  for (const auto& out : {fresh, empty}) {
    nsb::ReportDirectory report(out);
    fs::create_directories(report.path() / "private");
    nsb::write_file_atomic(report.path() / "private" / "table.md", "new");
    report.commit();
  }
  CHECK(mode(empty) == fs::perms(01777));
  CHECK(fs::exists(fresh / nsb::kOutputMarker));
  CHECK(fs::exists(empty / nsb::kOutputMarker));
  // The suite's own, re-permissioned by its user: written again, the modes stay.
  fs::permissions(empty / "private", fs::perms(0700));
  {
    nsb::ReportDirectory report(empty);
    nsb::write_file_atomic(report.path() / "private" / "table.md", "newer");
    report.commit();
  }
  CHECK(mode(empty) == fs::perms(01777));
  CHECK(mode(empty / "private") == fs::perms(0700));
  CHECK(nsb::test::read_text(empty / "private" / "table.md") == "newer");
  // A shard run claims its --out the same way (the merge later replaces it whole).
  const fs::path shards = tmp.path / "shards";
  nsb::claim_output_directory(shards, "--out");
  CHECK(fs::exists(shards / nsb::kOutputMarker));
  nsb::claim_output_directory(shards, "--out");
}

TEST_CASE("report directory: two writers of one target take turns, neither report is lost (issue 56)", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "report";
  std::thread second;
  {
    nsb::ReportDirectory first(out);
    nsb::write_file_atomic(first.path() / "first.md", "1");
    // Started while the first holds the target: it waits, then stages from the first's
    // committed report (before the lock both staged from the old one, the last commit won).
    second = std::thread([&] {
      nsb::ReportDirectory report(out);
      nsb::write_file_atomic(report.path() / "second.md", "2");
      report.commit();
    });
    first.commit();
  }
  second.join();
  CHECK(nsb::test::read_text(out / "first.md") == "1");
  CHECK(nsb::test::read_text(out / "second.md") == "2");
  CHECK(names(tmp.path) == std::vector<std::string>{"report"});  // the lock's file removed with it
}

TEST_CASE("report directory: SIGTERM removes the staging and the lock before the process ends by it (issue 56)", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path out = tmp.path / "report", ready = tmp.path / "ready";
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {  // a study's process: its report staged, then stopped by a signal
    nsb::ReportDirectory report(out);
    report.remove_on_signals();
    std::ofstream(ready) << "ready";
    for (;;) ::pause();
  }
  while (!fs::exists(ready)) ::usleep(1000);  // waits for the child, whatever it takes
  REQUIRE(::kill(child, SIGTERM) == 0);
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK(names(tmp.path) == std::vector<std::string>{"ready", "report"});  // no .report.staging.PID, no .report.lock
}

TEST_CASE("a file that cannot be written whole says why (issue 56: a full disk said only 'cannot write')", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const fs::path file = tmp.path / "table.csv";
  const pid_t child = ::fork();  // a file-size limit stands in for a full disk, in a process of its own
  REQUIRE(child >= 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{1000, 1000};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      nsb::write_file_atomic(file, std::string(100000, 'x'));
    } catch (const nsb::InputError& e) {
      ::_exit(std::string(e.what()) == "cannot write '" + file.string() + "': " + std::strerror(EFBIG) ? 0 : 1);
    }
    ::_exit(2);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(names(tmp.path).empty());  // written whole or not at all
}

TEST_CASE("stale temporaries of dead processes are removed, live ones kept", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  const std::string mine = ".series.csv.tmp." + std::to_string(::getpid());
  std::ofstream(tmp.path / (std::string(".series.csv.tmp.") + kDeadPid)) << "x";
  std::ofstream(tmp.path / mine) << "x";
  std::ofstream(tmp.path / "series.csv") << "x";
  nsb::remove_stale_temporaries(tmp.path);
  CHECK(names(tmp.path) == std::vector<std::string>{mine, "series.csv"});
}

TEST_CASE("an --out that takes no files is an input error before any work", "[core][output]") {
  CHECK_THROWS_WITH(nsb::ensure_directory("/proc/self"), Catch::StartsWith("--out '/proc/self': cannot write files there"));
  CHECK_THROWS_AS(nsb::ReportDirectory("/proc/self"), nsb::InputError);
}

TEST_CASE("bounded reads: a regular file in full, else one clear error", "[core][output]") {
  const nsb::test::TempDir tmp("output_test", true);
  std::ofstream(tmp.path / "a.toml") << "12345";
  CHECK(nsb::read_file_bounded(tmp.path / "a.toml", 5, "study file") == "12345");
  CHECK_THROWS_WITH(nsb::read_file_bounded(tmp.path / "a.toml", 4, "study file"),
                    Catch::EndsWith("a.toml': 5 bytes, larger than the limit of 4 bytes"));
  CHECK_THROWS_WITH(nsb::read_file_bounded("/dev/zero", 4, "study file"), "study file '/dev/zero': not a regular file");
  CHECK_THROWS_WITH(nsb::read_file_bounded(tmp.path / "none", 4, "study file"), Catch::EndsWith("none': no such file"));
  CHECK(nsb::fnv1a64("") == "cbf29ce484222325");
  CHECK(nsb::fnv1a64("a") == "af63dc4c8601ec8c");
}
