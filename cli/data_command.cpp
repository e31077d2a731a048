// palprig data: the shipped files palprig finds by name (cli/data_files.hpp).
//   palprig data list [KIND]   every kind and its names, or one kind's names with their files
//   palprig data dir           the folder the shipped files are taken from, and every place searched
#include <iomanip>
#include <iostream>
#include <memory>
#include <system_error>

#include "cli/commands.hpp"
#include "cli/data_files.hpp"

using namespace palprig;

namespace {

// One place: a heading and every kind with its names, or (KIND given) one name and file a line.
void list_place(const cli::DataPlace& place, const std::string& kind) {
  if (!kind.empty()) {
    for (const std::string& name : cli::data_names(place.dir, kind)) {
      const auto json = place.dir / kind / (name + ".json");
      std::cout << std::left << std::setw(32) << name << " "
                << (std::filesystem::exists(json) ? json : place.dir / kind / (name + ".csv")).string() << "\n";
    }
    return;
  }
  std::cout << "palprig data: " << place.dir.string() << " (" << place.origin << ")\n";
  for (const std::string& k : cli::data_kinds()) {
    const std::vector<std::string> names = cli::data_names(place.dir, k);
    if (names.empty() && place.origin == "$PALPRIG_DATA_DIR") continue;  // a lab's folder holds what it holds
    std::cout << "  " << k << ":";
    for (const std::string& name : names) std::cout << " " << name;
    std::cout << "\n";
  }
}

}  // namespace

void register_data_command(CLI::App& app) {
  CLI::App* data = app.add_subcommand(
      "data", "The shipped protocols, scenes, rig files, calibrations, traces and tracking examples, found by name");
  data->require_subcommand(1);
  auto kind = std::make_shared<std::string>();
  CLI::App* list = data->add_subcommand(
      "list", "Every kind of shipped file and the names options take (--protocol NAME, --scene NAME, ...)");
  list->add_option("kind", *kind, "Only this kind, one name and its file per line")
      ->check(CLI::IsMember(cli::data_kinds()));
  list->callback([kind]() {
    // The lab's own folder ($PALPRIG_DATA_DIR) first when there is one, as the search goes, then
    // the shipped files.
    for (const cli::DataPlace& p : cli::data_places()) {
      std::error_code ec;
      if (p.origin == "$PALPRIG_DATA_DIR" && std::filesystem::is_directory(p.dir, ec)) list_place(p, *kind);
    }
    list_place(cli::shipped_data_place(), *kind);
  });
  CLI::App* dir = data->add_subcommand("dir", "The folder the shipped files are taken from, and every place searched");
  dir->callback([]() {
    std::cout << cli::shipped_data_place().dir.string() << "\n";
    for (const cli::DataPlace& p : cli::data_places())
      std::cerr << "  searched: " << p.dir.string() << " (" << p.origin << ")\n";
  });
}
