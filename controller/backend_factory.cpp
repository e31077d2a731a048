// make_backend: the one place that turns a rig file's "backend" into an object. Hardware
// backends register here as they are added.
#include "controller/backend_factory.hpp"

#include "rigs/comedi_rig.hpp"
#include "rigs/modbus_rig.hpp"
#include "rigs/simulated_rig.hpp"
#include "core/input_error.hpp"

namespace palprig {

namespace {

std::unique_ptr<RigBackend> make_bare_backend(const RigConfig& rig) {
  if (rig.backend == "simulated") return std::make_unique<SimulatedRig>(rig.plants, rig.safety.p_max_kPa);
  if (rig.backend == "modbus" && rig.modbus) return std::make_unique<ModbusRig>(*rig.modbus);
  if (rig.backend == "comedi" && rig.comedi) return std::make_unique<ComediRig>(*rig.comedi);
  return nullptr;
}

}  // namespace

std::unique_ptr<RigBackend> make_backend(const RigConfig& rig) {
  if (auto backend = make_bare_backend(rig)) {
    if (rig.load_cells) backend->attach_load_cells(*rig.load_cells);
    return backend;
  }
  throw InputError(rig.source, "backend",
                   "a backend this build supports (\"simulated\", \"modbus\", \"comedi\") with its section loaded, "
                   "got \"" +
                       rig.backend + "\"");
}

}  // namespace palprig
