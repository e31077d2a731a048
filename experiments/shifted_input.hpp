#pragma once
// ShiftedInput: an input source whose time 0 is set when a trial starts, so a scripted pen
// (a raster) runs from each trial's onset. Samples come back on the caller's clock.
#include <memory>
#include <string>

#include "inputs/input_source.hpp"

namespace palprig {

class ShiftedInput final : public InputSource {
 public:
  ShiftedInput() = default;
  // Replace the inner source and make its time 0 the given time.
  void restart(std::unique_ptr<InputSource> inner, double t0_s) {
    inner_ = std::move(inner);
    t0_s_ = t0_s;
  }
  TouchSample latest(double t_s) noexcept override {
    if (!inner_) return TouchSample{t_s, 0, 0, 0, false};
    TouchSample s = inner_->latest(t_s - t0_s_);
    s.t_s += t0_s_;
    return s;
  }
  double duration_s() const noexcept override { return inner_ ? inner_->duration_s() : 0.0; }
  std::string describe() const override { return inner_ ? inner_->describe() : "none"; }

 private:
  std::unique_ptr<InputSource> inner_;
  double t0_s_ = 0;
};

}  // namespace palprig
