#pragma once
// Checking a report against a recomputation (nsbench-study STUDY --verify DIR): each table
// computed now is compared with DIR/<id>.csv cell by cell.
//   - the header row must be the same;
//   - the rows must be as many; when they are not (a sweep made shorter or longer), each row
//     computed now is compared with the next report row of the same leading labels (its text
//     cells before the first number), and the report rows passed over are listed;
//   - integers, statuses and other text: equal;
//   - reals: |a - b| <= atol + rtol max(|a|, |b|); "n/a" (NaN, empty) and "inf" only equal
//     themselves;
//   - columns declared timing (CPU times and what is derived from them, e.g. the rankings'
//     winners) are skipped, as are the metadata and build-stamp comment lines.
#include <filesystem>
#include <string>
#include <vector>

#include "studies/table.hpp"

namespace nsb {

struct VerifyTolerance {
  double rtol = 1e-9;
  double atol = 0.0;
};

struct VerifyResult {
  std::size_t cells_compared = 0;
  std::vector<std::string> differences;  // one line each: table, row, column, both values
};

// Compares `computed` with the CSV text of a report of the same table (as to_csv writes it).
VerifyResult verify_table(const Table& computed, const std::string& report_csv, const VerifyTolerance& tolerance);
// The same against DIR/<id>.csv; a missing or unreadable file is one difference.
VerifyResult verify_table(const Table& computed, const std::filesystem::path& report_dir,
                          const VerifyTolerance& tolerance);

// Records of a CSV text (RFC 4180 quoting), comment lines (#) left out.
std::vector<std::vector<std::string>> parse_csv(const std::string& text);

}  // namespace nsb
