// Every reader of an outside file takes only a regular file no larger than its bound
// (io/regular_file.hpp): a 3 GiB sparse file, /dev/zero, a FIFO and a directory are each
// refused with one line naming the file and "a regular file of at most N", before anything is
// read. Without the check a FIFO blocks the reader for ever (the watchdog below then fails the
// case), /dev/zero and the sparse file run memory up to gigabytes, a directory gives the
// library's raw text.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "calibration/force_window.hpp"
#include "calibration/stress_fit.hpp"
#include "calibration/sweep_csv.hpp"
#include "controller/telemetry_writer.hpp"
#include "study/protocol.hpp"
#include "formats/calibration_file.hpp"
#include "formats/function_scene_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "inputs/input_source.hpp"
#include "inputs/tablet_source.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"
#include "statistics/csv_table.hpp"
#include "tests/support/run_process.hpp"
#include "tests/support/temp_dir.hpp"

using namespace palprig;
using palprig::test_support::palprig_bin;
using palprig::test_support::run_process;
using palprig::test_support::TempDir;

namespace {

struct Reader {
  const char* kind;
  const char* extension;  // the readers that choose by extension get it
  std::function<void(const std::filesystem::path&)> read;
  std::uintmax_t sparse_bytes = std::uintmax_t(3) << 30;  // 3 GiB, past every bound but telemetry's
};

const std::vector<Reader>& readers() {
  static const std::vector<Reader> list = {
      {"map CSV", ".csv", [](const auto& p) { (void)load_stiffness_map_file(p, 10, 10, 0); }},
      {"map PGM", ".pgm", [](const auto& p) { (void)load_stiffness_map_file(p, 10, 10, 0); }},
      {"scene JSON", ".json", [](const auto& p) { (void)load_scene_file(p); }},
      {"rig", ".json", [](const auto& p) { (void)load_rig_file(p); }},
      {"calibration", ".json", [](const auto& p) { (void)load_calibration_file(p); }},
      {"protocol", ".json", [](const auto& p) { (void)load_protocol(p); }},
      {"trace", ".csv", [](const auto& p) { (void)load_trace_csv(p); }},
      {"stats CSV", ".csv", [](const auto& p) { (void)CsvTable::read(p); }},
      {"evemu", ".evemu", [](const auto& p) { (void)read_pen_recording(p); }},
      {"waveform", ".csv", [](const auto& p) { (void)load_waveform_csv(p); }},
      {"stress pairs CSV", ".csv", [](const auto& p) { (void)read_stress_pairs_csv(p); }},
      {"force presses CSV", ".csv", [](const auto& p) { (void)force_window_from_presses(p); }},
      {"sweep CSV", ".csv", [](const auto& p) { (void)read_sweep_csv(p); }},
      // Telemetry is streamed record by record; its bound is what the writer may write (4 GiB).
      {"telemetry binary", ".bin", [](const auto& p) { (void)convert_telemetry_to_csv(p, p.string() + ".out.csv"); },
       kMaxTelemetryFileBytes + 1},
  };
  return list;
}

// The reader's refusal, or "accepted"; a reader still blocked after 10 s fails the case (and is
// released by opening the FIFO for writing, so the test program ends).
std::string refusal(const Reader& r, const std::filesystem::path& p) {
  auto future = std::async(std::launch::async, [&]() -> std::string {
    try {
      r.read(p);
    } catch (const InputError& e) {
      return e.what();
    } catch (const std::exception& e) {
      return std::string("not an InputError: ") + e.what();
    }
    return "accepted";
  });
  if (future.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << r.kind << " blocked on " << p;
    const int fd = ::open(p.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  return future.get();
}

}  // namespace

TEST(UnboundedReads, EveryReaderRefusesASparseGiantAFifoADirectoryAndDevZero) {
  TempDir dir;
  for (const Reader& r : readers()) {
    SCOPED_TRACE(r.kind);
    const std::string ext = r.extension;
    const auto sparse = dir.path() / ("sparse" + ext);
    std::ofstream(sparse).close();
    std::filesystem::resize_file(sparse, r.sparse_bytes);  // a hole, no disk used
    const auto fifo = dir.path() / ("fifo" + ext);
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto folder = dir.path() / ("folder" + ext);
    std::filesystem::create_directories(folder);
    const auto zero = dir.path() / ("zero" + ext);
    std::filesystem::remove(zero);
    std::filesystem::create_symlink("/dev/zero", zero);
    const std::vector<std::pair<std::filesystem::path, std::string>> cases = {
        {sparse, std::to_string(r.sparse_bytes) + " bytes"},
        {fifo, "a FIFO"},
        {folder, "a directory"},
        {zero, "a device"}};
    for (const auto& [path, kind] : cases) {
      SCOPED_TRACE(path.string());
      const std::string why = refusal(r, path);
      EXPECT_EQ(why.rfind(path.string() + ": file: a regular file of at most ", 0), 0u) << why;
      EXPECT_NE(why.find(kind), std::string::npos) << why;
      EXPECT_EQ(why.find('\n'), std::string::npos) << why;
    }
    std::filesystem::remove(sparse);
  }
}

TEST(UnboundedReads, TheBoundIsNamedWithItsSize) {
  TempDir dir;
  const auto f = dir.write("t.csv", "a,b\n1,2\n");
  std::filesystem::resize_file(f, kMaxTableFileBytes + 1);
  EXPECT_EQ(refusal(readers()[7], f), f.string() +
                                          ": file: a regular file of at most 64 MiB holding a CSV table, got " +
                                          std::to_string(kMaxTableFileBytes + 1) + " bytes");
  EXPECT_EQ(file_size_text(16 * kMiB), "16 MiB");
  EXPECT_EQ(file_size_text(1024 * 1024 + 1024), "1025 KiB");
  EXPECT_EQ(regular_file_problem(dir.path() / "none", 10), "no such file");
  // A regular file within its bound is read whole.
  const auto small = dir.write("s.csv", "a,b\n1,2\n");
  EXPECT_EQ(read_regular_file(small, 8, "x"), "a,b\n1,2\n");
  EXPECT_THROW(read_regular_file(small, 7, "x"), InputError);
}

// From the command line: a directory as --rig or --protocol, a FIFO as --scene, /dev/zero as a
// stats CSV; one line of palprig's own, exit 2, at once.
TEST(UnboundedReads, TheCommandLineSaysOneLineAndExitsTwo) {
  TempDir dir;
  const auto folder = dir.path() / "folder.json";
  std::filesystem::create_directories(folder);
  const auto fifo = dir.path() / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string data = std::string(PALPRIG_SOURCE_DIR) + "/data/";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" run --rig " + folder.string() + " --scene " + data + "scenes/phantom_abc.json", folder.string()},
      {" experiment run --protocol " + folder.string() + " --participant sim:1 --db " + (dir.path() / "t.db").string(),
       folder.string()},
      {" run --scene " + fifo.string(), fifo.string()},
      {" stats ttest /dev/zero --column x --against 0", "/dev/zero"}};
  for (const auto& [args, file] : cases) {
    SCOPED_TRACE(args);
    const auto r = run_process("timeout 20 " + palprig_bin() + args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("palprig: " + file + ": file: a regular file of at most ", 0), 0u) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "t.db"));  // nothing was written
}
