#pragma once
// A measured run of palprig's own real-time loop (run_loop, the code `palprig run --realtime`
// runs) against the default simulated rig with a pen pressing still: what `palprig rt-check`
// and the real-time benchmarks report as the machine's wake-up latency at a rate.
#include "runtime/realtime.hpp"
#include "diagnostics/rt_readiness.hpp"

namespace palprig {

// Throws BadInput for a rate or length run_loop refuses.
LoopMeasurement measure_loop(double rate_hz, double seconds, const RealtimeOptions& options);

}  // namespace palprig
