#include "gui/gui_app.hpp"

#include <QApplication>
#include <QMessageBox>
#include <QPixmap>
#include <QScreen>
#include <QTimer>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "gui/experiment_page.hpp"
#include "gui/participant_screen.hpp"
#include "gui/main_window.hpp"
#include "gui/training_view.hpp"
#include "gui/statistics_view.hpp"
#include "sessions/session_telemetry.hpp"
#include "experiments/simulated_participant.hpp"
#include "core/error.hpp"

namespace palprig::gui {

namespace {

// The refusal line on stderr, and in a dialog when someone can see it (not offscreen, not a
// scripted screenshot run).
int refuse(const std::string& line, int code, bool interactive) {
  std::cerr << "palprig: " << line << "\n";
  if (interactive && QGuiApplication::platformName() != "offscreen")
    QMessageBox::critical(nullptr, "palprig", QString::fromStdString("palprig: " + line));
  return code;
}

nlohmann::json summary_json(const RunSummary& s) {
  auto lat = [](const LatencySummary& l) {
    return nlohmann::json{{"p50_us", l.p50_us}, {"p99_us", l.p99_us}, {"p999_us", l.p999_us}, {"max_us", l.max_us}};
  };
  return {{"ticks", s.ticks},
          {"overruns", s.overruns},
          {"missed_periods", s.missed_periods},
          {"wake_latency", lat(s.wake_latency)},
          {"tick_time", lat(s.tick_time)},
          {"io_time", lat(s.io_time)},
          {"realtime_note", s.realtime_note},
          {"fault", s.fault == FaultCode::none ? nlohmann::json(nullptr) : nlohmann::json(to_string(s.fault))}};
}

// Where the participant screen and the console ended up (which display, which rectangle):
// `--participant-display` runs are checked with it under a two-screen X server.
nlohmann::json participant_screen_json(MainWindow& window) {
  auto rect = [](const QRect& r) { return nlohmann::json{r.x(), r.y(), r.width(), r.height()}; };
  auto screen_index = [](const QScreen* screen) {
    const auto screens = QGuiApplication::screens();
    return static_cast<int>(screens.indexOf(const_cast<QScreen*>(screen))) + 1;
  };
  const ParticipantScreen& p = *window.experiment_page()->participant_screen();
  return {{"own_window", p.isWindow()},
          {"full_screen", p.isFullScreen()},
          {"display", screen_index(p.screen())},
          {"display_geometry", rect(p.screen()->geometry())},
          {"window_geometry", rect(p.frameGeometry())},
          {"console_display", screen_index(window.screen())},
          {"console_window_geometry", rect(window.frameGeometry())}};
}

}  // namespace

int run_gui(int argc, char** argv, const GuiOptions& o) {
  QApplication app(argc, argv);
  QApplication::setApplicationName("palprig");
  const bool interactive = o.screenshot_path.empty();
  std::unique_ptr<LiveRun> run;
  try {
    run = std::make_unique<LiveRun>(load_live_run(o.files), o.run);
  } catch (const Error& e) {  // core/error.hpp: BadInput (InputError) 2, anything else of palprig's 1
    return refuse(e.what(), e.exit_code(), interactive);
  } catch (const std::exception& e) {
    return refuse(e.what(), 1, interactive);
  }
  MainWindow window(std::move(run), o.files, o.run);
  window.show();
  int exit_code = 0;
  bool shot_taken = false;
  nlohmann::json participant_screen_seen;  // --participant-display: where it was while the session was open
  // The screenshot: the whole window, or with a session its statistics view, when the session
  // ended (and the statistics were refreshed) or after_s passed, whichever comes first.
  auto take_screenshot = [&](QWidget& what) {
    if (shot_taken) return;
    shot_taken = true;
    if (o.session.participant_display > 0) participant_screen_seen = participant_screen_json(window);
    const QPixmap shot = what.grab();
    if (!shot.save(QString::fromStdString(o.screenshot_path), "PNG")) {
      std::cerr << "palprig: " << o.screenshot_path << ": cannot write the screenshot\n";
      if (exit_code == 0) exit_code = 1;
    }
    window.set_close_without_asking(true);
    window.close();
  };
  if (!o.session.protocol.empty()) {
    ExperimentPage& page = *window.experiment_page();
    window.pages()->setCurrentWidget(&page);
    QObject::connect(&page.session_run(), &SessionRun::started, &window, [&](const SessionStart& s) {
      std::cout << "palprig gui: " << s.protocol_name << ", participant " << s.participant.code << ", session "
                << s.session_id << ", "
                << (s.resumed ? "resumed at trial " + std::to_string(s.start_position + 1) : std::string("new")) << ", "
                << s.total_trials << " trials, database " << o.session.store << "\n"
                << std::flush;
    });
    QObject::connect(&page, &ExperimentPage::sessionEnded, &window, [&](const SessionEnd& e) {
      if (!e.fault.empty()) {
        std::cerr << "palprig: rig fault: " << e.fault << "; " << e.committed_trials << " of " << e.total_trials
                  << " trials kept, continue with --resume" << (e.fault_record.empty() ? "" : "; " + e.fault_record)
                  << "\n";
        exit_code = 1;
      } else {
        std::cout << "palprig gui: session " << (e.completed ? "completed" : "stopped") << ": " << e.committed_trials
                  << " of " << e.total_trials << " trials in " << o.session.store << "\n"
                  << std::flush;
      }
      if (const std::string telemetry = telemetry_summary(e); !telemetry.empty())
        std::cout << "palprig gui: " << telemetry << "\n" << std::flush;
    });
    QObject::connect(&page, &ExperimentPage::sessionRefused, &window, [&](const QString& line, int code) {
      refuse(line.toStdString(), code, interactive);
      exit_code = code;
      if (!interactive) {
        shot_taken = true;  // nothing to show: the refusal is the result
        window.set_close_without_asking(true);
        window.close();
      }
    });
    if (!interactive) {
      // At the end: one more refresh of the statistics, then their picture (a store that cannot
      // be read is pictured with its message).
      StatisticsView& stats = *page.statistics();
      QObject::connect(&page.session_run(), &SessionRun::finished, &window, [&] {
        if (shot_taken) return;
        page.show_statistics();
        QObject::connect(&stats, &StatisticsView::refreshed, &window, [&] {
          if (!stats.refreshing()) take_screenshot(stats);  // the last of a coalesced chain
        });
        QObject::connect(&stats, &StatisticsView::refresh_failed, &window, [&] { take_screenshot(stats); });
        stats.refresh();
      });
    }
    page.set_fields({o.session.protocol, o.session.participant, o.session.store, o.session.speed, o.session.telemetry});
    if (o.session.participant_display > 0) {
      const auto screens = QGuiApplication::screens();
      if (o.session.participant_display > screens.size()) {
        window.set_close_without_asking(true);
        return refuse("command line: participant-display: a display this X server has (1 to " +
                          std::to_string(screens.size()) + "), got " + std::to_string(o.session.participant_display),
                      2, interactive);
      }
      page.participant_screen()->show_full_screen_on(screens[o.session.participant_display - 1]);
    }
    std::uint64_t seed = 0;
    const bool pilot = parse_simulated_participant(o.session.participant, seed);
    if ((pilot || o.session.resume) && !page.begin(o.session.resume)) {
      window.set_close_without_asking(true);
      return refuse(page.refusal_text().toStdString(), 2, interactive);
    }
  }
  if (!o.curriculum.empty()) {
    TrainingView& training = *window.training_view();
    window.pages()->setCurrentWidget(&training);
    training.set_files(QString::fromStdString(o.curriculum), QString::fromStdString(o.session.store));
    QString refusal = training.refusal_text();
    if (refusal.isEmpty() && !o.session.participant.empty() &&
        !training.select_trainee(QString::fromStdString(o.session.participant))) {
      refusal =
          QString::fromStdString(o.session.store + ": trainee '" + o.session.participant +
                                 "': a trainee enrolled in this curriculum (enrol them with: palprig train enrol)");
    }
    if (!refusal.isEmpty()) {
      window.set_close_without_asking(true);
      return refuse(refusal.toStdString(), 2, interactive);
    }
  }
  if (!o.screenshot_path.empty()) {
    QTimer::singleShot(int(o.after_s * 1000), &window, [&] {
      if (!o.session.protocol.empty()) {
        window.experiment_page()->show_statistics();
        take_screenshot(*window.experiment_page()->statistics());
      } else
        take_screenshot(window);
    });
  }
  app.exec();
  // SIGINT/SIGTERM ends the run (and a session: vented, committed trials kept) as a stop, exit 1.
  if (o.run.control && o.run.control->stop_signal() != 0 && exit_code == 0) exit_code = 1;
  window.run().stop();
  const RunSummary& s = window.run().last_summary();
  if (o.json) {
    nlohmann::json summary = summary_json(s);
    if (o.session.participant_display > 0)
      summary["participant_screen"] =
          participant_screen_seen.is_null() ? participant_screen_json(window) : participant_screen_seen;
    std::cout << summary.dump(2) << "\n";
  }
  if (s.fault != FaultCode::none) {
    std::cerr << "palprig: fault at t=" << s.fault.t_s << " s: " << to_string(s.fault)
              << (s.fault.detail().empty() ? "" : " (" + s.fault.detail() + ")") << "; all channels vented; "
              << s.fault_record << "\n";
    if (exit_code == 0) exit_code = 1;
  }
  return exit_code;
}

}  // namespace palprig::gui
