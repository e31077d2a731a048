#pragma once
// One reading of the pen on the touchpad, already in physical units.
namespace palprig {

struct TouchSample {
  double t_s = 0;        // when it was taken, on the loop's clock (seconds since run start)
  double x_mm = 0, y_mm = 0;
  double force_N = 0;    // pressing force, >= 0
  bool in_contact = false;
};

}  // namespace palprig
