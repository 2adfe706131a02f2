#include "studies/verify.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

namespace nsb {

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '#') {  // comment line: metadata and build stamp
      const std::size_t end = text.find('\n', i);
      i = end == std::string::npos ? text.size() : end + 1;
      continue;
    }
    std::vector<std::string> record;
    std::string field;
    bool quoted = false;
    for (; i < text.size(); ++i) {
      const char c = text[i];
      if (quoted) {
        if (c != '"') {
          field += c;
        } else if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        record.push_back(std::move(field));
        field.clear();
      } else if (c == '\n') {
        break;
      } else {
        field += c;
      }
    }
    ++i;  // past the newline
    record.push_back(std::move(field));
    records.push_back(std::move(record));
  }
  return records;
}

namespace {

// A CSV cell of a real column as a number: "n/a" is NaN; text that is no number, nullopt.
std::optional<double> real_of(const std::string& s) {
  if (s == "n/a") return std::numeric_limits<double>::quiet_NaN();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size()) return std::nullopt;
  return v;
}

bool reals_agree(double a, double b, const VerifyTolerance& tol) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  if (std::isinf(a) || std::isinf(b)) return a == b;
  return std::abs(a - b) <= tol.atol + tol.rtol * std::max(std::abs(a), std::abs(b));
}

}  // namespace

VerifyResult verify_table(const Table& computed, const std::string& report_csv, const VerifyTolerance& tol) {
  VerifyResult result;
  const auto fresh = parse_csv(to_csv(computed));
  const auto report = parse_csv(report_csv);
  const std::string file = computed.id + ".csv";
  const auto differ = [&](std::string line) { result.differences.push_back(file + ": " + std::move(line)); };
  if (report.empty() || report[0] != fresh[0]) {
    differ(fmt::format("header differs: report '{}', now '{}'", report.empty() ? "" : fmt::format("{}", fmt::join(report[0], ",")),
                       fmt::join(fresh[0], ",")));
    return result;
  }
  if (report.size() != fresh.size())
    differ(fmt::format("{} rows in the report, {} now", report.size() - 1, fresh.size() - 1));
  // Rows are paired in order. With as many rows on both sides, row r with row r; otherwise
  // (a sweep made shorter or longer) each row computed now with the next report row of the
  // same leading labels (the text cells before its first number), the report rows passed over
  // listed as not computed now.
  const auto label = [&](const std::vector<std::string>& row, std::size_t r) {
    std::vector<std::string> lead;
    const auto& cells = computed.rows[r - 1];
    for (std::size_t c = 0; c < std::min(row.size(), cells.size()) && std::holds_alternative<std::string>(cells[c]); ++c)
      lead.push_back(row[c]);
    return fmt::format("{}", fmt::join(lead, ", "));
  };
  const auto passed_over = [&](std::size_t first, std::size_t last, std::size_t r) {
    if (first < last)
      differ(fmt::format("report rows {}-{} ({} .. {}) not computed now", first, last - 1, label(report[first], r),
                         label(report[last - 1], r)));
  };
  std::size_t p = 1;  // the next report row
  for (std::size_t r = 1; r < fresh.size(); ++r) {
    if (p >= report.size()) {
      differ(fmt::format("row {} ({}) computed now, not in the report", r, label(fresh[r], r)));
      continue;
    }
    std::size_t q = p;
    if (report.size() != fresh.size()) {
      const std::string key = label(fresh[r], r);
      while (q < report.size() && !(report[q].size() == fresh[r].size() && label(report[q], r) == key)) ++q;
      if (q == report.size()) {
        differ(fmt::format("row {} ({}) computed now, not in the report", r, key));
        continue;
      }
    }
    passed_over(p, q, r);
    p = q + 1;
    if (report[q].size() != fresh[r].size()) {
      differ(fmt::format("row {}: {} cells in the report, {} now", r, report[q].size(), fresh[r].size()));
      continue;
    }
    for (std::size_t c = 0; c < fresh[r].size(); ++c) {
      const Column& column = computed.columns[c];
      if (column.timing) continue;
      ++result.cells_compared;
      const std::string &was = report[q][c], &now = fresh[r][c];
      if (was == now) continue;
      bool agree = false;
      std::string relative;
      if (std::holds_alternative<double>(computed.rows[r - 1][c])) {
        const auto a = real_of(was), b = real_of(now);
        agree = a && b && reals_agree(*a, *b, tol);
        if (a && b && std::isfinite(*a) && std::isfinite(*b))
          relative = fmt::format(" (relative difference {:.2e})", std::abs(*a - *b) / std::max(std::abs(*a), std::abs(*b)));
      }
      if (!agree)
        differ(fmt::format("row {} ({}), column '{}': report {}, now {}{}", r, fmt::join(fresh[r].begin(), fresh[r].begin() + std::min<std::size_t>(2, fresh[r].size()), ", "),
                           header_text(column), was, now, relative));
    }
  }
  if (fresh.size() > 1) passed_over(p, report.size(), fresh.size() - 1);
  return result;
}

VerifyResult verify_table(const Table& computed, const std::filesystem::path& report_dir, const VerifyTolerance& tol) {
  const auto path = report_dir / (computed.id + ".csv");
  std::ifstream in(path);
  if (!in) {
    VerifyResult missing;
    missing.differences.push_back(fmt::format("{}: not in the report ('{}' cannot be read)", computed.id + ".csv", path.string()));
    return missing;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return verify_table(computed, text.str(), tol);
}

}  // namespace nsb
