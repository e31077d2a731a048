#pragma once
// Faults of worker threads (bus I/O, pen reader) reach the real-time loop through here: a
// worker that dies of an exception, or loses its device for good, reports it; the loop polls
// every tick (one atomic load), vents every channel and stops with FaultCode::thread_exception
// and the worker's own words. The first report wins; later ones are kept only in the log.
#include <cstddef>

namespace palprig {

// Any thread. Copies `what` (no allocation) and prints one line to stderr.
void report_worker_fault(const char* worker, const char* what) noexcept;
// Loop thread: true once a worker reported; copies "worker: what" into detail.
bool worker_fault_pending(char* detail, std::size_t detail_size) noexcept;
// Forget a report (a new session in the same process, tests).
void clear_worker_faults() noexcept;

}  // namespace palprig
