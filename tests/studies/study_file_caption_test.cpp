// Study files: a declared table's caption says the grid that was run: each ${COLUMN} in it the
// values of that case-table column over the runs the table shows (the default grid's, or
// --full's), a caption's other braces kept as written; an unknown column or a "${" without its
// "}" refused in one line naming the file, line and key.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "studies/study.hpp"
#include "studies/study_file.hpp"

namespace {

// The Signorini bar refined N = 10, 20 (--full: 10, 20, 40) at 0.5 and 0.9 of its stable step, to
// t = 0.3 (a few steps each), by CD-Lagrange and CD-penalty: the grid as the study bar sets it.
const std::string kCaptionBar = R"TOML([study]
title = "t"
t_end = 0.3
cpu_repeats = 0

[[problem]]
name = "signorini-bar"
label = "bar"
parameters = { mass = "lumped" }
grid = { N = [10, 20] }
refine = "N"
stable_steps = [0.5, 0.9]
default_only = true

[[problem]]
name = "signorini-bar"
label = "bar, --full"
parameters = { mass = "lumped" }
grid = { N = [10, 20, 40] }
refine = "N"
stable_steps = [0.5, 0.9]
full_only = true

[[integrator]]
name = "cd-lagrange"

[[integrator]]
name = "cd-penalty"

[[measure]]
kind = "energy"
norm = "max"
label = "E max err"

[[table]]
id = "runs"
title = "runs"
caption = "Energy E_{k+1/2} over N = ${parameter N} at alpha = ${stable steps}."
columns = ["integrator", "parameter N", "stable steps", "E max err"]

[[table]]
id = "some"
title = "some"
caption = "${integrator} at alpha = ${stable steps}, N = ${parameter N}"
problems = ["bar, N = 20", "bar, --full, N = 20", "bar, --full, N = 40"]
where = { "stable steps" = 0.9 }
integrators = ["cd-penalty"]
columns = ["integrator", "parameter N", "stable steps", "E max err"]

[[table]]
id = "plain"
title = "plain"
caption = "No placeholder: {N} and $N stay."
columns = ["integrator", "parameter N"]
)TOML";

std::vector<nsb::Table> caption_study_tables(const std::string& text, bool full) {
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(text, "f.toml", false));
  const auto cases = nsb::study_cases(entry, {full});
  std::vector<nsb::Json> results;
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {full}));
  return nsb::study_tables(entry, cases, results, {full});
}

std::string caption_of(const std::vector<nsb::Table>& tables, const std::string& id) {
  const auto t = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& u) { return u.id == id; });
  REQUIRE(t != tables.end());
  return t->caption;
}

std::string caption_error(const std::string& caption) {
  std::string text = kCaptionBar;
  const std::string was = "caption = \"No placeholder: {N} and $N stay.\"";
  text.replace(text.find(was), was.size(), "caption = \"" + caption + "\"");
  try {
    (void)nsb::parse_study_text(text, "f.toml", false);
  } catch (const nsb::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("study file: a caption's ${COLUMN} is that column's values over the table's runs, the default grid's or --full's",
          "[studies][study_file]") {
  const auto normal = caption_study_tables(kCaptionBar, false);
  CHECK(caption_of(normal, "runs") == "Energy E_{k+1/2} over N = 10, 20 at alpha = 0.5, 0.9.");
  CHECK(caption_of(normal, "some") == "cd-penalty at alpha = 0.9, N = 20");
  CHECK(caption_of(normal, "plain") == "No placeholder: {N} and $N stay.");
  const auto full = caption_study_tables(kCaptionBar, true);
  CHECK(caption_of(full, "runs") == "Energy E_{k+1/2} over N = 10, 20, 40 at alpha = 0.5, 0.9.");
  CHECK(caption_of(full, "some") == "cd-penalty at alpha = 0.9, N = 20, 40");
  CHECK(caption_of(full, "plain") == "No placeholder: {N} and $N stay.");
}

TEST_CASE("study file: a caption's placeholder that names no case-table column, or has no }, refused in one line",
          "[studies][study_file][bad-input]") {
  using Catch::Matchers::Contains;
  using Catch::Matchers::StartsWith;
  const std::string at = "f.toml:53: table[2].caption: ";
  CHECK_THAT(caption_error("over N = ${parameter Nn}"),
             StartsWith(at + "'${parameter Nn}' names no case-table column (nearest: parameter N); valid: ${COLUMN} with COLUMN one of "
                             "problem, integrator, dt, ") &&
                 Contains("parameter N"));
  CHECK_THAT(caption_error("${}"), StartsWith(at + "'${}' names no case-table column"));
  CHECK(caption_error("over N = ${parameter N") == at + "'${parameter N' has no closing }; valid: ${COLUMN} with COLUMN a case-table column");
  const std::string one = caption_error("${x}");
  CHECK(std::count(one.begin(), one.end(), '\n') == 0);
}
