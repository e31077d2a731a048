#pragma once
// The thread that pushes a bench's journal to the lab server while a session runs. The session
// thread commits each trial to the local journal (fsync'd SQLite) and wakes the pusher; the
// pusher, on its own connections, sends what the server lacks. When the server is down the
// session is not held up: the pusher says so once, retries every second, and says when the
// server is back. Trial commit latency is therefore the journal's, never the network's.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "store/pg_target.hpp"

namespace palprig {

class JournalPusher {
 public:
  // `say` receives one line per change of state (server lost, server back); called on the
  // pusher's thread.
  JournalPusher(PgTarget target, std::filesystem::path journal_file, std::function<void(const std::string&)> say);
  ~JournalPusher();  // stops the thread; what is not pushed stays in the journal
  JournalPusher(const JournalPusher&) = delete;
  JournalPusher& operator=(const JournalPusher&) = delete;

  // A trial (or the end of a session) was committed to the journal.
  void committed();
  // Waits until everything committed so far is on the server, at most `timeout`. Returns the
  // number of journal commits not yet confirmed pushed (0: all there).
  std::int64_t flush(std::chrono::milliseconds timeout);
  bool server_reachable() const noexcept { return !offline_.load(); }

 private:
  void run();

  PgTarget target_;
  std::filesystem::path journal_file_;
  std::function<void(const std::string&)> say_;
  std::mutex mutex_;
  std::condition_variable wake_, pushed_;
  std::int64_t committed_ = 0, pushed_through_ = 0;  // counts of journal commits
  bool stop_ = false, work_ = false;
  std::atomic<bool> offline_{false};
  std::thread thread_;
};

}  // namespace palprig
