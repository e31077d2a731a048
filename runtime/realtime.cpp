#include "runtime/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

namespace palprig {

RealtimeSetup enter_realtime(int fifo_priority, bool want_fifo) noexcept {
  RealtimeSetup r;
  try {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) r.memory_locked = true;
    else r.note += std::string("mlockall refused (") + std::strerror(errno) + "); ";
    if (want_fifo) {
      sched_param sp{};
      sp.sched_priority = fifo_priority;
      const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
      if (rc == 0) r.fifo = true;
      else r.note += std::string("SCHED_FIFO refused (") + std::strerror(rc) +
                     "): running at normal priority; grant CAP_SYS_NICE or an rtprio limit for lower jitter; ";
    }
    if (!r.note.empty()) r.note.resize(r.note.size() - 2);
  } catch (...) {
  }
  return r;
}

}  // namespace palprig
