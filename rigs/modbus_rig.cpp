#include "rigs/modbus_rig.hpp"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "runtime/monotonic_clock.hpp"
#include "runtime/realtime.hpp"
#include "runtime/worker_fault.hpp"
#include "core/input_error.hpp"

namespace palprig {

namespace {

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", s);
  return buf;
}

}  // namespace

ModbusRig::ModbusRig(ModbusRigConfig config)
    : RigBackend(config.p_max_kPa),
      config_(std::move(config)),
      log_([](const std::string& line) { std::fprintf(stderr, "palprig: %s\n", line.c_str()); }) {
  for (std::size_t i = 0; i < config_.links.size(); ++i) {
    LinkState s;
    s.link = std::make_unique<ModbusLink>(config_, i);
    links_.push_back(std::move(s));
  }
  for (std::size_t c = 0; c < kFingerCount; ++c) zero_words_[c] = config_.channels[c].output.scale.word_from_kPa(0.0);
  Monitors nan_monitors;
  nan_monitors.kPa.fill(std::nan(""));
  nan_monitors.cell_volts.fill(std::nan(""));
  monitors_.publish(nan_monitors);
}

ModbusRig::~ModbusRig() { close(); }

std::string ModbusRig::describe() const {
  std::string s = "modbus";
  for (std::size_t i = 0; i < config_.links.size(); ++i) s += (i ? " + " : " ") + config_.links[i].endpoint();
  if (!config_.module.empty()) s += " (" + config_.module + ")";
  return s;
}

BackendCapabilities ModbusRig::capabilities() const {
  BackendCapabilities c;
  bool tcp = false, rtu = false;
  for (std::size_t i = 0; i < config_.links.size(); ++i) {
    const ModbusLinkConfig& link = config_.links[i];
    (link.rtu ? rtu : tcp) = true;
    // endpoint() reads "tcp HOST:PORT" or "rtu DEVICE ..."; the kind goes in link_kind.
    std::string where = link.endpoint();
    if (const auto space = where.find(' '); space != std::string::npos) where = where.substr(space + 1);
    c.endpoint += (i ? " + " : "") + where;
  }
  c.link_kind = tcp && rtu ? "modbus-tcp+rtu" : rtu ? "modbus-rtu" : "modbus-tcp";
  describe_load_cells(c);
  return c;
}

void ModbusRig::log(const std::string& line) {
  if (log_) log_(line);
}

void ModbusRig::do_open() {
  for (std::size_t i = 0; i < links_.size(); ++i)
    if (load_cells()) links_[i].link->plan_load_cells(*load_cells(), i);
  for (std::size_t i = 0; i < links_.size(); ++i) {
    ModbusLink& link = *links_[i].link;
    const std::string where =
        "modbus.links[" + std::to_string(i) + "] \"" + link.config().name + "\" (" + link.config().endpoint() + ")";
    if (!link.connect())
      throw InputError(config_.source, where, std::string("a Modbus device that answers (") + link.last_error() + ")");
    ChannelWords monitors{};
    ChannelWords cells{};
    if (!link.write_outputs(zero_words_) || !link.read_monitors(monitors) || !link.read_load_cells(cells)) {
      const std::string why = link.last_error();
      const bool device = link.last_error_kind() == LinkError::device;
      link.disconnect();
      throw InputError(config_.source, where,
                       device ? "registers the device accepts (it refused: " + why + ")"
                              : "a Modbus device that answers within " + seconds_text(config_.response_timeout_s) +
                                    " (" + why + ")");
    }
    links_[i].up = true;
  }
  stop_.store(false);
  fatal_.store(false);
  fatal_state_.store(0);
  down_since_ns_.store(0);
  linked_.store(true, std::memory_order_release);
  ramp_kPa_ = {};
  engaging_.fill(true);
  stats_ = {};
  cycle_hist_ = LatencyHistogram();
  start_ns_ = mono_ns();
  Command vent;
  vent.stamp_ns = start_ns_;
  commands_.publish(vent);
  io_thread_ = std::thread([this] { io_thread_main(); });
}

void ModbusRig::do_close() noexcept {
  if (io_thread_.joinable()) {
    stop_.store(true, std::memory_order_release);
    io_thread_.join();
  }
  write_zeros_everywhere();
  for (auto& l : links_) {
    l.link->disconnect();
    l.up = false;
  }
  linked_.store(false, std::memory_order_release);
}

void ModbusRig::write_zeros_everywhere() noexcept {
  for (auto& l : links_)
    if (l.up && l.link->connected()) l.link->write_outputs(zero_words_);
}

ModbusBusStats ModbusRig::bus_stats() const {
  ModbusBusStats s = stats_;
  s.cycle_time = cycle_hist_.summary();
  return s;
}

// ---- loop thread -------------------------------------------------------------------------

BackendStatus ModbusRig::do_write(const ChannelPressures& setpoint_kPa, double) noexcept {
  const std::int64_t now = mono_ns();
  if (fatal_.load(std::memory_order_acquire)) {
    return set_error(fatal_text_);
  }
  if (config_.max_outage_s > 0) {
    const std::int64_t since = down_since_ns_.load(std::memory_order_relaxed);
    if (since != 0 && double(now - since) * 1e-9 > config_.max_outage_s) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "modbus link down for more than max_outage_s = %.3f s", config_.max_outage_s);
      return set_error(msg);
    }
  }
  commands_.publish(Command{setpoint_kPa, now});
  return BackendStatus::ok;
}

BackendStatus ModbusRig::do_read(ChannelPressures& monitor_kPa, double) noexcept {
  monitor_kPa = monitors_.latest().kPa;
  return fatal_.load(std::memory_order_acquire) ? BackendStatus::failure(fatal_text_) : BackendStatus::ok;
}

BackendStatus ModbusRig::do_read_load_cells(std::array<double, kFingerCount>& volts, double) noexcept {
  volts = monitors_.latest().cell_volts;
  return fatal_.load(std::memory_order_acquire) ? BackendStatus::failure(fatal_text_) : BackendStatus::ok;
}

BackendStatus ModbusRig::do_vent() noexcept {
  // The I/O thread writes it within one bus period; the stamp keeps it fresh.
  commands_.publish(Command{ChannelPressures{}, mono_ns()});
  return fatal_.load(std::memory_order_acquire) ? BackendStatus::failure(fatal_text_) : BackendStatus::ok;
}

// ---- I/O thread --------------------------------------------------------------------------

void ModbusRig::io_thread_main() noexcept {
  try {
    // Below the loop's priority (80) and above the tablet reader and ordinary work
    // (runtime/thread_priorities.hpp); refused quietly when the system does not permit it
    // (the loop's own note says so once).
    (void)set_thread_fifo(config_.io_thread_fifo_priority);
    const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / config_.io_rate_hz));
    std::int64_t deadline = mono_ns();
    std::int64_t last = deadline;
    while (!stop_.load(std::memory_order_acquire)) {
      const std::int64_t start = mono_ns();
      io_cycle(start, double(start - last) * 1e-9);
      last = start;
      const std::int64_t end = mono_ns();
      cycle_hist_.record(double(end - start) / 1000.0);
      ++stats_.cycles;
      deadline += period_ns;
      if (end > deadline) {  // a slow bus: skip to the next free slot, keep the phase
        ++stats_.late_cycles;
        deadline += ((end - deadline) / period_ns + 1) * period_ns;
      }
      sleep_until_ns(deadline);
    }
    const ModbusBusStats s = bus_stats();
    char line[256];
    std::snprintf(
        line, sizeof line,
        "modbus: %llu bus cycles at %.0f Hz (%llu late), cycle p50/p99/max %.0f/%.0f/%.0f us, %llu outage(s), "
        "%llu reconnect(s)",
        static_cast<unsigned long long>(s.cycles), config_.io_rate_hz, static_cast<unsigned long long>(s.late_cycles),
        s.cycle_time.p50_us, s.cycle_time.p99_us, s.cycle_time.max_us, static_cast<unsigned long long>(s.outages),
        static_cast<unsigned long long>(s.reconnects));
    log(line);
  } catch (const std::exception& e) {
    char text[200];
    std::snprintf(text, sizeof text, "modbus I/O thread: %s", e.what());
    set_fatal(text);
    report_worker_fault("modbus I/O thread", e.what());
  } catch (...) {
    set_fatal("modbus I/O thread: unknown exception");
    report_worker_fault("modbus I/O thread", "unknown exception");
  }
}

void ModbusRig::io_cycle(std::int64_t now, double dt_s) {
  const Command cmd = commands_.latest();
  bool all_up = true;
  for (const auto& l : links_) all_up = all_up && l.up;
  const bool loop_silent = double(now - cmd.stamp_ns) * 1e-9 > config_.setpoint_timeout_s;
  // The loop stopped sending while it asked for pressure (a machine that stalled the loop's
  // thread longer than the timeout): the outputs go to 0 below. Counted before they do, so a
  // step that reads the count after this cycle knows its plant was vented (a calibration hold
  // would otherwise be recorded on the wrong hysteresis branch).
  bool pressure_asked = false;
  for (double p : cmd.kPa) pressure_asked = pressure_asked || (std::isfinite(p) && p > 0.0);
  const bool silenced = all_up && loop_silent && pressure_asked;
  if (silenced && !silenced_) {
    forced_vents_.fetch_add(1, std::memory_order_acq_rel);
    log("modbus: no setpoint from the loop for more than " + seconds_text(config_.setpoint_timeout_s) + " at t=" +
        seconds_text(double(now - start_ns_) * 1e-9) + ": all channels vented; the next setpoints ramp up from 0 kPa");
  }
  silenced_ = silenced;

  // Target per channel: the loop's setpoint while everything is linked and the loop is alive,
  // 0 kPa otherwise. Going down is immediate; coming up from a vent follows the ramp.
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    double target = (all_up && !loop_silent) ? cmd.kPa[c] : 0.0;
    if (!std::isfinite(target) || target < 0) target = 0;  // validated upstream; never trust a bus copy
    target = std::min(target, config_.p_max_kPa);
    if (target <= 0.0) engaging_[c] = true;  // after any vent, the next rise is ramped
    double out = target;
    if (engaging_[c]) {
      out = std::min(target, ramp_kPa_[c] + config_.slew_kPa_per_s * std::max(dt_s, 0.0));
      if (target > 0.0 && out >= target) engaging_[c] = false;  // caught up with a real setpoint
    }
    ramp_kPa_[c] = out;
    out_words_[c] = config_.channels[c].output.scale.word_from_kPa(out);
  }

  Monitors fresh;
  fresh.kPa.fill(std::nan(""));
  fresh.cell_volts.fill(std::nan(""));
  for (auto& l : links_) {
    if (!l.up) {
      if (now >= l.next_attempt_ns) try_reconnect(l, now);
      continue;
    }
    // While some other link is down this one carries 0 kPa (out_words_ hold 0 kPa then).
    if (l.link->write_outputs(out_words_) && l.link->read_monitors(mon_words_) && l.link->read_load_cells(cell_words_))
      continue;
    if (l.link->last_error_kind() == LinkError::device) {
      char text[256];
      std::snprintf(text, sizeof text, "modbus link '%s' (%s): device refused: %s", l.link->config().name.c_str(),
                    l.link->config().endpoint().c_str(), l.link->last_error());
      set_fatal(text);
      log(text);
    }
    mark_down(l, now);
  }
  bool now_all_up = true;
  for (const auto& l : links_) now_all_up = now_all_up && l.up;
  if (now_all_up) {
    for (std::size_t c = 0; c < kFingerCount; ++c)
      fresh.kPa[c] = config_.channels[c].monitor.scale.kPa_from_word(mon_words_[c]);
    if (load_cells())
      for (std::size_t i = 0; i < load_cells()->channels.size(); ++i)
        fresh.cell_volts[i] = load_cells()->channels[i].modbus->scale.volts_from_word(cell_words_[i]);
  }
  monitors_.publish(fresh);
  if (now_all_up != linked_.load(std::memory_order_relaxed)) {
    linked_.store(now_all_up, std::memory_order_release);
    down_since_ns_.store(now_all_up ? 0 : now, std::memory_order_relaxed);
  }
}

void ModbusRig::set_fatal(const char* text) noexcept {
  int expected = 0;
  if (!fatal_state_.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) return;  // first reason wins
  std::snprintf(fatal_text_, sizeof fatal_text_, "%s", text);
  fatal_.store(true, std::memory_order_release);
}

void ModbusRig::mark_down(LinkState& l, std::int64_t now) {
  const std::string why = l.link->last_error();
  l.link->disconnect();
  l.up = false;
  l.down_since_ns = now;
  l.backoff_s = config_.reconnect_initial_s;
  l.next_attempt_ns = now + static_cast<std::int64_t>(l.backoff_s * 1e9);
  l.attempts = 0;
  ++stats_.outages;
  forced_vents_.fetch_add(1, std::memory_order_acq_rel);
  // Every other link gets 0 kPa on the next cycle (all_up is false), and the loop sees
  // linked() == false after this cycle.
  write_zeros_everywhere();
  log("modbus link '" + l.link->config().name + "' (" + l.link->config().endpoint() + ") lost at t=" +
      seconds_text(double(now - start_ns_) * 1e-9) + ": " + why + "; all channels vented, reconnecting");
}

void ModbusRig::try_reconnect(LinkState& l, std::int64_t now) {
  ++l.attempts;
  // Back only when the module takes 0 kPa and answers a monitor read: a half-open link must
  // not be trusted with pressure.
  if (l.link->connect() && l.link->write_outputs(zero_words_) && l.link->read_monitors(mon_words_) &&
      l.link->read_load_cells(cell_words_)) {
    l.up = true;
    ++stats_.reconnects;
    for (std::size_t c = 0; c < kFingerCount; ++c) {
      ramp_kPa_[c] = 0;
      engaging_[c] = true;
    }
    log("modbus link '" + l.link->config().name + "' back after " + seconds_text(double(now - l.down_since_ns) * 1e-9) +
        " (" + std::to_string(l.attempts) + " attempt(s)); outputs written 0 kPa, setpoints ramp up from there");
    return;
  }
  l.link->disconnect();
  l.next_attempt_ns = now + static_cast<std::int64_t>(l.backoff_s * 1e9);
  l.backoff_s = std::min(l.backoff_s * 2, config_.reconnect_max_s);
}

}  // namespace palprig
