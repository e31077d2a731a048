// palprig load-cell read|press: the rig's load cells read at rest, for their
// calibration (tare, gain) and paper 003's reference presses at 60 and 120 mmHg, which
// `calibrate fit --force-presses` turns into the pulse's force window.
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <thread>

#include "cli/commands.hpp"
#include "controller/rig_lease.hpp"
#include "formats/rig_file.hpp"
#include "io/checked_output.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"
#include "rigs/simulated_rig.hpp"
#include "runtime/run_control.hpp"

using namespace palprig;

namespace {

struct CellStats {
  double sum_v = 0, sum_v2 = 0, sum_f = 0, sum_f2 = 0;
  std::size_t n = 0;
  void add(double v, double f) {
    sum_v += v, sum_v2 += v * v, sum_f += f, sum_f2 += f * f;
    ++n;
  }
  double mean_v() const { return n ? sum_v / double(n) : 0; }
  double mean_f() const { return n ? sum_f / double(n) : 0; }
  static double sd(double s, double s2, std::size_t n) {
    return n > 1 ? std::sqrt(std::max(0.0, (s2 - s * s / double(n)) / double(n - 1))) : 0;
  }
  double sd_v() const { return sd(sum_v, sum_v2, n); }
  double sd_f() const { return sd(sum_f, sum_f2, n); }
};

struct Reading {
  RigConfig rig;
  std::vector<CellStats> cells;
};

// Reads every load cell at 100 Hz for `seconds`: in real time on hardware, on simulated time on
// the simulated rig (with `load_N` placed on every cell by hand).
Reading read_cells(const std::string& rig_path, double seconds, double load_N) {
  Reading r;
  r.rig = load_rig_file(rig_path);
  if (!r.rig.load_cells)
    throw InputError(r.rig.source, "load_cells", "a \"load_cells\" section (the rig's force sensors)");
  if (load_N > 0 && r.rig.backend != "simulated")
    throw InputError("--load-N", r.rig.source, "a simulated rig (a real cell feels the weight you put on it)");
  std::unique_ptr<Rig> opened = open_rig(r.rig);  // connected and vented: reading moves nothing
  RigLease lease = opened->lease("palprig load-cell read");
  RigBackend* backend = &lease.backend();
  if (auto* sim = dynamic_cast<SimulatedRig*>(backend))
    for (std::size_t i = 0; i < kFingerCount; ++i) sim->place_load_N(i, load_N);
  r.cells.resize(backend->load_cell_count());
  const bool real_time = r.rig.backend != "simulated";
  const int samples = std::max(1, static_cast<int>(std::lround(seconds * 100)));
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < samples && !process_run_control().stop_requested(); ++k) {
    const double t_s = k * 0.01;
    if (real_time) std::this_thread::sleep_until(start + std::chrono::duration<double>(t_s));
    LoadCellReading reading;
    if (backend->read_load_cells(reading, t_s) != BackendStatus::ok) {
      const std::string why = backend->last_error();
      throw Error("load cells: " + why);
    }
    for (std::size_t i = 0; i < reading.count; ++i) r.cells[i].add(reading.volts[i], reading.force_N[i]);
  }
  return r;  // the lease goes back and the rig closes
}

// A mean that rounds to zero is shown as 0, never "-0.000".
double tidy(double v, double resolution) { return std::abs(v) < resolution / 2 ? 0.0 : v; }

std::string cell_name(const Reading& r, std::size_t i) {
  return r.rig.load_cells->per_finger ? "finger " + std::to_string(i + 1) : std::string("all fingers");
}

}  // namespace

void register_load_cell_command(CLI::App& app) {
  CLI::App* group =
      app.add_subcommand("load-cell", "Read the rig's load cells: tare, gain, and paper 003's reference presses");
  group->require_subcommand(1);

  struct ReadArgs {
    std::string rig;
    double seconds = 2, load_N = 0, known_N = -1;
  };
  auto a = std::make_shared<ReadArgs>();
  CLI::App* read = group->add_subcommand(
      "read", "Read each load cell for a while: volts and force (mean, sd) with the rig file's calibration");
  read->add_option("--rig", a->rig, "Rig file (JSON) with a \"load_cells\" section")
      ->required()
      ->check(CLI::ExistingFile);
  read->add_option("--seconds", a->seconds, "How long to read (100 readings a second)")
      ->default_val(2.0)
      ->check(CLI::Range(0.01, 600.0));
  read->add_option("--load-N", a->load_N, "Simulated rig: a weight of this many newtons on every cell")
      ->check(CLI::Range(0.0, 1000.0));
  read->add_option(
          "--known-N", a->known_N,
          "The load on the cells is known (a weight): print the gain N_per_V that reads it, from the rig file's tare_V")
      ->check(CLI::Range(0.0, 1000.0));
  read->callback([a] {
    install_stop_signals();
    const Reading r = read_cells(a->rig, a->seconds, a->load_N);
    std::cout << "palprig load-cell read: rig '" << r.rig.id << "' (" << r.rig.backend << "), " << r.cells.size()
              << (r.cells.size() == 1 ? " cell, " : " cells, ") << r.cells.front().n << " readings each\n"
              << "  cell          volts mean / sd       force N mean / sd    (tare_V, N_per_V)\n"
              << std::fixed;
    for (std::size_t i = 0; i < r.cells.size(); ++i) {
      const CellStats& c = r.cells[i];
      const LoadCellCalibration& cal = r.rig.load_cells->channels[i].calibration;
      std::cout << "  " << std::left << std::setw(12) << cell_name(r, i) << std::right << std::setprecision(4)
                << std::setw(10) << c.mean_v() << " / " << std::setw(6) << c.sd_v() << "   " << std::setprecision(3)
                << std::setw(8) << tidy(c.mean_f(), 1e-3) << " / " << std::setw(5) << c.sd_f() << "    ("
                << std::setprecision(4) << cal.tare_V << ", " << cal.N_per_V << ")\n";
      if (a->known_N >= 0) {
        const double above = c.mean_v() - cal.tare_V;
        if (a->known_N == 0)
          std::cout << "    no load: its tare_V is " << std::setprecision(4) << c.mean_v() << "\n";
        else if (std::abs(above) < 1e-6)
          std::cout << "    the reading is at the tare: no gain can be found (is the weight on?)\n";
        else
          std::cout << "    " << std::setprecision(3) << a->known_N << " N on it: its N_per_V is "
                    << std::setprecision(4) << a->known_N / above << "\n";
      }
    }
  });

  struct PressArgs {
    std::string rig, presses;
    double mmHg = 60, seconds = 3, load_N = 0;
  };
  auto p = std::make_shared<PressArgs>();
  CLI::App* press = group->add_subcommand(
      "press",
      "Record one reference press (a cuff at 60 or 120 mmHg over the cell, paper 003) into a presses CSV for "
      "calibrate fit --force-presses");
  press->add_option("--rig", p->rig, "Rig file (JSON) with a \"load_cells\" section")
      ->required()
      ->check(CLI::ExistingFile);
  press->add_option("--mmHg", p->mmHg, "The cuff's pressure")->required()->check(CLI::Range(1.0, 400.0));
  press
      ->add_option("--presses", p->presses,
                   "Presses CSV to append to (reference_mmHg,force_N; created with its header)")
      ->required();
  press->add_option("--seconds", p->seconds, "How long to average")->default_val(3.0)->check(CLI::Range(0.01, 600.0));
  press->add_option("--load-N", p->load_N, "Simulated rig: the force the cuff presses with")
      ->check(CLI::Range(0.0, 1000.0));
  press->callback([p] {
    install_stop_signals();
    const Reading r = read_cells(p->rig, p->seconds, p->load_N);
    // The force of the press: the mean of every cell (a cuff presses them all alike).
    double force = 0;
    for (const auto& c : r.cells) force += c.mean_f();
    force /= double(r.cells.size());
    // Appended by rewriting it whole (io/checked_output.hpp): a full disk never leaves half a file.
    std::string before;
    if (std::filesystem::exists(p->presses)) {
      std::ifstream in = open_regular_file(p->presses, kMaxTableFileBytes, "a presses CSV", std::ios::in);
      before.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (!before.empty() && before.back() != '\n') before += '\n';
    } else {
      before = "reference_mmHg,force_N\n";
    }
    CheckedOutputFile out(p->presses);
    out.stream() << before << p->mmHg << "," << std::setprecision(6) << force << "\n";
    out.commit();
    std::cout << "palprig load-cell press: " << std::fixed << std::setprecision(0) << p->mmHg << " mmHg read as "
              << std::setprecision(3) << force << " N (mean of " << r.cells.size()
              << (r.cells.size() == 1 ? " cell" : " cells") << " over " << std::setprecision(1) << p->seconds
              << " s); appended to " << p->presses << "\n";
  });
}
