#include "studies/driver.hpp"

#include <fmt/format.h>

#include <cmath>

#include <chrono>
#include <utility>

#include "core/output.hpp"
#include "core/parameters.hpp"
#include "studies/parallel.hpp"
#include "studies/report_index.hpp"

namespace nsb {

namespace fs = std::filesystem;

namespace {

// Every selected study's cases and, unless merging, the results of this shard's cases.
struct Pool {
  std::vector<std::vector<Json>> cases, results;
  std::vector<std::vector<std::size_t>> mine;  // per study, the indices of the cases run here
};

Pool run_pool(const std::vector<const StudyEntry*>& studies, const DriverOptions& o) {
  const StudyOptions options{o.full};
  Pool pool{std::vector<std::vector<Json>>(studies.size()), std::vector<std::vector<Json>>(studies.size()),
            std::vector<std::vector<std::size_t>>(studies.size())};
  std::vector<std::pair<std::size_t, std::size_t>> pending;  // (study, case)
  std::vector<std::string> locks;  // the process-wide lock each takes (parallel.hpp)
  std::vector<std::string> pooled;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    pool.cases[i] = study_cases(*studies[i], options);
    if (o.merge) continue;
    pool.results[i].resize(pool.cases[i].size());
    for (std::size_t k = 0; k < pool.cases[i].size(); ++k)
      if (!o.shard.count || static_cast<long>(k % static_cast<std::size_t>(o.shard.count)) == o.shard.index - 1) {
        pool.mine[i].push_back(k);
        pending.emplace_back(i, k);
        locks.push_back(case_lock(*studies[i], pool.cases[i][k]));
      }
    pooled.push_back(studies[i]->name);
  }
  const auto start = std::chrono::steady_clock::now();
  auto computed = parallel_map<Json>(pending.size(), [&](std::size_t j) {
    const auto [i, k] = pending[j];
    return run_study_case(*studies[i], pool.cases[i][k], options);
  }, fmt::format("{}", fmt::join(pooled, "+")), locks);
  for (std::size_t j = 0; j < pending.size(); ++j) pool.results[pending[j].first][pending[j].second] = std::move(computed[j]);
  if (!pending.empty())
    fmt::print(stderr, "{} cases of {} in {:.1f} s\n", pending.size(), fmt::join(pooled, ", "),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return pool;
}

void write_shard(const StudyEntry& s, const DriverOptions& o, const std::vector<Json>& cases, const std::vector<Json>& results,
                 const std::vector<std::size_t>& mine) {
  std::vector<Json> shard_results;
  for (std::size_t k : mine) shard_results.push_back(results[k]);
  ensure_directory(fs::path(o.out) / "shards");
  write_file_atomic(shard_path(o.out, s.name, o.shard.index, o.shard.count),
                    shard_text(s.name, o.full, o.shard, cases, mine, shard_results));
  fmt::print(stderr, "study {}: shard {}/{} ({} of {} cases) written\n", s.name, o.shard.index, o.shard.count, mine.size(),
             cases.size());
}

void add_verified(VerifyResult& total, const std::vector<Table>& tables, const DriverOptions& o) {
  for (const auto& t : tables) {
    auto r = verify_table(t, fs::path(o.verify_dir), o.tolerance);
    total.cells_compared += r.cells_compared;
    for (auto& d : r.differences) total.differences.push_back(std::move(d));
  }
}

int print_verified(const VerifyResult& verified, const DriverOptions& o) {
  for (const auto& d : verified.differences) fmt::print("{}\n", d);
  fmt::print("verify against {}: {} cells compared (reals to rtol {:g}, atol {:g}; integers, statuses and text "
             "exactly; CPU-time columns skipped), {} differences\n",
             o.verify_dir, verified.cells_compared, o.tolerance.rtol, o.tolerance.atol, verified.differences.size());
  return verified.differences.empty() ? 0 : 1;
}

std::function<std::string(const Json&, const Json&)> check_of(const StudyEntry& s, const DriverOptions& o) {
  if (!o.result_check) return {};
  return [&s, &o](const Json& c, const Json& r) { return o.result_check(s, c, r); };
}

}  // namespace

void check_driver_options(const DriverOptions& o) {
  for (const auto& [option, value] : {std::pair{"--rtol", o.tolerance.rtol}, {"--atol", o.tolerance.atol}})
    if (!(value >= 0.0 && std::isfinite(value))) throw InputError(fmt::format("{} {}: must be a finite number >= 0", option, value));
  if (o.shard.count && o.merge) throw InputError("--shard and --merge: give one of them");
  const bool verify = !o.verify_dir.empty();
  if (verify && (o.shard.count || o.merge)) throw InputError("--verify: recomputes whole studies, without --shard or --merge");
  if (verify && !fs::is_directory(o.verify_dir)) throw InputError(fmt::format("--verify '{}': no such directory", o.verify_dir));
}

int drive_studies(const std::vector<const StudyEntry*>& studies, const DriverOptions& o) {
  check_driver_options(o);
  study_jobs();  // a bad NSBENCH_JOBS is reported before any work
  const bool verify = !o.verify_dir.empty();
  if (!verify) claim_output_directory(o.out, "--out");  // a directory the suite did not write is refused
  std::optional<ReportDirectory> report;  // staged and swapped in whole
  std::optional<ReportIndex> index;
  if (!verify && !o.shard.count) {
    report.emplace(o.out);
    report->remove_on_signals();  // before the pool's threads
    std::vector<std::string> rewritten;
    for (const auto* s : studies) rewritten.push_back(s->name);
    index.emplace(o.full, report->path(), rewritten);
  }
  Pool pool = run_pool(studies, o);
  VerifyResult verified;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    const StudyEntry& s = *studies[i];
    if (o.shard.count) {
      write_shard(s, o, pool.cases[i], pool.results[i], pool.mine[i]);
      continue;
    }
    const std::vector<Json> results =
        o.merge ? merge_shards(s.name, pool.cases[i], o.out, o.full, check_of(s, o)) : std::move(pool.results[i]);
    const auto tables = study_tables(s, pool.cases[i], results, StudyOptions{o.full});
    if (verify) {
      add_verified(verified, tables, o);
      continue;
    }
    index->add_study(s, tables);
    fmt::print(stderr, "study {}: {} cases, {} tables\n", s.name, pool.cases[i].size(), tables.size());
  }
  if (verify) return print_verified(verified, o);
  if (report) {
    if (o.before_commit) o.before_commit(report->path());
    index->write();
    report->commit();
  }
  return 0;
}

}  // namespace nsb
