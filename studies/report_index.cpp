#include "studies/report_index.hpp"

#include <fmt/format.h>

#include <map>
#include <regex>
#include <system_error>

#include "core/build_info.hpp"
#include "core/environment.hpp"
#include "core/json.hpp"
#include "core/output.hpp"
#include "core/plugin.hpp"
#include "studies/report_text.hpp"

namespace nsb {

namespace {

namespace fs = std::filesystem;

// A study's entries: its section (a line per table linking its files and figures), its lead
// tables (the claims) shown in full at the top with their figures, and its headline tables (the
// rankings) linked at the top. Tables are read in their own files: index.md stays a page a
// reader takes in at once (at most 20,000 characters for the default studies).
struct IndexPart {
  std::string section, lead, headline;
  Json figures = Json::array();  // its entries of figures.json (table.hpp, figures_to_json)
};

std::string table_line(const Table& t) {
  std::string line = t.csv_only ? fmt::format("- {} ([csv]({}.csv))", one_line(t.title), t.id)
                                : fmt::format("- [{}]({}.md) ([csv]({}.csv), [tex]({}.tex))", one_line(t.title), t.id, t.id, t.id);
  for (const auto& f : t.figures) line += fmt::format(", [figure](figures/{}.png)", f.id);
  return line + "\n";
}

IndexPart index_part(const StudyEntry& s, const std::vector<Table>& tables) {
  IndexPart part;  // one_line: a label's newline must not split the index's lines
  part.section = fmt::format("## {}\n\n{}\n\n", one_line(s.name), one_line(s.description));
  for (const auto& t : tables) {
    part.section += table_line(t);
    std::string pictures;  // a lead table's figures go with it to the top
    for (const auto& f : t.figures) pictures += fmt::format("\n![{}](figures/{}.png)\n\n{}\n", one_line(f.title), f.id, one_line(f.caption));
    if (t.lead)
      part.lead += fmt::format("### [{}]({}.md) ({})\n\n{}\n\n{}\n{}", one_line(t.title), t.id, one_line(s.name), one_line(t.caption),
                               markdown_grid(t), pictures);
    if (t.lead_figures && !t.lead) part.lead += pictures;
    if (t.headline) part.headline += fmt::format("- [{}]({}.md) ({})\n", one_line(t.title), t.id, one_line(s.name));
  }
  part.section += "\n";
  return part;
}

std::vector<IndexPart> index_parts(const fs::path& report) {
  std::map<std::string, IndexPart> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(report / ".index", ec)) {
    if (e.path().extension() != ".json") continue;
    const Json j = parse_json_bounded(read_file_bounded(e.path(), std::size_t{1} << 28, "index part"));
    const auto text = [&](const char* key) { return j.is_object() && j.contains(key) && j[key].is_string(); };
    if (!text("section") || !text("lead") || !text("headline")) {
      fmt::print(stderr, "nsbench-study: warning: the report's .index/{}: damaged, its study is left out of index.md\n",
                 e.path().filename().string());
      continue;
    }
    const bool has_figures = j.contains("figures") && j["figures"].is_array();
    if (!has_figures)  // written before the parts kept their figures
      fmt::print(stderr, "nsbench-study: warning: the report's .index/{}: no figures kept, its study's figures are left "
                 "out of figures.json (run the study again)\n", e.path().filename().string());
    found[e.path().stem().string()] = {j["section"], j["lead"], j["headline"], has_figures ? j["figures"] : Json::array()};
  }
  std::vector<IndexPart> parts;
  for (const auto& s : study_registry())
    if (const auto it = found.find(s.name); it != found.end()) {
      parts.push_back(it->second);
      found.erase(it);
    }
  for (const auto& [name, part] : found) parts.push_back(part);
  return parts;
}

// Refuses a table id the report reserves or a table or figure id that another study's entries
// (.index/OTHER.json: the tables its section links, its figures) hold.
void check_owned_ids(const fs::path& report, const StudyEntry& s, const std::vector<Table>& tables) {
  std::map<std::string, std::string> owner;  // "table ID" / "figure ID" -> the study holding it
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(report / ".index", ec)) {
    if (e.path().extension() != ".json" || e.path().stem() == s.name) continue;
    const Json j = Json::parse(read_file_bounded(e.path(), std::size_t{1} << 28, "index part"), nullptr, false);
    if (!j.is_object()) continue;  // damaged: index_parts says so
    if (j.contains("section") && j["section"].is_string()) {
      static const std::regex csv_link(R"(\[csv\]\(([^()\s]+)\.csv\))");
      const std::string& section = j["section"].get_ref<const std::string&>();
      for (std::sregex_iterator m(section.begin(), section.end(), csv_link), end; m != end; ++m)
        owner.emplace("table " + (*m)[1].str(), e.path().stem().string());
    }
    for (const auto& f : j.value("figures", Json::array()))
      if (f.is_object() && f.contains("id") && f["id"].is_string()) owner.emplace("figure " + f["id"].get<std::string>(), e.path().stem().string());
  }
  const auto refuse_taken = [&](const std::string& what) {
    if (const auto it = owner.find(what); it != owner.end())
      throw InputError(fmt::format("study {}: {} is study {}'s in this report (its files would be overwritten); valid: an id "
                                   "no other study of the report uses, or another --out",
                                   s.name, what, it->second));
  };
  for (const auto& t : tables) {
    if (t.id == "index")
      throw InputError(fmt::format("study {}: table id 'index' is the report's own (index.md); valid: another id", s.name));
    refuse_taken("table " + t.id);
    for (const auto& f : t.figures) refuse_taken("figure " + f.id);
  }
}

}  // namespace

ReportIndex::ReportIndex(bool full, std::filesystem::path report, const std::vector<std::string>& rewritten)
    : report_(std::move(report)) {
  std::error_code ec;
  for (const auto& name : rewritten) fs::remove(report_ / ".index" / (name + ".json"), ec);
  const auto& b = build_info();
  const std::string plugged = plugins_stamp();
  header_ = fmt::format("# nsbench reports\n\nnsbench {}, revision `{}`, {} build, {}{}{}.\n\n", b.version, b.git_revision,
                        b.build_type, b.compiler, full ? ", full sweeps" : "", plugged.empty() ? "" : ", plugins " + plugged);
}

std::string ReportIndex::add_study(const StudyEntry& s, const std::vector<Table>& tables) const {
  check_owned_ids(report_, s, tables);
  for (const auto& t : tables) write_table(t, report_);
  const IndexPart part = index_part(s, tables);
  ensure_directory(report_ / ".index");
  write_file_atomic(report_ / ".index" / (s.name + ".json"),
                    Json{{"section", part.section}, {"lead", part.lead}, {"headline", part.headline},
                         {"figures", Json::parse(figures_to_json(tables))}}.dump() + "\n");
  return part.section;
}

void ReportIndex::write() const {
  std::string studies, lead, headline;
  Json figures = Json::array();
  for (const auto& part : index_parts(report_)) {
    studies += part.section;
    lead += part.lead;
    headline += part.headline;
    figures.insert(figures.end(), part.figures.begin(), part.figures.end());
  }
  write_file_atomic(report_ / "figures.json", figures.dump(2) + "\n");
  std::string index = header_;
  if (!lead.empty()) index += "## Claims\n\nEach claim is tested under the conditions its source states (as claimed) and beyond them; every "
                              "verdict is computed from measured figures by the rule in the caption, and the tables behind each "
                              "verdict are linked below.\n\n" + lead + "\n";
  if (!headline.empty())
    index += "## Headline ranking\n\nThe cheapest integrator at each target error, computed from the studies' "
             "work-precision data (the rules are in each table's caption).\n\n" + headline + "\n";
  const auto& env = environment();
  const auto& b = build_info();
  write_file_atomic(report_ / "index.md",
                    index + studies +
                        fmt::format("---\n\n<sub>{}, {} cores; {}; {} build, {}, nsbench {} revision {}. This index last written by `{}`; "
                                    "each table's footer names the command and revision that wrote it.</sub>\n",
                                    env.cpu, env.cores, env.libraries, b.build_type, b.compiler, b.version, b.git_revision,
                                    command_line()));
}

}  // namespace nsb
