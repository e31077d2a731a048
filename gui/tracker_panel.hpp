#pragma once
// TrackerPanel: a tracker input's state for the operator: the server and whether it
// is connected, the messages received, each tool of the tracking file with its finger, how
// many poses came and how old the last is (red once older than the stale-input limit: that
// finger is vented), and device names the tracker sends that the tracking file does not map
// (a misspelt tool name shows up there). Refreshed by the page's 16 ms poll.
#include <QGroupBox>
#include <vector>

#include "gui/live_run.hpp"

class QLabel;

namespace palprig::gui {

class TrackerPanel final : public QGroupBox {
  Q_OBJECT
 public:
  TrackerPanel(LiveRun& run, QWidget* parent = nullptr);
  void refresh();  // GUI poll
  QLabel* connection_label() const noexcept { return connection_; }
  QLabel* tool_label(int k) const noexcept { return tools_.at(std::size_t(k)); }

 private:
  LiveRun& run_;
  QLabel* connection_ = nullptr;
  QLabel* others_ = nullptr;
  std::vector<QLabel*> tools_;
};

}  // namespace palprig::gui
