#include "models/artery.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/error.hpp"

namespace palprig {

namespace {

void need_artery(bool ok, const std::string& what) {
  if (!ok) throw BadInput(what);
}

double segment_distance(const Point2_mm& p, const Point2_mm& a, const Point2_mm& b) noexcept {
  const double ex = b.x_mm - a.x_mm, ey = b.y_mm - a.y_mm;
  const double len2 = ex * ex + ey * ey;
  const double t = len2 > 0 ? std::clamp(((p.x_mm - a.x_mm) * ex + (p.y_mm - a.y_mm) * ey) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x_mm - a.x_mm - t * ex, p.y_mm - a.y_mm - t * ey);
}

}  // namespace

Artery::Artery(ArterySpec spec, double pad_radius_mm) : spec_(std::move(spec)) {
  const std::string who = "artery '" + spec_.name + "': ";
  need_artery(spec_.path.size() >= 2, who + "its path needs at least 2 points");
  for (const Point2_mm& p : spec_.path)
    need_artery(std::isfinite(p.x_mm) && std::isfinite(p.y_mm), who + "path points must be finite");
  need_artery(std::isfinite(spec_.radius_mm) && spec_.radius_mm > 0, who + "radius must be > 0");
  need_artery(std::isfinite(spec_.depth_mm) && spec_.depth_mm >= spec_.radius_mm,
              who + "depth of the centreline must be at least the radius (the artery lies under the skin)");
  need_artery(std::isfinite(spec_.amplitude_kPa) && spec_.amplitude_kPa >= 0, who + "amplitude must be >= 0");
  need_artery(std::isfinite(spec_.rate_bpm) && spec_.rate_bpm >= kMinPulseRateBpm && spec_.rate_bpm <= kMaxPulseRateBpm,
              who + "rate must lie in 20..250 BPM");
  need_artery(std::isfinite(spec_.phase_offset), who + "phase offset must be finite");
  const ForceWindow& fw = spec_.force_window;
  need_artery(std::isfinite(fw.min_N) && std::isfinite(fw.max_N) && fw.min_N >= 0 && fw.min_N < fw.max_N,
              who + "force window needs 0 <= min < max");
  need_artery(std::isfinite(fw.gain) && fw.gain > 0, who + "force window gain must be > 0");
  need_artery(std::isfinite(pad_radius_mm) && pad_radius_mm > 0, who + "fingertip pad radius must be > 0");
  need_artery(std::isfinite(spec_.release_margin_mm) && spec_.release_margin_mm >= 0,
              who + "release margin must be >= 0");

  const double depth = spec_.depth_mm;
  const double delta =
      spec_.activation_margin_mm >= 0 ? spec_.activation_margin_mm : std::hypot(depth, pad_radius_mm) - depth;
  need_artery(std::isfinite(delta), who + "activation margin must be finite");
  on_mm_ = depth + delta;  // R + h + delta
  off_mm_ = on_mm_ + spec_.release_margin_mm;
  range_mm_ = spec_.range_mm > 0 ? spec_.range_mm : off_mm_;
  need_artery(
      std::isfinite(range_mm_) && range_mm_ > depth,
      who + "source range must exceed the depth (" + std::to_string(depth) + " mm), or the pulse is never felt");

  // Sources at both ends and evenly between, no further apart than one range radius (000).
  std::vector<double> cumulative{0.0};
  for (std::size_t i = 1; i < spec_.path.size(); ++i)
    cumulative.push_back(cumulative.back() + std::hypot(spec_.path[i].x_mm - spec_.path[i - 1].x_mm,
                                                        spec_.path[i].y_mm - spec_.path[i - 1].y_mm));
  length_mm_ = cumulative.back();
  need_artery(length_mm_ > 0, who + "path has zero length");
  const std::size_t n = static_cast<std::size_t>(std::ceil(length_mm_ / range_mm_)) + 1;
  need_artery(n <= kMaxSourcesPerArtery,
              who + "too many pulse sources (" + std::to_string(n) + "); use a larger range");
  std::size_t seg = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = length_mm_ * static_cast<double>(k) / static_cast<double>(n - 1);
    while (seg + 2 < spec_.path.size() && cumulative[seg + 1] < s) ++seg;
    const double seg_len = cumulative[seg + 1] - cumulative[seg];
    const double f = seg_len > 0 ? std::clamp((s - cumulative[seg]) / seg_len, 0.0, 1.0) : 0.0;
    const Point2_mm& a = spec_.path[seg];
    const Point2_mm& b = spec_.path[seg + 1];
    sources_.push_back({a.x_mm + f * (b.x_mm - a.x_mm), a.y_mm + f * (b.y_mm - a.y_mm), depth});
  }

  // Broad phase box: the path's box grown by the farthest lateral reach of a source or of the
  // release distance.
  const double reach =
      std::max(std::sqrt(range_mm_ * range_mm_ - depth * depth), std::sqrt(off_mm_ * off_mm_ - depth * depth));
  region_x0_ = region_x1_ = spec_.path[0].x_mm;
  region_y0_ = region_y1_ = spec_.path[0].y_mm;
  for (const Point2_mm& p : spec_.path) {
    region_x0_ = std::min(region_x0_, p.x_mm);
    region_x1_ = std::max(region_x1_, p.x_mm);
    region_y0_ = std::min(region_y0_, p.y_mm);
    region_y1_ = std::max(region_y1_, p.y_mm);
  }
  region_x0_ -= reach;
  region_y0_ -= reach;
  region_x1_ += reach;
  region_y1_ += reach;
}

double Artery::centreline_distance_mm(const Point2_mm& p) const noexcept {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < spec_.path.size(); ++i)
    best = std::min(best, segment_distance(p, spec_.path[i - 1], spec_.path[i]));
  return best;
}

bool Artery::in_region(const Point2_mm& p) const noexcept {
  return p.x_mm >= region_x0_ && p.x_mm <= region_x1_ && p.y_mm >= region_y0_ && p.y_mm <= region_y1_;
}

double Artery::distance_factor(const Point2_mm& p) const noexcept {
  const double r = range_mm_, depth = spec_.depth_mm;
  double sum = 0;
  for (const Point3_mm& s : sources_) {
    const double dx = s.x_mm - p.x_mm, dy = s.y_mm - p.y_mm;
    if (std::abs(dx) > r || std::abs(dy) > r) continue;  // cheap reject before the square root
    const double d = std::sqrt(dx * dx + dy * dy + depth * depth);
    if (d < r) sum += r - d;
  }
  return std::min(sum / (r - depth), 1.0);
}

PulseField::PulseField(std::vector<ArterySpec> arteries, double pad_radius_mm) {
  if (arteries.size() > kMaxArteries)
    throw BadInput("at most " + std::to_string(kMaxArteries) + " arteries per scene, got " +
                   std::to_string(arteries.size()));
  for (ArterySpec& a : arteries) {
    if (find(a.name) >= 0) throw BadInput("two arteries are named '" + a.name + "'");
    arteries_.emplace_back(std::move(a), pad_radius_mm);
  }
}

int PulseField::find(const std::string& name) const noexcept {
  for (std::size_t i = 0; i < arteries_.size(); ++i)
    if (arteries_[i].spec().name == name) return static_cast<int>(i);
  return -1;
}

bool PulseField::valid_rate_bpm(double bpm) noexcept {
  return std::isfinite(bpm) && bpm >= kMinPulseRateBpm && bpm <= kMaxPulseRateBpm;
}

bool PulseField::valid_amplitude_kPa(double amplitude_kPa) noexcept {
  return std::isfinite(amplitude_kPa) && amplitude_kPa >= 0 && amplitude_kPa <= kMaxPulseAmplitude_kPa;
}

double PulseField::rate_bpm(std::size_t artery, const PulseSettings& settings) const noexcept {
  if (artery >= arteries_.size()) return 0.0;
  const double set = settings.rate_bpm[artery];
  return valid_rate_bpm(set) ? set : arteries_[artery].spec().rate_bpm;
}

double PulseField::amplitude_kPa(std::size_t artery, const PulseSettings& settings) const noexcept {
  if (artery >= arteries_.size()) return 0.0;
  const double set = settings.amplitude_kPa[artery];
  return valid_amplitude_kPa(set) ? set : arteries_[artery].spec().amplitude_kPa;
}

void PulseField::update_clocks(PulseClocks& clocks, double t_s, const PulseSettings& settings) const noexcept {
  for (std::size_t i = 0; i < arteries_.size(); ++i) {
    const double want = rate_bpm(i, settings);
    PulseClock& c = clocks.clock[i];
    if (!clocks.started) {
      c = PulseClock{want, 0.0, arteries_[i].spec().phase_offset};
    } else if (want != c.bpm && std::isfinite(t_s)) {
      c.change_rate(want, t_s);
    }
  }
  clocks.started = true;
}

PulseFelt PulseField::felt(const FingerContact& finger, const PulseClocks& clocks, PulseActivation& activation,
                           double t_s, const PulseLookahead& ahead, const ForceWindow* measured_window,
                           const PulseSettings& settings) const noexcept {
  PulseFelt out;
  const Point2_mm& at = finger.at;
  const double force_N = finger.force_N;
  const bool in_contact = finger.in_contact;
  const double lead_s = ahead.lead_s, rise_advance_s = ahead.rise_advance_s, fall_advance_s = ahead.fall_advance_s;
  const bool usable = in_contact && std::isfinite(at.x_mm) && std::isfinite(at.y_mm) && std::isfinite(force_N);
  for (std::size_t i = 0; i < arteries_.size(); ++i) {
    bool& on = activation.on[i];
    const Artery& a = arteries_[i];
    if (!usable || !a.in_region(at)) {
      on = false;
      continue;
    }
    const double lateral = a.centreline_distance_mm(at);
    const double d = std::hypot(lateral, a.spec().depth_mm);
    if (on ? d >= a.off_distance_mm() : d > a.on_distance_mm()) {
      on = false;
      continue;
    }
    on = true;
    ++out.arteries_on;
    const ForceWindow& window =
        !a.spec().own_force_window && measured_window ? *measured_window : a.spec().force_window;
    const double amp = amplitude_kPa(i, settings) * a.distance_factor(at) * window.factor(force_N);
    if (amp <= 0) continue;
    const PulseClock& c = clocks.clock[i];
    out.now_kPa += amp * a.spec().waveform.value(c.phase(t_s));
    const double cycles_per_s = c.bpm / 60.0;
    out.ahead_kPa += amp * a.spec().waveform.value_advanced(c.phase(t_s + lead_s), rise_advance_s * cycles_per_s,
                                                            fall_advance_s * cycles_per_s);
  }
  return out;
}

}  // namespace palprig
