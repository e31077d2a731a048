#pragma once
// Volts <-> DAQ counts for one comedi channel, and kPa on top. Pure functions over comedilib's
// conversion polynomials, so they are tested without a device.
//
// comedi_from_physical() evaluates the polynomial and rounds; it does not clamp, and a value
// below 0 or above maxdata would wrap into a wild count on the DAC. So the volts are clamped
// first to what is safe: the regulator's span, the card's range, and the volts the polynomial
// maps to counts 0 and maxdata (a calibrated polynomial may reach past the range edges).
#include <comedilib.h>

#include "models/regulator_scale.hpp"

namespace palprig {

struct ComediConversion {
  comedi_polynomial_t to_counts{};  // volts -> counts (COMEDI_FROM_PHYSICAL)
  comedi_polynomial_t to_volts{};   // counts -> volts (COMEDI_TO_PHYSICAL)
  lsampl_t maxdata = 0;
  double safe_lo_V = 0, safe_hi_V = 0;  // volts that convert to counts within 0..maxdata
  RegulatorScale regulator;
};

// The straight line a range gives an uncalibrated board (what comedi_get_hardcal_converter
// returns for it): counts 0..maxdata over range_min..range_max volts.
comedi_polynomial_t linear_polynomial(double range_min_V, double range_max_V, lsampl_t maxdata,
                                      comedi_conversion_direction direction);

// Combine the polynomials of one channel/range with the regulator's span and scale.
ComediConversion make_comedi_conversion(const comedi_polynomial_t& to_counts, const comedi_polynomial_t& to_volts,
                                        lsampl_t maxdata, double range_min_V, double range_max_V, double span_lo_V,
                                        double span_hi_V, const RegulatorScale& regulator);

// kPa -> volts -> clamp -> comedi_from_physical -> counts (never above maxdata).
lsampl_t counts_from_kPa(const ComediConversion& conv, double pressure_kPa) noexcept;
lsampl_t counts_from_volts(const ComediConversion& conv, double volts) noexcept;
// counts -> comedi_to_physical -> volts -> kPa.
double kPa_from_counts(const ComediConversion& conv, lsampl_t counts) noexcept;
// counts -> comedi_to_physical -> volts (a load cell's input).
double volts_from_counts(const ComediConversion& conv, lsampl_t counts) noexcept;

}  // namespace palprig
