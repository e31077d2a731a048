#pragma once
// Paper 002's two finite-element experiments (section 2.3) on the bodies of models/fe_bodies.hpp:
// - indentation: the fingertip's bone pushed straight down into the tissue block, step by step
//   to a depth (7 mm in the paper), the peak contact stress and its profile at every step;
// - the actuator: the fingertip pressed onto the actuator (1 mm), then the air pressure raised
//   in steps (0..100 kPa), the peak contact stress at every pressure and its straight line.
// Both cut a step in half when Newton fails (at most `max_cuts` times in a row) and report
// progress after every step.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "mechanics/contact_solver.hpp"
#include "models/fe_bodies.hpp"

namespace palprig::mechanics {

struct SolveOptions {
  PlaneMode plane = PlaneMode::plane_strain;
  double element_mm = 1.0;  // where the contact is (body_meshes.hpp)
  int max_cuts = 6;
  int max_newton_iterations = 40;
  double augmentation_factor = 1.0;  // times the default contact augmentation (softest modulus / element)
};

struct StepProgress {
  int step = 0, steps = 0;  // done, of
  std::string what;         // "depth 3.5 mm", "air 40 kPa"
  double elapsed_s = 0;
  double remaining_s = 0;     // estimated from the steps so far
  int cuts = 0;               // steps halved so far
  int newton_iterations = 0;  // of the step just done
};
using ProgressFn = std::function<void(const StepProgress&)>;

// The contact stress a report quotes is averaged over this length of surface around each point:
// paper 002's element size (ABAQUS's CPRESS at a node of 1 mm elements stands for its two half
// elements), so the figure means the same whatever mesh computed it.
inline constexpr double kStressAveragingLength_mm = 1.0;

struct ContactStep {
  double load = 0;               // indentation depth (mm) or air pressure (kPa)
  double peak_kPa = 0;           // the highest contact stress averaged over kStressAveragingLength_mm
  double node_peak_kPa = 0;      // the highest nodal value (before that average)
  double peak_s_mm = 0;          // where on the fingertip (arc position from its lowest point)
  double force_N_per_m = 0;      // total contact force per unit thickness (= kPa mm)
  double contact_length_mm = 0;  // undeformed arc length of the fingertip carrying stress
  int newton_iterations = 0;
  std::vector<ContactNode> profile;
};

struct ContactRun {
  std::vector<ContactStep> steps;
  QuadMesh mesh;                       // the reference mesh (fingertip body 0, other body 1)
  std::vector<MaterialLaw> materials;  // by the mesh's material index
  std::vector<std::string> material_names;
  DeformedMesh last;  // the deformed mesh of the last step
  std::size_t unknowns = 0;
  int cuts = 0;  // steps halved on the way
  double wall_s = 0;
};

struct IndentationOptions {
  SolveOptions solve;
  double depth_mm = 7.0;
  double step_mm = 1.0;
  std::vector<double> depths_mm;  // when given: these steps instead of depth_mm / step_mm
  double finger_x_mm = 0.0;       // where the fingertip presses, from the block's middle
};
// Throws palprig::Error when a step cannot be solved even after max_cuts halvings.
ContactRun run_indentation(const FingertipBody& finger, const TissueBlock& block, const IndentationOptions& options,
                           const ProgressFn& progress = {});

// How the press and the air are applied. Paper 002: "The air pressure was simulated by a
// distributed load, increasing from 0 to 100 kPa ... At the same time, a downward displacement of
// 1 mm was applied to the finger bone": read as `together`, the press at air p is
// press_mm * p / (the highest pressure), so each step is a different press; `press_first` (the
// default) presses the finger fully, then raises the air, as a user pressing a rig does.
enum class ActuatorLoading { press_first, together };

struct ActuatorOptions {
  SolveOptions solve;
  double press_mm = 1.0;
  double press_step_mm = 0.25;
  std::vector<double> pressures_kPa{0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100};
  ActuatorLoading loading = ActuatorLoading::press_first;
};
ContactRun run_actuator(const FingertipBody& finger, const ActuatorBody& actuator, const ActuatorOptions& options,
                        const ProgressFn& progress = {});
// The load of one air-pressure step: the bone held at the full press (press_first) or at the press
// in proportion to the air (together: press_mm * pressure / highest), the chamber at the pressure.
LoadState actuator_load(const ActuatorOptions& options, double pressure_kPa, double highest_kPa);

// A least-squares line y = slope x + intercept with R^2 (the actuator's stress line). Written
// here rather than taken from calibration/, which sits above this floor.
struct StressLine {
  double slope = 0, intercept_kPa = 0, r_squared = 0;
  std::size_t points = 0;
};
StressLine fit_stress_line(const std::vector<double>& pressure_kPa, const std::vector<double>& stress_kPa);
// The same over a run's steps: each step's load (the air pressure) against its peak stress.
StressLine fit_stress_line(const ContactRun& run);

// The peak of one profile (averaged over kStressAveragingLength_mm) and where it is.
void summarise_profile(ContactStep& step);
// The mean of the piecewise-linear profile over [s - half, s + half] (0 beyond its ends).
double averaged_stress_kPa(const std::vector<ContactNode>& profile, double s_mm, double half_mm);

}  // namespace palprig::mechanics
