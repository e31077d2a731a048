#pragma once
// What the experiment console's Qt suites share (experiment_console_test.cpp,
// pulse_console_test.cpp): the main window on the default simulated rig with the Experiment tab
// shown, waiting on the window's poll signal (never a fixed sleep), the page's session end, the
// trial list's committed rows and the README's pictures.
#include <QMessageBox>
#include <QObject>
#include <QPushButton>
#include <QTest>
#include <QSignalSpy>
#include <QString>
#include <QTableWidget>
#include <QWidget>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>

#include "gui/experiment_page.hpp"
#include "gui/main_window.hpp"

namespace palprig::gui::console_test {

inline std::string data_dir() { return std::string(PALPRIG_SOURCE_DIR) + "/data"; }

struct Window {
  LiveRunFiles files;
  std::unique_ptr<MainWindow> window;
  ExperimentPage& page() { return *window->experiment_page(); }
};

inline Window open_window() {
  Window w;
  w.files.data_dir = data_dir();
  LiveRunOptions opt;
  opt.want_fifo = false;
  w.window = std::make_unique<MainWindow>(std::make_unique<LiveRun>(load_live_run(w.files), opt), w.files, opt);
  w.window->show();
  w.window->pages()->setCurrentWidget(w.window->experiment_page());
  return w;
}

// Process events until cond holds or timeout_s passes (waits on the window's poll signal).
inline bool wait_until(MainWindow& w, const std::function<bool()>& cond, double timeout_s = 60.0) {
  QSignalSpy spy(&w, &MainWindow::polled);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!cond()) {
    if (std::chrono::steady_clock::now() > end) return false;
    spy.wait(100);
  }
  return true;
}

// What the page reported at its end (a lambda, not QSignalSpy: SessionEnd is no QVariant type).
// Disconnects when it goes out of scope, so a later session's end never writes into it.
struct EndSeen {
  int count = 0;
  SessionEnd end;
  QMetaObject::Connection connection;
  explicit EndSeen(ExperimentPage& page) {
    connection = QObject::connect(&page, &ExperimentPage::sessionEnded, &page, [this](const SessionEnd& e) {
      ++count;
      end = e;
    });
  }
  ~EndSeen() { QObject::disconnect(connection); }
  EndSeen(const EndSeen&) = delete;
  EndSeen& operator=(const EndSeen&) = delete;
};

// With PALPRIG_SCREENSHOT_DIR set, saves `what` there (the README's pictures come from here).
inline void keep_screenshot(QWidget& what, const char* name) {
  const char* dir = std::getenv("PALPRIG_SCREENSHOT_DIR");
  if (dir == nullptr) return;
  what.grab().save(QString("%1/%2").arg(dir, name), "PNG");
}

// The abort confirmation on show (an answered one lingers, hidden, until its deferred delete).
inline QMessageBox* abort_question(ExperimentPage& page) {
  for (auto* box : page.findChildren<QMessageBox*>("abort_confirmation"))
    if (box->isVisible()) return box;
  return nullptr;
}

// The experimenter's Abort: the button, then "Yes" in the confirmation it asks.
inline void abort_confirmed(ExperimentPage& page) {
  QTest::mouseClick(page.findChild<QPushButton*>("abort_session"), Qt::LeftButton);
  if (auto* box = abort_question(page)) box->button(QMessageBox::Yes)->click();
}

// Rows of the trial list ticked as committed (the last column).
inline int committed_rows(QTableWidget& t) {
  int n = 0;
  for (int r = 0; r < t.rowCount(); ++r) n += t.item(r, t.columnCount() - 1)->text().isEmpty() ? 0 : 1;
  return n;
}

}  // namespace palprig::gui::console_test
