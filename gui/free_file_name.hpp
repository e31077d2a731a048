#pragma once
// The file name a recording or a default output takes so that nothing earlier is replaced:
// the wanted path when nothing is there, else the first free NAME-2.EXT, NAME-3.EXT, ... beside
// it (live telemetry, calibration sweeps and their fitted files).
#include <filesystem>

namespace palprig::gui {

std::filesystem::path first_free_file(const std::filesystem::path& wanted);

}  // namespace palprig::gui
