#pragma once
// The rig file (JSON, versioned) describes one physical or simulated rig: which backend, its
// safety limits, the virtual hand (finger spacing and orientation) and, for the simulated
// backend, the plant of each channel. Backends other than "simulated" have their own section
// (e.g. "modbus"), parsed and checked once at load into a typed config.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/comedi_config.hpp"
#include "formats/load_cell_config.hpp"
#include "formats/modbus_register_map.hpp"
#include "formats/tablet_config.hpp"
#include "models/finger_layout.hpp"
#include "models/safety_limits.hpp"
#include "models/pneumatic_plant.hpp"

namespace palprig {

inline constexpr int kRigFileVersion = 1;

struct RigConfig {
  std::string source;  // file it came from, for messages
  std::string id;
  std::string backend = "simulated";
  SafetyLimits safety;
  FingerLayout layout;
  double contact_force_N = 0.05;
  std::array<PlantParams, kFingerCount> plants{};
  // The hardware backend's own configuration, parsed and checked at load: the one named by
  // `backend` is set ("simulated" needs none beyond `plants` and `safety`).
  std::optional<ModbusRigConfig> modbus;
  std::optional<ComediRigConfig> comedi;
  TabletConfig tablet;  // the pen tablet ("tablet" section; defaults when absent)
  // Load cells measuring the pressing force ("load_cells" section; absent: none).
  std::optional<LoadCellConfig> load_cells;
};

RigConfig load_rig_file(const std::filesystem::path& path);
// The built-in default: the simulated rig described in data/rigs/simulated.json.
RigConfig default_rig();
// Plant parameters from a JSON object, starting from `base` (fields absent keep base's value).
class JsonObject;
PlantParams parse_plant(const JsonObject& obj, const PlantParams& base);

}  // namespace palprig
