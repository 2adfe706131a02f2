// nsbench-study: runs the registered studies and writes their tables.
//
//   nsbench-study list
//   nsbench-study all|NAME... --out DIR [--full]
//
// Writes DIR/<table>.csv, .md, .tex for every table, DIR/figures.json (the figures for
// scripts/figures.py to draw) and DIR/index.md linking them all.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>

#include "core/build_info.hpp"
#include "core/output.hpp"
#include "core/parameters.hpp"
#include "studies/study.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nsbench-study: run studies and write citable tables"};
  std::vector<std::string> names;
  std::string out = "reports";
  bool full = false;
  app.add_option("studies", names, "'list', 'all', or study names")->required();
  app.add_option("--out", out, "output directory (default reports)");
  app.add_flag("--full", full, "run the long sweeps");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  const auto& registry = nsb::study_registry();
  if (names == std::vector<std::string>{"list"}) {
    for (const auto& s : registry) fmt::print("{:<12} {}\n", s.name, s.description);
    return 0;
  }
  std::vector<const nsb::StudyEntry*> selected;
  for (const auto& n : names) {
    bool found = false;
    for (const auto& s : registry)
      if (n == "all" || s.name == n) {
        selected.push_back(&s);
        found = true;
      }
    if (!found) {
      std::vector<std::string> valid{"all"};
      for (const auto& s : registry) valid.push_back(s.name);
      fmt::print(stderr, "nsbench-study: error: unknown study '{}' (valid: {})\n", n, fmt::join(valid, ", "));
      return 2;
    }
  }
  try {
    nsb::ensure_directory(out);
    std::string index = "# nsbench reports\n\n";
    const auto& b = nsb::build_info();
    index += fmt::format("Revision `{}`, {} build, {}.\n\n", b.git_revision, b.build_type, b.compiler);
    std::vector<nsb::Table> all_tables;
    for (const auto* s : selected) {
      const auto start = std::chrono::steady_clock::now();
      fmt::print(stderr, "study {}: running\n", s->name);
      const auto tables = s->run(nsb::StudyOptions{full});
      index += fmt::format("## {}\n\n{}\n\n", s->name, s->description);
      for (const auto& t : tables) {
        nsb::write_table(t, out);
        index += fmt::format("- [{}]({}.md) ([csv]({}.csv), [tex]({}.tex))\n", t.title, t.id, t.id, t.id);
        for (const auto& f : t.figures)
          index += fmt::format("\n  ![{}](figures/{}.png) ([pdf](figures/{}.pdf))\n", f.title, f.id, f.id);
        all_tables.push_back(t);
      }
      index += "\n";
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print(stderr, "study {}: {} tables in {:.1f} s\n", s->name, tables.size(), secs);
    }
    nsb::write_file_atomic(std::filesystem::path(out) / "figures.json", nsb::figures_to_json(all_tables));
    nsb::write_file_atomic(std::filesystem::path(out) / "index.md", index);
  } catch (const nsb::InputError& e) {
    fmt::print(stderr, "nsbench-study: error: {}\n", e.what());
    return 2;
  }
  return 0;
}
