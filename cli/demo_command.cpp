// palprig demo: the bundled phantom (tumors A, B, C), a pen trace passing over them and the
// default simulated rig, with a table showing that fingers over a tumor get more pressure than
// fingers over soft tissue. No hardware, no display.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

#include "cli/commands.hpp"
#include "controller/run_report.hpp"
#include "controller/run_setup.hpp"

using namespace palprig;

namespace {

// Accumulates, per tumor and for soft tissue, the pressures of fingers that lie over it.
class RegionTable final : public TickObserver {
 public:
  RegionTable(const std::vector<TumorTruth>& tumors, const FingerLayout& layout, double soft_margin_mm)
      : tumors_(tumors), layout_(layout), margin_mm_(soft_margin_mm), rows_(tumors.size() + 1) {}

  void on_tick(const TelemetryRecord& r) noexcept override {
    if (!(r.flags & kInContact)) return;
    const auto fingers = layout_.centres(r.x_mm, r.y_mm);
    for (int f = 0; f < kFingerCount; ++f) {
      bool near_any = false;
      for (std::size_t t = 0; t < tumors_.size(); ++t) {
        const double d = std::hypot(fingers[f].x_mm - tumors_[t].x_mm, fingers[f].y_mm - tumors_[t].y_mm);
        if (d <= tumors_[t].radius_mm) rows_[t].add(r.target_kPa[f], r.monitor_kPa[f]);
        if (d <= tumors_[t].radius_mm + margin_mm_) near_any = true;
      }
      if (!near_any) rows_.back().add(r.target_kPa[f], r.monitor_kPa[f]);
    }
  }

  struct Row {
    std::uint64_t n = 0;
    double target_sum = 0, target_max = 0, plant_sum = 0, plant_max = 0;
    void add(double target, double plant) noexcept {
      ++n;
      target_sum += target;
      plant_sum += plant;
      target_max = std::max(target_max, target);
      plant_max = std::max(plant_max, plant);
    }
    double target_mean() const { return n ? target_sum / double(n) : 0; }
    double plant_mean() const { return n ? plant_sum / double(n) : 0; }
  };
  const std::vector<Row>& rows() const { return rows_; }

 private:
  const std::vector<TumorTruth>& tumors_;
  FingerLayout layout_;
  double margin_mm_;
  std::vector<Row> rows_;
};

}  // namespace

void register_demo_command(CLI::App& app) {
  auto out_dir = std::make_shared<std::string>("/tmp/palprig-demo");
  auto json_out = std::make_shared<bool>(false);
  CLI::App* sub = app.add_subcommand(
      "demo", "Run the bundled phantom (tumors A, B, C) with a recorded pen pass on the simulated rig and show the "
              "pressure each finger got over each tumor and over soft tissue");
  sub->add_option("--out", *out_dir, "Directory for the telemetry file")->default_val("/tmp/palprig-demo");
  sub->add_flag("--json", *json_out, "Print the run summary and the table as JSON");
  auto cal_file = std::make_shared<std::string>();
  auto compensate = std::make_shared<bool>(false);
  sub->add_option("--cal", *cal_file, "Calibration file (JSON); default: paper 002's models (with --compensate-lag: "
                                      "the simulated rig's calibration, data/calibration/sim-default.json)");
  sub->add_flag("--compensate-lag", *compensate,
                "Lag-compensate the whole target with the calibration's identified regulator dynamics");
  sub->callback([=]() {
    const auto data = cli::data_dir();
    RunFiles files;
    files.scene = data / "scenes" / "phantom_abc.json";
    files.input = "trace:" + (data / "traces" / "phantom_abc_pass.csv").string();
    files.rig = data / "rigs" / "simulated.json";
    files.calibration = !cal_file->empty()  ? std::filesystem::path(*cal_file)
                        : *compensate         ? data / "calibration" / "sim-default.json"
                                              : data / "calibration" / "paper002.json";
    if (*compensate) files.compensate_lag = true;
    LoadedRun run = load_run(files);
    for (const auto& note : run.lag_compensation_notes) std::cerr << "palprig: " << note << "\n";
    std::filesystem::create_directories(*out_dir);
    RegionTable table(run.scene.tumors, run.config.layout, 8.0);
    RunOptions opt;
    opt.rate_hz = 1000;
    opt.duration_s = run.input->duration_s();
    opt.mode = LoopMode::replay;
    opt.telemetry_path = std::filesystem::path(*out_dir) / "telemetry.csv";
    opt.observer = &table;
    cli::install_stop_signals();
    opt.stop_signal = &cli::stop_signal();
    const RunSummary s = execute_run(run, opt);

    const auto& rows = table.rows();
    const auto& soft = rows.back();
    bool all_higher = soft.n > 0;
    for (std::size_t t = 0; t < run.scene.tumors.size(); ++t)
      all_higher = all_higher && rows[t].n > 0 && rows[t].target_mean() > soft.target_mean() &&
                   rows[t].plant_mean() > soft.plant_mean();
    if (*json_out) {
      nlohmann::json j = run_summary_json(s, run, opt);
      nlohmann::json regions = nlohmann::json::array();
      for (std::size_t t = 0; t <= run.scene.tumors.size(); ++t) {
        const auto& r = rows[t];
        regions.push_back({{"region", t < run.scene.tumors.size() ? "tumor " + run.scene.tumors[t].name : "soft tissue"},
                           {"finger_ticks", r.n}, {"target_kPa_mean", r.target_mean()}, {"target_kPa_max", r.target_max},
                           {"plant_kPa_mean", r.plant_mean()}, {"plant_kPa_max", r.plant_max}});
      }
      j["regions"] = regions;
      j["tumors_feel_harder"] = all_higher;
      std::cout << j.dump(2) << "\n";
    } else {
      print_run_summary(std::cout, s, run, opt);
      std::cout << "\n  Pressure per region (fingers over it while the pen pressed; plant = regulator monitor)\n"
                << "  region            finger-ticks   target kPa mean / max   plant kPa mean / max\n"
                << std::fixed;
      for (std::size_t t = 0; t <= run.scene.tumors.size(); ++t) {
        const auto& r = rows[t];
        std::string name = t < run.scene.tumors.size()
                               ? "tumor " + run.scene.tumors[t].name + " (r " +
                                     std::to_string(int(run.scene.tumors[t].radius_mm)) + " mm)"
                               : "soft tissue";
        std::cout << "  " << std::left << std::setw(18) << name << std::right << std::setw(12) << r.n << "   "
                  << std::setprecision(2) << std::setw(9) << r.target_mean() << " / " << std::setw(6) << r.target_max
                  << "       " << std::setw(7) << r.plant_mean() << " / " << std::setw(6) << r.plant_max << "\n";
      }
      std::cout << "\n  " << (all_higher ? "Every tumor got higher pressure than soft tissue."
                                         : "WARNING: a tumor did not get higher pressure than soft tissue.")
                << "\n";
    }
    if (s.fault != FaultCode::none) cli::finish(cli::kExitFault);
    if (!all_higher) cli::finish(cli::kExitFault);
  });
}
