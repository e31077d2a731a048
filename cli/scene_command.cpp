// palprig scene: work with scenes outside the loop.
//   render    bake what the fingers feel on a scene (any kind) into a stiffness map (PGM or CSV)
//   generate  make a random rehearsal case from a seed and a difficulty (ground truth inside)
//   info      list a scene's layers, inclusions, tumors and arteries
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "formats/function_scene_file.hpp"
#include "formats/scene_file.hpp"
#include "models/artery.hpp"
#include "models/case_generator.hpp"
#include "io/checked_output.hpp"
#include "core/input_error.hpp"
#include "models/stiffness_map.hpp"
#include "models/tissue_scene.hpp"

using namespace palprig;

namespace {

struct RenderArgs {
  std::string scene, out, map_scene;
  double res_mm = 1.0, force_N = 2.0, t_s = 0.0;
};

// The map covers x 0..x1, y 0..y1 of the scene so that map and scene coordinates agree (a map's
// vertex (0, 0) is at x = 0, y = 0).
void render(const RenderArgs& a) {
  const std::filesystem::path out = a.out;
  const std::string ext = out.extension().string();
  if (ext != ".pgm" && ext != ".csv") throw InputError("--out", a.out, "a .pgm (16-bit) or .csv map file name");
  const SceneFile sf = load_scene_file(a.scene);
  const SceneBounds b = sf.scene->bounds();
  if (!(b.x1_mm > 0 && b.y1_mm > 0))
    throw InputError(a.scene, "bounds", "a scene reaching into positive x and y (the map starts at 0, 0)");
  const auto cols = static_cast<std::size_t>(std::floor(b.x1_mm / a.res_mm)) + 1;
  const auto rows = static_cast<std::size_t>(std::floor(b.y1_mm / a.res_mm)) + 1;
  if (cols < 2 || rows < 2 || cols * rows > 50'000'000)
    throw InputError("--res-mm", std::to_string(a.res_mm), "a resolution giving 2..50 million vertices per side pair");
  MapValues values(cols * rows);  // the map's own storage: moved into it, not copied
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < cols; ++c)
      values[r * cols + c] = static_cast<float>(std::clamp(
          sf.scene->sample({double(c) * a.res_mm, double(r) * a.res_mm}, a.force_N, a.t_s).stiffness, 0.0, 1.0));
  const double width_mm = double(cols - 1) * a.res_mm, height_mm = double(rows - 1) * a.res_mm;
  const StiffnessMap map(cols, rows, width_mm, height_mm, std::move(values));
  {
    CheckedOutputFile f(out);
    if (ext == ".pgm")
      write_stiffness_pgm16(f.stream(), map);
    else
      write_stiffness_csv(f.stream(), map);
    f.commit();
  }
  std::cout << "palprig scene render: " << a.scene << " -> " << out.string() << " (" << cols << " x " << rows
            << " vertices, " << a.res_mm << " mm apart, " << width_mm << " x " << height_mm << " mm, pressing "
            << a.force_N << " N, t = " << a.t_s << " s)\n";
  if (!a.map_scene.empty()) {
    // A map scene over the baked map, so the case also runs as a paper 002-style map.
    nlohmann::json tumors = nlohmann::json::array();
    for (const TumorTruth& t : sf.tumors)
      tumors.push_back({{"name", t.name}, {"x_mm", t.x_mm}, {"y_mm", t.y_mm}, {"radius_mm", t.radius_mm}});
    const std::filesystem::path ms = a.map_scene;
    std::filesystem::path rel =
        std::filesystem::relative(std::filesystem::absolute(out), std::filesystem::absolute(ms).parent_path());
    nlohmann::json j = {
        {"version", kSceneFileVersion},
        {"name", sf.name + "-map"},
        {"description",
         "Baked from " + a.scene + " by palprig scene render (pressing " + std::to_string(a.force_N) + " N)."},
        {"kind", "map"},
        {"map",
         {{"file", rel.generic_string()},
          {"width_mm", width_mm},
          {"height_mm", height_mm},
          {"sampling", "bilinear"},
          {"outside", {{"background", 0.0}}}}},
    };
    if (!tumors.empty()) j["tumors"] = tumors;
    write_scene_json(ms, j);
    std::cout << "  map scene: " << ms.string() << "\n";
  }
}

struct GenerateArgs {
  std::int64_t seed = 0;
  std::string difficulty = "medium", out;
  bool show_truth = false;
};

void generate(const GenerateArgs& a) {
  const GeneratedCase c = generate_case(static_cast<std::uint64_t>(a.seed), parse_difficulty(a.difficulty));
  write_scene_json(a.out, generated_case_json(c));
  std::cout << "palprig scene generate: " << a.out << " (seed " << a.seed << ", " << a.difficulty << ", "
            << c.tumors.size() << (c.tumors.size() == 1 ? " tumor" : " tumors") << ")\n";
  if (a.show_truth)
    for (const GeneratedTumor& t : c.tumors)
      std::cout << std::fixed << std::setprecision(1) << "  " << t.name << " at (" << t.centre.x_mm << ", "
                << t.centre.y_mm << ") mm, radius " << t.lateral_radius_mm << " mm, centre " << t.centre.z_mm
                << " mm deep, " << t.stiffness_kPa << " kPa\n";
}

void info(const std::string& path) {
  const SceneFile sf = load_scene_file(path);
  const SceneBounds b = sf.scene->bounds();
  std::cout << sf.name << " (" << path << ")\n"
            << "  area x " << b.x0_mm << ".." << b.x1_mm << " mm, y " << b.y0_mm << ".." << b.y1_mm << " mm\n";
  const auto* fs = dynamic_cast<const FunctionScene*>(sf.scene.get());
  if (!fs) {
    std::cout << "  kind: map\n";
  } else {
    const TissueDefinition& d = fs->field().definition();
    std::cout << "  kind: function; felt 0 at " << d.felt.soft_kPa << " kPa, 1 at " << d.felt.hard_kPa << " kPa\n";
    std::cout << "  layers:";
    for (const TissueLayer& l : d.layers) {
      std::cout << " " << l.name << ": " << l.thickness_mm << " mm, " << l.stiffness_kPa << " kPa";
      if (l.drag.drags())
        std::cout << " (drags from " << l.drag.f_stick_N << " N up to " << l.drag.d_lat_max_mm << " mm, relaxes in "
                  << l.drag.relax_s << " s)";
      std::cout << ";";
    }
    std::cout << "\n";
    for (const Inclusion& i : d.inclusions)
      std::cout << "  inclusion " << i.name << " (" << to_string(i.kind) << ", " << i.stiffness_kPa << " kPa"
                << (d.respiration.breathing() &&
                            (i.breathing_excursion_mm.x_mm != 0.0 || i.breathing_excursion_mm.y_mm != 0.0 ||
                             i.breathing_excursion_mm.z_mm != 0.0)
                        ? ", moves with breathing"
                        : "")
                << ")\n";
    if (d.respiration.breathing()) std::cout << "  breathing: period " << d.respiration.period_s << " s\n";
    const PulseField& pf = fs->arteries();
    for (std::size_t i = 0; i < pf.size(); ++i) {
      const Artery& a = pf.artery(i);
      std::cout << "  artery " << a.spec().name << ": " << a.length_mm() << " mm long, " << a.spec().depth_mm
                << " mm deep, radius " << a.spec().radius_mm << " mm, " << a.sources().size() << " pulse sources "
                << a.range_mm() << " mm range, " << a.spec().amplitude_kPa << " kPa at " << a.spec().rate_bpm
                << " BPM, felt with " << a.spec().force_window.min_N << ".." << a.spec().force_window.max_N << " N\n";
    }
  }
  for (const TumorTruth& t : sf.tumors)
    std::cout << "  tumor " << t.name << " at (" << t.x_mm << ", " << t.y_mm << ") mm, radius " << t.radius_mm
              << " mm\n";
}

}  // namespace

void register_scene_command(CLI::App& app) {
  CLI::App* scene = app.add_subcommand("scene", "Scenes: bake to a map, generate rehearsal cases, describe");
  scene->require_subcommand(1);

  auto ra = std::make_shared<RenderArgs>();
  CLI::App* r =
      scene->add_subcommand("render", "Bake the stiffness the fingers feel on a scene into a map (PGM or CSV)");
  r->add_option("scene", ra->scene, "Scene file (JSON, map or function)")->required()->check(CLI::ExistingFile);
  r->add_option("--out", ra->out, "Map file to write: .pgm (16-bit) or .csv")->required();
  r->add_option("--res-mm", ra->res_mm, "Distance between map vertices in mm")
      ->default_val(1.0)
      ->check(CLI::Range(0.05, 100.0));
  r->add_option("--force-N", ra->force_N, "Pressing force the map is felt with (deep inclusions need more)")
      ->default_val(2.0)
      ->check(CLI::Range(0.01, 100.0));
  r->add_option("--t-s", ra->t_s, "Time in the breathing cycle (s)")->default_val(0.0)->check(CLI::Range(0.0, 1e6));
  r->add_option("--map-scene", ra->map_scene, "Also write a map scene (JSON) that uses the baked map");
  r->callback([ra]() { render(*ra); });

  auto ga = std::make_shared<GenerateArgs>();
  CLI::App* g =
      scene->add_subcommand("generate", "Make a random rehearsal case (same seed, same case) with its ground truth");
  g->add_option("--seed", ga->seed, "Seed (0..2^63-1)")->required()->check(CLI::Range(std::int64_t{0}, INT64_MAX));
  g->add_option("--difficulty", ga->difficulty, "easy, medium or hard")
      ->default_val("medium")
      ->check(CLI::IsMember({"easy", "medium", "hard"}));
  g->add_option("--out", ga->out, "Scene file to write (JSON)")->required();
  g->add_flag("--show-truth", ga->show_truth, "Also print where the tumors are (for the instructor)");
  g->callback([ga]() { generate(*ga); });

  auto path = std::make_shared<std::string>();
  CLI::App* i = scene->add_subcommand("info", "Describe a scene: layers, inclusions, tumors, arteries");
  i->add_option("scene", *path, "Scene file (JSON)")->required()->check(CLI::ExistingFile);
  i->callback([path]() { info(*path); });
}
