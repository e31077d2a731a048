#pragma once
// The pen tablet (paper 002's touchpad) in the rig file: where its active area sits relative
// to the scene and how its pressure reading turns into a pressing force.
//
//   "tablet": {"device": "auto",                 (or /dev/input/eventN; --input tablet:PATH wins)
//              "origin_mm": [20, 15],            (tablet mm that land on the scene's 0,0)
//              "pressure_curve_N": [[0, 0], [0.5, 1.2], [1, 4]],
//              "size_mm": [152, 95],             (only for tablets that report no resolution)
//              "grab": false,                    (true: the desktop stops seeing the pen)
//              "reader_fifo_priority": 60}       (SCHED_FIFO of the reader thread, below the
//                                                 loop's 80; 0: normal scheduling)
//
// The pressure curve maps the normalised pressure reading (0 at the device minimum, 1 at its
// maximum) to newtons, piecewise linear through the points; measure it once with a scale.
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace palprig {

class JsonObject;

struct PressureCurve {
  // (normalised pressure 0..1, force N), starting at pressure 0 and ending at 1, rising in
  // pressure and never falling in force. Default: linear to 4 N at full pressure (a typical
  // pen's maximum force is 3-5 N).
  std::vector<std::pair<double, double>> points{{0.0, 0.0}, {1.0, 4.0}};
  double force_N(double normalised) const noexcept;
};

struct TabletConfig {
  std::string device = "auto";
  std::array<double, 2> origin_mm{0.0, 0.0};
  PressureCurve pressure;
  std::array<double, 2> size_mm{0.0, 0.0};  // 0: use the device's resolution
  bool grab = false;
  int reader_fifo_priority = 60;  // see runtime/thread_priorities.hpp
};

// Throws InputError naming the file and field.
TabletConfig parse_tablet_config(const JsonObject& section);

}  // namespace palprig
