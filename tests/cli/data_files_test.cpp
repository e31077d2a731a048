// Shipped files found by name (cli/data_files.cpp), as an installed palprig needs them: from a
// folder far from the clone, --protocol NAME, --scene NAME, --rig NAME and --input trace:NAME
// find the shipped files; $PALPRIG_DATA_DIR comes first; a path is taken as given; an unknown
// name is one line and exit 2; `palprig data list` says where the files are taken from; and
// --version names the version and the commit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig::test_support;

namespace {

// palprig run from FOLDER with no PALPRIG_* variable but those given.
ProcessResult palprig_in(const std::filesystem::path& folder, const std::string& args, const std::string& env = "") {
  return run_process("cd " + folder.string() + " && env -u PALPRIG_DATA_DIR -u PALPRIG_DATA " + env + " " +
                     palprig_bin() + " " + args);
}

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

}  // namespace

TEST(DataFiles, ShippedFilesByNameFromAnEmptyFolder) {
  TempDir dir;
  const ProcessResult session = palprig_in(
      dir.path(), "experiment run --protocol discrimination_002 --participant sim:1 --db s.db --rig simulated --quiet");
  ASSERT_EQ(session.exit_code, 0) << session.err;
  EXPECT_NE(session.out.find("stiffness-discrimination-002, participant sim:1"), std::string::npos) << session.out;
  EXPECT_NE(session.out.find("session 1 completed: 32 trials in s.db"), std::string::npos) << session.out;

  const ProcessResult run =
      palprig_in(dir.path(), "run --scene phantom_abc --input trace:phantom_abc_pass --rig simulated --cal paper002");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("phantom_abc"), std::string::npos) << run.out;
}

TEST(DataFiles, DataDirComesBeforeTheShippedFiles) {
  TempDir dir;
  const auto own = dir.path() / "lab-data" / "protocols";
  std::filesystem::create_directories(own);
  std::ifstream shipped(source_dir() + "/data/protocols/discrimination_002.json");
  std::string text((std::istreambuf_iterator<char>(shipped)), std::istreambuf_iterator<char>());
  const std::string name = "\"stiffness-discrimination-002\"";
  ASSERT_NE(text.find(name), std::string::npos);
  text.replace(text.find(name), name.size(), "\"our-lab-discrimination\"");
  std::ofstream(own / "discrimination_002.json") << text;

  const std::string env = "PALPRIG_DATA_DIR=" + (dir.path() / "lab-data").string();
  const ProcessResult r =
      palprig_in(dir.path(), "experiment run --protocol discrimination_002 --participant sim:1 --db s.db --quiet", env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("our-lab-discrimination, participant sim:1"), std::string::npos) << r.out;

  // The lab's folder lacks rigs/: the default rig and --rig NAME still come from the shipped files.
  const ProcessResult list = palprig_in(dir.path(), "data list", env);
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_EQ(first_line(list.out), "palprig data: " + (dir.path() / "lab-data").string() + " ($PALPRIG_DATA_DIR)");
}

TEST(DataFiles, APathIsTakenAsGivenAndAnUnknownNameIsOneLine) {
  TempDir dir;
  const ProcessResult unknown =
      palprig_in(dir.path(), "experiment run --protocol discrimination_003 --participant sim:1 --db s.db");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
  EXPECT_NE(unknown.err.find("--protocol: 'discrimination_003' is neither a file nor the name of a shipped file in "),
            std::string::npos)
      << unknown.err;
  EXPECT_NE(unknown.err.find("(palprig data list protocols)"), std::string::npos) << unknown.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "s.db"));

  // A value with a '/' is a path, even when a shipped file has its last name: the reader says it is missing.
  const ProcessResult path =
      palprig_in(dir.path(), "experiment run --protocol ./discrimination_002.json --participant sim:1 --db s.db");
  EXPECT_EQ(path.exit_code, 2);
  EXPECT_NE(path.err.find("./discrimination_002.json"), std::string::npos) << path.err;

  // A file name found nowhere is left to its reader, which names the missing file.
  const ProcessResult file =
      palprig_in(dir.path(), "experiment run --protocol my_study.json --participant sim:1 --db s.db");
  EXPECT_EQ(file.exit_code, 2);
  EXPECT_NE(file.err.find("my_study.json: file:"), std::string::npos) << file.err;
  EXPECT_EQ(file.err.find("neither a file"), std::string::npos) << file.err;

  // A file of that name in the folder is the file meant, not the shipped one.
  std::ofstream(dir.path() / "discrimination_002") << "{}";
  const ProcessResult local =
      palprig_in(dir.path(), "experiment run --protocol discrimination_002 --participant sim:1 --db s.db");
  EXPECT_EQ(local.exit_code, 2);
  EXPECT_NE(local.err.find("discrimination_002"), std::string::npos) << local.err;
  EXPECT_EQ(local.err.find("stiffness-discrimination-002"), std::string::npos) << local.err;
}

TEST(DataFiles, DataListNamesEveryKindFromTheSourceTree) {
  TempDir dir;
  const ProcessResult r = palprig_in(dir.path(), "data list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(first_line(r.out), "palprig data: " + source_dir() + "/data (source tree)");
  for (const char* line :
       {"  protocols: discrimination_002 discrimination_002_confidence localisation_002",
        "  scenes: brachial_pulse fe_depths groin_femoral liver_edge phantom_abc phantom_abc_function",
        "  traces: phantom_abc_pass", "  waveforms: brachial_pressure", "  curricula: palpation_basics",
        "  fe: actuator_002 fingertip_002 soft_tissue_002 soft_tissue_002_nodule stress_model_002 stress_table_002"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  const ProcessResult rigs = palprig_in(dir.path(), "data list rigs");
  ASSERT_EQ(rigs.exit_code, 0) << rigs.err;
  EXPECT_NE(rigs.out.find(source_dir() + "/data/rigs/simulated.json"), std::string::npos) << rigs.out;
  EXPECT_EQ(palprig_in(dir.path(), "data list recipes").exit_code, 2);
}

// The finite-element model's files by name too (data/fe): palprig check reads the shipped fingertip,
// and an unknown one is the same one line naming the kind to list.
TEST(DataFiles, FiniteElementFilesAndCurriculaByName) {
  TempDir dir;
  const ProcessResult fe =
      palprig_in(dir.path(), "fe indent --fingertip fingertip_00 --tissue soft_tissue_002 --out o");
  EXPECT_EQ(fe.exit_code, 2);
  EXPECT_NE(fe.err.find("--fingertip: 'fingertip_00' is neither a file nor the name of a shipped file in "),
            std::string::npos)
      << fe.err;
  EXPECT_NE(fe.err.find("(palprig data list fe)"), std::string::npos) << fe.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "o"));
  const ProcessResult fit =
      palprig_in(dir.path(), "calibrate fit none.csv --stress-model stress_model_002 --out c.json");
  EXPECT_EQ(fit.err.find("stress_model_002' is neither"), std::string::npos) << fit.err;
  const ProcessResult unknown =
      palprig_in(dir.path(), "train enrol --curriculum palpation_basic --trainee T01 --db t.db");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("(palprig data list curricula)"), std::string::npos) << unknown.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "t.db"));
  const ProcessResult enrol =
      palprig_in(dir.path(), "train enrol --curriculum palpation_basics --trainee T01 --db t.db");
  EXPECT_EQ(enrol.exit_code, 0) << enrol.err;
  EXPECT_NE(enrol.out.find("T01 enrolled in"), std::string::npos) << enrol.out;
}

TEST(DataFiles, VersionNamesTheCommit) {
  const ProcessResult r = run_process(palprig_bin() + " --version");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(
      std::regex_search(r.out, std::regex(R"(^palprig [0-9]+\.[0-9]+\.[0-9]+ \(commit [0-9a-f]{12}(-dirty)?\)\n$)")))
      << r.out;
}
