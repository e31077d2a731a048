// palprig tracking register|pivot|digitize: calibrating a tracker to the rig, from a
// live OpenIGTLink server (calibration/tracker_calibration.hpp); each writes the tracking file.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "calibration/tracker_calibration.hpp"
#include "cli/commands.hpp"
#include "formats/tracking_file.hpp"
#include "inputs/igtl_input.hpp"
#include "core/input_error.hpp"

using namespace palprig;

namespace {

struct Common {
  std::string tracking, out, igtl, tool;
  TouchRules rules;
};

void add_common(CLI::App* sub, Common& c, bool need_igtl) {
  sub->add_option("--tracking", c.tracking, "Tracking file to start from (tools, tips, registration)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", c.out, "Tracking file to write (may be the same file)")->required();
  auto* igtl = sub->add_option("--igtl", c.igtl, "The tracker's OpenIGTLink server, HOST:PORT");
  if (need_igtl) igtl->required();
  sub->add_option("--timeout-s", c.rules.timeout_s, "Give up when the tool is not seen (or does not rest) this long")
      ->default_val(60.0)
      ->check(CLI::Range(0.1, 3600.0));
}

IgtlEndpoint endpoint_of(const std::string& text) { return parse_igtl_spec("igtl:" + text); }

const TrackedTool& tool_in(const TrackingConfig& t, const std::string& name) {
  if (name.empty()) return t.tools.front();
  if (const TrackedTool* tool = t.tool_named(name)) return *tool;
  std::string names;
  for (const auto& x : t.tools) names += (names.empty() ? "" : ", ") + x.name;
  throw InputError(t.source, "tools", "a tool named '" + name + "' (the file has " + names + ")");
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

const Say say = [](const std::string& line) { std::cout << "  " << line << std::endl; };

void register_register(CLI::App* parent) {
  struct Args : Common {
    std::string fiducials;
    double max_fre_mm = 2.0;
    std::vector<double> tool_tip;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = parent->add_subcommand(
      "register",
      "Tracker -> scene registration from fiducials touched with a tracked tip (fiducial registration error reported)");
  add_common(sub, *a, false);
  sub->add_option("--fiducials", a->fiducials,
                  "Fiducials CSV name,x_mm,y_mm,z_mm (scene); with tracker_x_mm,tracker_y_mm,tracker_z_mm columns no "
                  "tracker is needed")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--tool", a->tool,
                  "The tool whose tip touches them (default: the tracking file's first); a tool the file does not name "
                  "(a stylus) has its tip at its origin, or at --tool-tip");
  sub->add_option("--tool-tip", a->tool_tip, "The tip of a --tool the tracking file does not name, mm in its frame")
      ->expected(3);
  sub->add_option("--hold-s", a->rules.hold_s, "A touch is taken when the tip rests this long")
      ->default_val(1.0)
      ->check(CLI::Range(0.05, 60.0));
  sub->add_option("--radius-mm", a->rules.radius_mm, "... within this radius")
      ->default_val(1.0)
      ->check(CLI::Range(0.01, 50.0));
  sub->add_option("--max-fre-mm", a->max_fre_mm, "Refuse to write a registration whose FRE is larger")
      ->default_val(2.0)
      ->check(CLI::Range(0.0, 1000.0));
  sub->callback([a] {
    TrackingConfig t = load_tracking_file(a->tracking);
    // The stylus (or any tool) need not be a finger: a name the file lacks is a tool of its own.
    TrackedTool other;
    if (!a->tool.empty() && !t.tool_named(a->tool)) {
      other.name = a->tool;
      if (a->tool_tip.size() == 3) other.tip.offset_mm = {a->tool_tip[0], a->tool_tip[1], a->tool_tip[2]};
    } else if (!a->tool_tip.empty()) {
      throw InputError("--tool-tip", a->tool.empty() ? t.tools.front().name : a->tool,
                       "a --tool the tracking file does not name (its own tools' tips are in the file)");
    }
    const TrackedTool& tool = other.name.empty() ? tool_in(t, a->tool) : other;
    const std::vector<Fiducial> fiducials = load_fiducials(a->fiducials);
    std::vector<Vec3_mm> touched;
    const bool given = fiducials.front().touched_mm.has_value();
    if (given) {
      for (const auto& f : fiducials) touched.push_back(*f.touched_mm);
      std::cout << "palprig tracking register: " << fiducials.size() << " fiducials with their touched points from "
                << a->fiducials << "\n";
    } else {
      if (a->igtl.empty())
        throw InputError(a->fiducials, "header",
                         "tracker_x_mm,tracker_y_mm,tracker_z_mm columns, or --igtl HOST:PORT to touch them live");
      const IgtlEndpoint e = endpoint_of(a->igtl);
      std::cout << "palprig tracking register: " << fiducials.size() << " fiducials from " << a->fiducials << ", tool "
                << tool.name << " at igtl:" << e.text() << std::endl;
      IgtlPoseReader tracker(e.host, e.port, "--igtl");
      try {
        touched = touch_fiducials(tracker, tool, fiducials, a->rules, say);
      } catch (const Error& err) {
        std::cerr << "palprig tracking register: " << err.what() << "; nothing written\n";
        cli::finish(cli::kExitFault);
      }
    }
    const PointRegistration reg = register_fiducials(fiducials, touched, a->fiducials);
    std::cout << "  fiducial   residual mm\n";
    for (std::size_t i = 0; i < fiducials.size(); ++i)
      std::cout << "  " << std::left << std::setw(10) << fiducials[i].name << " " << fixed(reg.residual_mm[i], 2)
                << "\n";
    std::cout << std::right << "  FRE " << fixed(reg.fre_mm, 2) << " mm (RMS over " << fiducials.size()
              << " fiducials)\n";
    const RigidTransform& r = reg.from_to;
    std::cout << "  tracker -> scene: rotation [";
    for (int i = 0; i < 3; ++i)
      std::cout << (i ? ", " : "") << "[" << fixed(r.rotation[i][0], 4) << ", " << fixed(r.rotation[i][1], 4) << ", "
                << fixed(r.rotation[i][2], 4) << "]";
    std::cout << "], translation (" << fixed(r.translation_mm[0], 2) << ", " << fixed(r.translation_mm[1], 2) << ", "
              << fixed(r.translation_mm[2], 2) << ") mm\n";
    if (reg.fre_mm > a->max_fre_mm) {
      std::cerr << "palprig tracking register: FRE " << fixed(reg.fre_mm, 2) << " mm is over --max-fre-mm "
                << fixed(a->max_fre_mm, 2) << ": " << a->out
                << " not written (touch the fiducials again; check their coordinates and the tool's tip)\n";
      cli::finish(cli::kExitFault);
    }
    t.registration.tracker_to_scene = reg.from_to;
    t.registration.fre_mm = reg.fre_mm;
    t.registration.fiducials = static_cast<int>(fiducials.size());
    write_tracking_file(a->out, t);
    std::cout << "  wrote " << a->out << "\n";
  });
}

void register_pivot(CLI::App* parent) {
  struct Args : Common {
    double seconds = 10, max_rms_mm = 1.0;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = parent->add_subcommand(
      "pivot", "The fingertip offset of a tool by pivot calibration (least squares; RMS residual reported)");
  add_common(sub, *a, true);
  sub->add_option("--tool", a->tool, "The tool to calibrate (default: the tracking file's first)");
  sub->add_option("--seconds", a->seconds, "How long to collect poses once the tool is seen")
      ->default_val(10.0)
      ->check(CLI::Range(0.5, 600.0));
  sub->add_option("--max-rms-mm", a->max_rms_mm, "Refuse to write a tip whose RMS residual is larger")
      ->default_val(1.0)
      ->check(CLI::Range(0.0, 1000.0));
  sub->callback([a] {
    TrackingConfig t = load_tracking_file(a->tracking);
    const std::string name = tool_in(t, a->tool).name;
    const IgtlEndpoint e = endpoint_of(a->igtl);
    std::cout << "palprig tracking pivot: tool " << name << " at igtl:" << e.text() << std::endl;
    IgtlPoseReader tracker(e.host, e.port, "--igtl");
    PivotCalibration pc;
    try {
      pc = pivot_from_tracker(tracker, name, a->seconds, a->rules.timeout_s, say);
    } catch (const Error& err) {
      std::cerr << "palprig tracking pivot: " << err.what() << "; nothing written\n";
      cli::finish(cli::kExitFault);
    }
    std::cout << "  tip (" << fixed(pc.tip_mm[0], 2) << ", " << fixed(pc.tip_mm[1], 2) << ", " << fixed(pc.tip_mm[2], 2)
              << ") mm in the tool's frame; pivot point (" << fixed(pc.pivot_mm[0], 2) << ", "
              << fixed(pc.pivot_mm[1], 2) << ", " << fixed(pc.pivot_mm[2], 2) << ") mm in the tracker's\n"
              << "  RMS residual " << fixed(pc.rms_mm, 2) << " mm (max " << fixed(pc.max_mm, 2)
              << " mm), rotation spread " << fixed(pc.rotation_spread_deg, 0) << " degrees\n";
    if (pc.rms_mm > a->max_rms_mm) {
      std::cerr << "palprig tracking pivot: RMS residual " << fixed(pc.rms_mm, 2) << " mm is over --max-rms-mm "
                << fixed(a->max_rms_mm, 2) << ": " << a->out << " not written (keep the tip in the divot)\n";
      cli::finish(cli::kExitFault);
    }
    for (auto& tool : t.tools)
      if (tool.name == name) tool.tip = {pc.tip_mm, "pivot", pc.rms_mm};
    write_tracking_file(a->out, t);
    std::cout << "  wrote " << a->out << "\n";
  });
}

void register_digitize(CLI::App* parent) {
  struct Args : Common {
    std::string digitizer;
    std::vector<double> digitizer_tip{0, 0, 0};
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = parent->add_subcommand(
      "digitize",
      "The fingertip offset of a finger's sensor by static digitization with a tracked digitizer (paper 003)");
  add_common(sub, *a, true);
  sub->add_option("--tool", a->tool, "The finger's sensor (default: the tracking file's first tool)");
  sub->add_option("--digitizer", a->digitizer, "The digitizer tool, e.g. StylusTipToTracker")->required();
  sub->add_option(
         "--digitizer-tip", a->digitizer_tip,
         "The digitizer's tip in its own frame, mm (default 0 0 0: a tip transform such as PLUS's StylusTipToTracker)")
      ->expected(3);
  sub->add_option("--hold-s", a->rules.hold_s, "Taken when the two rest together this long")
      ->default_val(1.0)
      ->check(CLI::Range(0.05, 60.0));
  sub->add_option("--radius-mm", a->rules.radius_mm, "... within this radius")
      ->default_val(1.0)
      ->check(CLI::Range(0.01, 50.0));
  sub->callback([a] {
    TrackingConfig t = load_tracking_file(a->tracking);
    const std::string name = tool_in(t, a->tool).name;
    const IgtlEndpoint e = endpoint_of(a->igtl);
    std::cout << "palprig tracking digitize: " << name << "'s fingertip with " << a->digitizer
              << " at igtl:" << e.text() << std::endl;
    IgtlPoseReader tracker(e.host, e.port, "--igtl");
    Vec3_mm tip{};
    try {
      tip = digitize_from_tracker(tracker, name, a->digitizer,
                                  {a->digitizer_tip[0], a->digitizer_tip[1], a->digitizer_tip[2]}, a->rules, say);
    } catch (const Error& err) {
      std::cerr << "palprig tracking digitize: " << err.what() << "; nothing written\n";
      cli::finish(cli::kExitFault);
    }
    for (auto& tool : t.tools)
      if (tool.name == name) tool.tip = {tip, "digitized", std::nan("")};
    write_tracking_file(a->out, t);
    std::cout << "  wrote " << a->out << "\n";
  });
}

}  // namespace

void register_tracking_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "tracking",
      "Calibrate a tracker to the rig: tracker -> scene registration, fingertip offsets (pivot, digitization)");
  sub->require_subcommand(1);
  register_register(sub);
  register_pivot(sub);
  register_digitize(sub);
}
