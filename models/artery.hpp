#pragma once
// Arteries and the pulse each finger feels (papers 000, 003, 004).
//
// An artery is a centreline (a polyline on the skin plane) at a depth, with a radius. Along it
// sit pulse point sources spaced at most one range radius apart (000), at the centreline's
// depth. The artery is a pulse region (004): a box around it (broad phase) decides whether a
// finger is near at all, then the sources are tested one by one (narrow phase).
//
// Per finger, with T the finger centre on the skin and F the pressing force:
//   activation (003)  on when d <= R + h + delta, off when d >= R + h + delta + epsilon, with d
//                     the distance from T to the centreline, R the artery radius and h the
//                     tissue over it (so R + h is the centreline depth). delta defaults to the
//                     margin that switches the pulse on when the centreline passes under the
//                     fingertip pad (8 mm from its centre); epsilon to 003's 0.57 mm.
//   distance (000)    each source within range r gives k (r - |P_i - T|); the sources' sum,
//                     capped, is scaled so that a finger straight over a source feels the full
//                     amplitude (k = 1 / (r - depth)). Summing keeps the pulse nearly even along
//                     the artery where neighbouring ranges overlap.
//   force (003)       A = (F - F_min) / (F_max - F_min) * mu inside the window, 0 outside it:
//                     too light a touch feels nothing, pressing harder than systolic occludes.
//   pulse pressure    amplitude_kPa * distance factor * force factor * waveform(phase).
// A finger over two arteries feels both; every finger over an artery feels it.
//
// Rates and amplitudes can change while running: the operator's values arrive with each tick as
// PulseSettings (the tick's inputs), and a new rate applies from that tick with the phase kept
// continuous (PulseClock). The field itself never changes after it is made.
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "models/finger_layout.hpp"
#include "models/frep.hpp"
#include "models/pulse_waveform.hpp"

namespace palprig {

inline constexpr std::size_t kMaxArteries = 8;
inline constexpr std::size_t kMaxSourcesPerArtery = 512;
inline constexpr double kMaxPulseAmplitude_kPa = 50.0;

// 003's force window. Defaults: 60 and 120 mmHg (diastolic, systolic) over a 1.5 cm^2 fingertip
// contact, i.e. 8.0 kPa and 16.0 kPa times 150 mm^2.
struct ForceWindow {
  double min_N = 1.2;
  double max_N = 2.4;
  double gain = 1.0;  // mu: the factor reached at F_max

  double factor(double force_N) const noexcept {
    if (!(force_N >= min_N && force_N <= max_N)) return 0.0;
    return gain * (force_N - min_N) / (max_N - min_N);
  }
};

struct ArterySpec {
  std::string name;
  std::vector<Point2_mm> path;  // centreline on the skin plane, at least 2 points
  double depth_mm = 6.0;        // of the centreline below the skin (R + h)
  double radius_mm = 2.0;       // R
  double range_mm = 0.0;        // r of each source; 0: depth + activation + release margins
  double amplitude_kPa = 6.0;   // pulse pressure straight over the artery at the force window's top
  double rate_bpm = 72.0;
  double phase_offset = 0.0;  // cycles: the pulse wave arrives later in distal arteries
  PulseWaveform waveform;
  ForceWindow force_window;
  // False when the scene left the window out: a window measured by calibration (003's
  // sphygmomanometer procedure) then takes its place.
  bool own_force_window = true;
  double activation_margin_mm = -1.0;  // delta; negative: from the fingertip pad radius
  double release_margin_mm = 0.57;     // epsilon
};

class Artery {
 public:
  // Validates (BadInput naming the problem) and places the sources.
  Artery(ArterySpec spec, double finger_pad_radius_mm);

  const ArterySpec& spec() const noexcept { return spec_; }
  const std::vector<Point3_mm>& sources() const noexcept { return sources_; }
  double on_distance_mm() const noexcept { return on_mm_; }
  double off_distance_mm() const noexcept { return off_mm_; }
  double range_mm() const noexcept { return range_mm_; }
  double length_mm() const noexcept { return length_mm_; }

  // Distance on the skin plane from a point to the centreline (what a mark is scored by).
  double centreline_distance_mm(const Point2_mm& p) const noexcept;
  // Broad phase: may the pulse be felt (or activation change) at p?
  bool in_region(const Point2_mm& p) const noexcept;
  // 000's distance law, normalised: 1 straight over a source, 0 beyond every range.
  double distance_factor(const Point2_mm& p) const noexcept;

 private:
  ArterySpec spec_;
  std::vector<Point3_mm> sources_;
  double range_mm_ = 0, on_mm_ = 0, off_mm_ = 0, length_mm_ = 0;
  double region_x0_ = 0, region_y0_ = 0, region_x1_ = 0, region_y1_ = 0;
};

// The operator's rate and amplitude per artery for one tick; NaN: the scene's own value.
struct PulseSettings {
  static constexpr double kScene = std::numeric_limits<double>::quiet_NaN();
  std::array<double, kMaxArteries> rate_bpm = filled(kScene);
  std::array<double, kMaxArteries> amplitude_kPa = filled(kScene);

 private:
  static constexpr std::array<double, kMaxArteries> filled(double v) {
    std::array<double, kMaxArteries> a{};
    for (double& x : a) x = v;
    return a;
  }
};

struct PulseClocks {
  std::array<PulseClock, kMaxArteries> clock{};
  bool started = false;
};

struct PulseActivation {
  std::array<bool, kMaxArteries> on{};
};

// One finger on the skin, for felt(): its centre, the pen's pressing force, and whether the pen
// is down (a lifted finger releases every artery).
struct FingerContact {
  Point2_mm at{};
  double force_N = 0;
  bool in_contact = false;
};

// How far ahead felt() also looks, for the lag compensator: the value lead_s ahead, with
// rectangular pulses starting rise_advance_s and ending fall_advance_s early (its anticipation).
struct PulseLookahead {
  double lead_s = 0;
  double rise_advance_s = 0;
  double fall_advance_s = 0;
};

struct PulseFelt {
  double now_kPa = 0;    // pulse pressure at t
  double ahead_kPa = 0;  // the same finger's pulse pressure at t + lead (for lag compensation)
  int arteries_on = 0;
};

class PulseField {
 public:
  PulseField() = default;
  PulseField(std::vector<ArterySpec> arteries, double finger_pad_radius_mm);
  PulseField(const PulseField&) = delete;
  PulseField& operator=(const PulseField&) = delete;

  std::size_t size() const noexcept { return arteries_.size(); }
  bool empty() const noexcept { return arteries_.empty(); }
  const Artery& artery(std::size_t i) const { return arteries_.at(i); }
  // Index of the artery with this name, or -1.
  int find(const std::string& name) const noexcept;

  // The rates and amplitudes an operator may set: kMinPulseRateBpm..kMaxPulseRateBpm, and
  // 0..kMaxPulseAmplitude_kPa (kPa straight over the artery at the force window's top).
  static bool valid_rate_bpm(double bpm) noexcept;
  static bool valid_amplitude_kPa(double amplitude_kPa) noexcept;
  // What artery i beats at and how strongly with these settings (the scene's where they are NaN).
  double rate_bpm(std::size_t artery, const PulseSettings& settings) const noexcept;
  double amplitude_kPa(std::size_t artery, const PulseSettings& settings) const noexcept;

  // Loop thread, once per tick before felt(): start the clocks (phase 0 + offset at t = 0 of
  // the run) or apply the settings' rates from t.
  void update_clocks(PulseClocks& clocks, double t_s, const PulseSettings& settings = {}) const noexcept;
  // Loop thread, per finger: update its activation and return its pulse pressure now and
  // ahead.lead_s ahead (see PulseLookahead). measured_window, when given, serves arteries whose
  // scene left their force window out. A lifted finger releases every artery.
  PulseFelt felt(const FingerContact& finger, const PulseClocks& clocks, PulseActivation& activation, double t_s,
                 const PulseLookahead& ahead, const ForceWindow* measured_window = nullptr,
                 const PulseSettings& settings = {}) const noexcept;

 private:
  std::vector<Artery> arteries_;
};

}  // namespace palprig
