#pragma once
// Command-line conventions shared by nsbench and nsbench-study (CLI11):
// - every option takes one value per occurrence, so an option may stand before or after the
//   subcommand or the study names ("--plugin F bouncing" leaves "bouncing" to the studies;
//   CLI11's vector options otherwise swallow the words that follow);
// - an option given an empty value ("--shard ''") is refused, not taken as not given;
// - an option that no command declares fails first, naming the nearest declared one (CLI11
//   would report a missing required option instead: "--t-ned 1" gave "--t-end is required").
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "core/parameters.hpp"

namespace nsb::cli {

inline void collect_option_names(const CLI::App& app, std::vector<std::string>& names) {
  for (const CLI::Option* o : app.get_options()) {
    for (const auto& l : o->get_lnames()) names.push_back("--" + l);
    for (const auto& s : o->get_snames()) names.push_back("-" + s);
  }
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    collect_option_names(*sub, names);
}

// Call once every option is declared.
inline void one_value_each(CLI::App& app) {
  for (CLI::Option* o : app.get_options())
    if (o->nonpositional()) o->allow_extra_args(false);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) one_value_each(*sub);
}

// Throws InputError naming the first option given an empty value: "--fields ''" would
// otherwise read as the option not given (no field output, no sharding) without a word.
inline void refuse_empty_values(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options())
    if (o->nonpositional() && o->get_expected_min() > 0 && o->count() > 0)
      for (const auto& value : o->results())
        if (value.empty()) throw InputError(fmt::format("{} '': an empty value; valid: {}", o->get_name(), o->get_description()));
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->parsed()) refuse_empty_values(*sub);
}

// Throws InputError on the first word of argv that is written as an option ("--x" or
// "--x=v") and is declared by no command of `app`.
inline void check_option_names(const CLI::App& app, int argc, char** argv) {
  std::vector<std::string> names;
  collect_option_names(app, names);
  for (int k = 1; k < argc; ++k) {
    const std::string word = argv[k];
    if (word == "--") return;  // the rest are values
    if (word.rfind("--", 0) != 0) continue;
    const std::string name = word.substr(0, word.find('='));
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InputError(fmt::format("{}: unknown option (nearest: {}; see --help)", name, nearest_name(name, names)));
  }
}

}  // namespace nsb::cli
