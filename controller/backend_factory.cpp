// make_backend: the one place that turns a rig file's "backend" into an object. Hardware
// backends register here as they are added.
#include "controller/rig_file.hpp"
#include "controller/simulated_rig.hpp"
#include "models/parse_error.hpp"

namespace palprig {

std::unique_ptr<RigBackend> make_backend(const RigConfig& rig) {
  if (rig.backend == "simulated") return std::make_unique<SimulatedRig>(rig.plants, rig.safety.p_max_kPa);
  throw InputError(rig.source, "backend", "a backend this build supports (\"simulated\"), got \"" + rig.backend + "\"");
}

}  // namespace palprig
