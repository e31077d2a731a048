#pragma once
// Arguments the calibrate subcommands share: the channel list, the rig (default: the simulated
// one), simulated or real time, and whether --plot can be honoured in this build.
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
// --plot needs gui's chart drawing (Qt); a build without it refuses the option up front.
void check_plot_available(const std::string& dir);

}  // namespace palprig::cli
