#pragma once
// make_backend: the one place that turns a rig file's "backend" into an object.
#include <memory>

#include "formats/rig_file.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

// Open the backend the rig file names. Throws InputError for a bad backend section and
// Error (core/error.hpp) when the device cannot be reached.
std::unique_ptr<RigBackend> make_backend(const RigConfig& rig);

}  // namespace palprig
