#include "cli/data_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <system_error>

namespace palprig::cli {

namespace {

namespace fs = std::filesystem;

// The option (long name) -> the kind of shipped file it takes.
const std::map<std::string, std::string>& option_kinds() {
  static const std::map<std::string, std::string> kinds{
      {"--protocol", "protocols"},
      {"--scene", "scenes"},
      {"--rig", "rigs"},
      {"--cal", "calibration"},
      {"--tracking", "tracking"},
      {"--curriculum", "curricula"},
      // palprig fe's inputs and calibrate fit's finite-element stress model (data/fe).
      {"--fingertip", "fe"},
      {"--tissue", "fe"},
      {"--actuator", "fe"},
      {"--stress-model", "fe"},
  };
  return kinds;
}

const char* const kTracePrefix = "trace:";

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// The folder of the running program (/proc/self/exe), empty when it cannot be read.
fs::path program_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

std::string not_found(const std::string& name, const std::string& kind) {
  std::string searched;
  for (const DataPlace& p : data_places()) searched += (searched.empty() ? "" : ", ") + (p.dir / kind).string();
  return "'" + name + "' is neither a file nor the name of a shipped file in " + searched + " (palprig data list " +
         kind + ")";
}

}  // namespace

std::vector<DataPlace> data_places() {
  std::vector<DataPlace> places;
  if (const char* env = std::getenv("PALPRIG_DATA_DIR"); env && *env) places.push_back({env, "$PALPRIG_DATA_DIR"});
  // The name palprig read before it was installable; kept so that older scripts still work.
  if (const char* env = std::getenv("PALPRIG_DATA"); env && *env) places.push_back({env, "$PALPRIG_DATA"});
  if (const fs::path bin = program_dir(); !bin.empty())
    places.push_back({(bin.parent_path() / "share" / "palprig").lexically_normal(), "installed"});
  places.push_back({PALPRIG_SOURCE_DATA_DIR, "source tree"});
  return places;
}

DataPlace shipped_data_place() {
  const std::vector<DataPlace> places = data_places();
  for (const DataPlace& p : places) {
    std::error_code ec;
    if (p.origin != "$PALPRIG_DATA_DIR" && fs::is_directory(p.dir, ec)) return p;
  }
  return places.back();
}

std::optional<fs::path> find_data_file(const std::string& given, const std::string& kind) {
  if (given.empty() || is_file(given) || given.find('/') != std::string::npos) return fs::path(given);
  for (const DataPlace& p : data_places()) {
    for (const char* ext : {"", ".json", ".csv"}) {
      const fs::path candidate = p.dir / kind / (given + ext);
      if (is_file(candidate)) return candidate;
    }
  }
  return std::nullopt;
}

const std::vector<std::string>& data_kinds() {
  static const std::vector<std::string> kinds{"protocols", "scenes",    "rigs",      "calibration", "traces",
                                              "tracking",  "waveforms", "curricula", "fe"};
  return kinds;
}

std::vector<std::string> data_names(const fs::path& dir, const std::string& kind) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir / kind, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if ((p.extension() == ".json" || p.extension() == ".csv") && is_file(p)) names.push_back(p.stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void resolve_data_names(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* opt : sub->get_options()) {
      const std::string name = opt->get_lnames().empty() ? std::string() : "--" + opt->get_lnames().front();
      if (const auto kind = option_kinds().find(name); kind != option_kinds().end()) {
        opt->transform(CLI::Validator(
            [k = kind->second](std::string& value) -> std::string {
              const auto found = find_data_file(value, k);
              // A bare name found nowhere is refused with the places searched; a file name (with
              // an extension) is left to its reader, which names the missing file as for a path.
              if (!found && value.find('.') == std::string::npos) return not_found(value, k);
              value = found ? found->string() : value;
              return {};
            },
            "", "data file"));
      } else if (name == "--input") {
        opt->transform(CLI::Validator(
            [](std::string& value) -> std::string {
              if (value.rfind(kTracePrefix, 0) != 0) return {};
              const std::string rest = value.substr(std::string(kTracePrefix).size());
              const auto found = find_data_file(rest, "traces");
              if (!found && rest.find('.') == std::string::npos) return not_found(rest, "traces");
              value = kTracePrefix + (found ? found->string() : rest);
              return {};
            },
            "", "data file"));
      }
    }
    resolve_data_names(*sub);
  }
}

}  // namespace palprig::cli
