#include "experiments/pulse_task.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "experiments/adaptive_track.hpp"
#include "formats/function_scene_file.hpp"
#include "formats/json_file.hpp"
#include "models/artery.hpp"
#include "models/parse_error.hpp"

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
  p.repetitions = static_cast<int>(root.integer_or("repetitions", 1, 1, 10000));
  const auto conditions = root.objects("conditions");
  if (conditions.empty()) root.fail("conditions", "at least one condition with a scene");
  for (const JsonObject& c : conditions) {
    PulseCondition pc;
    pc.name = c.string("name");
    if (pc.name.empty()) c.fail("name", "a non-empty condition name");
    for (const auto& other : p.conditions) {
      if (other.name == pc.name) c.fail("name", "a name used by one condition only");
    }
    if (c.has("generate") == c.has("scene")) c.fail("scene", "either a scene file or \"generate\": {\"difficulty\": ...}");
    if (c.has("generate")) {
      const JsonObject g = c.object("generate");
      pc.generated = parse_difficulty(g.choice("difficulty", {"easy", "medium", "hard"}));
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
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[static_cast<std::size_t>(random.below(i))]);
  return order;
}

SceneFile generated_pulse_scene(std::uint64_t seed, CaseDifficulty difficulty) {
  const GeneratedCase c = generate_case(seed, difficulty);
  nlohmann::json doc = generated_case_json(c);
  RandomSource random(seed ^ 0xA5A5A5A5DEADBEEFULL);
  const double cx = c.body.centre.x_mm, cy = c.body.centre.y_mm;
  const double hx = c.body.half_width_mm, hy = c.body.half_height_mm;
  const double x0 = cx + (random.uniform() - 0.5) * hx;        // enters within the middle half
  const double x1 = cx + (random.uniform() - 0.5) * hx;
  const double xm = 0.5 * (x0 + x1) + (random.uniform() - 0.5) * 0.4 * hx;
  const double depth = difficulty == CaseDifficulty::easy ? 6.0 : difficulty == CaseDifficulty::medium ? 10.0 : 14.0;
  doc["arteries"] = nlohmann::json::array({{{"name", "artery"},
                                            {"path_mm", {{x0, cy - 0.85 * hy}, {xm, cy}, {x1, cy + 0.85 * hy}}},
                                            {"depth_mm", depth},
                                            {"radius_mm", 3.0},
                                            {"amplitude_kPa", 8.0},
                                            {"rate_bpm", 60.0 + 40.0 * random.uniform()},
                                            {"waveform", {{"shape", "rectangular"}, {"duty", 0.2}}},
                                            {"force_window_N", {1.0, 4.0}}}});
  const std::string source = "generated pulse case (seed " + std::to_string(seed) + ", " + to_string(difficulty) + ")";
  const JsonObject root(doc, source, "");
  root.require_version(1);
  SceneFile out;
  out.source = source;
  out.name = root.string_or("name", "generated");
  (void)root.choice_or("kind", "function", {"function"});
  (void)root.string_or("description", "");
  load_function_scene(root, std::filesystem::path("."), out);
  return out;
}

namespace {
struct Stopped {};
}  // namespace

PulseSessionResult run_pulse_session(const PulseProtocol& protocol, const std::vector<SceneFile>& scenes,
                                     StimulusOutput& output, PulseParticipant& participant, SessionClock& clock,
                                     const PulseSessionOptions& options) {
  PulseSessionResult result;
  const std::vector<int> order = pulse_trial_order(protocol, options.seed);
  double next_s = clock.now_s();
  ChannelPressures felt{};
  auto pass = [&]() {
    const double t = clock.now_s();
    if (options.stop && options.stop->load() != 0) {
      output.vent(t);
      throw Stopped{};
    }
    felt = output.service(t);
    next_s += options.period_s;
    clock.wait_until(next_s);
    return t;
  };
  auto pause_asked = [&] { return options.pause && options.pause->load(); };
  // The participant's go-ahead (the rig is serviced, vented, meanwhile). The simulated observer
  // is ready at once: no pass, no time, so its sessions are unchanged by this wait.
  auto wait_ready = [&](int position) {
    bool told = false;
    while (!participant.ready(clock.now_s())) {
      if (!told && options.on_waiting) options.on_waiting(position, false);
      told = true;
      pass();
      if (pause_asked()) return false;  // paused again before the Ready: hold first
    }
    return true;
  };
  // A pause: vent at once and hold (servicing the vented rig) until it is lifted.
  auto hold = [&](int position) {
    output.vent(clock.now_s());
    if (options.on_waiting) options.on_waiting(position, true);
    while (pause_asked()) pass();
  };
  try {
    bool need_ready = true;  // before the first trial and after a pause
    for (int position = options.start_position; position < static_cast<int>(order.size());) {
      if (pause_asked()) {
        hold(position);
        need_ready = true;
      }
      if (need_ready) {
        if (!wait_ready(position)) continue;
        need_ready = false;
      }
      const auto c = static_cast<std::size_t>(order[static_cast<std::size_t>(position)]);
      const PulseCondition& condition = protocol.conditions[c];
      PulseTrialRecord r;
      r.position = position;
      r.condition = condition.name;
      SceneFile generated;
      if (condition.generated) {
        r.scene_seed = trial_seed(options.seed, position, 3) >> 1;  // the generator takes 0..2^63-1
        generated = generated_pulse_scene(*r.scene_seed, *condition.generated);
      }
      const Scene& scene = condition.generated ? *generated.scene : *scenes.at(c).scene;
      r.onset_s = clock.now_s();
      if (options.on_trial_started) options.on_trial_started(PulseTrialStart{position, static_cast<int>(c), r.scene_seed, r.onset_s});
      InputSource& pen = participant.trial_started(position, condition, scene, r.onset_s);
      output.palpate(scene, pen, r.onset_s);
      std::optional<Mark> mark;
      bool interrupted = false;
      for (double t = r.onset_s; t - r.onset_s < protocol.max_present_s + protocol.response_timeout_s && !mark;) {
        t = pass();
        if (pause_asked()) {
          interrupted = true;  // the trial is held: not scored, presented again from its start
          break;
        }
        if (t - r.onset_s >= protocol.max_present_s) output.vent(t);
        FeltSample sample;
        sample.t_s = t;
        sample.felt_kPa = felt;
        sample.active = {true, true, true};
        sample.record = output.last_record();
        participant.feel(sample);
        mark = participant.answer(t);
        if (mark) r.response_time_s = t - r.onset_s;
      }
      output.vent(clock.now_s());
      if (interrupted) continue;  // the loop's top holds the pause, then waits for the Ready
      r.answered = mark.has_value();
      r.distance_mm = std::numeric_limits<double>::quiet_NaN();
      if (mark) {
        r.mark_x_mm = mark->x_mm;
        r.mark_y_mm = mark->y_mm;
        const PulseMarkScore score = score_pulse_mark(*scene.pulse(), Point2_mm{mark->x_mm, mark->y_mm},
                                                      protocol.hit_radius_mm, condition.artery);
        r.distance_mm = score.distance_mm;
        r.hit = score.hit;
        if (score.artery >= 0) r.artery = scene.pulse()->artery(static_cast<std::size_t>(score.artery)).spec().name;
      } else {
        r.response_time_s = std::numeric_limits<double>::quiet_NaN();
      }
      if (options.on_trial) options.on_trial(r);
      ++position;
      // The inter-trial interval; a pause here cuts it short (the trial is committed).
      const double pause = clock.now_s();
      for (double t = pause; t - pause < protocol.inter_trial_s && !pause_asked();) t = pass();
    }
  } catch (const Stopped&) {
    result.stopped = true;
    return result;
  } catch (const RigFault& fault) {
    result.fault = fault.what();
    return result;
  }
  result.completed = true;
  return result;
}

InputSource& SimulatedPulseObserver::trial_started(int, const PulseCondition&, const Scene& scene, double t_s) {
  // A pen raster (the model's sweep_* fields keep their stored names).
  RasterPlan plan;
  plan.speed_mm_per_s = model_.sweep_speed_mm_per_s;
  plan.row_step_mm = model_.sweep_row_step_mm;
  plan.force_N = model_.press_force_N;
  plan.margin_mm = 2.0 + random_.uniform() * model_.sweep_row_step_mm;
  auto raster = std::make_unique<RasterInput>(scene.bounds(), plan);
  done_at_s_ = t_s + raster->duration_s();
  pen_.restart(std::move(raster), t_s);
  for (auto& h : history_) h.clear();
  best_swing_kPa_ = 0;
  best_ = {};
  return pen_;
}

void SimulatedPulseObserver::feel(const FeltSample& s) {
  if (!s.record || s.t_s > done_at_s_) return;
  constexpr double kBefore_s = 0.3, kAfter_s = 0.15;
  const auto fingers = layout_.centres(s.record->x_mm, s.record->y_mm);
  for (std::size_t f = 0; f < kFingerCount; ++f) {
    auto& h = history_[f];
    h.push_back({s.t_s, s.felt_kPa[f], fingers[f].x_mm, fingers[f].y_mm});
    while (!h.empty() && h.front().t_s < s.t_s - kBefore_s - kAfter_s) h.pop_front();
    if (h.front().t_s > s.t_s - kBefore_s - kAfter_s + 0.01) continue;  // not a full window yet
    // The candidate peak is the sample kAfter_s ago.
    std::size_t centre = h.size() - 1;
    while (centre > 0 && h[centre].t_s > s.t_s - kAfter_s) --centre;
    double left = h[centre].kPa, right = h[centre].kPa;
    for (std::size_t i = 0; i < centre; ++i) left = std::min(left, h[i].kPa);
    for (std::size_t i = centre + 1; i < h.size(); ++i) right = std::min(right, h[i].kPa);
    const double prominence = h[centre].kPa - std::max(left, right);
    if (prominence > best_swing_kPa_) {
      best_swing_kPa_ = prominence;
      best_ = {h[centre].x_mm, h[centre].y_mm};
    }
  }
}

std::optional<Mark> SimulatedPulseObserver::answer(double t_s) {
  if (t_s < done_at_s_ + 1.0) return std::nullopt;
  if (best_swing_kPa_ <= 0) return std::nullopt;  // felt nothing: no mark (the trial times out)
  return Mark{best_.x_mm + model_.mark_noise_mm * random_.normal(), best_.y_mm + model_.mark_noise_mm * random_.normal()};
}

}  // namespace palprig
