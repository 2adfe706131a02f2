#include "studies/report_index.hpp"

#include <fmt/format.h>

#include "core/build_info.hpp"
#include "core/environment.hpp"
#include "core/plugin.hpp"

namespace nsb {

ReportIndex::ReportIndex(bool full) {
  const auto& b = build_info();
  const std::string plugged = plugins_stamp();
  header_ = fmt::format("# nsbench reports\n\nnsbench {}, revision `{}`, {} build, {}{}{}.\n\n", b.version, b.git_revision, b.build_type, b.compiler,
                        full ? ", full sweeps" : "", plugged.empty() ? "" : ", plugins " + plugged);
}

void ReportIndex::add_study(const StudyEntry& s, const std::vector<Table>& tables, const std::filesystem::path& dir) {
  studies_ += fmt::format("## {}\n\n{}\n\n", s.name, s.description);
  for (const auto& t : tables) {
    write_table(t, dir);
    if (t.csv_only)
      studies_ += fmt::format("- {} ([csv]({}.csv))\n", t.title, t.id);
    else
      studies_ += fmt::format("- [{}]({}.md) ([csv]({}.csv), [tex]({}.tex))\n", t.title, t.id, t.id, t.id);
    for (const auto& f : t.figures)
      studies_ += fmt::format("\n  ![{}](figures/{}.png) ([pdf](figures/{}.pdf)){}\n", f.title, f.id, f.id,
                              f.caption.empty() ? "" : "\n\n  " + f.caption);
    if (t.lead) lead_ += fmt::format("### [{}]({}.md) ({})\n\n{}\n\n{}\n", t.title, t.id, s.name, t.caption, markdown_grid(t));
    if (t.headline)
      headline_ += fmt::format("### [{}]({}.md) ({})\n\n{}\n\n{}\n", t.title, t.id, s.name, t.caption, markdown_grid(t));
  }
  studies_ += "\n";
}

std::string ReportIndex::text() const {
  const auto& env = environment();
  const auto& b = build_info();
  std::string index = header_;
  if (!lead_.empty()) index += "## Claims\n\nThe verdicts are computed from measured figures (the rules are in the caption).\n\n" + lead_ + "\n";
  if (!headline_.empty())
    index += "## Headline ranking\n\nComputed from the studies' work-precision data (the rules are in each "
             "caption).\n\n" + headline_ + "\n";
  return index + studies_ +
         fmt::format("---\n\n<sub>{}, {} cores; {}; {} build, {}, nsbench {} revision {}. Rerun: `{}`</sub>\n", env.cpu,
                     env.cores, env.libraries, b.build_type, b.compiler, b.version, b.git_revision, command_line());
}

}  // namespace nsb
