#pragma once
// What one session may hold: every protocol kind is refused at load when its sessions could
// exceed it. 20,000 trials is about 17 hours at one trial every 3 s, more than any person sits
// for; it keeps a session's plan, its stored rows and a resume's replay small (the stores'
// rows have constant size, so a store grows linearly up to it).
#include <string>

namespace palprig {

inline constexpr long long kMaxSessionTrials = 20000;

inline std::string session_bound_text(long long trials) {
  return "at most " + std::to_string(kMaxSessionTrials) + " trials in a session (about 17 hours at 3 s a trial), got " +
         std::to_string(trials);
}

}  // namespace palprig
