// Leaks one allocation on purpose, for sanitizer.LeakDetectionIsOn: in the sanitizer build
// (make test-asan) LeakSanitizer must report it, so the suites' "no leak reported" means the
// leak check ran (ASAN_OPTIONS=detect_leaks=1 with tools/lsan-suppressions.txt), not that it
// was switched off.
#include <cstdio>

int* volatile g_kept = nullptr;

int main() {
  g_kept = new int[4]{1, 2, 3, 4};
  std::printf("allocated %d\n", g_kept[3]);
  g_kept = nullptr;  // the only pointer dropped: a direct leak of 16 bytes
  return 0;
}
