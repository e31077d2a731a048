#pragma once
// Excursions of the plant from its command: stretches where a channel's regulator monitor is
// further from what was commanded than the regulator tolerance (3 kPa: `calibrate fit`'s
// --regulator-tolerance-kPa, beyond any hysteresis or offset a working regulator shows). A dip
// of 16 kPa for half a second is a leak, a supply that sagged or a link that lost frames, and a
// calibration or an evaluation that went on over it must say so, with the time, even when no
// outage was counted.
#include <cstddef>
#include <string>
#include <vector>

#include "models/channel_pressures.hpp"

namespace palprig {

inline constexpr double kDefaultRegulatorTolerance_kPa = 3.0;

struct Excursion {
  int channel = 0;        // 1-based
  double start_s = 0;     // time of its first sample (the caller's clock)
  double duration_s = 0;  // to its last sample
  double worst_kPa = 0;   // monitor minus command at its furthest (negative: a dip)
  double worst_at_s = 0;
};

// Follows samples in time order and joins consecutive ones beyond the tolerance into one
// excursion per channel.
class ExcursionWatch {
 public:
  explicit ExcursionWatch(double tolerance_kPa = kDefaultRegulatorTolerance_kPa) : tolerance_kPa_(tolerance_kPa) {}

  // One sample of a channel (0-based); a non-finite monitor (no reading) ends any open excursion.
  void add(std::size_t channel, double t_s, double command_kPa, double monitor_kPa);
  // Ends the open excursions; call before reading them.
  void close();
  const std::vector<Excursion>& excursions() const noexcept { return done_; }
  double tolerance_kPa() const noexcept { return tolerance_kPa_; }

 private:
  double tolerance_kPa_;
  struct Open {
    bool open = false;
    Excursion e;
    double last_s = 0;
  };
  Open open_[kFingerCount];
  std::vector<Excursion> done_;
};

// "channel 2: 16.1 kPa below the command at 20.31 s (0.42 s beyond 3 kPa)"
std::string excursion_text(const Excursion& e, double tolerance_kPa);

}  // namespace palprig
