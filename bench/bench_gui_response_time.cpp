// The error of the response times the window stores, against key presses and mouse clicks
// injected at known moments: a person's discrimination session in the real window on a real X
// server (Xvfb, xcb), each answer a real key press ("0") or a click on "None" sent through the
// server's XTEST extension (bench/xtest_input.hpp) at a steady_clock time the program notes just
// before the request leaves. The stored answer time (the session clock's origin + onset_s +
// response_time_s, as stored in the SQLite file) minus that time is the error: what the X
// server's millisecond stamp, its scheduling and the window's mapping of the stamp
// (gui/event_clock.hpp) add. Beside it, how late the window's handler got each event (what a
// response time taken when the handler ran would have carried at best).
//
// Two passes: the window idle, then its GUI thread kept busy 30 ms out of every 100 ms (a
// repaint, a slow disk). Prints a table per pass and the machine.
//   build/bin/bench_gui_response_time [--trials N]   (default 40 per pass; runs itself under
//   xvfb-run -a -s "-screen 0 1600x1000x24" with QT_QPA_PLATFORM=xcb unless it is already there)
#include <QApplication>
#include <QElapsedTimer>
#include <QKeyEvent>
#include <QPushButton>
#include <QTableWidget>
#include <QTest>
#include <QTimer>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/xtest_input.hpp"
#include "gui/experiment_page.hpp"
#include "gui/live_run.hpp"
#include "gui/main_window.hpp"
#include "gui/participant_screen.hpp"
#include "gui/session_run.hpp"
#include "store/trial_store.hpp"

using namespace palprig;
using namespace palprig::gui;
using steady = std::chrono::steady_clock;

namespace {

double ms(steady::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

std::string first_line_of(const char* file, const char* key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "?";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

// Notes when the window first sees each key press and mouse press (before any widget acts).
class DeliverySeen final : public QObject {
 public:
  DeliverySeen() { QCoreApplication::instance()->installEventFilter(this); }
  ~DeliverySeen() override { QCoreApplication::instance()->removeEventFilter(this); }
  std::vector<steady::time_point> delivered;
  std::vector<std::uint64_t> stamps;  // the X server's timestamp of each (ms of CLOCK_MONOTONIC, 32 bits)

 protected:
  bool eventFilter(QObject* o, QEvent* e) override {
    if ((e->type() == QEvent::KeyPress || e->type() == QEvent::MouseButtonPress) && e != last_) {
      if (!(e->type() == QEvent::KeyPress && static_cast<QKeyEvent*>(e)->isAutoRepeat())) {
        delivered.push_back(steady::now());
        stamps.push_back(static_cast<QInputEvent*>(e)->timestamp());
      }
      last_ = e;
    }
    return QObject::eventFilter(o, e);
  }

 private:
  const QEvent* last_ = nullptr;
};

struct Stats {
  int n = 0;
  double mean = 0, sd = 0, max_abs = 0;
};

Stats stats_of(const std::vector<double>& v) {
  Stats s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= s.n;
  for (double x : v) {
    s.sd += (x - s.mean) * (x - s.mean);
    s.max_abs = std::max(s.max_abs, std::abs(x));
  }
  s.sd = s.n > 1 ? std::sqrt(s.sd / (s.n - 1)) : 0;
  return s;
}

struct Pass {
  std::vector<double> key_error_ms, click_error_ms, key_delivery_ms, click_delivery_ms, key_stamp_ms, click_stamp_ms;
  std::vector<double> window_ms;  // stored - the X server's stamp: what the window itself adds
};

// The X server's stamp as a steady_clock moment: its millisecond of CLOCK_MONOTONIC (the low 32
// bits), the middle of it.
steady::time_point stamp_time(std::uint64_t stamp, steady::time_point near) {
  const double near_ms = std::chrono::duration<double, std::milli>(near.time_since_epoch()).count();
  double ms_value = static_cast<double>(stamp);
  ms_value += 4294967296.0 * std::round((near_ms - ms_value) / 4294967296.0);
  return steady::time_point(
      std::chrono::duration_cast<steady::duration>(std::chrono::duration<double, std::milli>(ms_value + 0.5)));
}

// Rows of the trial list ticked as committed (its last column).
int committed(const QTableWidget& t) {
  int n = 0;
  for (int r = 0; r < t.rowCount(); ++r) n += t.item(r, t.columnCount() - 1)->text().isEmpty() ? 0 : 1;
  return n;
}

bool wait_for(MainWindow& w, const std::function<bool()>& cond, double timeout_s = 60) {
  const auto end = steady::now() + std::chrono::duration<double>(timeout_s);
  while (!cond()) {
    if (steady::now() > end) return false;
    QTest::qWait(2);
    (void)w;
  }
  return true;
}

// One session of `trials` answers, every other one by a click; the GUI thread busy
// `busy_ms` out of every 100 ms when busy_ms > 0.
Pass run_pass(MainWindow& window, bench::XTestInput& x, const std::string& protocol, const std::string& db,
              const std::string& participant, int trials, int busy_ms, std::mt19937& rng) {
  Pass pass;
  ExperimentPage& page = *window.experiment_page();
  page.set_fields({protocol, participant, db, 0, ""});
  std::map<int, steady::time_point> origins;
  const QMetaObject::Connection on_start =
      QObject::connect(&page.session_run(), &SessionRun::started, &page, [&](const SessionStart& s) {
        if (s.clock_origin) origins[s.start_position] = *s.clock_origin;
      });
  QTimer busy;
  if (busy_ms > 0) {
    busy.setInterval(100);
    QObject::connect(&busy, &QTimer::timeout, [busy_ms] {
      const auto until = steady::now() + std::chrono::milliseconds(busy_ms);
      while (steady::now() < until) {}
    });
    busy.start();
  }
  if (!page.begin(false)) {
    std::fprintf(stderr, "bench_gui_response_time: the session was refused: %s\n", qPrintable(page.refusal_text()));
    std::exit(1);
  }
  ParticipantScreen& screen = *page.participant_screen();
  auto* ready = screen.findChild<QPushButton*>("ready_button");
  auto* none = screen.findChild<QPushButton*>("none_button");
  std::uniform_int_distribution<int> think_ms(150, 450);
  std::map<int, steady::time_point> injected;
  std::map<int, steady::time_point> delivered, stamped;
  std::map<int, bool> clicked;
  for (int k = 0; k < trials; ++k) {
    const bool ok = wait_for(window, [&] {
      if (ready->isVisible() && ready->isEnabled()) x.key("space");
      return screen.answering_position() == k;
    });
    if (!ok) {
      std::fprintf(stderr, "bench_gui_response_time: trial %d was never asked\n", k + 1);
      std::exit(1);
    }
    QTest::qWait(think_ms(rng));  // the participant's own time, varied against the loop and the ms
    DeliverySeen seen;
    const bool click = k % 2 == 1;
    clicked[k] = click;
    if (click) {
      const QPoint p = none->mapToGlobal(none->rect().center());
      x.move(p.x(), p.y());
      x.sync();
      injected[k] = x.button_down(1);
      x.button_up(1);
    } else {
      injected[k] = x.key("0");
    }
    if (!wait_for(window, [&] { return !seen.delivered.empty() && committed(*page.trial_table()) == k + 1; })) {
      std::fprintf(stderr, "bench_gui_response_time: the answer to trial %d never arrived\n", k + 1);
      std::exit(1);
    }
    delivered[k] = seen.delivered.front();
    stamped[k] = stamp_time(seen.stamps.front(), delivered[k]);
  }
  page.abort_and_wait();
  QObject::disconnect(on_start);
  busy.stop();
  const auto store = open_trial_store(db, TrialStore::Access::read_only);
  for (const StoredTrial& t : store->read_trials(true)) {
    if (!injected.count(t.position) || !t.response_time_s || origins.empty()) continue;
    const auto origin = std::prev(origins.upper_bound(t.position))->second;
    const auto stored = origin + std::chrono::duration_cast<steady::duration>(
                                     std::chrono::duration<double>(t.onset_s + *t.response_time_s));
    const double error = ms(stored - injected.at(t.position));
    const double delivery = ms(delivered.at(t.position) - injected.at(t.position));
    (clicked.at(t.position) ? pass.click_error_ms : pass.key_error_ms).push_back(error);
    (clicked.at(t.position) ? pass.click_delivery_ms : pass.key_delivery_ms).push_back(delivery);
    (clicked.at(t.position) ? pass.click_stamp_ms : pass.key_stamp_ms)
        .push_back(ms(stamped.at(t.position) - injected.at(t.position)));
    pass.window_ms.push_back(ms(stored - stamped.at(t.position)));
  }
  return pass;
}

void print_row(const char* what, const std::vector<double>& v) {
  const Stats s = stats_of(v);
  std::printf("| %-48s | %3d | %7.3f | %6.3f | %7.3f |\n", what, s.n, s.mean, s.sd, s.max_abs);
}

void print_pass(const char* title, const Pass& p) {
  std::printf("\n%s\n\n", title);
  std::printf("| %-48s | %3s | %7s | %6s | %7s |\n", "ms", "n", "mean", "sd", "max |x|");
  std::printf("|---|---:|---:|---:|---:|\n");
  print_row("stored RT error, key press (0)", p.key_error_ms);
  print_row("stored RT error, click (None)", p.click_error_ms);
  print_row("of which the X server's stamp (+0.5 ms), key", p.key_stamp_ms);
  print_row("of which the X server's stamp (+0.5 ms), click", p.click_stamp_ms);
  print_row("stored - the X server's stamp (+0.5 ms), all", p.window_ms);
  print_row("handler delay after injection, key", p.key_delivery_ms);
  print_row("handler delay after injection, click", p.click_delivery_ms);
}

// Runs this program again under its own Xvfb on the xcb platform.
void run_under_xvfb(int argc, char** argv) {
  std::vector<std::string> args = {
      "xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", "env", "QT_QPA_PLATFORM=xcb", "PALPRIG_BENCH_UNDER_XVFB=1"};
  for (int i = 0; i < argc; ++i) args.emplace_back(argv[i]);
  std::vector<char*> c;
  c.reserve(args.size() + 1);
  for (auto& a : args) c.push_back(a.data());
  c.push_back(nullptr);
  execvp("xvfb-run", c.data());
  std::fprintf(stderr, "bench_gui_response_time: cannot run xvfb-run (package xvfb): %s\n", std::strerror(errno));
  std::exit(1);
}

int run_benchmark(int argc, char** argv) {
  int trials = 40;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--trials") trials = std::max(4, std::atoi(argv[i + 1]));
  }
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  if (std::getenv("PALPRIG_BENCH_UNDER_XVFB") == nullptr || !platform || std::string(platform) != "xcb") {
    run_under_xvfb(argc, argv);
  }
  QApplication app(argc, argv);
  const std::string data = std::string(PALPRIG_SOURCE_DIR) + "/data";
  char dir_template[] = "/tmp/palprig-bench-rt-XXXXXX";
  const std::string dir = mkdtemp(dir_template);
  // The shipped discrimination protocol, both conditions, with a stimulus that stays until the
  // answer (simultaneous) and a short sequence; enough repetitions for the trials asked.
  auto doc = nlohmann::json::parse(std::ifstream(data + "/protocols/discrimination_002.json"));
  doc["practice_trials"] = 0;
  doc["repetitions"] = 1 + trials / 28;
  doc["timing"] = {{"max_present_s", 30},      {"sequential_step_s", 0.05}, {"sequential_gap_s", 0.02},
                   {"response_timeout_s", 60}, {"inter_trial_s", 0.2},      {"break_s", 0}};
  const std::string protocol = dir + "/protocol.json";
  std::ofstream(protocol) << doc.dump(2);

  LiveRunFiles files;
  files.data_dir = data;
  LiveRunOptions options;
  options.want_fifo = false;
  MainWindow window(std::make_unique<LiveRun>(load_live_run(files), options), files, options);
  window.resize(1280, 800);
  window.show();
  window.pages()->setCurrentWidget(window.experiment_page());
  if (!QTest::qWaitForWindowExposed(&window)) {
    std::fprintf(stderr, "bench_gui_response_time: the window never showed\n");
    return 1;
  }
  bench::XTestInput x;
  window.activateWindow();
  x.focus(window.winId());
  x.sync();

  std::printf("bench_gui_response_time: %d answers per pass, half key presses, half clicks\n", trials);
  std::printf("machine: %s, %u cores\n", first_line_of("/proc/cpuinfo", "model name").c_str(),
              std::thread::hardware_concurrency());
  std::printf("load average at start: %s\n", load_average().c_str());
  std::mt19937 rng(22);
  const Pass idle = run_pass(window, x, protocol, dir + "/idle.db", "B01", trials, 0, rng);
  const Pass busy = run_pass(window, x, protocol, dir + "/busy.db", "B02", trials, 30, rng);
  print_pass("The window idle:", idle);
  print_pass("The window's GUI thread busy 30 ms of every 100 ms:", busy);
  std::printf("\nload average at end: %s\n", load_average().c_str());
  std::printf(
      "(error = stored answer time - the moment the XTEST request was sent; PsychoPy's Keyboard "
      "class: sub-millisecond sd)\n");
  std::filesystem::remove_all(dir);
  return 0;
}

}  // namespace

// A failure (a file, the simulator, the rig) ends the benchmark with one line and exit 1, not
// with std::terminate.
int main(int argc, char** argv) {
  try {
    return run_benchmark(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_gui_response_time: %s\n", e.what());
    return 1;
  }
}
