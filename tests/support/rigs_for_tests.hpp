#pragma once
// What the loop and rig-step tests share: a scene hard on the right, quiet plants, a pen at
// rest and a backend that records every setpoint reaching the device and fails on request.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "inputs/input_source.hpp"
#include "models/pneumatic_plant.hpp"
#include "models/scene.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig::test_rigs {

// Finger 2 (16 mm along x from the pen) over hard tissue when the pen is at x = 50.
inline MapScene hard_right_scene() {
  std::vector<float> v(std::size_t{11} * 11);
  for (int r = 0; r < 11; ++r)
    for (int c = 0; c < 11; ++c) v[r * 11 + c] = c >= 6 ? 1.0f : 0.0f;
  return MapScene(StiffnessMap(11, 11, 100, 100, v), MapSampling::nearest);
}

inline std::array<PlantParams, kFingerCount> quiet_plants() {
  PlantParams p;
  p.noise_sd_kPa = 0;
  p.hysteresis_kPa = 0;
  return {p, p, p};
}

// A pen resting at one place, pressing 2 N.
class RestingPen final : public InputSource {
 public:
  explicit RestingPen(double x = 50, double y = 20) : x_(x), y_(y) {}
  TouchSample latest(double t) noexcept override { return {t, x_, y_, 2.0, true}; }
  double duration_s() const noexcept override { return 0; }
  std::string describe() const override { return "resting pen"; }

 private:
  double x_, y_;
};

// Records every setpoint that reaches the device; the write numbered fail_at_write (1-based)
// fails with fail_message. Monitors read the last setpoint (0 after a vent).
class RecordingRig : public RigBackend {
 public:
  explicit RecordingRig(int fail_at = -1, std::string message = "valve driver overheated on channel 3")
      : RigBackend(60), fail_at_write(fail_at), fail_message(std::move(message)) {}
  std::string describe() const override { return "recording"; }
  BackendCapabilities capabilities() const override {
    BackendCapabilities c;
    c.link_kind = "in-process";
    return c;
  }
  std::vector<ChannelPressures> writes;
  ChannelPressures last{};
  int vents = 0;
  int fail_at_write;
  std::string fail_message;

 protected:
  void do_open() override {}
  void do_close() noexcept override {}
  BackendStatus do_write(const ChannelPressures& p, double) noexcept override {
    writes.push_back(p);
    last = p;
    if (int(writes.size()) == fail_at_write) {
      set_error(fail_message.c_str());
      return BackendStatus::error;
    }
    return BackendStatus::ok;
  }
  BackendStatus do_read(ChannelPressures& m, double) noexcept override {
    m = last;
    return BackendStatus::ok;
  }
  BackendStatus do_vent() noexcept override {
    ++vents;
    last = {};
    return BackendStatus::ok;
  }
};

}  // namespace palprig::test_rigs
