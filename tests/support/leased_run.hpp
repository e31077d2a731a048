#pragma once
// Tests that drive a backend of their own through the loop: the backend behind a Rig and its
// lease (controller/rig_lease.hpp), as every front end drives one, for the length of one run.
#include "controller/loop_runner.hpp"
#include "controller/rig_lease.hpp"

namespace palprig::testing {

inline RunSummary run_loop_leased(const TickConfig& config, const Scene& scene, InputSource& input,
                                  RigBackend& opened_backend, const RunOptions& options) {
  Rig rig(opened_backend, "the test's rig");
  RigLease lease = rig.lease("the test's loop");
  return run_loop(config, scene, input, lease, options);
}

}  // namespace palprig::testing

namespace palprig::testing {

// A backend the test opened, behind a Rig and its lease, for calls that drive a rig through a
// lease (calibration's sweep and evaluation).
struct LeasedRig {
  explicit LeasedRig(RigBackend& opened_backend)
      : rig(opened_backend, "the test's rig"), lease(rig.lease("the test")) {}
  Rig rig;
  RigLease lease;
};

}  // namespace palprig::testing
