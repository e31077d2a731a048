#pragma once
// The wall-clock time stamps the trial store writes (started_utc, completed_utc, since_utc).
#include <string>

namespace palprig {

// Now, UTC, as 2026-11-23T09:01:02Z.
std::string utc_now_text();

}  // namespace palprig
