// Qt Test suite for pulse localisation in the window (ctest gui.PulseConsole.*),
// offscreen: the Experiment tab with a "task": "pulse" protocol, the participant's marking
// screen (gui/participant_screen_pulse.cpp), SessionRun running run_pulse_study, and the pulse
// statistics in the statistics view. Sessions run for real against the default simulated rig
// and real SQLite files; answers are QTest clicks and keys; `palprig experiment run` and
// `palprig stats trials` run as real processes. Tests wait on signals, never on fixed sleeps.
#include <QApplication>
#include <QLabel>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QtTest>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "gui/experiment_page.hpp"
#include "gui/localisation_marking.hpp"
#include "gui/main_window.hpp"
#include "gui/participant_screen.hpp"
#include "gui/scene_view.hpp"
#include "gui/statistics_view.hpp"
#include "models/pulse_localisation.hpp"
#include "store/pulse_store.hpp"
#include "tests/gui/qt/console_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace palprig::gui;
using palprig::test_support::TempDir;
using namespace palprig::gui::console_test;

namespace {

// The shipped pulse protocol (groin and brachial scenes), each scene `repetitions` times, with a
// short inter-trial interval so a person's session (real time) takes seconds.
std::string short_pulse(const TempDir& dir, int repetitions) {
  auto doc = nlohmann::json::parse(test_support::read_file(data_dir() + "/protocols/pulse_localisation_000.json"));
  for (auto& c : doc["conditions"])
    c["scene"] = data_dir() + "/scenes/" + std::filesystem::path(c["scene"].get<std::string>()).filename().string();
  doc["repetitions"] = repetitions;
  doc["pulse"]["inter_trial_s"] = 0.05;
  return dir.write("pulse.json", doc.dump(2)).string();
}

std::vector<PulseTrialRecord> stored_pulse_trials(const std::string& db) {
  SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
  std::vector<PulseTrialRecord> all;
  for (const SessionOverview& s : store.list_sessions()) {
    const auto trials = PulseStore(store, false).read_trials(s.id);
    all.insert(all.end(), trials.begin(), trials.end());
  }
  return all;
}

// A stored trial without what depends on the clock (onset, response time), doubles bit-exact.
std::string row_text(const PulseTrialRecord& t) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%d|%s|%lld|%d|%a|%a|%s|%a|%d", t.position, t.condition.c_str(),
                t.scene_seed ? static_cast<long long>(*t.scene_seed) : -1LL, int(t.answered), t.mark_x_mm, t.mark_y_mm,
                t.artery.c_str(), t.distance_mm, int(t.hit));
  return buf;
}

// The participant presses on the scene at `target` (palpating), marks a wrong spot first, marks
// again at `target` (the one mark moves), undoes (and, with `empty_done`, says Done without a
// mark, which hands nothing over), and marks again. Done is the caller's.
void palpate_and_mark(ParticipantScreen& screen, const Point2_mm& target, const Point2_mm& wrong,
                      bool empty_done = true) {
  LocalisationMarking& marking = *screen.marking();
  SceneView& view = *marking.scene_view();
  const QPoint at = view.pixel_of(target.x_mm, target.y_mm).toPoint();
  QTest::mousePress(&view, Qt::LeftButton, {}, at);
  QTest::mouseRelease(&view, Qt::LeftButton, {}, at);
  QTest::mouseClick(&view, Qt::RightButton, {}, view.pixel_of(wrong.x_mm, wrong.y_mm).toPoint());
  QTest::mouseClick(&view, Qt::RightButton, {}, at);
  QCOMPARE(marking.marks().size(), std::size_t(1));  // marking again moved the one mark
  QVERIFY(std::abs(marking.marks()[0].x_mm - target.x_mm) < 1.0);
  QTest::mouseClick(marking.findChild<QPushButton*>("undo_mark"), Qt::LeftButton);
  QCOMPARE(marking.marks().size(), std::size_t(0));
  if (empty_done) {
    QTest::mouseClick(marking.findChild<QPushButton*>("marks_done"), Qt::LeftButton);  // no mark: not handed over
    QVERIFY(screen.answering_position() >= 0);
  }
  QTest::mouseClick(&view, Qt::RightButton, {}, at);
}

// A point on the scored artery's centreline (the middle of its first segment), and one 30 mm
// across it (perpendicular to that segment).
std::pair<Point2_mm, Point2_mm> artery_point(const PulseProtocol& protocol, const std::string& condition_name) {
  for (const PulseCondition& c : protocol.conditions) {
    if (c.name != condition_name) continue;
    const SceneFile scene = load_scene_file(c.scene_file);
    const PulseField& arteries = *scene.scene->pulse();
    const int a = c.artery.empty() ? 0 : arteries.find(c.artery);
    const auto& path = arteries.artery(static_cast<std::size_t>(a)).spec().path;
    const Point2_mm on{0.5 * (path[0].x_mm + path[1].x_mm), 0.5 * (path[0].y_mm + path[1].y_mm)};
    const double dx = path[1].x_mm - path[0].x_mm, dy = path[1].y_mm - path[0].y_mm, len = std::hypot(dx, dy);
    return {on, Point2_mm{on.x_mm + 30.0 * dy / len, on.y_mm - 30.0 * dx / len}};  // across the artery
  }
  return {};
}

}  // namespace

class PulseConsoleTest : public QObject {
  Q_OBJECT
 private slots:
  void pulseMarkedByClicksIsScoredByDistanceToTheArtery() {
    TempDir dir;
    const std::string protocol_file = short_pulse(dir, 1);
    const std::string db = (dir.path() / "pulse.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol_file, "P01", db, 0});
    QVERIFY2(page.pulse_protocol() != nullptr, qPrintable(page.refusal_text()));
    const PulseProtocol protocol = *page.pulse_protocol();
    QTableWidget& table = *page.trial_table();
    QCOMPARE(table.rowCount(), 2);  // the plan, before Begin
    EndSeen ended(page);
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    std::vector<Point2_mm> clicked;
    for (int k = 0; k < 2; ++k) {
      QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == k; }),
               qPrintable(QString("trial %1 never presented").arg(k + 1)));
      SceneView& view = *screen.marking()->scene_view();
      QVERIFY(!view.arteries_visible());  // nothing gives the artery away
      QVERIFY(!view.tumors_visible());
      const auto [on, beside] = artery_point(protocol, table.item(k, 1)->text().toStdString());
      const Point2_mm target = k == 0 ? on : beside;  // the first a hit, the second a miss
      palpate_and_mark(screen, target, k == 0 ? beside : on, k == 1);
      if (k == 0 && std::getenv("PALPRIG_SCREENSHOT_DIR")) {
        // The README's picture: the participant screen on its own (full-screen) window.
        screen.show_full_screen_on(QGuiApplication::screens().back());
        QVERIFY(
            wait_until(*w.window, [&] { return screen.isWindow() && screen.marking()->scene_view()->height() > 250; }));
        // Only for the picture (no assertion waits on time): the offscreen platform lays the new
        // top-level window out over a few more event-loop passes than the wait above sees.
        QTest::qWait(300);
        keep_screenshot(screen, "participant_pulse.png");
        screen.back_to_console();
      }
      QTest::keyClick(&screen, Qt::Key_Return);  // Done
      clicked.push_back(target);
      QVERIFY(wait_until(*w.window, [&] { return committed_rows(table) == k + 1; }));
    }
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1 && !page.session_running(); }));
    QVERIFY(ended.end.completed);
    QCOMPARE(ended.end.committed_trials, 2);

    // The stored rows are score_pulse_mark of the marks on the scenes, as the CLI scores them.
    const auto trials = stored_pulse_trials(db);
    QCOMPARE(trials.size(), std::size_t(2));
    for (std::size_t k = 0; k < trials.size(); ++k) {
      const PulseTrialRecord& t = trials[k];
      QVERIFY(t.answered);
      QVERIFY(std::abs(t.mark_x_mm - clicked[k].x_mm) < 1.0 && std::abs(t.mark_y_mm - clicked[k].y_mm) < 1.0);
      const PulseCondition* c = nullptr;
      for (const auto& cond : protocol.conditions)
        if (cond.name == t.condition) c = &cond;
      QVERIFY(c != nullptr);
      const SceneFile scene = load_scene_file(c->scene_file);
      const PulseMarkScore score = score_pulse_mark(*scene.scene->pulse(), Point2_mm{t.mark_x_mm, t.mark_y_mm},
                                                    protocol.hit_radius_mm, c->artery);
      QCOMPARE(t.distance_mm, score.distance_mm);
      QCOMPARE(t.hit, score.hit);
      QCOMPARE(t.hit, k == 0);
      QCOMPARE(table.item(static_cast<int>(k), 4)->text(), QString::number(t.distance_mm, 'f', 1));
      QCOMPARE(table.item(static_cast<int>(k), 5)->text(), QString(t.hit ? "hit" : "miss"));
    }
    {
      SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
      QVERIFY(!store.find_participant("P01")->simulated);  // a person, stored as one
    }

    // The statistics view's numbers are `palprig stats trials`'s.
    StatisticsView& view = *page.statistics();
    QVERIFY(wait_until(*w.window, [&] {
      int n = 0;
      for (const auto& r : view.pulse_rows()) n += r.trials;
      return n == 2 && !view.refreshing();
    }));
    const auto r = test_support::run_process(test_support::palprig_bin() + " stats trials " + db + " --json");
    QVERIFY2(r.exit_code == 0, r.err.c_str());
    const auto j = nlohmann::json::parse(r.out);
    QCOMPARE(j["conditions"].size(), view.pulse_rows().size());
    for (std::size_t i = 0; i < view.pulse_rows().size(); ++i) {
      const PulseConditionSummary& s = view.pulse_rows()[i];
      const auto& c = j["conditions"][i];
      QCOMPARE(QString::fromStdString(c["condition"].get<std::string>()), QString::fromStdString(s.condition));
      QCOMPARE(c["trials"].get<int>(), s.trials);
      QCOMPARE(c["hits"].get<int>(), s.hits);
      QCOMPARE(c["hit_rate"].get<double>(), s.hit_rate);
      QCOMPARE(c["hit_rate_low"].get<double>(), s.hit_low);
      QCOMPARE(c["hit_rate_high"].get<double>(), s.hit_high);
      QCOMPARE(c["distance_mean_mm"].get<double>(), s.distance_mean_mm);
      QCOMPARE(c["distance_median_mm"].get<double>(), s.distance_median_mm);
    }
    // The Statistics JSON export is byte for byte `stats trials --json`.
    QSignalSpy exported(&view, &StatisticsView::exported);
    view.export_to(StatisticsView::ExportKind::statistics_json,
                   QString::fromStdString((dir.path() / "exports").string()));
    QVERIFY(exported.wait(30000));
    QCOMPARE(QString::fromStdString(test_support::read_file(dir.path() / "exports" / "statistics.json")),
             QString::fromStdString(r.out));
    auto* pulse_table = view.findChild<QTableWidget*>("pulseTable");
    QVERIFY(pulse_table && !pulse_table->isHidden());  // shown for a store with pulse trials
    QCOMPARE(pulse_table->rowCount(), 2);
    page.show_statistics();
    keep_screenshot(*w.window, "experiment_pulse_statistics.png");
  }

  void pulsePauseHoldsTheTrialAbortKeepsAndResumeContinuesAtTheExactTrial() {
    TempDir dir;
    const std::string protocol_file = short_pulse(dir, 2);  // 4 trials
    const std::string db = (dir.path() / "pulse.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol_file, "P02", db, 0});
    QVERIFY(page.pulse_protocol() != nullptr);
    const PulseProtocol protocol = *page.pulse_protocol();
    std::vector<int> started;
    connect(&page.session_run(), &SessionRun::pulseTrialStarted, &page,
            [&](const PulseTrialStart& s, const PulseCondition&) { started.push_back(s.position); });
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    QTest::mouseClick(page.findChild<QPushButton*>("pause_session"), Qt::LeftButton);
    QVERIFY(page.session_run().paused());
    QCOMPARE(screen.answering_position(), -1);  // nothing can be marked while paused
    auto* go_on = page.findChild<QPushButton*>("continue_session");
    QVERIFY(wait_until(*w.window, [&] { return go_on->isEnabled(); }));  // the session holds, vented
    QTest::mouseClick(go_on, Qt::LeftButton);
    // After a pause the participant says Ready again; then the held trial, from its start.
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QCOMPARE(started, std::vector<int>{0});
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return started.size() == 2 && screen.answering_position() == 0; }));
    QCOMPARE(started, (std::vector<int>{0, 0}));
    const QTableWidget& table = *page.trial_table();
    auto mark = [&](int row) {
      const auto [on, beside] = artery_point(protocol, table.item(row, 1)->text().toStdString());
      palpate_and_mark(screen, on, beside);
      QTest::keyClick(&screen, Qt::Key_Return);
    };
    mark(0);
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 1; }));
    EndSeen ended(page);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 1; }));
    abort_confirmed(page);
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1 && !page.session_running(); }));
    QVERIFY(ended.end.stopped);
    QCOMPARE(ended.end.committed_trials, 1);
    QCOMPARE(stored_pulse_trials(db).size(), std::size_t(1));

    // The console offers the unfinished session at trial 2, by itself and when the fields are set again.
    QVERIFY(page.resume_offered());
    QCOMPARE(page.offered_start_position(), 1);
    page.set_fields({protocol_file, "P02", db, 0});
    QVERIFY(page.resume_offered());
    QCOMPARE(page.offered_start_position(), 1);
    QCOMPARE(committed_rows(*page.trial_table()), 1);  // the committed row read back from the store
    QVERIFY(!page.findChild<QPushButton*>("begin_session")->isEnabled());
    started.clear();
    QTest::mouseClick(page.findChild<QPushButton*>("resume_session"), Qt::LeftButton);
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 1; }));
    QCOMPARE(started.front(), 1);  // the exact trial
    mark(1);
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 2; }));
    page.abort_and_wait();
    const auto trials = stored_pulse_trials(db);
    QCOMPARE(trials.size(), std::size_t(2));  // none lost, none twice
    QCOMPARE(trials[0].position, 0);
    QCOMPARE(trials[1].position, 1);
    SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
    QCOMPARE(store.list_sessions().size(), std::size_t(1));
  }

  void pulsePilotThroughTheWindowEqualsTheCliAndCliResumeContinues() {
    TempDir dir;
    const std::string protocol_file = data_dir() + "/protocols/pulse_localisation_000.json";
    const std::string db = (dir.path() / "pilot.db").string(), cli_db = (dir.path() / "cli.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol_file, "sim:5", db, 0});
    QCOMPARE(page.trial_table()->rowCount(), 10);
    QStringList planned;
    for (int r = 0; r < 10; ++r) planned << page.trial_table()->item(r, 1)->text();
    EndSeen ended(page);
    QVERIFY(page.begin(false));
    QVERIFY(wait_until(
        *w.window, [&] { return ended.count == 1 && !page.session_running(); }, 240));
    QVERIFY2(ended.end.completed, ended.end.fault.c_str());
    QCOMPARE(committed_rows(*page.trial_table()), 10);
    const auto c = test_support::run_process(test_support::palprig_bin() + " experiment run --protocol " +
                                             protocol_file + " --participant sim:5 --quiet --db " + cli_db);
    QVERIFY2(c.exit_code == 0, c.err.c_str());
    const auto gui_rows = stored_pulse_trials(db), cli_rows = stored_pulse_trials(cli_db);
    QCOMPARE(gui_rows.size(), std::size_t(10));
    QCOMPARE(cli_rows.size(), std::size_t(10));
    for (std::size_t i = 0; i < gui_rows.size(); ++i) {
      QCOMPARE(QString::fromStdString(row_text(gui_rows[i])), QString::fromStdString(row_text(cli_rows[i])));
      QCOMPARE(QString::fromStdString(gui_rows[i].condition), planned[static_cast<int>(i)]);  // the plan shown
    }
    {
      SqliteTrialStore store = open_sqlite_trial_store_for_reading(db);
      QVERIFY(store.find_participant("sim:5")->simulated);
    }

    // A pilot at a watchable speed, aborted after its first commit: `experiment run --resume`
    // continues at the exact trial.
    const std::string resumed_db = (dir.path() / "resumed.db").string();
    page.set_fields({protocol_file, "sim:6", resumed_db, 50});
    EndSeen stopped(page);
    // Aborted from the first commit's own signal, not from a poll of the trial list: a slow
    // (sanitizer) build on a busy machine saw the whole pilot end before its poll noticed.
    const QMetaObject::Connection abort_at_first =
        connect(&page, &ExperimentPage::trialCommitted, &page, [&page](int) { page.abort(); });
    QVERIFY(page.begin(false));
    QVERIFY(wait_until(
        *w.window, [&] { return stopped.count == 1 && !page.session_running(); }, 120));
    disconnect(abort_at_first);
    const auto kept = stored_pulse_trials(resumed_db);
    QVERIFY(!kept.empty() && kept.size() < 10);
    QVERIFY(page.resume_offered());
    QCOMPARE(page.offered_start_position(), static_cast<int>(kept.size()));
    const auto r = test_support::run_process(test_support::palprig_bin() + " experiment run --protocol " +
                                             protocol_file + " --participant sim:6 --resume --db " + resumed_db);
    QVERIFY2(r.exit_code == 0, (r.out + r.err).c_str());
    QVERIFY2(r.out.find("resumed at trial " + std::to_string(kept.size() + 1)) != std::string::npos, r.out.c_str());
    const auto after = stored_pulse_trials(resumed_db);
    QCOMPARE(after.size(), std::size_t(10));
    for (std::size_t i = 0; i < after.size(); ++i) QCOMPARE(after[i].position, static_cast<int>(i));
    for (std::size_t i = 0; i < kept.size(); ++i)
      QCOMPARE(QString::fromStdString(row_text(after[i])), QString::fromStdString(row_text(kept[i])));
  }
};

QTEST_MAIN(PulseConsoleTest)
#include "pulse_console_test.moc"
