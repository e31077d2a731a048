// Qt Test suite for the Training tab (gui/training_view, gui/experiment_page_training),
// offscreen (ctest gui.TrainingView.*). Real sessions: a simulated pilot trainee's sessions run
// by run_training_session on the experiment console's thread against the default simulated rig
// and a real SQLite store; the store is read back with the library the command line uses, and
// `palprig train status` runs as a real process over what the window stored. Tests wait on
// signals, never on fixed sleeps.
#include <QApplication>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QtTest>
#include <set>

#include <nlohmann/json.hpp>

#include "gui/chart_view.hpp"
#include "gui/experiment_page.hpp"
#include "gui/localisation_marking.hpp"
#include "gui/main_window.hpp"
#include "gui/participant_screen.hpp"
#include "gui/training_view.hpp"
#include "store/training_history.hpp"
#include "tests/gui/qt/console_support.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using namespace palprig::gui;
using palprig::test_support::TempDir;
using namespace palprig::gui::console_test;

namespace {

// Two levels of easy tumor cases, two cases a session, passed on one session that finds half the
// tumors; a pilot that learns fast.
std::string two_level_course(const TempDir& dir) {
  nlohmann::json level = {{"name", "easy"},         {"cases", {{"generate", "easy"}}},
                          {"cases_per_session", 2}, {"feedback", "none"},
                          {"time_limit_s", 60},     {"benchmark", {{"found_min", 0.5}, {"consecutive_sessions", 1}}}};
  nlohmann::json second = level;
  second["name"] = "easy again";
  const nlohmann::json doc = {{"version", 1},
                              {"kind", "curriculum"},
                              {"name", "window-course"},
                              {"levels", {level, second}},
                              {"pilot", {{"initial_skill", 0.9}, {"learning_rate_per_case", 1.0}}}};
  return dir.write("course.json", doc.dump(2)).string();
}

TrainingView& view(Window& w) { return *w.window->training_view(); }

// Starts the selected trainee's next session from the view and waits for its thread to end.
bool run_next(Window& w) {
  QSignalSpy finished(&w.page(), &ExperimentPage::trainingFinished);
  if (!view(w).start_next()) return false;
  if (w.window->pages()->currentWidget() != &w.page()) return false;  // the session shows on the console
  return finished.count() > 0 || finished.wait(120000);
}

}  // namespace

class TrainingViewTest : public QObject {
  Q_OBJECT

 private slots:
  // A trainer enrols a pilot in the tab, runs its sessions with a simulated trainee until it has
  // passed every level: each session is stored with its training row, the standings, the session
  // table and both charts follow, and no case is given twice.
  void pilotTrainsThroughTheCourseFromTheTab() {
    TempDir dir;
    const std::string course = two_level_course(dir);
    const std::string db = (dir.path() / "course.db").string();
    Window w = open_window();
    w.window->resize(1280, 800);
    w.window->pages()->setCurrentWidget(&view(w));
    view(w).set_files(QString::fromStdString(course), QString::fromStdString(db));
    QVERIFY2(view(w).refusal_text().isEmpty(), qPrintable(view(w).refusal_text()));
    QVERIFY(!view(w).start_button()->isEnabled());  // no trainee yet
    QVERIFY(view(w).enrol("P1"));
    QVERIFY(view(w).enrol("T01"));
    QCOMPARE(view(w).trainee_table()->rowCount(), 2);
    QVERIFY(view(w).select_trainee("P1"));
    QVERIFY(view(w).start_button()->isEnabled());
    QVERIFY(!view(w).curve_view()->has_data());
    QVERIFY(!view(w).cusum_view()->has_data());  // no case yet: no chart of a limit alone
    view(w).participant_edit()->setText("sim:5");

    int sessions = 0;
    while (!view(w).standing_text().contains("every level passed") && sessions < 6) {
      QVERIFY2(run_next(w), qPrintable(view(w).refusal_text() + " / " + w.page().refusal_text()));
      ++sessions;
      QVERIFY2(view(w).refusal_text().isEmpty(), qPrintable(view(w).refusal_text()));
      QCOMPARE(view(w).selected_trainee(), QString("P1"));  // kept through the reload
      QCOMPARE(view(w).session_table()->rowCount(), sessions);
      QVERIFY(view(w).findChild<QLabel*>("training_status")->text().contains("completed"));
    }
    QVERIFY2(view(w).standing_text().contains("every level passed"), qPrintable(view(w).standing_text()));
    QVERIFY(sessions >= 2);
    // The column counts marks where no tumor is: its header says so (a session that found every
    // tumor reads 0.00 there).
    QCOMPARE(view(w).session_table()->horizontalHeaderItem(4)->text(), QString("False marks/case"));
    QVERIFY(!view(w).start_button()->isEnabled());  // nothing left to run
    QVERIFY(!view(w).start_next());
    QVERIFY2(view(w).refusal_text().contains("passed every level"), qPrintable(view(w).refusal_text()));
    QVERIFY(view(w).curve_view()->has_data());
    QVERIFY(view(w).cusum_view()->has_data());
    view(w).chart_box()->setCurrentIndex(1);  // CUSUM (monitoring)
    QVERIFY(view(w).cusum_view()->has_data());
    view(w).measure_box()->setCurrentIndex(1);  // false marks per case
    QVERIFY(view(w).curve_view()->has_data());

    // What the window stored is the trainee's record, as the command line reads it.
    const Curriculum c = load_curriculum(course);
    const TraineeStanding p1 = trainee_standing(db, c, "P1");
    QCOMPARE(static_cast<int>(p1.sessions.size()), sessions);
    QVERIFY(p1.standing.finished);
    std::set<std::string> cases;
    for (const auto& s : p1.sessions) {
      QVERIFY(s.completed());
      for (const auto& k : s.cases) QVERIFY2(cases.insert(k).second, k.c_str());  // never twice
    }
    QCOMPARE(static_cast<int>(cases.size()), 2 * sessions);
    QCOMPARE(trainee_standing(db, c, "T01").standing.sessions, 0);
    const auto status =
        test_support::run_process(std::string(PALPRIG_BIN) + " train status --curriculum " + course + " --db " + db);
    QCOMPARE(status.exit_code, 0);
    QVERIFY2(status.out.find("every level passed") != std::string::npos, status.out.c_str());

    // The tab at 1280 x 800 (docs/training.md's picture): P1's tumors found and LC-CUSUM.
    view(w).reload();
    QVERIFY(view(w).select_trainee("P1"));
    view(w).measure_box()->setCurrentIndex(0);
    view(w).chart_box()->setCurrentIndex(0);
    view(w).participant_edit()->clear();
    w.window->pages()->setCurrentWidget(&view(w));
    keep_screenshot(*w.window, "training_view.png");
  }

  // A person's session from the tab: the participant screen shows the case's tissue without its
  // answer (no outlines), the trial list hides the answer key, and an abort keeps the session
  // for the next Start, which continues it with the same cases.
  void personSessionHidesTheAnswerAndContinuesAfterAnAbort() {
    TempDir dir;
    const std::string course = two_level_course(dir);
    const std::string db = (dir.path() / "course.db").string();
    Window w = open_window();
    view(w).set_files(QString::fromStdString(course), QString::fromStdString(db));
    QVERIFY(view(w).enrol("T02"));
    QVERIFY(view(w).select_trainee("T02"));
    QVERIFY(view(w).start_next());
    QCOMPARE(w.window->pages()->currentWidget(), static_cast<QWidget*>(&w.page()));
    QVERIFY(w.page().training_running());
    ParticipantScreen& screen = *w.page().participant_screen();
    QVERIFY(wait_until(*w.window, [&] { return screen.findChild<QPushButton*>("ready_button")->isVisible(); }));
    QVERIFY(w.page().answer_key_hidden());
    QVERIFY(!view(w).start_next());  // one session at a time
    QVERIFY(view(w).refusal_text().contains("running"));
    QSignalSpy finished(&w.page(), &ExperimentPage::trainingFinished);
    abort_confirmed(w.page());
    QVERIFY(finished.count() > 0 || finished.wait(60000));
    QVERIFY(view(w).standing_text().contains("unfinished"));
    const Curriculum c = load_curriculum(course);
    const TraineeStanding before = trainee_standing(db, c, "T02");
    QCOMPARE(static_cast<int>(before.sessions.size()), 1);
    QVERIFY(!before.sessions[0].completed());
    // Start again: the same session, its same cases (a pilot answers this time).
    view(w).participant_edit()->setText("sim:3");
    QVERIFY(run_next(w));
    const TraineeStanding after = trainee_standing(db, c, "T02");
    QCOMPARE(static_cast<int>(after.sessions.size()), 1);
    QVERIFY(after.sessions[0].completed());
    QCOMPARE(after.sessions[0].cases, before.sessions[0].cases);
  }

  // Refusals: one line, nothing stored changed.
  void refusalsAreOneLineAndChangeNothing() {
    TempDir dir;
    const std::string course = two_level_course(dir);
    const std::string db = (dir.path() / "course.db").string();
    Window w = open_window();
    // A bad curriculum: the line names the file and the field.
    auto bad = nlohmann::json::parse(test_support::read_file(course));
    bad["levels"][0]["cases_per_session"] = 0;
    const std::string bad_file = dir.write("bad.json", bad.dump()).string();
    view(w).set_files(QString::fromStdString(bad_file), QString::fromStdString(db));
    QVERIFY(view(w).refusal_text().contains("bad.json"));
    QVERIFY(view(w).refusal_text().contains("cases_per_session"));
    QVERIFY(!view(w).refusal_text().contains('\n'));
    QVERIFY(!view(w).enrol("T03"));
    QVERIFY(!std::filesystem::exists(db));  // nothing made
    // No trainee picked.
    view(w).set_files(QString::fromStdString(course), QString::fromStdString(db));
    QVERIFY(!view(w).start_next());
    QVERIFY(view(w).refusal_text().contains("pick a trainee"));
    // The store changed under the view (the trainee's record is on another file now): refused
    // at Start with the store's line, nothing stored.
    QVERIFY(view(w).enrol("T03"));
    QVERIFY(view(w).select_trainee("T03"));
    const auto size = std::filesystem::file_size(db);
    const std::string other = (dir.path() / "other.db").string();
    enrol_trainee(other, load_curriculum(course), "X9");
    view(w).findChild<QLineEdit*>("training_store")->setText(QString::fromStdString(other));
    QVERIFY(!view(w).start_next());
    QVERIFY2(view(w).refusal_text().contains("T03"), qPrintable(view(w).refusal_text()));
    QVERIFY(!w.page().session_running());
    QCOMPARE(std::filesystem::file_size(db), size);
    QCOMPARE(trainee_standing(other, load_curriculum(course), "X9").standing.sessions, 0);
  }
};

QTEST_MAIN(TrainingViewTest)
#include "training_view_test.moc"
