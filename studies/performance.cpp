#include "studies/performance.hpp"

#include <fmt/format.h>

#include <fstream>
#include <map>
#include <optional>
#include <string>

#include "core/parameters.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

struct Measured {
  std::string family, name, limit;
  double ns = 0.0;                  // time per step (per call)
  std::optional<double> limit_ns;   // the limit's time per step
  std::optional<double> peak_rss_mb;  // a whole run's peak resident set (the memory benchmark)
  std::optional<double> bytes_per_unit;  // compulsory memory traffic of one pass, per unit (counter bytes_per_element)
  long threads = 0, units = 0;
};

double to_ns(double value, const std::string& unit, const std::filesystem::path& file) {
  if (unit == "ns") return value;
  if (unit == "us") return value * 1e3;
  if (unit == "ms") return value * 1e6;
  if (unit == "s") return value * 1e9;
  throw InputError(fmt::format("{}: time_unit '{}' (valid: ns, us, ms, s)", file.string(), unit));
}

std::string family_of(const Json& context) {
  std::string exe = context.value("executable", std::string("?"));
  exe = std::filesystem::path(exe).filename().string();
  const std::string prefix = "nsbench-bench-";
  return exe.rfind(prefix, 0) == 0 ? exe.substr(prefix.size()) : exe;
}

// The benchmarks of one file: the "min" aggregate of each when there is one, else its
// least repetition.
std::vector<Measured> read_file(const std::filesystem::path& file, std::vector<std::pair<std::string, std::string>>& machine) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot read the file", file.string()));
  Json j;
  try {
    j = Json::parse(in);
  } catch (const Json::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", file.string(), e.what()));
  }
  if (!j.is_object() || !j.contains("benchmarks") || !j["benchmarks"].is_array() || !j.contains("context"))
    throw InputError(fmt::format("{}: not Google Benchmark output (no 'context' and 'benchmarks' array; write it "
                                 "with --benchmark_out=FILE --benchmark_out_format=json)", file.string()));
  const Json& ctx = j["context"];
  const std::string family = family_of(ctx);
  if (machine.empty()) {
    std::string caches;
    for (const Json& c : ctx.value("caches", Json::array()))
      caches += fmt::format("{}L{} {} {} KiB{}", caches.empty() ? "" : ", ", c.value("level", 0),
                            c.value("type", std::string("?")), c.value("size", 0L) / 1024,
                            c.value("num_sharing", 1) > 1 ? fmt::format(" (shared by {})", c.value("num_sharing", 1)) : "");
    machine = {{"benchmark_host", ctx.value("host_name", std::string("?"))},
               {"benchmark_cpus", fmt::format("{} at {} MHz", ctx.value("num_cpus", 0), ctx.value("mhz_per_cpu", 0))},
               {"benchmark_caches", caches.empty() ? "?" : caches},
               {"benchmark_date", ctx.value("date", std::string("?"))}};
  }
  std::vector<Measured> rows;
  std::map<std::string, std::size_t> index;  // run name -> row
  std::map<std::string, bool> from_min;      // that row is the min aggregate
  try {
    for (const Json& b : j["benchmarks"]) {
      const std::string run_type = b.value("run_type", std::string("iteration"));
      const bool is_min = run_type == "aggregate" && b.value("aggregate_name", std::string()) == "min";
      if (run_type == "aggregate" && !is_min) continue;
      std::string name = b.at("run_name").get<std::string>();
      if (const auto p = name.rfind("/real_time"); p != std::string::npos && p + 10 == name.size()) name.resize(p);
      if (name.rfind("BM_", 0) == 0) name.erase(0, 3);
      Measured m;
      m.family = family;
      m.name = name;
      m.ns = to_ns(b.at("real_time").get<double>(), b.at("time_unit").get<std::string>(), file);
      if (b.contains("limit_ns")) m.limit_ns = b["limit_ns"].get<double>();
      if (b.contains("peak_rss_mb")) m.peak_rss_mb = b["peak_rss_mb"].get<double>();
      if (b.contains("bytes_per_element")) m.bytes_per_unit = b["bytes_per_element"].get<double>();
      if (b.contains("run_threads")) m.threads = std::lround(b["run_threads"].get<double>());
      if (b.contains("units")) m.units = std::lround(b["units"].get<double>());
      const std::string label = b.value("label", std::string());
      if (label.rfind("limit: ", 0) == 0) m.limit = label.substr(7);
      const auto it = index.find(name);
      if (it == index.end()) {
        index[name] = rows.size();
        from_min[name] = is_min;
        rows.push_back(m);
      } else if (is_min || (!from_min[name] && m.ns < rows[it->second].ns)) {
        rows[it->second] = m;
        from_min[name] = from_min[name] || is_min;
      }
    }
  } catch (const Json::exception& e) {
    throw InputError(fmt::format("{}: a benchmark entry lacks a field ({})", file.string(), e.what()));
  }
  return rows;
}

}  // namespace

Table performance_table(const std::vector<std::filesystem::path>& benchmark_files) {
  if (benchmark_files.empty()) throw InputError("performance: give at least one benchmark JSON file");
  std::vector<Measured> all;
  std::vector<std::pair<std::string, std::string>> machine;
  for (const auto& f : benchmark_files)
    for (auto& m : read_file(f, machine)) all.push_back(std::move(m));

  Table t;
  t.id = "performance";
  t.title = "Performance: each step against its limit";
  t.caption =
      "Time per step (least over the repetitions) beside the limit measured in the same process on the same size: "
      "the STREAM triad over N+1 doubles for the bar's explicit steps (at least 3.5 triads per step is the "
      "bandwidth floor of their three passes, studies/benchmarks/bar_step.cpp; at N = 1e6 the triad's 24 MB still fit "
      "in the last-level cache and the step's 88 MB do not, at 1e7 both stream from memory), the element force's flops at the "
      "build's peak multiply-add rate (the 2D block's and the hex8 bar's), the bare force evaluation for the block's "
      "and the hex8 bar's CD-Lagrange steps, for moving contacts the same step with constant contact rows (the rocking "
      "block with its rows frozen, the two blocks with small sliding: issue 32's limit is a ratio of 1.3), the bare "
      "CHOLMOD solve (and factorisation) of the same matrix for the implicit schemes. ratio = step / limit. "
      "speed-up: against the same benchmark on one thread. peak RSS: the memory benchmark's `nsbench run` of the "
      "bouncing mass, one row per length (its time the whole run's, units its steps): flat in the length, the "
      "series streamed to disk (studies/benchmarks/memory.cpp).";
  t.columns = {{"family", "", "", "benchmark binary nsbench-bench-<family>"},
               {"benchmark", "", "", ""},
               {"threads", "", "", ""},
               {"units", "", "", "dofs or elements"},
               {"time per step", "us", "{:.4g}", "", true},
               {"time per unit", "ns", "{:.3g}", "", true},
               {"limit", "", "", ""},
               {"limit per step", "us", "{:.4g}", "", true},
               {"ratio", "", "{:.2f}", "step / limit", true},
               {"speed-up", "", "{:.2f}", "one thread's time / this", true},
               {"peak RSS", "MB", "{:.1f}", "the run's peak resident set (memory benchmark)", true},
               {"bytes per unit", "B", "{:.4g}", "compulsory traffic of one F_int pass per element (the hex8 bar)", true}};
  for (const auto& m : all) {
    std::optional<double> speed_up;
    if (m.threads > 1)
      for (const auto& one : all)
        if (one.threads == 1 && one.family == m.family && one.name == m.name) speed_up = one.ns / m.ns;
    const auto cell = [](std::optional<double> x) { return x ? Cell{*x} : Cell{}; };
    t.add_row({m.family, m.name, m.threads ? Cell{m.threads} : Cell{}, m.units ? Cell{m.units} : Cell{}, m.ns * 1e-3,
               m.units ? Cell{m.ns / static_cast<double>(m.units)} : Cell{}, m.limit.empty() ? Cell{} : Cell{m.limit},
               m.limit_ns ? Cell{*m.limit_ns * 1e-3} : Cell{}, m.limit_ns ? Cell{m.ns / *m.limit_ns} : Cell{},
               cell(speed_up), cell(m.peak_rss_mb), cell(m.bytes_per_unit)});
  }
  t.metadata = machine;
  std::string files;
  for (const auto& f : benchmark_files) {
    if (!files.empty()) files += ' ';
    files += f.filename().string();
  }
  t.metadata.emplace_back("benchmark_files", files);
  return t;
}

}  // namespace nsb
