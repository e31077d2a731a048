// make_backend: the one place that turns a rig file's "backend" into an object. Hardware
// backends register here as they are added.
#include "controller/comedi_rig.hpp"
#include "controller/modbus_rig.hpp"
#include "controller/rig_file.hpp"
#include "controller/simulated_rig.hpp"
#include "models/parse_error.hpp"

namespace palprig {

void validate_backend_section(const RigConfig& rig) {
  if (rig.backend == "modbus") parse_modbus_config(rig);
  if (rig.backend == "comedi") parse_comedi_config(rig);
}

std::unique_ptr<RigBackend> make_backend(const RigConfig& rig) {
  if (rig.backend == "simulated") return std::make_unique<SimulatedRig>(rig.plants, rig.safety.p_max_kPa);
  if (rig.backend == "modbus") return std::make_unique<ModbusRig>(parse_modbus_config(rig));
  if (rig.backend == "comedi") return std::make_unique<ComediRig>(parse_comedi_config(rig));
  throw InputError(rig.source, "backend",
                   "a backend this build supports (\"simulated\", \"modbus\", \"comedi\"), got \"" + rig.backend + "\"");
}

}  // namespace palprig
