#include "study/pulse_protocol.hpp"

#include <utility>

#include "formats/json_file.hpp"
#include "formats/scene_file.hpp"
#include "models/artery.hpp"
#include "core/input_error.hpp"
#include "study/session_bounds.hpp"
#include "study/random_source.hpp"

namespace palprig {

bool is_pulse_protocol(const nlohmann::json& document) {
  return document.is_object() && document.contains("task") && document["task"] == "pulse";
}

PulseProtocol parse_pulse_protocol(const nlohmann::json& document, const std::string& source,
                                   const std::filesystem::path& base_dir) {
  const JsonObject root(document, source, "");
  root.require_version(1);
  PulseProtocol p;
  p.source = source;
  p.snapshot = document;
  p.name = root.string("name");
  if (p.name.empty()) root.fail("name", "a non-empty protocol name");
  root.choice("task", {"pulse"});
  p.description = root.string_or("description", "");
  p.bids_task = root.string_or("bids_task", "pulse");
  const JsonObject task = root.object("pulse");
  p.hit_radius_mm = task.number("hit_radius_mm", 0.0, 1000.0);
  p.max_present_s = task.number_or("max_present_s", 60.0, 1.0, 3600.0);
  p.response_timeout_s = task.number_or("response_timeout_s", 10.0, 0.1, 3600.0);
  p.inter_trial_s = task.number_or("inter_trial_s", 2.0, 0.0, 600.0);
  task.refuse_unknown();
  p.repetitions = static_cast<int>(root.integer_or("repetitions", 1, 1, kMaxSessionTrials));
  const auto conditions = root.objects("conditions");
  if (conditions.empty()) root.fail("conditions", "at least one condition with a scene");
  for (const JsonObject& c : conditions) {
    PulseCondition pc;
    pc.name = c.string("name");
    if (pc.name.empty()) c.fail("name", "a non-empty condition name");
    for (const auto& other : p.conditions) {
      if (other.name == pc.name) c.fail("name", "a name used by one condition only");
    }
    if (c.has("generate") == c.has("scene"))
      c.fail("scene", "either a scene file or \"generate\": {\"difficulty\": ...}");
    if (c.has("generate")) {
      const JsonObject g = c.object("generate");
      pc.generated = parse_difficulty(g.choice("difficulty", {"easy", "medium", "hard"}));
      if (g.has("seed")) pc.generated_seed = static_cast<std::uint64_t>(g.integer("seed", 0, 999999999999LL));
      g.refuse_unknown();
      c.refuse_unknown();
      p.conditions.push_back(pc);
      continue;
    }
    const std::filesystem::path scene = c.string("scene");
    pc.scene_file = scene.is_absolute() ? scene : base_dir / scene;
    pc.artery = c.string_or("artery", "");
    c.refuse_unknown();
    const SceneFile file = load_scene_file(pc.scene_file);
    const PulseField* arteries = file.scene->pulse();
    if (!arteries || arteries->empty()) {
      c.fail("scene", "a scene with at least one artery (" + pc.scene_file.string() + " has none)");
    }
    if (!pc.artery.empty() && arteries->find(pc.artery) < 0) {
      c.fail("artery", "the name of an artery of " + pc.scene_file.string() + ", got '" + pc.artery + "'");
    }
    p.conditions.push_back(pc);
  }
  const long long session_trials = static_cast<long long>(p.repetitions) * static_cast<long long>(p.conditions.size());
  if (session_trials > kMaxSessionTrials)
    root.fail("repetitions", "a protocol of " + session_bound_text(session_trials));
  root.refuse_unknown();
  return p;
}

PulseProtocol load_pulse_protocol(const std::filesystem::path& path) {
  return parse_pulse_protocol(read_json_file(path), path.string(), path.parent_path());
}

std::vector<int> pulse_trial_order(const PulseProtocol& protocol, std::uint64_t seed) {
  std::vector<int> order;
  for (int r = 0; r < protocol.repetitions; ++r) {
    for (std::size_t c = 0; c < protocol.conditions.size(); ++c) order.push_back(static_cast<int>(c));
  }
  RandomSource random(seed);
  for (std::size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1], order[static_cast<std::size_t>(random.below(i))]);
  return order;
}

}  // namespace palprig
