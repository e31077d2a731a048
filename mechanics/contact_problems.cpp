#include "mechanics/contact_problems.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "mechanics/body_meshes.hpp"

namespace palprig::mechanics {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(digits);
  o << v;
  return o.str();
}

// The fingertip (body 0, materials 0..2) and the other body (body 1, materials from 3).
struct TwoBodies {
  QuadMesh mesh;
  std::vector<MaterialLaw> materials;
  std::vector<std::string> names;
};

TwoBodies fingertip_with(const FingertipBody& finger, double element_mm, const QuadMesh& other,
                         const std::vector<MaterialLaw>& other_materials, const std::vector<std::string>& other_names,
                         double finger_x_mm) {
  TwoBodies t;
  t.mesh = mesh_fingertip(finger, element_mm);
  for (auto& n : t.mesh.nodes) n.x_mm += finger_x_mm;
  t.materials = {finger.skin, finger.tissue, finger.nail};
  t.names = {"skin", "finger tissue", "nail"};
  t.mesh.append(other, 1, int(t.materials.size()));
  t.materials.insert(t.materials.end(), other_materials.begin(), other_materials.end());
  t.names.insert(t.names.end(), other_names.begin(), other_names.end());
  return t;
}

// The contact parameters: the augmentation about the softer body's modulus per element, the
// release distance a few elements (GetFEM's advice: less than the bodies' thickness).
ContactPair contact_between(const std::string& master, double softest_kPa, const SolveOptions& o) {
  const double element_mm = o.element_mm;
  ContactPair c;
  c.slave = "fingertip_contact";
  c.master = master;
  c.augmentation_kPa_per_mm = o.augmentation_factor * softest_kPa / element_mm;
  c.release_distance_mm = std::max(1.5, 3 * element_mm);
  return c;
}

// Steps the load from `from` to each target in turn, halving a step that fails. record(load)
// keeps the result of each target reached.
template <class Apply, class Record>
void step_through(ContactSolver& solver, ContactRun& run, const std::vector<double>& targets, double from,
                  const SolveOptions& options, const std::string& unit, Apply apply, Record record,
                  const ProgressFn& progress, Clock::time_point t0) {
  double at = from;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const double target = targets[k];
    double increment = target - at;
    int cuts = 0, iterations = 0;
    while (at < target - 1e-12) {
      const double trial = std::min(target, at + increment);
      const NewtonReport r = solver.solve(apply(trial), options.max_newton_iterations);
      iterations += r.iterations;
      if (r.converged) {
        at = trial;
        continue;
      }
      if (++cuts > options.max_cuts)
        throw Error("finite-element model: no equilibrium at " + fixed(trial, 3) + " " + unit + " after " +
                    std::to_string(options.max_cuts) + " step halvings (" + r.failure + ")");
      ++run.cuts;
      increment /= 2;
    }
    record(target, iterations);
    if (progress) {
      StepProgress p;
      p.step = int(k + 1);
      p.steps = int(targets.size());
      p.what = fixed(target, 2) + " " + unit;
      p.elapsed_s = seconds_since(t0);
      p.remaining_s = p.elapsed_s / p.step * (p.steps - p.step);
      p.cuts = run.cuts;
      p.newton_iterations = iterations;
      progress(p);
    }
  }
}

}  // namespace

double averaged_stress_kPa(const std::vector<ContactNode>& profile, double s_mm, double half_mm) {
  const double lo = s_mm - half_mm, hi = s_mm + half_mm;
  double integral = 0;
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const ContactNode &a = profile[i], &b = profile[i + 1];
    const double l = std::max(lo, a.s_mm), r = std::min(hi, b.s_mm);
    if (!(r > l) || !(b.s_mm > a.s_mm)) continue;
    auto at = [&](double s) {
      return a.pressure_kPa + (b.pressure_kPa - a.pressure_kPa) * (s - a.s_mm) / (b.s_mm - a.s_mm);
    };
    integral += (at(l) + at(r)) / 2 * (r - l);
  }
  return integral / (hi - lo);
}

void summarise_profile(ContactStep& step) {
  step.peak_kPa = step.node_peak_kPa = 0;
  step.contact_length_mm = 0;
  double most = 0;
  for (const ContactNode& n : step.profile) most = std::max(most, n.pressure_kPa);
  step.node_peak_kPa = most;
  for (std::size_t i = 0; i < step.profile.size(); ++i) {
    const ContactNode& n = step.profile[i];
    const double averaged = averaged_stress_kPa(step.profile, n.s_mm, kStressAveragingLength_mm / 2);
    if (averaged > step.peak_kPa) {
      step.peak_kPa = averaged;
      step.peak_s_mm = n.s_mm;
    }
    // Carrying stress: above 1 % of the peak (the multiplier's noise far from the contact is
    // a thousandth of it).
    if (i > 0 && n.pressure_kPa > 0.01 * most && step.profile[i - 1].pressure_kPa > 0.01 * most)
      step.contact_length_mm += n.s_mm - step.profile[i - 1].s_mm;
  }
}

ContactRun run_indentation(const FingertipBody& finger, const TissueBlock& block, const IndentationOptions& o,
                           const ProgressFn& progress) {
  const auto t0 = Clock::now();
  BlockMeshSizes sizes;
  sizes.element_mm = o.solve.element_mm;
  sizes.fine_half_width_mm = std::min(block.width_mm / 2, std::abs(o.finger_x_mm) + finger.width_mm / 2 + 2);
  sizes.fine_depth_mm = std::min(block.height_mm, (o.depths_mm.empty() ? o.depth_mm : o.depths_mm.back()) + 5);
  std::vector<MaterialLaw> block_laws{block.tissue};
  std::vector<std::string> block_names{"tissue"};
  for (const auto& inc : block.inclusions) {
    block_laws.push_back(inc.law);
    block_names.push_back(inc.name.empty() ? "inclusion" : inc.name);
  }
  TwoBodies bodies =
      fingertip_with(finger, o.solve.element_mm, mesh_block(block, sizes), block_laws, block_names, o.finger_x_mm);
  ProblemSpec spec;
  spec.mesh = bodies.mesh;
  spec.materials = bodies.materials;
  spec.plane = o.solve.plane;
  spec.held = {{"bone"}, {"block_bottom"}};
  if (block.sides == BlockSides::rollers) spec.rollers = {{"block_left"}, {"block_right"}};
  double softest = block.tissue.initial_youngs_kPa();
  softest = std::min(softest, finger.skin.initial_youngs_kPa());
  spec.contact = contact_between("block_top", softest, o.solve);
  ContactSolver solver(spec);

  ContactRun run;
  run.mesh = bodies.mesh;
  run.materials = bodies.materials;
  run.material_names = bodies.names;
  run.unknowns = solver.unknowns();
  std::vector<double> depths = o.depths_mm;
  if (depths.empty()) {
    const int n = std::max(1, static_cast<int>(std::lround(o.depth_mm / o.step_mm)));
    for (int k = 1; k <= n; ++k) depths.push_back(o.depth_mm * k / n);
  }
  step_through(
      solver, run, depths, 0.0, o.solve, "mm",
      [](double depth) {
        LoadState s;
        s.held_mm["bone"] = {0.0, -depth};
        return s;
      },
      [&](double depth, int iterations) {
        ContactStep step;
        step.load = depth;
        step.newton_iterations = iterations;
        step.profile = solver.contact_profile();
        step.force_N_per_m = solver.contact_force_per_mm()[1];
        summarise_profile(step);
        run.steps.push_back(std::move(step));
      },
      progress, t0);
  run.last = solver.deformed();
  run.wall_s = seconds_since(t0);
  return run;
}

ContactRun run_actuator(const FingertipBody& finger, const ActuatorBody& actuator, const ActuatorOptions& o,
                        const ProgressFn& progress) {
  const auto t0 = Clock::now();
  TwoBodies bodies = fingertip_with(finger, o.solve.element_mm, mesh_actuator(actuator, o.solve.element_mm),
                                    {actuator.membrane, actuator.layer}, {"membrane", "silicone layer"}, 0.0);
  ProblemSpec spec;
  spec.mesh = bodies.mesh;
  spec.materials = bodies.materials;
  spec.plane = o.solve.plane;
  spec.held = {{"bone"}, {"bonded"}};
  if (actuator.membrane_slides) {  // on a frictionless substrate: down held, along free
    spec.held = {{"bone"}};
    spec.rollers = {{"bonded"}, {"actuator_left"}, {"actuator_right"}};
  }
  spec.pressures = {{"chamber"}};
  const double softest = std::min(actuator.layer.initial_youngs_kPa(), finger.skin.initial_youngs_kPa());
  spec.contact = contact_between("actuator_top", softest, o.solve);
  ContactSolver solver(spec);

  ContactRun run;
  run.mesh = bodies.mesh;
  run.materials = bodies.materials;
  run.material_names = bodies.names;
  run.unknowns = solver.unknowns();
  const bool together = o.loading == ActuatorLoading::together;
  const int press_steps = together ? 0 : std::max(1, static_cast<int>(std::lround(o.press_mm / o.press_step_mm)));
  const int total = press_steps + int(o.pressures_kPa.size());
  int done = 0;
  auto relay = [&](const StepProgress& p) {
    if (!progress) return;
    StepProgress q = p;
    q.step = ++done;
    q.steps = total;
    q.elapsed_s = seconds_since(t0);
    q.remaining_s = q.elapsed_s / q.step * (q.steps - q.step);
    progress(q);
  };
  // First the press, with no air (press_first; `together` presses as the air rises).
  std::vector<double> depths;
  for (int k = 1; k <= press_steps; ++k) depths.push_back(o.press_mm * k / press_steps);
  step_through(
      solver, run, depths, 0.0, o.solve, "mm",
      [](double depth) {
        LoadState s;
        s.held_mm["bone"] = {0.0, -depth};
        return s;
      },
      [](double, int) {}, relay, t0);
  // Then the air, the finger held (or pressed in proportion to the air).
  std::vector<double> pressures = o.pressures_kPa;
  std::sort(pressures.begin(), pressures.end());
  const double highest_kPa = pressures.empty() ? 0.0 : pressures.back();
  auto at_pressure = [&](double p) { return actuator_load(o, p, highest_kPa); };
  auto record = [&](double p, int iterations) {
    ContactStep step;
    step.load = p;
    step.newton_iterations = iterations;
    step.profile = solver.contact_profile();
    step.force_N_per_m = solver.contact_force_per_mm()[1];
    summarise_profile(step);
    run.steps.push_back(std::move(step));
  };
  if (!pressures.empty() && pressures.front() <= 0) {
    // Pressed and no air: the state the press left (press_first), or the finger resting on the
    // actuator untouched (together), solved so that its profile is a solution's.
    const int iterations = together ? solver.solve(at_pressure(0.0), o.solve.max_newton_iterations).iterations : 0;
    record(0.0, iterations);
    relay({});
    pressures.erase(pressures.begin());
  }
  step_through(solver, run, pressures, 0.0, o.solve, "kPa", at_pressure, record, relay, t0);
  run.last = solver.deformed();
  run.wall_s = seconds_since(t0);
  return run;
}

LoadState actuator_load(const ActuatorOptions& o, double pressure_kPa, double highest_kPa) {
  LoadState s;
  const bool together = o.loading == ActuatorLoading::together;
  const double press_mm = !together ? o.press_mm : highest_kPa > 0 ? o.press_mm * pressure_kPa / highest_kPa : 0.0;
  s.held_mm["bone"] = {0.0, -press_mm};
  s.pressure_kPa["chamber"] = pressure_kPa;
  return s;
}

StressLine fit_stress_line(const std::vector<double>& x, const std::vector<double>& y) {
  StressLine line;
  line.points = std::min(x.size(), y.size());
  if (line.points < 2) return line;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < line.points; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= double(line.points);
  my /= double(line.points);
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < line.points; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(sxx > 0)) return line;
  line.slope = sxy / sxx;
  line.intercept_kPa = my - line.slope * mx;
  // At most 1: a line through two points, or through points on a line, has R^2 1 exactly, which
  // the rounding of sxy^2 / (sxx syy) can put a few ulp above (1.0000000000000002 refused by the
  // stress-model file's own check, 2026-11-28).
  line.r_squared = syy > 0 ? std::min(1.0, sxy * sxy / (sxx * syy)) : 1.0;
  return line;
}

StressLine fit_stress_line(const ContactRun& run) {
  std::vector<double> pressure_kPa, stress_kPa;
  pressure_kPa.reserve(run.steps.size());
  stress_kPa.reserve(run.steps.size());
  for (const ContactStep& step : run.steps) {
    pressure_kPa.push_back(step.load);
    stress_kPa.push_back(step.peak_kPa);
  }
  return fit_stress_line(pressure_kPa, stress_kPa);
}

}  // namespace palprig::mechanics
