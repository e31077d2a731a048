#pragma once
// A number carrying its first and second derivatives with respect to four variables (forward
// mode, second order): what a strain energy needs to hand GetFEM its gradient and Hessian in
// C++ (mechanics/strain_energy.cpp, contact_solver.cpp's energy operators). Written by hand:
// Ceres' Jet carries first derivatives only, and Eigen's AutoDiffScalar nested twice allocates.
// Only the operations the energies use.
#include <array>
#include <cmath>

namespace palprig::mechanics {

struct SecondOrderDual {
  double value = 0;
  std::array<double, 4> gradient{};
  std::array<double, 16> hessian{};  // (i, j) at 4 i + j

  static SecondOrderDual constant(double c) {
    SecondOrderDual r;
    r.value = c;
    return r;
  }
  // Variable k of the four, at value v.
  static SecondOrderDual variable(int k, double v) {
    SecondOrderDual r;
    r.value = v;
    r.gradient[static_cast<std::size_t>(k)] = 1;
    return r;
  }
};

inline SecondOrderDual operator+(const SecondOrderDual& a, const SecondOrderDual& b) {
  SecondOrderDual r;
  r.value = a.value + b.value;
  for (std::size_t i = 0; i < 4; ++i) r.gradient[i] = a.gradient[i] + b.gradient[i];
  for (std::size_t i = 0; i < 16; ++i) r.hessian[i] = a.hessian[i] + b.hessian[i];
  return r;
}
inline SecondOrderDual operator+(const SecondOrderDual& a, double c) {
  SecondOrderDual r = a;
  r.value += c;
  return r;
}
inline SecondOrderDual operator*(double c, const SecondOrderDual& a) {
  SecondOrderDual r;
  r.value = c * a.value;
  for (std::size_t i = 0; i < 4; ++i) r.gradient[i] = c * a.gradient[i];
  for (std::size_t i = 0; i < 16; ++i) r.hessian[i] = c * a.hessian[i];
  return r;
}
inline SecondOrderDual operator-(const SecondOrderDual& a, const SecondOrderDual& b) { return a + (-1.0) * b; }
inline SecondOrderDual operator*(const SecondOrderDual& a, const SecondOrderDual& b) {
  SecondOrderDual r;
  r.value = a.value * b.value;
  for (std::size_t i = 0; i < 4; ++i) r.gradient[i] = a.gradient[i] * b.value + b.gradient[i] * a.value;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      r.hessian[4 * i + j] = a.hessian[4 * i + j] * b.value + b.hessian[4 * i + j] * a.value +
                             a.gradient[i] * b.gradient[j] + b.gradient[i] * a.gradient[j];
  return r;
}
// f(a), given f(a), f'(a) and f''(a).
inline SecondOrderDual chain(const SecondOrderDual& a, double f, double df, double d2f) {
  SecondOrderDual r;
  r.value = f;
  for (std::size_t i = 0; i < 4; ++i) r.gradient[i] = df * a.gradient[i];
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      r.hessian[4 * i + j] = df * a.hessian[4 * i + j] + d2f * a.gradient[i] * a.gradient[j];
  return r;
}
inline SecondOrderDual pow(const SecondOrderDual& a, double p) {
  return chain(a, std::pow(a.value, p), p * std::pow(a.value, p - 1), p * (p - 1) * std::pow(a.value, p - 2));
}

}  // namespace palprig::mechanics
