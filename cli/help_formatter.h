// The help text of every command: CLI11's layout, with the option column as a person reads it.
// A flag that sets false is shown by its name alone (`--no-hairs`, not `--no-hairs{false}`); a
// checked type by what it takes (`FILE`, `INT in [1 - 64]`, not `TEXT:FILE` or
// `INT:INT in [1 - 64]`); and the options an option needs or excludes in its description, where
// they no longer push the description out of its column.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace hirsute::cli {

class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* option, bool isPositional) const override {
    std::string name = CLI::Formatter::make_option_name(option, isPositional);
    // "--no-hairs{false}": the value a flag sets, which the name already says.
    for (std::size_t open = name.find('{'); open != std::string::npos; open = name.find('{')) {
      const std::size_t close = name.find('}', open);
      if (close == std::string::npos) break;
      name.erase(open, close - open + 1);
    }
    return name;
  }

  std::string make_option_opts(const CLI::Option* option) const override {
    if (!option->get_option_text().empty()) return " " + option->get_option_text();
    std::string text;
    if (option->get_type_size() != 0) {
      std::string type = option->get_type_name();
      // "TEXT:FILE", "INT:INT in [0 - 64]": the checked type after the colon says it all.
      if (const std::size_t colon = type.find(':'); colon != std::string::npos)
        type = type.substr(colon + 1);
      if (!type.empty()) text += " " + type;
      if (!option->get_default_str().empty()) text += "=" + option->get_default_str();
      if (option->get_expected_max() == CLI::detail::expected_max_vector_size)
        text += " ...";
      else if (option->get_expected_min() > 1)
        text += " x " + std::to_string(option->get_expected());
      if (option->get_required()) text += " REQUIRED";
    }
    return text;
  }

  std::string make_option_desc(const CLI::Option* option) const override {
    std::string description = option->get_description();
    const auto names = [](const std::set<CLI::Option*>& options) {
      std::string list;
      for (const CLI::Option* other : options) {
        if (other->get_group().empty()) continue;  // a hidden alias is not named
        if (!list.empty()) list += ", ";
        list += other->get_name();
      }
      return list;
    };
    if (const std::string needed = names(option->get_needs()); !needed.empty())
      description += " (with " + needed + ")";
    if (const std::string excluded = names(option->get_excludes()); !excluded.empty())
      description += " (not with " + excluded + ")";
    return description;
  }
};

}  // namespace hirsute::cli
