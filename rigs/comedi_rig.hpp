#pragma once
// ComediRig: the regulators on a DAQ card through comedilib (NI PCI/PCIe M-series and other
// comedi boards): three analog outputs command them, three analog inputs read their monitors.
// A PCI card answers in microseconds, so the I/O stays on the loop thread: each write() and
// read is one comedi_do_insnlist() call (one ioctl for the three channels), prepared in open().
#include <array>
#include <string>

#include "formats/comedi_config.hpp"
#include "rigs/comedi_conversion.hpp"
#include "rigs/rig_backend.hpp"

namespace palprig {

class ComediRig final : public RigBackend {
 public:
  explicit ComediRig(ComediRigConfig config);
  ~ComediRig() override;

  std::string describe() const override;
  BackendCapabilities capabilities() const override;
  const ComediConversion& output_conversion(std::size_t channel) const noexcept { return out_conv_[channel]; }
  const ComediConversion& monitor_conversion(std::size_t channel) const noexcept { return mon_conv_[channel]; }

 protected:
  // Opens the device, finds the subdevices and ranges, loads the calibration, writes 0 kPa.
  // A missing or wrong device, a channel or range the card lacks, a missing soft calibration:
  // InputError with the device path and comedi's own words (the command line exits 2).
  void do_open() override;
  void do_close() noexcept override;
  BackendStatus do_write(const ChannelPressures& setpoint_kPa, double t_s) noexcept override;
  BackendStatus do_read(ChannelPressures& monitor_kPa, double t_s) noexcept override;
  BackendStatus do_vent() noexcept override;
  // The load cells' analog inputs, one instruction list prepared in open().
  BackendStatus do_read_load_cells(std::array<double, kFingerCount>& volts, double t_s) noexcept override;

 private:
  [[noreturn]] void refuse(const std::string& field, const std::string& expected) const;
  BackendStatus write_counts() noexcept;

  ComediRigConfig config_;
  comedi_t* dev_ = nullptr;
  std::string board_;
  unsigned ao_subdevice_ = 0, ai_subdevice_ = 0;
  std::array<ComediConversion, kFingerCount> out_conv_{}, mon_conv_{};
  std::array<lsampl_t, kFingerCount> out_counts_{}, mon_counts_{};
  std::array<comedi_insn, kFingerCount> write_insns_{}, read_insns_{};
  comedi_insnlist write_list_{}, read_list_{};
  std::array<ComediConversion, kFingerCount> cell_conv_{};
  std::array<lsampl_t, kFingerCount> cell_counts_{};
  std::array<comedi_insn, kFingerCount> cell_insns_{};
  comedi_insnlist cell_list_{};
};

}  // namespace palprig
