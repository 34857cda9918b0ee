// The options the subcommands share: name lists, values checked against the name tables,
// --precision, the printing of a report's files.
#include <algorithm>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "oblique/protocol/names.h"

namespace oblique::cli {

int print_paths(const std::optional<std::vector<std::filesystem::path>>& paths) {
  if (!paths) return 2;
  for (const auto& path : *paths) std::cout << path.string() << "\n";
  return 0;
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

CLI::Validator one_of(const std::vector<std::string>& names, const std::string& what) {
  return CLI::Validator(
      [names, what](std::string& value) {
        if (std::find(names.begin(), names.end(), value) != names.end()) return std::string();
        return oblique::protocol::unknown_name(what, value, names);
      },
      "{" + oblique::protocol::name_list(names) + "}");
}

CLI::Option* add_precision_option(CLI::App* app, std::string& precision, const std::string& what,
                                  std::vector<oblique::protocol::Precision> allowed) {
  std::vector<std::string> names;
  for (const oblique::protocol::Precision p : allowed)
    names.emplace_back(oblique::protocol::precision_name(p));
  return app->add_option("--precision", precision, what)
      ->check(one_of(names, "precision"))
      ->capture_default_str();
}

}  // namespace oblique::cli
