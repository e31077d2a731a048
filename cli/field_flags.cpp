#include "cli/field_flags.hpp"

#include <array>
#include <utility>

namespace palprig::cli {

namespace {

constexpr std::string_view kCommandLine = "command line";

// field (as libraries name it) -> flag (as the user types it)
constexpr std::array<std::pair<std::string_view, std::string_view>, 42> kFieldFlags{{
    {"participant", "--participant"},
    {"resume", "--resume"},
    {"seed", "--seed"},
    {"store", "--db"},
    {"input", "--input"},
    {"duration_s", "--duration-s"},
    {"replay", "--replay"},
    {"realtime", "--realtime"},
    {"plot_dir", "--plot"},
    {"out_dir", "--out"},
    {"group_by", "--by"},
    {"groups", "--groups"},
    {"from_kPa", "--from-kPa"},
    {"to_kPa", "--to-kPa"},
    {"step_kPa", "--step-kPa"},
    {"repeats", "--repeats"},
    {"excitation", "--excitation"},
    {"random_levels", "--random-levels"},
    {"sine_cycles", "--sine-cycles"},
    {"sine_steps_per_cycle", "--sine-steps"},
    {"ramp_kPa_per_s", "--ramp-kPa-per-s"},
    {"rest_s", "--rest-s"},
    {"record_hz", "--record-hz"},
    {"rate_hz", "--rate-hz"},
    {"channels", "--channels"},
    {"max_threshold_kPa", "--max-threshold-kPa"},
    {"loss_scale_kPa", "--robust-scale-kPa"},
    {"regulator_tolerance_kPa", "--regulator-tolerance-kPa"},
    {"rig_id", "--rig-id"},
    {"hysteresis_from", "--hysteresis-from"},
    {"operator_count", "--operators"},
    {"fixed_thresholds", "--no-refine"},
    {"cpu", "--cpu"},
    {"speed", "--speed"},
    {"journal", "--journal"},  // palprig experiment run: the bench journal of a postgresql:// store
    {"from", "--from"},        // palprig store sync/copy
    {"to", "--to"},
    {"study", "--study"},
    {"level", "--level"},
    {"response", "--response"},
    {"n", "--n"},
    {"telemetry", "--telemetry"},  // palprig experiment run: the session's tick recording
}};

}  // namespace

std::string_view flag_of_field(std::string_view field) noexcept {
  for (const auto& [name, flag] : kFieldFlags) {
    if (name == field) return flag;
  }
  return field;
}

std::string with_flags(const std::string& text) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t open = text.find('`', at);
    const std::size_t close = open == std::string::npos ? std::string::npos : text.find('`', open + 1);
    if (close == std::string::npos) {
      out.append(text, at, std::string::npos);
      break;
    }
    out.append(text, at, open - at);
    out.append(flag_of_field(std::string_view(text).substr(open + 1, close - open - 1)));
    at = close + 1;
  }
  return out;
}

std::string input_error_line(const InputError& e) {
  // Options are named three ways: (field, value given, expected), ("command line", field,
  // expected), and `field` quoted anywhere. A file's own fields (a rig file's "channels") are
  // never flags and stay as they are.
  std::string file(flag_of_field(e.file())), where = e.where();
  if (e.file() == kCommandLine) where = std::string(flag_of_field(where));
  return with_flags(file) + ": " + with_flags(where) + ": " + with_flags(e.expected());
}

}  // namespace palprig::cli
