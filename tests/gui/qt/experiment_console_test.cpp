// Over 400 lines: one Qt Test class (QTest runs a class's slots as its cases), whose flows share
// the store, the simulated rig and the participant screen of its fixtures.
// Qt Test suite for the experiment console and the participant screens (gui/experiment_page,
// gui/participant_screen, gui/localisation_marking), offscreen (ctest gui.ExperimentConsole.*).
// Sessions run for real: run_study_session on its own thread against the default simulated rig
// and a real SQLite trial store; answers are QTest clicks and keys; the command line runs as a
// real process. Tests wait on signals, never on fixed sleeps.
#include <QApplication>
#include <QLabel>
#include <QMessageBox>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTimer>
#include <QLineEdit>
#include <QTabBar>
#include <QTabWidget>
#include <QtTest>
#include <chrono>
#include <algorithm>
#include <functional>
#include <memory>

#include <nlohmann/json.hpp>

#include "gui/experiment_page.hpp"
#include "gui/calibration_page.hpp"
#include "gui/live_page.hpp"
#include "gui/localisation_marking.hpp"
#include "gui/rig_panel.hpp"
#include "gui/main_window.hpp"
#include "gui/participant_screen.hpp"
#include "gui/scene_view.hpp"
#include "store/trial_store.hpp"
#include "tests/gui/qt/console_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace palprig::gui;
using palprig::test_support::TempDir;
using namespace palprig::gui::console_test;

namespace {

// The shipped discrimination protocol cut to 3 combinations x 2 conditions with short timings,
// so a person's session (real time) takes seconds.
std::string short_discrimination(const TempDir& dir, double inter_trial_s = 0.05) {
  auto doc = nlohmann::json::parse(test_support::read_file(data_dir() + "/protocols/discrimination_002.json"));
  doc["combinations"]["list_kPa"] = {{0, 30, 0}, {0, 0, 0}, {30, 10, 10}};
  doc["practice_trials"] = 0;
  doc["timing"] = {{"max_present_s", 0.2},     {"sequential_step_s", 0.05},      {"sequential_gap_s", 0.02},
                   {"response_timeout_s", 60}, {"inter_trial_s", inter_trial_s}, {"break_s", 0}};
  return dir.write("short.json", doc.dump(2)).string();
}

// The shipped confidence protocol (4 rating levels) cut like short_discrimination; the
// stimulus is on for `present_s` (simultaneous) before the participant may answer.
std::string short_confidence(const TempDir& dir, double present_s = 0.2) {
  auto doc =
      nlohmann::json::parse(test_support::read_file(data_dir() + "/protocols/discrimination_002_confidence.json"));
  doc["combinations"]["list_kPa"] = {{0, 30, 0}, {0, 0, 0}, {30, 30, 0}};
  doc["practice_trials"] = 0;
  doc["timing"] = {{"max_present_s", present_s},     {"sequential_step_s", 0.05}, {"sequential_gap_s", 0.02},
                   {"response_timeout_s", 60},       {"inter_trial_s", 0.05},     {"break_s", 0},
                   {"answer_during_stimulus", false}};  // as the shipped file: a fixed-length stimulus
  return dir.write("rated.json", doc.dump(2)).string();
}

std::string short_localisation(const TempDir& dir) {
  auto doc = nlohmann::json::parse(test_support::read_file(data_dir() + "/protocols/localisation_002.json"));
  doc["localisation"]["scene"] = data_dir() + "/scenes/phantom_abc.json";
  doc["timing"]["inter_trial_s"] = 0.05;
  return dir.write("loc.json", doc.dump(2)).string();
}

// The stored trials without what depends on the wall clock (times, felt pressures, dates).
std::vector<std::string> stored_rows(const std::string& db) {
  std::vector<std::string> rows;
  const auto store = open_trial_store(db, TrialStore::Access::read_only);
  for (const StoredTrial& t : store->read_trials(true)) {
    rows.push_back(t.participant + "|" + std::to_string(t.simulated) + "|" + std::to_string(t.participant_number) +
                   "|" + std::to_string(t.position) + "|" + std::to_string(t.block) + "|" + t.condition + "|" + t.mode +
                   "|" + std::to_string(t.practice) + "|" + t.combination_label + "|" + t.truth + "|" + t.answer + "|" +
                   std::to_string(t.answered) + "|" + t.outcome[0] + t.outcome[1] + t.outcome[2] + "|" +
                   (t.confidence ? std::to_string(*t.confidence) : std::string("-")));
  }
  return rows;
}

// `palprig stats trials DB --json` without the response-time figures (a person's times differ).
nlohmann::json stats_without_times(const std::string& db) {
  const auto r = test_support::run_process(test_support::palprig_bin() + " stats trials " + db + " --json");
  if (r.exit_code != 0) return {{"error", r.err}};
  nlohmann::json j = nlohmann::json::parse(r.out);
  std::function<void(nlohmann::json&)> strip = [&](nlohmann::json& v) {
    if (v.is_object()) {
      for (auto it = v.begin(); it != v.end();) {
        const std::string key = it.key();
        if (key.find("rt") == 0 || key.find("response_time") != std::string::npos ||
            key.find("time") != std::string::npos)
          it = v.erase(it);
        else {
          strip(*it);
          ++it;
        }
      }
    } else if (v.is_array()) {
      for (auto& e : v) strip(e);
    }
  };
  strip(j);
  // The response-time tests between conditions come from the times too.
  if (j.contains("comparisons"))
    j["comparisons"].erase(std::remove_if(j["comparisons"].begin(), j["comparisons"].end(),
                                          [](const nlohmann::json& c) { return c.value("measure", "") == "RT"; }),
                           j["comparisons"].end());
  return j;
}

// Answers one discrimination trial through the participant screen: "0" by key, "13" by keys
// and Enter, "2" by clicking the finger button and Answer.
void answer_by_hand(ParticipantScreen& screen, const std::string& answer, int style) {
  if (answer == "0") {
    if (style % 2 == 0)
      QTest::keyClick(&screen, Qt::Key_0);
    else
      QTest::mouseClick(screen.findChild<QPushButton*>("none_button"), Qt::LeftButton);
    return;
  }
  for (char c : answer) {
    if (style % 2 == 0)
      QTest::keyClick(&screen, Qt::Key(Qt::Key_0 + (c - '0')));
    else
      QTest::mouseClick(screen.findChild<QPushButton*>(QString("finger_%1").arg(c)), Qt::LeftButton);
  }
  if (style % 2 == 0)
    QTest::keyClick(&screen, Qt::Key_Return);
  else
    QTest::mouseClick(screen.findChild<QPushButton*>("answer_button"), Qt::LeftButton);
}

// The rating step after the finger answer: key `rating` (even styles) or its button.
void rate_by_hand(MainWindow& w, ParticipantScreen& screen, int rating, int style) {
  QVERIFY(wait_until(
      w, [&] { return screen.rating(); }, 30.0));
  auto* button = screen.findChild<QPushButton*>(QString("confidence_%1").arg(rating));
  QVERIFY(button != nullptr && button->isVisible() && button->isEnabled());
  if (style % 2 == 0)
    QTest::keyClick(&screen, Qt::Key(Qt::Key_0 + rating));
  else
    QTest::mouseClick(button, Qt::LeftButton);
}

}  // namespace

class ExperimentConsoleTest : public QObject {
  Q_OBJECT
 private slots:
  void planShownBeforeBeginIsTheCliPlan() {
    TempDir dir;
    const std::string protocol = short_discrimination(dir);
    Window w = open_window();
    w.page().set_fields({protocol, "P07", (dir.path() / "p.db").string(), 0});
    QTableWidget& table = *w.page().trial_table();
    QCOMPARE(table.rowCount(), 6);
    const auto r = test_support::run_process(test_support::palprig_bin() + " experiment plan --protocol " + protocol +
                                             " --participant P07");
    QCOMPARE(r.exit_code, 0);
    const QStringList lines = QString::fromStdString(r.out).trimmed().split('\n');
    QCOMPARE(lines.size(), 7);
    for (int row = 0; row < 6; ++row) {
      const QStringList cli = lines[row + 1].split(',');
      QCOMPARE(table.item(row, 2)->text(), cli[2]);  // condition
      QCOMPARE(table.item(row, 3)->text(), cli[5]);  // stimulus
      QCOMPARE(table.item(row, 4)->text(), cli[6]);  // tumor fingers
    }
  }

  void clickedSessionEqualsTheCliSession() {
    TempDir dir;
    const std::string protocol = short_discrimination(dir);
    const std::vector<std::string> answers = {"2", "0", "13", "1", "23", "0"};
    const std::string gui_db = (dir.path() / "gui.db").string(), cli_db = (dir.path() / "cli.db").string();

    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "P01", gui_db, 0});
    EndSeen ended(page);
    // Where the plan has a break (between the condition blocks) the participant says Ready again.
    const auto plan = test_support::run_process(test_support::palprig_bin() + " experiment plan --protocol " +
                                                protocol + " --participant P01");
    const QStringList plan_lines = QString::fromStdString(plan.out).trimmed().split('\n');
    QCOMPARE(plan_lines.size(), 7);
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    std::string typed;  // the same, typed at the terminal
    for (int k = 0; k < int(answers.size()); ++k) {
      if (k == 0 || plan_lines[k].split(',').at(7) == "1") {
        QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
        QTest::keyClick(&screen, Qt::Key_Space);
        typed += "\n";
      }
      QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == k; }),
               qPrintable(QString("trial %1 never asked").arg(k + 1)));
      if (k == 3) {
        QTest::keyClick(&screen, Qt::Key_2);  // chosen, not yet answered: seen on the screenshot
        keep_screenshot(*w.window, "experiment_console.png");
        keep_screenshot(screen, "participant_screen.png");
        QTest::keyClick(&screen, Qt::Key_2);  // and unchosen again
      }
      answer_by_hand(screen, answers[static_cast<std::size_t>(k)], k);
      typed += answers[static_cast<std::size_t>(k)] + "\n";
      QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == k + 1; }));
    }
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1 && !page.session_running(); }));
    QVERIFY(ended.end.completed);
    QCOMPARE(ended.end.committed_trials, 6);

    // The command line, the same participant code (same seed and order), the same answers typed.
    const auto input = dir.write("answers.txt", typed);
    const auto r =
        test_support::run_process("(" + test_support::palprig_bin() + " experiment run --protocol " + protocol +
                                  " --participant P01 --db " + cli_db + " < " + input.string() + ")");
    QVERIFY2(r.exit_code == 0, (r.out + r.err).c_str());

    const auto gui_rows = stored_rows(gui_db), cli_rows = stored_rows(cli_db);
    QCOMPARE(gui_rows.size(), std::size_t(6));
    for (std::size_t i = 0; i < gui_rows.size(); ++i)
      QCOMPARE(QString::fromStdString(gui_rows[i]), QString::fromStdString(cli_rows[i]));
    QCOMPARE(QString::fromStdString(stats_without_times(gui_db).dump()),
             QString::fromStdString(stats_without_times(cli_db).dump()));
    // The console's list shows the same answers.
    QCOMPARE(page.files_written(), QStringList{QString::fromStdString(gui_db)});
  }

  void pauseVentsHoldsAndContinuesTheSameTrial() {
    TempDir dir;
    const std::string protocol = short_discrimination(dir);
    const std::string db = (dir.path() / "p.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "P02", db, 0});
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::mouseClick(ready, Qt::LeftButton);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    std::vector<int> started;
    connect(&page.session_run(), &SessionRun::trialStarted, &page,
            [&](int position, const PlannedTrial&, const Condition&) { started.push_back(position); });
    QTest::mouseClick(page.findChild<QPushButton*>("pause_session"), Qt::LeftButton);
    QVERIFY(page.session_run().paused());
    QCOMPARE(screen.answering_position(), -1);  // nothing can be answered while paused
    auto* go_on = page.findChild<QPushButton*>("continue_session");
    QVERIFY(wait_until(*w.window, [&] { return go_on->isEnabled(); }));  // the loop holds, vented
    QTest::mouseClick(go_on, Qt::LeftButton);
    // Continue alone presents nothing: the participant is asked for Ready again first.
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QVERIFY(started.empty());
    QCOMPARE(screen.answering_position(), -1);
    QTest::mouseClick(ready, Qt::LeftButton);
    QVERIFY(wait_until(*w.window, [&] { return !started.empty(); }));
    QCOMPARE(started.front(), 0);  // the held trial, presented again
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    QTest::keyClick(&screen, Qt::Key_0);
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 1; }));
    EndSeen ended(page);
    abort_confirmed(page);
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1; }));
    QVERIFY(ended.end.stopped);
    QCOMPARE(ended.end.committed_trials, 1);
    QCOMPARE(stored_rows(db).size(), std::size_t(1));
    // The console now offers to resume at trial 2, by itself and when the fields are set again.
    QVERIFY(wait_until(*w.window, [&] { return !page.session_running(); }));
    QVERIFY(page.resume_offered());
    QVERIFY(page.findChild<QPushButton*>("resume_session")->isEnabled());
    QVERIFY(!page.findChild<QPushButton*>("begin_session")->isEnabled());
    page.set_fields({protocol, "P02", db, 0});
    QVERIFY(page.resume_offered());
    QCOMPARE(page.offered_start_position(), 1);
  }

  // Paused before the participant's first Ready: the loop holds (Continue enabled), and after
  // Continue the first trial still waits for Ready.
  void pauseWhileWaitingForReadyCanContinue() {
    TempDir dir;
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({short_discrimination(dir), "P07", (dir.path() / "p.db").string(), 0});
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::mouseClick(page.findChild<QPushButton*>("pause_session"), Qt::LeftButton);
    auto* go_on = page.findChild<QPushButton*>("continue_session");
    QVERIFY(wait_until(*w.window, [&] { return go_on->isEnabled(); }));
    QTest::mouseClick(go_on, Qt::LeftButton);
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::mouseClick(ready, Qt::LeftButton);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    EndSeen ended(page);
    abort_confirmed(page);
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1; }));
    QCOMPARE(ended.end.committed_trials, 0);
  }

  void participantScreenLeavesTheConsoleAndComesBack() {
    TempDir dir;
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({short_discrimination(dir), "P05", (dir.path() / "p.db").string(), 0});
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    QWidget* console_box = screen.parentWidget();
    screen.show_full_screen_on(QGuiApplication::screens().back());
    QVERIFY(screen.isWindow());
    QVERIFY(!screen.in_console());
    // The participant answers on their own screen while the console stays.
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    QTest::keyClick(&screen, Qt::Key_0);
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 1; }));
    screen.back_to_console();
    QVERIFY(!screen.isWindow());
    QCOMPARE(screen.parentWidget(), console_box);
    page.abort_and_wait();
  }

  void closingMidSessionAsksVentsAndKeepsWhatWasCommitted() {
    TempDir dir;
    const std::string protocol = short_discrimination(dir);
    const std::string db = (dir.path() / "p.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "P03", db, 0});
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    for (int k = 0; k < 2; ++k) {
      QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == k; }));
      QTest::keyClick(&screen, Qt::Key_0);
    }
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 2; }));
    // First "No": the window stays and the session goes on; then "Yes".
    bool asked_no = false, asked_yes = false;
    QTimer::singleShot(0, [&] {
      QVERIFY(w.window->close_question());
      asked_no = true;
      w.window->close_question()->button(QMessageBox::No)->click();
    });
    QVERIFY(!w.window->close());
    QVERIFY(asked_no);
    QVERIFY(page.session_running());
    QTimer::singleShot(0, [&] {
      QVERIFY(w.window->close_question());
      asked_yes = true;
      w.window->close_question()->button(QMessageBox::Yes)->click();
    });
    QVERIFY(w.window->close());
    QVERIFY(asked_yes);
    QVERIFY(!page.session_running());
    QCOMPARE(stored_rows(db).size(), std::size_t(2));
    const auto store = open_trial_store(db, TrialStore::Access::read_only);
    const auto sessions = store->list_sessions();
    QCOMPARE(sessions.size(), std::size_t(1));
    QCOMPARE(QString::fromStdString(sessions[0].status), QString("running"));  // resumable
  }

  void killedGuiResumesAtTheRightTrial() {
    TempDir dir;
    const std::string protocol = short_discrimination(dir, 0.4);
    const std::string db = (dir.path() / "p.db").string();
    QProcess gui;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("QT_QPA_PLATFORM", "offscreen");
    gui.setProcessEnvironment(env);
    gui.start(QString::fromStdString(test_support::palprig_bin()),
              {"gui", "--protocol", QString::fromStdString(protocol), "--participant", "sim:11", "--db",
               QString::fromStdString(db), "--speed", "1"});
    QVERIFY(gui.waitForStarted(10000));
    // Wait (polling the database the GUI writes) until two trials are committed, then kill -9.
    std::size_t before = 0;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (before < 2 && std::chrono::steady_clock::now() < end) {
      gui.waitForFinished(50);  // returns at once if it exited; otherwise a 50 ms wait on the process
      if (std::filesystem::exists(db)) {
        try {
          before = stored_rows(db).size();
        } catch (const std::exception&) {
          // the schema may not be complete yet
        }
      }
    }
    QVERIFY2(before >= 2, gui.readAllStandardError().constData());
    gui.kill();  // SIGKILL
    QVERIFY(gui.waitForFinished(10000));
    QCOMPARE(gui.exitStatus(), QProcess::CrashExit);
    const auto kept = stored_rows(db);
    QVERIFY(kept.size() >= 2 && kept.size() < 6);

    const auto png = dir.path() / "resumed.png";
    const auto r = test_support::run_process("QT_QPA_PLATFORM=offscreen " + test_support::palprig_bin() +
                                             " gui --protocol " + protocol + " --participant sim:11 --db " + db +
                                             " --resume --screenshot " + png.string() + " --after-s 120");
    QVERIFY2(r.exit_code == 0, (r.out + r.err).c_str());
    QVERIFY2(r.out.find("resumed at trial " + std::to_string(kept.size() + 1)) != std::string::npos, r.out.c_str());
    QVERIFY2(r.out.find("session completed: 6 of 6") != std::string::npos, r.out.c_str());
    QVERIFY(std::filesystem::file_size(png) > 1000);
    const auto after = stored_rows(db);
    QCOMPARE(after.size(), std::size_t(6));  // none lost, none twice
    for (std::size_t i = 0; i < kept.size(); ++i)
      QCOMPARE(QString::fromStdString(after[i]), QString::fromStdString(kept[i]));
    const auto store = open_trial_store(db, TrialStore::Access::read_only);
    const auto trials = store->read_trials(true);
    for (int p = 0; p < 6; ++p) QCOMPARE(trials[static_cast<std::size_t>(p)].position, p);
    QCOMPARE(QString::fromStdString(store->list_sessions().at(0).status), QString("completed"));
  }

  void pilotScreenshotRunsTheSimulatedParticipantThroughTheWindow() {
    TempDir dir;
    const auto png = dir.path() / "pilot.png";
    const std::string db = (dir.path() / "pilot.db").string();
    const auto r = test_support::run_process("QT_QPA_PLATFORM=offscreen " + test_support::palprig_bin() +
                                             " gui --protocol " + data_dir() + "/protocols/discrimination_002.json" +
                                             " --participant sim:3 --db " + db + " --screenshot " + png.string() +
                                             " --after-s 120 --session-telemetry " + (dir.path() / "gui.bin").string());
    QVERIFY2(r.exit_code == 0, (r.out + r.err).c_str());
    QVERIFY2(r.out.find("session completed: 32 of 32") != std::string::npos, r.out.c_str());
    QVERIFY2(r.out.find("palprig gui: telemetry: ") != std::string::npos, r.out.c_str());
    QVERIFY(std::filesystem::file_size(png) > 1000);
    const auto rows = stored_rows(db);
    QCOMPARE(rows.size(), std::size_t(32));
    QVERIFY(rows[0].find("sim:3|1|") == 0);  // stored as simulated
    // The same seed through the command line gives the same trials.
    const std::string cli_db = (dir.path() / "cli.db").string();
    const auto c = test_support::run_process(test_support::palprig_bin() + " experiment run --protocol " + data_dir() +
                                             "/protocols/discrimination_002.json --participant sim:3 --quiet --db " +
                                             cli_db + " --telemetry " + (dir.path() / "cli.bin").string());
    QVERIFY2(c.exit_code == 0, c.err.c_str());
    QCOMPARE(stored_rows(cli_db), rows);
    // The session's telemetry: the same ticks on simulated time (record for record in number; the
    // wake-up and I/O times in each record are measured, so the bytes differ).
    QVERIFY(std::filesystem::file_size(dir.path() / "gui.bin") > 100000);
    QCOMPARE(std::filesystem::file_size(dir.path() / "gui.bin"), std::filesystem::file_size(dir.path() / "cli.bin"));
  }

  // A real window on a real X server with two displays: one Xvfb screen split into two RandR
  // monitors (as a desktop with two monitors is), 1600x1000 and 1280x800 beside it, and no window
  // manager. `--participant-display 2` puts the participant screen over exactly the second
  // display; the console stays on the first.
  void participantScreenFillsTheSecondDisplayUnderXvfb() {
    if (std::system("command -v xvfb-run >/dev/null 2>&1 && command -v xrandr >/dev/null 2>&1") != 0)
      QSKIP("xvfb-run or xrandr is not installed (packages xvfb, x11-xserver-utils)");
    TempDir dir;
    const std::string protocol = short_discrimination(dir);
    // The simulated rig, patient with a machine that stalls (under the sanitizers a virtual
    // machine once lost 100 ms and the loop vented, as it must on a rig): where the participant
    // screen goes is what this test is about.
    auto rig = nlohmann::json::parse(test_support::read_file(data_dir() + "/rigs/simulated.json"));
    rig["safety"]["max_lost_time_s"] = 10;
    rig["safety"]["max_consecutive_overruns"] = 100000;
    const std::string rig_path = dir.write("rig.json", rig.dump()).string();
    const std::string gui = "env QT_QPA_PLATFORM=xcb " + test_support::palprig_bin() + " gui --protocol " + protocol +
                            " --rig " + rig_path + " --participant P08 --db " + (dir.path() / "p.db").string() +
                            " --json --screenshot " + (dir.path() / "s.png").string() + " --after-s 1";
    // -noreset: the monitors set by xrandr would go with a server reset when xrandr disconnects.
    auto under_two_displays = [&](const std::string& display) {
      const auto script = dir.write("two_displays.sh",
                                    "set -e\n"
                                    "xrandr --setmonitor A 1600/400x1000/250+0+0 none\n"
                                    "xrandr --setmonitor B 1280/300x800/200+1600+0 none\n" +
                                        gui + " --participant-display " + display + "\n");
      return test_support::run_process("xvfb-run -a -s '-noreset -screen 0 2880x1000x24' bash " + script.string());
    };
    const auto r = under_two_displays("2");
    if (r.exit_code != 0 && (r.err.find("xvfb-run: error") != std::string::npos ||
                             r.err.find("could not connect to display") != std::string::npos))
      QSKIP(qPrintable("Xvfb could not start here: " + QString::fromStdString(r.err).left(200)));
    QVERIFY2(r.exit_code == 0, (r.out + r.err).c_str());
    const auto json_at = r.out.find('{');
    QVERIFY2(json_at != std::string::npos, r.out.c_str());
    const auto summary = nlohmann::json::parse(r.out.substr(json_at));
    const auto& p = summary.at("participant_screen");
    QVERIFY2(p.at("own_window").get<bool>(), r.out.c_str());
    QVERIFY2(p.at("full_screen").get<bool>(), r.out.c_str());
    QCOMPARE(p.at("display").get<int>(), 2);
    QVERIFY2(p.at("display_geometry") == (nlohmann::json{1600, 0, 1280, 800}), r.out.c_str());
    QVERIFY2(p.at("window_geometry") == p.at("display_geometry"), r.out.c_str());  // covers exactly the second display
    QCOMPARE(p.at("console_display").get<int>(), 1);
    const auto& console = p.at("console_window_geometry");
    QVERIFY2(console.at(0).get<int>() + console.at(2).get<int>() <= 1600, r.out.c_str());  // within the first display
    // A display the server does not have (A, B and the whole screen's own monitor: 3): one line, exit 2.
    const auto bad = under_two_displays("4");
    QCOMPARE(bad.exit_code, 2);
    QVERIFY2(bad.err.find("participant-display") != std::string::npos, bad.err.c_str());
  }

  void refusedProtocolExitsTwoWithOneLine() {
    TempDir dir;
    const auto bad = dir.write("bad.json", R"({"version": 1, "name": "x", "task": "discrimination", "repetitons": 2})");
    const auto r =
        test_support::run_process("QT_QPA_PLATFORM=offscreen " + test_support::palprig_bin() + " gui --protocol " +
                                  bad.string() + " --participant sim:1 --db " + (dir.path() / "x.db").string() +
                                  " --screenshot " + (dir.path() / "x.png").string());
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.find("bad.json") != std::string::npos, r.err.c_str());
    QVERIFY(!std::filesystem::exists(dir.path() / "x.db"));
  }

  void ratedSessionByClicksAndKeysEqualsTheCliSession() {
    TempDir dir;
    const std::string protocol = short_confidence(dir);
    const std::vector<std::string> answers = {"2", "0", "12", "1", "0", "2"};
    const std::vector<int> ratings = {4, 1, 3, 2, 4, 1};
    const std::string gui_db = (dir.path() / "gui.db").string(), cli_db = (dir.path() / "cli.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "R01", gui_db, 0});
    EndSeen ended(page);
    const auto plan = test_support::run_process(test_support::palprig_bin() + " experiment plan --protocol " +
                                                protocol + " --participant R01");
    const QStringList plan_lines = QString::fromStdString(plan.out).trimmed().split('\n');
    QCOMPARE(plan_lines.size(), 7);
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    std::string typed;
    for (int k = 0; k < int(answers.size()); ++k) {
      if (k == 0 || plan_lines[k].split(',').at(7) == "1") {
        QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
        QTest::keyClick(&screen, Qt::Key_Space);
        typed += "\n";
      }
      QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == k; }),
               qPrintable(QString("trial %1 never asked").arg(k + 1)));
      answer_by_hand(screen, answers[static_cast<std::size_t>(k)], k);
      if (k == 2) {
        keep_screenshot(screen, "participant_rating.png");
        // Nothing is handed over before the rating: the trial is still open.
        QCOMPARE(committed_rows(*page.trial_table()), k);
        QTest::keyClick(&screen, Qt::Key_9);  // not a level: ignored
        QTest::keyClick(&screen, Qt::Key_Return);
        QVERIFY(screen.rating());
      }
      rate_by_hand(*w.window, screen, ratings[static_cast<std::size_t>(k)], k + 1);
      typed +=
          answers[static_cast<std::size_t>(k)] + "\n" + std::to_string(ratings[static_cast<std::size_t>(k)]) + "\n";
      QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == k + 1; }));
      // The console's list shows the rating and the RT after the stimulus.
      QTableWidget& table = *page.trial_table();
      QCOMPARE(table.item(k, 9)->text(), QString::number(ratings[static_cast<std::size_t>(k)]));
      bool ok = false;
      const double after_s = table.item(k, 8)->text().toDouble(&ok);
      QVERIFY(ok);
      QVERIFY(after_s >= 0.0 && after_s < table.item(k, 7)->text().toDouble());
    }
    keep_screenshot(*w.window, "experiment_console_rated.png");
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1 && !page.session_running(); }));
    QVERIFY(ended.end.completed);

    const auto input = dir.write("answers.txt", typed);
    const auto r =
        test_support::run_process("(" + test_support::palprig_bin() + " experiment run --protocol " + protocol +
                                  " --participant R01 --db " + cli_db + " < " + input.string() + ")");
    QVERIFY2(r.exit_code == 0, (r.out + r.err).c_str());
    const auto gui_rows = stored_rows(gui_db), cli_rows = stored_rows(cli_db);
    QCOMPARE(gui_rows.size(), std::size_t(6));
    for (std::size_t i = 0; i < gui_rows.size(); ++i)
      QCOMPARE(QString::fromStdString(gui_rows[i]), QString::fromStdString(cli_rows[i]));
    const auto gui_stats = stats_without_times(gui_db);
    QCOMPARE(QString::fromStdString(gui_stats.dump()), QString::fromStdString(stats_without_times(cli_db).dump()));
    QCOMPARE(gui_stats["rows"][0]["rated"].get<int>() + gui_stats["rows"][1]["rated"].get<int>(), 6);
    // Every GUI answer came after its stimulus ended.
    const auto store = open_trial_store(gui_db, TrialStore::Access::read_only);
    for (const StoredTrial& t : store->read_trials(true)) {
      QVERIFY(t.stimulus_end_s && t.response_time_s);
      QVERIFY(t.onset_s + *t.response_time_s >= *t.stimulus_end_s);
    }
  }

  // Paper 002's three-finger trials (timing.answer_during_stimulus true, the default): the
  // stimulus stays until the answer, so the buttons are on while it is presented and the answer
  // ends it (after-stimulus RT 0), as the terminal and the runner have it.
  void simultaneousStimulusIsAnsweredWhileItIsOn() {
    TempDir dir;
    auto doc = nlohmann::json::parse(test_support::read_file(short_discrimination(dir)));
    doc["timing"]["max_present_s"] = 30;
    const std::string protocol = dir.write("long.json", doc.dump(2)).string();
    const std::string db = (dir.path() / "p.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "S01", db, 0});
    std::vector<RunnerState> states;
    connect(&page.session_run(), &SessionRun::runnerState, &page, [&](RunnerState s, int) { states.push_back(s); });
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    QVERIFY(!states.empty() && states.back() == RunnerState::present);  // 30 s stimulus, still on
    QVERIFY(screen.findChild<QPushButton*>("none_button")->isEnabled());
    QTest::keyClick(&screen, Qt::Key_0);
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 1; }));
    page.abort_and_wait();
    const auto store = open_trial_store(db, TrialStore::Access::read_only);
    const auto trials = store->read_trials(true);
    QCOMPARE(trials.size(), std::size_t(1));
    QVERIFY(trials[0].response_time_s && *trials[0].response_time_s < 29.0);
    QVERIFY(trials[0].stimulus_end_s);
    QVERIFY(std::abs(*trials[0].stimulus_end_s - (trials[0].onset_s + *trials[0].response_time_s)) < 1e-9);
  }

  // "feedback": "all": after each committed trial the participant is told how it went, in the
  // words the terminal prints (experiments/trial_feedback); without it only "Answer recorded."
  void feedbackIsShownOnlyWhenTheProtocolAsks() {
    TempDir dir;
    auto doc = nlohmann::json::parse(test_support::read_file(short_discrimination(dir, 1.0)));
    doc["feedback"] = "all";
    const std::string protocol = dir.write("feedback.json", doc.dump(2)).string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "F01", (dir.path() / "f.db").string(), 0});
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* prompt = screen.findChild<QLabel*>("participant_prompt");
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    for (int k = 0; k < 2; ++k) {
      QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == k; }));
      QTest::keyClick(&screen, Qt::Key_0);
      QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == k + 1; }));
      // The trial list's Tumor column says where the tumor was: "none" when there was none.
      const bool no_tumor = page.trial_table()->item(k, 4)->text() == "none";
      const QString expected = no_tumor ? "Correct." : "Not quite: the tumor was under";
      QVERIFY2(wait_until(*w.window, [&] { return prompt->text().startsWith(expected); }),
               qPrintable(prompt->text() + " / tumor column: " + page.trial_table()->item(k, 4)->text()));
    }
    page.abort_and_wait();
  }

  void answerButtonsDisabledWhilePresenting() {
    TempDir dir;
    const std::string protocol = short_confidence(dir, 1.5);
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "R02", (dir.path() / "p.db").string(), 0});
    std::vector<RunnerState> states;
    connect(&page.session_run(), &SessionRun::runnerState, &page, [&](RunnerState s, int) { states.push_back(s); });
    QVERIFY(page.begin(false));
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return !states.empty() && states.back() == RunnerState::present; }));
    QVERIFY(wait_until(*w.window,
                       [&] { return screen.findChild<QLabel*>("participant_prompt")->text().startsWith("Trial 1"); }));
    // Presenting: nothing can be answered, by click or key.
    for (const char* name : {"finger_1", "finger_2", "finger_3", "none_button", "answer_button"}) {
      QVERIFY2(!screen.findChild<QPushButton*>(name)->isEnabled(), name);
    }
    QCOMPARE(screen.answering_position(), -1);
    QTest::keyClick(&screen, Qt::Key_0);
    QTest::mouseClick(screen.findChild<QPushButton*>("none_button"), Qt::LeftButton);
    QVERIFY(!screen.rating());
    QVERIFY(states.back() == RunnerState::present);  // still presenting: the keys did nothing
    keep_screenshot(screen, "participant_presenting.png");
    // The stimulus ends: the buttons come on.
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    QVERIFY(states.back() == RunnerState::respond);
    for (const char* name : {"finger_1", "none_button", "answer_button"}) {
      QVERIFY2(screen.findChild<QPushButton*>(name)->isEnabled(), name);
    }
    QTest::keyClick(&screen, Qt::Key_0);
    rate_by_hand(*w.window, screen, 2, 0);
    QVERIFY(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 1; }));
    page.abort_and_wait();
    const auto store = open_trial_store((dir.path() / "p.db").string(), TrialStore::Access::read_only);
    const auto trials = store->read_trials(true);
    QCOMPARE(trials.size(), std::size_t(1));
    QCOMPARE(trials[0].confidence.value_or(0), 2);
    QVERIFY(*trials[0].stimulus_end_s - trials[0].onset_s > 1.49);
  }

  void localisationMarkedByClicksIsScoredPerTumor() {
    TempDir dir;
    const std::string protocol = short_localisation(dir);
    const std::string db = (dir.path() / "loc.db").string();
    Window w = open_window();
    ExperimentPage& page = w.page();
    page.set_fields({protocol, "P04", db, 0});
    EndSeen ended(page);
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    ParticipantScreen& screen = *page.participant_screen();
    LocalisationMarking& marking = *screen.marking();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    QVERIFY(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(*w.window, [&] { return screen.answering_position() == 0; }));
    SceneView& view = *marking.scene_view();
    QVERIFY(!view.tumors_visible());
    // Palpate with the pen (left button), then mark tumor B and a false spot, undo, mark again.
    const auto scene = load_scene_file(data_dir() + "/scenes/phantom_abc.json");
    QPointF b, far;
    for (const TumorTruth& t : scene.tumors)
      if (t.name == "B") b = view.pixel_of(t.x_mm, t.y_mm);
    far = view.pixel_of(scene.scene->bounds().x0_mm + 2, scene.scene->bounds().y0_mm + 2);
    QTest::mousePress(&view, Qt::LeftButton, {}, b.toPoint());
    QTest::mouseRelease(&view, Qt::LeftButton, {}, b.toPoint());
    QTest::mouseClick(&view, Qt::RightButton, {}, far.toPoint());
    QTest::mouseClick(&view, Qt::RightButton, {}, b.toPoint());
    QCOMPARE(marking.marks().size(), std::size_t(2));
    QTest::mouseClick(marking.findChild<QPushButton*>("undo_mark"), Qt::LeftButton);
    QCOMPARE(marking.marks().size(), std::size_t(1));
    QTest::mouseClick(&view, Qt::RightButton, {}, b.toPoint());
    keep_screenshot(screen, "participant_localisation.png");
    QTest::mouseClick(marking.findChild<QPushButton*>("marks_done"), Qt::LeftButton);
    QVERIFY(wait_until(*w.window, [&] { return ended.count == 1; }));
    QVERIFY(ended.end.completed);
    const auto store = open_trial_store(db, TrialStore::Access::read_only);
    const auto trials = store->read_trials(true);
    QCOMPARE(trials.size(), std::size_t(1));
    QCOMPARE(trials[0].false_marks.value_or(-1), std::int64_t(1));
    QCOMPARE(trials[0].marks.size(), std::size_t(2));
    std::map<std::string, std::string> outcome(trials[0].tumor_outcomes.begin(), trials[0].tumor_outcomes.end());
    QCOMPARE(QString::fromStdString(outcome["A"]), QString("FN"));
    QCOMPARE(QString::fromStdString(outcome["B"]), QString("TP"));
    QCOMPARE(QString::fromStdString(outcome["C"]), QString("FN"));
  }

  // The flow of the crash report: a person's localisation session to its end, then a
  // discrimination session with a new participant and database in the same window; the
  // participant's keys reach the participant whatever has the focus (the Live rig tab shown and
  // back, a key sent to the Abort button); Space after Pause does not abort; Abort asks first;
  // "Resume session" continues; every answer is stored once. Runs under ASan in make test-asan.
  // A lab's 1280 x 800 screen holds the window in every state: each tab, a localisation
  // session's marking screen, a discrimination session, the statistics. The window is never
  // made larger than that by its own layout (a minimum size above it would grow it off the
  // screen). PALPRIG_SCREENSHOT_DIR keeps each state as docs/ shows it.
  void windowFitsA1280x800ScreenInEveryState() {
    TempDir dir;
    Window w = open_window();
    MainWindow& win = *w.window;
    win.resize(1280, 800);
    ExperimentPage& page = w.page();
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    auto fits = [&](const char* state, const char* picture) {
      QCoreApplication::sendPostedEvents();
      QCoreApplication::processEvents();
      const QSize hint = win.minimumSizeHint(), size = win.size();
      keep_screenshot(win, picture);
      return QString("%1: window %2x%3, its minimum %4x%5")
          .arg(state)
          .arg(size.width())
          .arg(size.height())
          .arg(hint.width())
          .arg(hint.height());
    };
    // What holds the window up, when it does not fit: each widget whose minimum is large.
    std::function<void(QWidget*, int)> dump = [&](QWidget* wdg, int depth) {
      const QSize h = wdg->minimumSizeHint(), m = wdg->minimumSize();
      if (h.width() > 500 || h.height() > 300 || m.width() > 500 || m.height() > 300)
        qInfo("%*s%s %s: minimum hint %dx%d, minimum %dx%d", depth * 2, "", wdg->metaObject()->className(),
              qPrintable(wdg->objectName()), h.width(), h.height(), m.width(), m.height());
      for (QObject* c : wdg->children())
        if (auto* cw = qobject_cast<QWidget*>(c); cw && cw->isVisibleTo(&win)) dump(cw, depth + 1);
    };
    auto check = [&](const char* state, const char* picture) {
      const QString what = fits(state, picture);
      if (win.height() > 800 || win.width() > 1280) dump(&win, 0);
      QVERIFY2(win.width() <= 1280 && win.height() <= 800, qPrintable(what));
      QVERIFY2(win.minimumSizeHint().width() <= 1280 && win.minimumSizeHint().height() <= 800, qPrintable(what));
    };
    win.pages()->setCurrentIndex(0);
    check("live rig", "window_live_rig.png");
    win.pages()->setCurrentWidget(win.calibration_page());
    check("calibration", "window_calibration.png");
    win.pages()->setCurrentWidget(&page);
    page.set_fields({short_localisation(dir), "L01", (dir.path() / "loc.db").string(), 0});
    check("experiment, planned", "window_experiment_planned.png");
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    QVERIFY(wait_until(win, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(win, [&] { return screen.answering_position() == 0; }));
    check("localisation session", "window_localisation_session.png");
    abort_confirmed(page);
    QVERIFY(wait_until(win, [&] { return !page.session_running(); }));
    page.set_fields({short_discrimination(dir), "D01", (dir.path() / "disc.db").string(), 0});
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    QVERIFY(wait_until(win, [&] { return ready->isVisible() && ready->isEnabled(); }));
    QTest::keyClick(&screen, Qt::Key_Space);
    QVERIFY(wait_until(win, [&] { return screen.answering_position() == 0; }));
    QTest::keyClick(&screen, Qt::Key_2);
    QTest::keyClick(&screen, Qt::Key_Return);
    QVERIFY(wait_until(win, [&] { return committed_rows(*page.trial_table()) == 1; }));
    check("discrimination session", "window_discrimination_session.png");
    win.pages()->setCurrentIndex(0);
    check("live rig during a session", "window_live_rig_during_session.png");
    win.pages()->setCurrentWidget(&page);
    page.show_statistics();
    check("statistics", "window_statistics.png");
    abort_confirmed(page);
    QVERIFY(wait_until(win, [&] { return !page.session_running(); }));
    keep_screenshot(screen, "participant_screen.png");
  }

  void personFlowLocalisationThenDiscriminationWithPauseTabSwitchAndResume() {
    TempDir dir;
    Window w = open_window();
    ExperimentPage& page = w.page();
    ParticipantScreen& screen = *page.participant_screen();
    auto* ready = screen.findChild<QPushButton*>("ready_button");
    EndSeen ended(page);  // every session's end, counted
    {                     // 1. localisation, one trial, one mark
      page.set_fields({short_localisation(dir), "L01", (dir.path() / "loc.db").string(), 0});
      QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
      QVERIFY2(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }), "step 1");
      QTest::keyClick(&screen, Qt::Key_Space);
      QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == 0; }), "step 2");
      SceneView& view = *screen.marking()->scene_view();
      QTest::mouseClick(&view, Qt::RightButton, {}, view.rect().center());
      QTest::mouseClick(screen.marking()->findChild<QPushButton*>("marks_done"), Qt::LeftButton);
      QVERIFY2(wait_until(*w.window, [&] { return ended.count == 1; }), "step 3");
      QVERIFY(ended.end.completed);
      QVERIFY2(wait_until(*w.window, [&] { return !page.session_running(); }), "step 4");
    }
    // 2. discrimination, a new participant and database
    const std::string db = (dir.path() / "disc.db").string();
    page.set_fields({short_discrimination(dir), "D01", db, 0});
    QVERIFY2(page.begin(false), qPrintable(page.refusal_text()));
    auto* abort_button = page.findChild<QPushButton*>("abort_session");
    QVERIFY2(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }), "step 5");
    QTest::keyClick(abort_button, Qt::Key_Space);  // Ready, though the key went to Abort
    QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == 0; }), "step 6");
    QVERIFY(page.session_running());
    {  // The participant screen shares this window (one display here): the answer key is hidden
       // until the experimenter shows it.
      QTableWidget& table = *page.trial_table();
      auto key_hidden = [&] { return table.isColumnHidden(3) && table.isColumnHidden(4) && table.isColumnHidden(6); };
      QVERIFY(page.answer_key_hidden() && key_hidden());
      QVERIFY(!table.isColumnHidden(2) && !table.isColumnHidden(5));  // condition and answer stay
      QPushButton* show_key = page.show_answer_key_button();
      QVERIFY(show_key->isVisible());
      QTest::mouseClick(show_key, Qt::LeftButton);
      QVERIFY(!page.answer_key_hidden() && !table.isColumnHidden(3) && !table.isColumnHidden(4));
      QTest::mouseClick(show_key, Qt::LeftButton);
      QVERIFY(page.answer_key_hidden() && key_hidden());
      // The experimenter sees the pressures the session delivers: the live page follows its ticks.
      LivePage& live = *w.window->live_page();
      const std::size_t seen = live.history().size();
      QVERIFY2(wait_until(*w.window, [&] { return live.history().size() > seen + 20; }),
               "the live page got no session ticks");
      QVERIFY(live.rig_panel()->findChild<QLabel*>("rig_state")->text().startsWith("study session"));
      QVERIFY(!live.rig_panel()->arm_button()->isEnabled());
      QVERIFY(live.rig_panel()->vent_button()->isEnabled());
    }
    // The experimenter looks at the Live rig tab and comes back: keys still answer.
    w.window->pages()->setCurrentIndex(0);
    w.window->pages()->setCurrentWidget(w.window->experiment_page());
    QTest::keyClick(w.window->pages()->tabBar(), Qt::Key_1);
    QTest::keyClick(w.window->pages()->tabBar(), Qt::Key_Return);
    QVERIFY2(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 1; }), "step 7");
    // Pause; Space (wherever the focus went) neither aborts nor presents anything.
    QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == 1; }), "step 8");
    QTest::mouseClick(page.findChild<QPushButton*>("pause_session"), Qt::LeftButton);
    auto* go_on = page.findChild<QPushButton*>("continue_session");
    QVERIFY2(wait_until(*w.window, [&] { return go_on->isEnabled(); }), "step 9");
    QWidget* focus = QApplication::focusWidget() ? QApplication::focusWidget() : abort_button;
    QTest::keyClick(focus, Qt::Key_Space);
    QTest::keyClick(abort_button, Qt::Key_Space);
    QVERIFY(page.session_running());
    QVERIFY(abort_question(page) == nullptr);
    QTest::mouseClick(go_on, Qt::LeftButton);
    QVERIFY2(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }), "step 10");
    QTest::keyClick(go_on, Qt::Key_Space);
    QVERIFY2(wait_until(*w.window, [&] { return screen.answering_position() == 1; }), "step 11");
    QTest::keyClick(page.trial_table(), Qt::Key_0);
    QVERIFY2(wait_until(*w.window, [&] { return committed_rows(*page.trial_table()) == 2; }), "step 12");
    // Abort asks; "No" keeps the session, "Yes" ends it.
    QTest::mouseClick(abort_button, Qt::LeftButton);
    QMessageBox* ask = abort_question(page);
    QVERIFY(ask);
    keep_screenshot(*ask, "abort_confirmation.png");
    keep_screenshot(*w.window, "console_abort_asked.png");
    ask->button(QMessageBox::No)->click();
    QVERIFY(page.session_running());
    QVERIFY(abort_question(page) == nullptr);
    QTest::mouseClick(abort_button, Qt::LeftButton);
    ask = abort_question(page);
    QVERIFY(ask);
    ask->button(QMessageBox::Yes)->click();
    QVERIFY2(wait_until(*w.window, [&] { return ended.count == 2 && !page.session_running(); }), "step 14");
    QCOMPARE(ended.end.committed_trials, 2);
    // 3. "Resume session" continues at trial 3 of the same session.
    auto* resume = page.findChild<QPushButton*>("resume_session");
    QVERIFY2(wait_until(*w.window, [&] { return resume->isVisible() && resume->isEnabled(); }), "step 15");
    QTest::mouseClick(resume, Qt::LeftButton);
    QVERIFY2(wait_until(*w.window, [&] { return ready->isVisible() && ready->isEnabled(); }), "step 16");
    QTest::keyClick(resume, Qt::Key_Space);
    for (int k = 2; k < 6; ++k) {  // the rest of the 6 trials, keys sent to whatever widget
      // A new block asks for Ready again: Space, wherever the focus is.
      QVERIFY2(wait_until(*w.window,
                          [&] {
                            if (ready->isVisible() && ready->isEnabled()) QTest::keyClick(abort_button, Qt::Key_Space);
                            return screen.answering_position() == k;
                          }),
               "step 17");
      QTest::keyClick(k % 2 ? static_cast<QWidget*>(page.trial_table()) : static_cast<QWidget*>(&screen), Qt::Key_0);
    }
    QVERIFY2(wait_until(*w.window, [&] { return ended.count == 3; }),
             qPrintable(QString("step 18: %1 ends; status '%2'")
                            .arg(ended.count)
                            .arg(page.findChild<QLabel*>("session_status")->text())));
    QVERIFY(ended.end.completed);
    const auto store = open_trial_store(db, TrialStore::Access::read_only);
    const auto trials = store->read_trials(true);
    QCOMPARE(trials.size(), std::size_t(6));
    for (int i = 0; i < 6; ++i) QCOMPARE(trials[static_cast<std::size_t>(i)].position, i);  // each once, in order
    QCOMPARE(QString::fromStdString(trials[0].answer), QString("100"));  // key 1 via the tab bar, then Enter
    // The keyboard is the experimenter's again: a digit reaches an ordinary widget.
    QVERIFY2(wait_until(*w.window, [&] { return !page.session_running(); }), "step 19");
    QVERIFY(!page.answer_key_hidden() && !page.trial_table()->isColumnHidden(3));  // the key is back after the session
    QVERIFY(!page.show_answer_key_button()->isVisible());
    auto* participant = page.findChild<QLineEdit*>("participant_code");
    if (participant) {
      participant->setFocus();
      participant->clear();
      QTest::keyClick(participant, Qt::Key_7);
      QCOMPARE(participant->text(), QString("7"));
    }
  }
};

QTEST_MAIN(ExperimentConsoleTest)
#include "experiment_console_test.moc"
