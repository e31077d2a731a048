#include "rigs/comedi_rig.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "core/input_error.hpp"

namespace palprig {

namespace {

std::string comedi_error_text() { return comedi_strerror(comedi_errno()); }

int aref_of(ComediReference r) {
  switch (r) {
    case ComediReference::ground: return AREF_GROUND;
    case ComediReference::common: return AREF_COMMON;
    case ComediReference::differential: return AREF_DIFF;
    case ComediReference::other: return AREF_OTHER;
  }
  return AREF_GROUND;
}

std::string ranges_text(comedi_t* dev, unsigned subdevice, unsigned channel) {
  std::ostringstream s;
  const int n = comedi_get_n_ranges(dev, subdevice, channel);
  for (int r = 0; r < n; ++r) {
    const comedi_range* range = comedi_get_range(dev, subdevice, channel, unsigned(r));
    if (!range) continue;
    s << (r ? ", " : "") << "[" << range->min << ", " << range->max << "]"
      << (range->unit == UNIT_volt ? " V" : " (not volts)");
  }
  return s.str();
}

}  // namespace

ComediRig::ComediRig(ComediRigConfig config) : RigBackend(config.p_max_kPa), config_(std::move(config)) {}

ComediRig::~ComediRig() { close(); }

std::string ComediRig::describe() const {
  return "comedi " + config_.device + (board_.empty() ? std::string() : " (" + board_ + ")");
}

void ComediRig::refuse(const std::string& field, const std::string& expected) const {
  throw InputError(config_.source, field, expected);
}

BackendCapabilities ComediRig::capabilities() const {
  BackendCapabilities c;
  c.link_kind = "comedi";
  c.endpoint = config_.device;
  describe_load_cells(c);
  return c;
}

void ComediRig::do_open() {
  // Quiet comedilib's own perror output: our message says it once, with the device path.
  comedi_loglevel(0);
  dev_ = comedi_open(config_.device.c_str());
  if (!dev_)
    refuse("comedi.device", "a comedi device at " + config_.device + " (comedi_open: " + comedi_error_text() + ")");
  board_ = std::string(comedi_get_driver_name(dev_)) + "/" + comedi_get_board_name(dev_);

  auto pick_subdevice = [&](int wanted, int type, const char* field, const char* what) -> unsigned {
    if (wanted >= 0) {
      if (comedi_get_subdevice_type(dev_, unsigned(wanted)) != type)
        refuse(std::string("comedi.") + field, std::string("an ") + what + " subdevice of " + config_.device + " (" +
                                                   board_ + "), subdevice " + std::to_string(wanted) + " is not one");
      return unsigned(wanted);
    }
    const int found = comedi_find_subdevice_by_type(dev_, type, 0);
    if (found < 0)
      refuse("comedi.device",
             std::string("a card with an ") + what + " subdevice; " + config_.device + " (" + board_ + ") has none");
    return unsigned(found);
  };
  ao_subdevice_ = pick_subdevice(config_.ao_subdevice, COMEDI_SUBD_AO, "ao_subdevice", "analog output");
  ai_subdevice_ = pick_subdevice(config_.ai_subdevice, COMEDI_SUBD_AI, "ai_subdevice", "analog input");

  // Soft calibration: the board needs it (SDF_SOFT_CALIBRATED) or the file asks for it.
  std::unique_ptr<comedi_calibration_t, void (*)(comedi_calibration_t*)> calibration(nullptr,
                                                                                     comedi_cleanup_calibration);
  const bool soft_needed = (comedi_get_subdevice_flags(dev_, ao_subdevice_) & SDF_SOFT_CALIBRATED) ||
                           (comedi_get_subdevice_flags(dev_, ai_subdevice_) & SDF_SOFT_CALIBRATED);
  const bool use_soft = config_.calibration == ComediCalibration::soft ||
                        (config_.calibration == ComediCalibration::automatic && soft_needed);
  if (use_soft) {
    std::string path = config_.calibration_file;
    if (path.empty()) {
      char* p = comedi_get_default_calibration_path(dev_);
      if (p) {
        path = p;
        std::free(p);
      }
    }
    calibration.reset(path.empty() ? nullptr : comedi_parse_calibration_file(path.c_str()));
    if (!calibration)
      refuse("comedi.calibration",
             "a soft calibration file for " + board_ + " (cannot read '" + path +
                 "': run comedi_soft_calibrate, or set \"calibration\": \"hard\" to use the nominal ranges)");
  } else if (config_.calibration == ComediCalibration::hard && soft_needed) {
    refuse("comedi.calibration", "\"soft\" or \"auto\": " + board_ + " is soft-calibrated (no hardware calibration)");
  }

  auto prepare = [&](unsigned subdevice, const ComediChannelSpec& spec, const std::string& field, bool output,
                     ComediConversion& conv, comedi_insn& insn, lsampl_t* data) {
    const int n_channels = comedi_get_n_channels(dev_, subdevice);
    if (spec.channel >= n_channels)
      refuse(field + ".channel", "a channel of subdevice " + std::to_string(subdevice) + " (0.." +
                                     std::to_string(n_channels - 1) + " on " + board_ + "), got " +
                                     std::to_string(spec.channel));
    const unsigned chan = unsigned(spec.channel);
    const int range = comedi_find_range(dev_, subdevice, chan, UNIT_volt, spec.volts_lo, spec.volts_hi);
    if (range < 0)
      refuse(field + ".volts_span",
             "a span one of the card's ranges holds (" + ranges_text(dev_, subdevice, chan) + ")");
    const comedi_range* r = comedi_get_range(dev_, subdevice, chan, unsigned(range));
    const lsampl_t maxdata = comedi_get_maxdata(dev_, subdevice, chan);
    comedi_polynomial_t to_counts{}, to_volts{};
    const comedi_conversion_direction fwd = output ? COMEDI_FROM_PHYSICAL : COMEDI_TO_PHYSICAL;
    const comedi_conversion_direction back = output ? COMEDI_TO_PHYSICAL : COMEDI_FROM_PHYSICAL;
    int rc_a, rc_b;
    if (use_soft) {
      rc_a = comedi_get_softcal_converter(subdevice, chan, unsigned(range), fwd, calibration.get(),
                                          output ? &to_counts : &to_volts);
      rc_b = comedi_get_softcal_converter(subdevice, chan, unsigned(range), back, calibration.get(),
                                          output ? &to_volts : &to_counts);
    } else {
      rc_a = comedi_get_hardcal_converter(dev_, subdevice, chan, unsigned(range), fwd, output ? &to_counts : &to_volts);
      rc_b =
          comedi_get_hardcal_converter(dev_, subdevice, chan, unsigned(range), back, output ? &to_volts : &to_counts);
    }
    // A soft calibration covers the directions the board needs; the reverse one of a channel
    // is then the nominal line of its range.
    if (rc_a < 0)
      refuse(field, "a calibrated conversion for channel " + std::to_string(chan) + " (" + comedi_error_text() + ")");
    if (rc_b < 0) {
      const comedi_polynomial_t nominal = linear_polynomial(r->min, r->max, maxdata, back);
      (output ? to_volts : to_counts) = nominal;
    }
    if (!output) {  // inputs only need counts -> volts; keep a nominal volts -> counts for symmetry
      to_counts = linear_polynomial(r->min, r->max, maxdata, COMEDI_FROM_PHYSICAL);
    }
    try {
      conv = make_comedi_conversion(to_counts, to_volts, maxdata, r->min, r->max, spec.volts_lo, spec.volts_hi,
                                    spec.regulator);
    } catch (const BadInput& e) {
      refuse(field, std::string("a usable conversion (") + e.what() + ")");
    }
    insn = comedi_insn{};
    insn.insn = output ? INSN_WRITE : INSN_READ;
    insn.n = 1;
    insn.data = data;
    insn.subdev = subdevice;
    insn.chanspec = CR_PACK(chan, unsigned(range), output ? AREF_GROUND : aref_of(config_.ai_reference));
  };
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    const std::string where = "channels[" + std::to_string(c) + "]";
    prepare(ao_subdevice_, config_.outputs[c], where + ".output", true, out_conv_[c], write_insns_[c], &out_counts_[c]);
    prepare(ai_subdevice_, config_.monitors[c], where + ".monitor", false, mon_conv_[c], read_insns_[c],
            &mon_counts_[c]);
  }
  if (load_cells()) {
    const auto& cells = load_cells()->channels;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      ComediChannelSpec spec;
      spec.channel = cells[i].comedi_channel;
      spec.volts_lo = cells[i].volts_lo;
      spec.volts_hi = cells[i].volts_hi;
      prepare(ai_subdevice_, spec, "load_cells.channels[" + std::to_string(i) + "].input", false, cell_conv_[i],
              cell_insns_[i], &cell_counts_[i]);
    }
    cell_list_.n_insns = unsigned(cells.size());
    cell_list_.insns = cell_insns_.data();
  }
  write_list_.n_insns = kFingerCount;
  write_list_.insns = write_insns_.data();
  read_list_.n_insns = kFingerCount;
  read_list_.insns = read_insns_.data();
  for (std::size_t c = 0; c < kFingerCount; ++c) out_counts_[c] = counts_from_kPa(out_conv_[c], 0.0);
  if (write_counts() != BackendStatus::ok)
    refuse("comedi.device", std::string("a device that accepts analog output (") + last_error() + ")");
}

void ComediRig::do_close() noexcept {
  if (!dev_) return;
  for (std::size_t c = 0; c < kFingerCount; ++c) out_counts_[c] = counts_from_kPa(out_conv_[c], 0.0);
  write_counts();
  comedi_close(dev_);
  dev_ = nullptr;
}

BackendStatus ComediRig::write_counts() noexcept {
  if (!dev_) {
    return set_error("comedi device not open");
  }
  if (comedi_do_insnlist(dev_, &write_list_) != int(kFingerCount)) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "comedi write on %s: %s", config_.device.c_str(), comedi_strerror(comedi_errno()));
    return set_error(msg);
  }
  return BackendStatus::ok;
}

BackendStatus ComediRig::do_write(const ChannelPressures& setpoint_kPa, double) noexcept {
  // RigBackend::write has refused anything non-finite or outside 0..p_max; the conversion
  // clamps to the regulator's span once more before comedi_from_physical.
  for (std::size_t c = 0; c < kFingerCount; ++c) out_counts_[c] = counts_from_kPa(out_conv_[c], setpoint_kPa[c]);
  return write_counts();
}

BackendStatus ComediRig::do_read(ChannelPressures& monitor_kPa, double) noexcept {
  if (!dev_) {
    return set_error("comedi device not open");
  }
  if (comedi_do_insnlist(dev_, &read_list_) != int(kFingerCount)) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "comedi read on %s: %s", config_.device.c_str(), comedi_strerror(comedi_errno()));
    return set_error(msg);
  }
  for (std::size_t c = 0; c < kFingerCount; ++c) monitor_kPa[c] = kPa_from_counts(mon_conv_[c], mon_counts_[c]);
  return BackendStatus::ok;
}

BackendStatus ComediRig::do_read_load_cells(std::array<double, kFingerCount>& volts, double) noexcept {
  if (!dev_ || cell_list_.n_insns == 0) {
    return set_error("comedi device not open");
  }
  if (comedi_do_insnlist(dev_, &cell_list_) != int(cell_list_.n_insns)) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "comedi load cell read on %s: %s", config_.device.c_str(),
                  comedi_strerror(comedi_errno()));
    return set_error(msg);
  }
  for (std::size_t i = 0; i < cell_list_.n_insns; ++i) volts[i] = volts_from_counts(cell_conv_[i], cell_counts_[i]);
  return BackendStatus::ok;
}

BackendStatus ComediRig::do_vent() noexcept {
  if (!dev_) return BackendStatus::ok;  // nothing is connected, nothing is pressurised by us
  for (std::size_t c = 0; c < kFingerCount; ++c) out_counts_[c] = counts_from_kPa(out_conv_[c], 0.0);
  return write_counts();
}

}  // namespace palprig
