#pragma once
// Real-time set-up for the loop thread: lock memory and ask for SCHED_FIFO when the system
// permits it. When it does not, the loop still runs, and the returned note says why in one line.
#include <string>

namespace palprig {

struct RealtimeSetup {
  bool memory_locked = false;
  bool fifo = false;
  std::string note;  // empty when both succeeded
};

RealtimeSetup enter_realtime(int fifo_priority = 80, bool want_fifo = true) noexcept;

}  // namespace palprig
