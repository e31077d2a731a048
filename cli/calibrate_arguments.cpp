#include "cli/calibrate_arguments.hpp"

#include <sstream>

#include "cli/commands.hpp"
#include "core/input_error.hpp"

namespace palprig::cli {

std::array<bool, kFingerCount> parse_channels(const std::string& text) {
  std::array<bool, kFingerCount> on{};
  std::istringstream in(text);
  std::string item;
  bool any = false;
  while (std::getline(in, item, ',')) {
    if (item.size() != 1 || item[0] < '1' || item[0] > char('0' + kFingerCount))
      throw InputError("--channels", text,
                       "channel numbers 1.." + std::to_string(kFingerCount) + " separated by commas");
    on[std::size_t(item[0] - '1')] = true;
    any = true;
  }
  if (!any) throw InputError("--channels", text, "at least one channel");
  return on;
}

std::string channels_text(const std::array<bool, kFingerCount>& on) {
  std::string s;
  for (std::size_t c = 0; c < kFingerCount; ++c)
    if (on[c]) s += (s.empty() ? "" : ",") + std::to_string(c + 1);
  return s;
}

RigConfig load_rig(const std::string& path) {
  return path.empty() ? load_rig_file(cli::data_dir() / "rigs" / "simulated.json") : load_rig_file(path);
}

bool use_realtime(const RigConfig& rig, bool realtime_flag, bool fast_flag) {
  if (fast_flag && rig.backend != "simulated")
    throw InputError("--fast", rig.backend, "a simulated rig (hardware runs in real time)");
  return realtime_flag || rig.backend != "simulated";
}

}  // namespace palprig::cli
