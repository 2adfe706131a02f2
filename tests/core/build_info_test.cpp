// The build stamp (core/build_info.cmake, issue 57 item 5): a binary built from a tree whose
// code differs from HEAD is "-dirty" and lists what differed (the docs and prose not), which a
// run then says (nsbench run's note on stderr, summary.json's build.dirty_files).
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/build_info.hpp"
#include "tests/app/run_cli.hpp"
#include "tests/support/files.hpp"

namespace fs = std::filesystem;

namespace {

// build_info.cpp as the build writes it for the git tree `dir`.
std::string stamp_of(const fs::path& dir) {
  const fs::path out = dir / "build_info.cpp";
  const std::string script = std::string(NSBENCH_SOURCE_DIR) + "/core/build_info.cmake";
  REQUIRE(std::system(fmt::format("cmake -DSOURCE_DIR='{}' -DVERSION=1 -DOUTPUT='{}' -DBUILD_TYPE=Release -DCOMPILER=gcc -DSANITIZE=OFF "
                                  "-DNATIVE=OFF -P '{}' >/dev/null", dir.string(), out.string(), script).c_str()) == 0);
  return nsb::test::read_text(out);
}

}  // namespace

TEST_CASE("build info: a dirty tree's stamp lists the code files that differ, not the prose", "[core][build_info]") {
  const nsb::test::TempDir dir("build_info", true);
  const fs::path repo = dir.path / "repo";
  fs::create_directories(repo / "docs");
  for (const char* f : {"a.cpp", "b.hpp", "notes.md", "docs/guide.txt"}) std::ofstream(repo / f) << "one\n";
  const std::string git = fmt::format("git -C '{}' -c user.name=t -c user.email=t@t ", repo.string());
  REQUIRE(std::system((git + "init -q && " + git + "add . && " + git + "commit -q -m one").c_str()) == 0);
  CHECK_THAT(stamp_of(repo), Catch::Contains("\", \"Release\", \"gcc\", \"\"}") && !Catch::Contains("-dirty"));
  for (const char* f : {"a.cpp", "notes.md", "docs/guide.txt"}) std::ofstream(repo / f, std::ios::app) << "two\n";
  CHECK_THAT(stamp_of(repo), Catch::Contains("-dirty\", \"Release\", \"gcc\", \"a.cpp\"}"));
  std::ofstream(repo / "b.hpp", std::ios::app) << "two\n";
  CHECK_THAT(stamp_of(repo), Catch::Contains("-dirty\", \"Release\", \"gcc\", \"a.cpp, b.hpp\"}"));
}

TEST_CASE("build info: a run from a dirty build says what differed; a clean build says nothing", "[core][build_info][app]") {
  const nsb::BuildInfo& b = nsb::build_info();
  const bool dirty = b.git_revision.size() > 6 && b.git_revision.substr(b.git_revision.size() - 6) == "-dirty";
  CHECK(dirty == !b.dirty_files.empty());
  const nsb::test::TempDir dir("build_info_run");
  const auto r = nsb::test::run_command(nsb::test::nsbench_command(
      fmt::format("run --problem bouncing-mass --integrator cd-lagrange --dt 0.1 --t-end 0.2 --out '{}'", dir.path.string())));
  REQUIRE(r.code == 0);
  const std::string note = fmt::format("nsbench: note: built from revision {} with changes to {}\n", b.git_revision, b.dirty_files);
  const std::string summary = nsb::test::read_text(dir.path / "summary.json");
  if (dirty) {
    CHECK_THAT(r.output, Catch::Contains(note));
    CHECK_THAT(summary, Catch::Contains("\"dirty_files\": \"" + b.dirty_files + "\""));
  } else {
    CHECK(r.output.find("nsbench: note: built from") == std::string::npos);
    CHECK(summary.find("dirty_files") == std::string::npos);
  }
}
