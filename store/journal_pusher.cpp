#include "store/journal_pusher.hpp"

#include <memory>

#include "store/lab_sync.hpp"
#include "store/pg_connection.hpp"
#include "store/sqlite_db.hpp"

namespace palprig {

JournalPusher::JournalPusher(PgTarget target, std::filesystem::path journal_file,
                             std::function<void(const std::string&)> say)
    : target_(std::move(target)), journal_file_(std::move(journal_file)), say_(std::move(say)) {
  thread_ = std::thread([this] { run(); });
}

JournalPusher::~JournalPusher() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void JournalPusher::committed() {
  {
    std::lock_guard lock(mutex_);
    ++committed_;
    work_ = true;
  }
  wake_.notify_all();
}

std::int64_t JournalPusher::flush(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  work_ = true;
  wake_.notify_all();
  pushed_.wait_for(lock, timeout, [this] { return pushed_through_ >= committed_; });
  return committed_ - pushed_through_;
}

void JournalPusher::run() {
  std::unique_ptr<PgConnection> server;
  std::unique_ptr<Database> journal;
  PushOptions options;
  options.journal_only = true;
  options.mark_synced = true;
  int pushed_while_offline = 0;
  for (;;) {
    std::int64_t target_count = 0;
    {
      std::unique_lock lock(mutex_);
      // Offline: try again every second. Online: sleep until a commit arrives.
      const auto wait = offline_ ? std::chrono::seconds(1) : std::chrono::seconds(30);
      wake_.wait_for(lock, wait, [this] { return stop_ || work_; });
      if (stop_) return;
      work_ = false;
      target_count = committed_;
    }
    try {
      if (!journal) journal = std::make_unique<Database>(journal_file_, Database::Mode::read_write_create);
      if (!server || !server->ok()) server = std::make_unique<PgConnection>(target_, 3);
      const PushReport report = push_file_to_server(*journal, *server, options);
      if (offline_) {
        pushed_while_offline += report.trials_added;
        say_("lab server back at " + target_.describe() + ": " + std::to_string(pushed_while_offline) +
             " journal trials pushed");
        pushed_while_offline = 0;
        offline_ = false;
      }
      {
        std::lock_guard lock(mutex_);
        pushed_through_ = std::max(pushed_through_, target_count);
      }
      pushed_.notify_all();
    } catch (const std::exception& e) {
      server.reset();
      if (!offline_) {
        say_(std::string("lab server unreachable (") + e.what() + "); trials are kept in the journal " +
             journal_file_.string() + " and pushed when it returns");
        offline_ = true;
      }
    }
  }
}

}  // namespace palprig
