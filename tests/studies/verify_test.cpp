#include <catch2/catch.hpp>
#include <cmath>

#include "studies/verify.hpp"

namespace {

nsb::Table table() {
  nsb::Table t;
  t.id = "t";
  t.metadata = {{"study", "test"}};
  t.columns = {{"name", "", "", ""}, {"err", "m", "", ""}, {"n", "", "", ""}, {"CPU", "s", "", "", true}};
  t.add_row({std::string("a, \"quoted\""), 1.5e-3, 7L, 0.25});
  t.add_row({std::string("b"), std::numeric_limits<double>::quiet_NaN(), 8L, 0.5});
  return t;
}

// The report of table() with cell (row, col) of the CSV replaced by `text`.
std::string edited(std::size_t row, std::size_t col, const std::string& text) {
  nsb::Table t = table();
  t.rows[row][col] = text;
  return nsb::to_csv(t);
}

}  // namespace

TEST_CASE("verify: CSV records with quotes and comments read back", "[studies][verify]") {
  const auto records = nsb::parse_csv(nsb::to_csv(table()));
  REQUIRE(records.size() == 3);  // header and two rows; the # lines left out
  CHECK(records[0] == std::vector<std::string>{"name", "err [m]", "n", "CPU [s]"});
  CHECK(records[1] == std::vector<std::string>{"a, \"quoted\"", "0.0015", "7", "0.25"});
  CHECK(records[2][1] == "n/a");
}

TEST_CASE("verify: reals to the tolerance, integers and text exactly, CPU columns skipped", "[studies][verify]") {
  const nsb::Table now = table();
  const nsb::VerifyTolerance tol{1e-9, 0.0};
  const auto same = nsb::verify_table(now, nsb::to_csv(now), tol);
  CHECK(same.differences.empty());
  CHECK(same.cells_compared == 6);  // 2 rows x 3 columns: CPU skipped

  CHECK(nsb::verify_table(now, edited(0, 3, "99"), tol).differences.empty());         // CPU time
  CHECK(nsb::verify_table(now, edited(0, 1, "0.0015000000001"), tol).differences.empty());  // 7e-11 relative
  const auto real = nsb::verify_table(now, edited(0, 1, "0.0016"), tol).differences;
  REQUIRE(real.size() == 1);
  CHECK_THAT(real[0], Catch::Contains("t.csv: row 1") && Catch::Contains("column 'err [m]': report 0.0016, now 0.0015") &&
                          Catch::Contains("relative difference 6.25e-02"));
  CHECK(nsb::verify_table(now, edited(0, 1, "0.0016"), {0.1, 0.0}).differences.empty());
  CHECK(nsb::verify_table(now, edited(0, 1, "0.0016"), {0.0, 2e-4}).differences.empty());
  CHECK(nsb::verify_table(now, edited(1, 1, "0"), tol).differences.size() == 1);     // n/a is no number
  CHECK(nsb::verify_table(now, edited(0, 1, "diverged"), tol).differences.size() == 1);
  CHECK(nsb::verify_table(now, edited(0, 2, "7.0000000001"), {0.1, 0.0}).differences.size() == 1);  // integer
  CHECK(nsb::verify_table(now, edited(1, 0, "c"), {0.1, 0.0}).differences.size() == 1);
}

TEST_CASE("verify: another header, missing rows or a missing file are differences", "[studies][verify]") {
  const nsb::Table now = table();
  nsb::Table other = now;
  other.columns[1].unit = "mm";
  CHECK_THAT(nsb::verify_table(now, nsb::to_csv(other), {}).differences.at(0), Catch::Contains("header differs"));
  nsb::Table shorter = now;
  shorter.rows.pop_back();
  CHECK_THAT(nsb::verify_table(now, nsb::to_csv(shorter), {}).differences.at(0),
             Catch::Contains("1 rows in the report, 2 now"));
  CHECK_THAT(nsb::verify_table(now, std::filesystem::path("/nonexistent-nsbench-dir"), {}).differences.at(0),
             Catch::Contains("t.csv: not in the report"));
}

TEST_CASE("verify: rows removed from a sweep are listed, the others compared with their own", "[studies][verify]") {
  const nsb::Table now = table();
  nsb::Table longer = now;  // the report of a longer sweep: a row between a and b, one after b
  longer.rows.insert(longer.rows.begin() + 1, std::vector<nsb::Cell>{std::string("x"), 2.0, 9L, 0.1});
  longer.add_row({std::string("y"), 3.0, 10L, 0.1});
  const auto removed = nsb::verify_table(now, nsb::to_csv(longer), {0.0, 0.0});
  REQUIRE(removed.differences.size() == 3);
  CHECK_THAT(removed.differences[0], Catch::Contains("4 rows in the report, 2 now"));
  CHECK_THAT(removed.differences[1], Catch::Contains("report rows 2-2 (x .. x) not computed now"));
  CHECK_THAT(removed.differences[2], Catch::Contains("report rows 4-4 (y .. y) not computed now"));
  CHECK(removed.cells_compared == 6);  // a and b, each with its own report row

  // A row of a new label is listed, not compared with another.
  nsb::Table added = now;
  added.add_row({std::string("z"), 1.0, 1L, 0.1});
  const auto extra = nsb::verify_table(added, nsb::to_csv(now), {0.0, 0.0}).differences;
  REQUIRE(extra.size() == 2);
  CHECK_THAT(extra[1], Catch::Contains("row 3 (z) computed now, not in the report"));

  // A kept row that changed is still a difference of its own.
  longer.rows[2][1] = 1.0;  // b's err (n/a now)
  const auto changed = nsb::verify_table(now, nsb::to_csv(longer), {0.0, 0.0}).differences;
  REQUIRE(changed.size() == 4);
  CHECK_THAT(changed[2], Catch::Contains("row 2 (b") && Catch::Contains("report 1, now n/a"));
}
