// palprig check FILE...: load each file through the reader palprig itself uses for its kind
// and say what it is, or refuse it with the reader's one line (exit 2). No rig is opened and
// nothing moves: it is how a user (and tools/check_docs.py, for the docs' examples) checks a
// rig, scene, calibration or protocol file, a pen trace, a stiffness map, a waveform table or
// an evemu recording without running anything.
//
// The kind is read from the file (JSON: "kind" fingertip, tissue, actuator, stress_model or
// fe_stress_table -> those finite-element files, any other "kind" -> scene, "task" -> protocol, "stress_model" or
// "rig_id" -> calibration, "tools" -> tracking file, otherwise rig; CSV: the header
// t_s,x_mm,y_mm,force_N -> pen trace, t_s,tool,... -> tracker pose recording, name,x_mm,... ->
// fiducials, t_s and one more column -> waveform, otherwise a stiffness map; .pgm -> map;
// .evemu -> pen recording) or given with --kind.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "formats/calibration_file.hpp"
#include "formats/fe_body_files.hpp"
#include "formats/fe_result_files.hpp"
#include "formats/function_scene_file.hpp"
#include "formats/json_file.hpp"
#include "formats/rig_file.hpp"
#include "formats/scene_file.hpp"
#include "formats/tracking_file.hpp"
#include "calibration/tracker_calibration.hpp"
#include "inputs/pose_recording.hpp"
#include "inputs/input_source.hpp"
#include "inputs/tablet_source.hpp"
#include "core/input_error.hpp"
#include "models/stiffness_map.hpp"
#include "study/curriculum.hpp"
#include "study/protocol.hpp"
#include "study/training.hpp"
#include "study/pulse_protocol.hpp"
#include "study/threshold_protocol.hpp"

using namespace palprig;

namespace {

const std::vector<std::string> kKinds = {
    "rig",   "scene",     "calibration", "protocol",  "trace",  "map",      "waveform",     "evemu",   "tracking",
    "poses", "fiducials", "curriculum",  "fingertip", "tissue", "actuator", "stress-model", "fe-table"};

std::string count(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string first_line(const std::filesystem::path& path) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    return line;
  }
  return {};
}

std::string detect_kind(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".pgm") return "map";
  if (ext == ".evemu") return "evemu";
  if (ext == ".csv") {
    std::string header = first_line(path);
    header.erase(std::remove(header.begin(), header.end(), ' '), header.end());
    if (header == "t_s,x_mm,y_mm,force_N") return "trace";
    if (header == "t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw") return "poses";
    if (header.rfind("name,x_mm,y_mm,z_mm", 0) == 0) return "fiducials";
    // A beat: t_s and one value column (its name is free, e.g. pressure_mmHg).
    if (header.rfind("t_s,", 0) == 0 && std::count(header.begin(), header.end(), ',') == 1) return "waveform";
    return "map";
  }
  const nlohmann::json doc = read_json_file(path);
  if (!doc.is_object()) throw InputError(path.string(), "(root)", "a JSON object");
  if (std::string fe = fe_body_kind(doc); !fe.empty()) return fe;
  if (const std::string fe = fe_result_kind(doc); !fe.empty())
    return fe == "stress_model" ? "stress-model" : "fe-table";
  if (is_curriculum(doc)) return "curriculum";
  if (doc.contains("kind")) return "scene";
  if (doc.contains("task")) return "protocol";
  if (doc.contains("stress_model") || doc.contains("rig_id")) return "calibration";
  if (doc.contains("tools")) return "tracking";
  return "rig";
}

std::string check_protocol(const std::filesystem::path& path) {
  const nlohmann::json doc = read_json_file(path);
  if (is_threshold_protocol(doc)) {
    const ThresholdProtocol p = load_threshold_protocol(path);
    return "threshold protocol '" + p.name + "', " + count(p.tracks.size(), "track");
  }
  if (is_pulse_protocol(doc)) {
    const PulseProtocol p = load_pulse_protocol(path);
    return "pulse protocol '" + p.name + "', " + count(p.conditions.size(), "condition");
  }
  const Protocol p = load_protocol(path);
  return std::string(p.task == TaskKind::localisation ? "localisation" : "discrimination") + " protocol '" + p.name +
         "', " + count(p.conditions.size(), "condition");
}

std::string check_one(const std::filesystem::path& path, const std::string& kind) {
  if (kind == "rig") {
    const RigConfig rig = load_rig_file(path);
    return "rig '" + rig.id + "', backend " + rig.backend;
  }
  if (kind == "scene") {
    const SceneFile sf = load_scene_file(path);
    const bool map = dynamic_cast<const MapScene*>(sf.scene.get()) != nullptr;
    return std::string(map ? "map" : "function") + " scene '" + sf.name + "', " + count(sf.tumors.size(), "tumor") +
           (sf.scene->pulse() != nullptr ? ", arteries" : "");
  }
  if (kind == "calibration") {
    const CalibrationModels cal = load_calibration_file(path);
    return "calibration for rig '" + cal.rig_id + "'";
  }
  if (kind == "protocol") return check_protocol(path);
  if (kind == "fingertip") {
    const FingertipBody f = load_fingertip_file(path);
    std::ostringstream o;
    o << "fingertip, " << f.width_mm << " x " << f.height_mm << " mm, skin " << f.skin_thickness_mm << " mm ("
      << f.skin.describe() << "), tissue " << f.tissue.describe();
    return o.str();
  }
  if (kind == "tissue") {
    const TissueBlock t = load_tissue_file(path);
    std::ostringstream o;
    o << "tissue block '" << t.name << "', " << t.width_mm << " x " << t.height_mm << " mm, " << t.tissue.describe()
      << ", " << count(t.inclusions.size(), "inclusion");
    return o.str();
  }
  if (kind == "actuator") {
    const ActuatorBody a = load_actuator_file(path);
    std::ostringstream o;
    o << "actuator '" << a.name << "', chamber " << a.chamber_width_mm << " mm, membrane " << a.membrane_thickness_mm
      << " mm (E " << a.membrane.youngs_kPa / 1000 << " MPa), layer " << a.layer_thickness_mm << " mm";
    if (a.membrane_slides) o << ", the membrane sliding on the substrate";
    return o.str();
  }
  if (kind == "stress-model") {
    const FeStressModelFile m = load_stress_model_file(path);
    std::ostringstream o;
    o << "finite-element stress model, soft " << m.soft_stress_kPa << " / nodule " << m.hard_stress_kPa
      << " kPa, actuator line " << m.actuator.slope << " x air + " << m.actuator.intercept_kPa << " kPa";
    if (m.uninflated == "soft-tissue") o << " (the uninflated actuator as soft tissue)";
    return o.str();
  }
  if (kind == "fe-table") {
    const FeTableFile t = load_fe_table_file(path);
    return "finite-element table, " + count(t.table->axes().values(), "value") + " from " + count(t.solves, "solve");
  }
  if (kind == "curriculum") {
    const Curriculum c = load_curriculum(path);
    std::string out = "curriculum '" + c.name + "', " + count(c.levels.size(), "level");
    // What the pilot section predicts for a simulated trainee (train next --participant sim:SEED).
    const auto first = predict_pilot_sessions(c, 200);
    std::string at;
    for (std::size_t i = 1; i < first.size(); ++i) {
      at += (at.empty() ? "" : ", ") + std::string("level ") + std::to_string(i + 1) + " at " +
            (first[i] ? "session " + std::to_string(*first[i]) : std::string("none of 200 sessions"));
    }
    if (!at.empty()) out += "; a pilot trainee who would find every tumor once skilled reaches " + at;
    return out;
  }
  if (kind == "trace") {
    const auto samples = load_trace_csv(path);
    return "pen trace, " + count(samples.size(), "row");
  }
  if (kind == "map") {
    // The size in mm belongs to the scene that lays the map out; the values are what is checked.
    const StiffnessMap map = load_stiffness_map_file(path, 100.0, 100.0);
    return "stiffness map, " + std::to_string(map.cols()) + " x " + std::to_string(map.rows()) + " vertices";
  }
  if (kind == "tracking") {
    const TrackingConfig t = load_tracking_file(path);
    std::string names;
    for (const auto& tool : t.tools)
      names += (names.empty() ? "" : ", ") + tool.name +
               (t.placement == TrackedPlacement::per_finger ? " -> finger " + std::to_string(tool.finger + 1) : "");
    return std::string("tracking file, ") +
           (t.placement == TrackedPlacement::per_finger ? "one tool per finger ("
                                                        : "one tool, the fingers around it (") +
           names + ")" +
           (t.registration.fiducials > 0 ? ", registered on " + count(t.registration.fiducials, "fiducial") : "");
  }
  if (kind == "poses") {
    const auto poses = load_pose_recording(path);
    return "tracker pose recording, " + count(recorded_tools(poses).size(), "tool") + ", " +
           count(poses.size(), "pose");
  }
  if (kind == "fiducials") return "fiducials, " + count(load_fiducials(path).size(), "point");
  if (kind == "waveform") {
    (void)load_waveform_csv(path);
    return "waveform table";
  }
  const PenRecording rec = read_pen_recording(path);
  return "evemu pen recording '" + rec.device_name + "', " + count(rec.events.size(), "event");
}

}  // namespace

void register_check_command(CLI::App& app) {
  struct Args {
    std::vector<std::string> files;
    std::string kind;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "check",
      "Load files through palprig's readers and say what each is (rig, scene, calibration, protocol, curriculum, "
      "trace, map, waveform, evemu, tracking, poses, fiducials, fingertip, tissue, actuator, stress-model, "
      "fe-table); a refused file is one line, exit 2");
  sub->add_option("files", a->files, "files to check")->required();
  sub->add_option("--kind", a->kind, "the kind, instead of reading it from the file")->check(CLI::IsMember(kKinds));
  sub->callback([a] {
    for (const std::string& file : a->files) {
      const std::string kind = a->kind.empty() ? detect_kind(file) : a->kind;
      const std::string what = check_one(file, kind);  // a refusal throws before anything is printed
      std::cout << file << ": " << what << "\n";
    }
  });
}
