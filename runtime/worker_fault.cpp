#include "runtime/worker_fault.hpp"

#include <atomic>
#include <cstdio>
#include <cstring>

namespace palprig {

namespace {
// 0 = none, 1 = being written, 2 = ready to read.
std::atomic<int> g_state{0};
char g_detail[256];
}  // namespace

void report_worker_fault(const char* worker, const char* what) noexcept {
  std::fprintf(stderr, "palprig: %s failed: %s\n", worker, what);
  int expected = 0;
  if (!g_state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) return;
  std::snprintf(g_detail, sizeof g_detail, "%s: %s", worker, what);
  g_state.store(2, std::memory_order_release);
}

bool worker_fault_pending(char* detail, std::size_t detail_size) noexcept {
  if (g_state.load(std::memory_order_acquire) != 2) return false;
  if (detail && detail_size) {
    std::strncpy(detail, g_detail, detail_size - 1);
    detail[detail_size - 1] = '\0';
  }
  return true;
}

void clear_worker_faults() noexcept { g_state.store(0, std::memory_order_release); }

}  // namespace palprig
