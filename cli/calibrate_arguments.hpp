#pragma once
// Arguments the calibrate subcommands share: the channel list, the rig (default: the simulated
// one) and simulated or real time.
#include <array>
#include <string>

#include "formats/rig_file.hpp"
#include "models/channel_pressures.hpp"

namespace palprig::cli {

// "1,3" -> channels 1 and 3 on; throws InputError naming --channels.
std::array<bool, kFingerCount> parse_channels(const std::string& text);
std::string channels_text(const std::array<bool, kFingerCount>& on);
RigConfig load_rig(const std::string& path);
// Simulated backends run on simulated time unless asked otherwise; hardware always in real time.
bool use_realtime(const RigConfig& rig, bool realtime_flag, bool fast_flag);

}  // namespace palprig::cli
