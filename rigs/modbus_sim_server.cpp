#include "rigs/modbus_sim_server.hpp"
#include "core/error.hpp"
#include "runtime/monotonic_clock.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <termios.h>
#include <modbus.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace palprig {

ListenAddress parse_listen_address(const std::string& text) {
  if (text == "pty") {
    ListenAddress a;
    a.pty = true;
    return a;
  }
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size())
    throw BadInput("HOST:PORT (e.g. 127.0.0.1:1502, port 0 for any free port) or pty, got '" + text + "'");
  ListenAddress a;
  a.host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  std::size_t used = 0;
  int value = -1;
  try {
    value = std::stoi(port, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != port.size() || value < 0 || value > 65535)
    throw BadInput("a port number 0..65535 after the colon, got '" + text + "'");
  in_addr probe{};
  if (inet_pton(AF_INET, a.host.c_str(), &probe) != 1)
    throw BadInput("an IPv4 address before the colon (e.g. 127.0.0.1 or 0.0.0.0), got '" + text + "'");
  a.port = value;
  return a;
}

ModbusSimServer::ModbusSimServer(ModbusRigConfig map, const std::array<PlantParams, kFingerCount>& plants)
    : map_(std::move(map)),
      plants_{PneumaticPlant(plants[0]), PneumaticPlant(plants[1]), PneumaticPlant(plants[2])},
      log_([](const std::string& line) { std::fprintf(stderr, "palprig sim-rig: %s\n", line.c_str()); }) {}

ModbusSimServer::~ModbusSimServer() {
  stop();
  if (write_log_) std::fclose(write_log_);
}

void ModbusSimServer::log(const std::string& line) {
  if (log_) log_(line);
}

void ModbusSimServer::set_write_log(const std::filesystem::path& path) {
  if (write_log_) std::fclose(write_log_);
  write_log_ = std::fopen(path.c_str(), "w");
  if (!write_log_) throw Error("cannot create the write log " + path.string() + ": " + std::strerror(errno));
  std::setvbuf(write_log_, nullptr, _IOLBF, 0);  // a killed simulator still leaves whole lines
  std::fprintf(write_log_, "t_s,channel,word,kPa,mono_ns\n");
}

std::uint16_t* ModbusSimServer::output_register(std::size_t c) const noexcept {
  const auto& ref = map_.channels[c].output;
  modbus_mapping_t* m = links_[ref.link]->mapping;
  return &m->tab_registers[ref.address - static_cast<int>(m->start_registers)];
}

std::uint16_t* ModbusSimServer::register_of(const ModbusRegisterRef& ref) const noexcept {
  modbus_mapping_t* m = links_[ref.link]->mapping;
  if (ref.kind == RegisterKind::input)
    return &m->tab_input_registers[ref.address - static_cast<int>(m->start_input_registers)];
  return &m->tab_registers[ref.address - static_cast<int>(m->start_registers)];
}

void ModbusSimServer::set_load_cells(const LoadCellConfig& cells, double load_N) {
  cell_registers_.clear();
  cells_.clear();
  cell_load_N_ = load_N;
  for (std::size_t i = 0; i < cells.channels.size(); ++i) {
    const LoadCellChannel& ch = cells.channels[i];
    if (!ch.modbus) continue;
    cell_registers_.push_back(*ch.modbus);
    SimulatedLoadCellParams p;
    p.tare_V = ch.calibration.tare_V;  // the rig file's calibration is this simulated cell's truth
    p.N_per_V = ch.calibration.N_per_V;
    p.max_V = ch.modbus->scale.volts_hi;
    p.seed = 21 + i;
    cells_.emplace_back(p);
  }
}

std::uint16_t* ModbusSimServer::monitor_register(std::size_t c) const noexcept {
  const auto& ref = map_.channels[c].monitor;
  modbus_mapping_t* m = links_[ref.link]->mapping;
  if (ref.kind == RegisterKind::input)
    return &m->tab_input_registers[ref.address - static_cast<int>(m->start_input_registers)];
  return &m->tab_registers[ref.address - static_cast<int>(m->start_registers)];
}

void ModbusSimServer::start(const std::vector<ListenAddress>& listen) {
  stop();
  if (listen.size() != map_.links.size())
    throw BadInput("the register map has " + std::to_string(map_.links.size()) +
                   " link(s); give one listen address each, got " + std::to_string(listen.size()));
  links_.clear();
  for (std::size_t i = 0; i < map_.links.size(); ++i) {
    auto link = std::make_unique<Link>();
    link->address = listen[i];
    // The register space this module offers: exactly the span of the registers the map uses,
    // so a client reading outside it gets "illegal data address", as from a real module.
    int h_lo = 65536, h_hi = -1, i_lo = 65536, i_hi = -1;
    for (std::size_t c = 0; c < kFingerCount; ++c) {
      const auto& ch = map_.channels[c];
      if (ch.output.link == i) h_lo = std::min(h_lo, ch.output.address), h_hi = std::max(h_hi, ch.output.address);
      if (ch.monitor.link == i) {
        if (ch.monitor.kind == RegisterKind::holding)
          h_lo = std::min(h_lo, ch.monitor.address), h_hi = std::max(h_hi, ch.monitor.address);
        else
          i_lo = std::min(i_lo, ch.monitor.address), i_hi = std::max(i_hi, ch.monitor.address);
      }
    }
    for (const ModbusRegisterRef& ref : cell_registers_) {
      if (ref.link != i) continue;
      if (ref.kind == RegisterKind::holding)
        h_lo = std::min(h_lo, ref.address), h_hi = std::max(h_hi, ref.address);
      else
        i_lo = std::min(i_lo, ref.address), i_hi = std::max(i_hi, ref.address);
    }
    link->mapping = modbus_mapping_new_start_address(
        0, 0, 0, 0, h_hi < 0 ? 0 : unsigned(h_lo), h_hi < 0 ? 0 : unsigned(h_hi - h_lo + 1),
        i_hi < 0 ? 0 : unsigned(i_lo), i_hi < 0 ? 0 : unsigned(i_hi - i_lo + 1));
    if (!link->mapping) throw Error(std::string("cannot allocate the register space: ") + modbus_strerror(errno));
    if (link->address.pty) {
      link->pty_master = posix_openpt(O_RDWR | O_NOCTTY);
      if (link->pty_master < 0 || grantpt(link->pty_master) != 0 || unlockpt(link->pty_master) != 0)
        throw Error(std::string("cannot create a pseudo-terminal: ") + std::strerror(errno));
      link->pty_path = ptsname(link->pty_master);
      // Hold the slave side open in raw mode: the line discipline must not echo or edit the
      // binary frames, and the master must not see a hang-up between clients.
      link->pty_slave = ::open(link->pty_path.c_str(), O_RDWR | O_NOCTTY);
      termios raw{};
      if (link->pty_slave < 0 || tcgetattr(link->pty_slave, &raw) != 0)
        throw Error("cannot open " + link->pty_path + ": " + std::strerror(errno));
      cfmakeraw(&raw);
      tcsetattr(link->pty_slave, TCSANOW, &raw);
      const ModbusLinkConfig& cfg = map_.links[i];
      link->ctx = modbus_new_rtu(link->pty_path.c_str(), cfg.baud, cfg.parity, cfg.data_bits, cfg.stop_bits);
      if (!link->ctx) throw Error(std::string("modbus_new_rtu: ") + modbus_strerror(errno));
      modbus_set_slave(link->ctx, cfg.unit_id);  // an RTU module answers its own address only
      modbus_set_socket(link->ctx, link->pty_master);
      links_.push_back(std::move(link));
      continue;
    }
    link->ctx = modbus_new_tcp(link->address.host.c_str(), link->address.port);
    if (!link->ctx) throw Error(std::string("modbus_new_tcp: ") + modbus_strerror(errno));
    link->listen_fd = modbus_tcp_listen(link->ctx, 16);
    if (link->listen_fd == -1)
      throw Error("cannot listen on " + link->address.host + ":" + std::to_string(link->address.port) + ": " +
                  modbus_strerror(errno));
    sockaddr_in bound{};
    socklen_t len = sizeof bound;
    getsockname(link->listen_fd, reinterpret_cast<sockaddr*>(&bound), &len);
    link->port = ntohs(bound.sin_port);
    links_.push_back(std::move(link));
  }
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    plants_[c].reset(0.0);
    *output_register(c) = map_.channels[c].output.scale.word_from_kPa(0.0);
    if (!map_.monitor_is_readback(c)) *monitor_register(c) = map_.channels[c].monitor.scale.word_from_kPa(0.0);
  }
  // A load cell's register holds a reading from the start, as a real module's does: a client
  // served before the plant thread's first step would otherwise read a zero word (a force of
  // minus the tare) as a measurement.
  for (std::size_t i = 0; i < cells_.size(); ++i)
    *register_of(cell_registers_[i]) = cell_registers_[i].scale.word_from_volts(cells_[i].volts(0.0, cell_load_N_));
  stop_.store(false);
  start_ns_ = mono_ns();
  last_step_ns_ = 0;
  for (auto& l : links_) l->last_request_ns = start_ns_;
  plant_thread_ = std::thread([this] {
    std::int64_t deadline = mono_ns();
    while (!stop_.load(std::memory_order_acquire)) {
      step_plants();
      deadline += 1'000'000;
      const std::int64_t now = mono_ns();
      if (deadline < now) deadline = now;  // the simulator was paused (SIGSTOP): do not catch up in a burst
      sleep_until_ns(deadline);
    }
  });
  for (std::size_t i = 0; i < links_.size(); ++i)
    links_[i]->thread =
        std::thread([this, i] { links_[i]->address.pty ? serve_rtu(*links_[i], i) : serve(*links_[i], i); });
}

void ModbusSimServer::stop() noexcept {
  stop_.store(true, std::memory_order_release);
  for (auto& l : links_)
    if (l->thread.joinable()) l->thread.join();
  if (plant_thread_.joinable()) plant_thread_.join();
  for (auto& l : links_) {
    if (l->listen_fd >= 0) ::close(l->listen_fd);
    l->listen_fd = -1;
    if (l->pty_slave >= 0) ::close(l->pty_slave);
    if (l->pty_master >= 0) ::close(l->pty_master);
    l->pty_slave = l->pty_master = -1;
    if (l->ctx) modbus_free(l->ctx);
    l->ctx = nullptr;
    if (l->mapping) modbus_mapping_free(l->mapping);
    l->mapping = nullptr;
  }
  links_.clear();
}

void ModbusSimServer::step_plants() noexcept {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::int64_t now = mono_ns();
  // A paused simulator (SIGSTOP) resumes where it was rather than leaping ahead.
  const double dt = last_step_ns_ == 0 ? 0.0 : std::min(double(now - last_step_ns_) * 1e-9, 0.1);
  last_step_ns_ = now;
  if (watchdog_s_ > 0) {
    for (std::size_t i = 0; i < links_.size(); ++i) {
      Link& l = *links_[i];
      const bool silent = double(now - l.last_request_ns) * 1e-9 > watchdog_s_;
      if (silent && !l.watchdog_tripped) {
        for (std::size_t c = 0; c < kFingerCount; ++c)
          if (map_.channels[c].output.link == i) *output_register(c) = map_.channels[c].output.scale.word_from_kPa(0.0);
        l.watchdog_tripped = true;
        log("link '" + map_.links[i].name + "': no request for " + std::to_string(watchdog_s_) +
            " s, outputs set to 0 kPa (watchdog)");
      }
    }
  }
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    const double command_kPa = map_.channels[c].output.scale.kPa_from_word(*output_register(c));
    plants_[c].step(command_kPa, dt);
    if (!map_.monitor_is_readback(c))
      *monitor_register(c) = map_.channels[c].monitor.scale.word_from_kPa(plants_[c].monitor_kPa());
  }
  for (std::size_t i = 0; i < cells_.size(); ++i)
    *register_of(cell_registers_[i]) = cell_registers_[i].scale.word_from_volts(cells_[i].volts(0.0, cell_load_N_));
}

void ModbusSimServer::after_write(std::size_t link, const std::uint8_t* query, int offset) noexcept {
  const int function = query[offset];
  int start = 0, count = 0;
  if (function == MODBUS_FC_WRITE_SINGLE_REGISTER) {
    start = (query[offset + 1] << 8) | query[offset + 2];
    count = 1;
  } else if (function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS || function == MODBUS_FC_WRITE_AND_READ_REGISTERS) {
    const int base = function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS ? offset + 1 : offset + 5;
    start = (query[base] << 8) | query[base + 1];
    count = (query[base + 2] << 8) | query[base + 3];
  } else {
    return;
  }
  Link& l = *links_[link];
  if (l.watchdog_tripped) {
    l.watchdog_tripped = false;
    log("link '" + map_.links[link].name + "': written again, watchdog cleared");
  }
  if (!write_log_) return;
  const std::int64_t arrival_ns = mono_ns();  // CLOCK_MONOTONIC: comparable with the client's clock
  const double t = double(arrival_ns - start_ns_) * 1e-9;
  for (std::size_t c = 0; c < kFingerCount; ++c) {
    const auto& out = map_.channels[c].output;
    if (out.link != link || out.address < start || out.address >= start + count) continue;
    const std::uint16_t word = *output_register(c);
    std::fprintf(write_log_, "%.6f,%zu,%u,%.6f,%lld\n", t, c + 1, unsigned(word), out.scale.kPa_from_word(word),
                 static_cast<long long>(arrival_ns));
  }
}

void ModbusSimServer::serve(Link& link, std::size_t index) noexcept {
  std::vector<int> clients;
  std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
  while (!stop_.load(std::memory_order_acquire)) {
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(link.listen_fd, &readable);
    int max_fd = link.listen_fd;
    for (int fd : clients) {
      FD_SET(fd, &readable);
      max_fd = std::max(max_fd, fd);
    }
    timeval timeout{0, 50'000};  // wake up to notice stop()
    const int n = select(max_fd + 1, &readable, nullptr, nullptr, &timeout);
    if (n <= 0) continue;
    if (FD_ISSET(link.listen_fd, &readable)) {
      const int fd = accept(link.listen_fd, nullptr, nullptr);
      if (fd >= 0) {
        const int one = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        if (fd < FD_SETSIZE) {
          clients.push_back(fd);
          clients_.fetch_add(1, std::memory_order_relaxed);
        } else {
          ::close(fd);
        }
      }
    }
    for (auto it = clients.begin(); it != clients.end();) {
      const int fd = *it;
      if (!FD_ISSET(fd, &readable)) {
        ++it;
        continue;
      }
      modbus_set_socket(link.ctx, fd);
      const int rc = modbus_receive(link.ctx, query);
      if (rc > 0) {
        handle(link, index, query, rc);
        ++it;
      } else if (rc == -1) {  // the client closed or sent garbage: drop it
        ::close(fd);
        it = clients.erase(it);
        clients_.fetch_sub(1, std::memory_order_relaxed);
      } else {
        ++it;
      }
    }
  }
  for (int fd : clients) ::close(fd);
  clients_.fetch_sub(static_cast<int>(clients.size()), std::memory_order_relaxed);
}

void ModbusSimServer::handle(Link& link, std::size_t index, const std::uint8_t* query, int length) noexcept {
  std::lock_guard<std::mutex> lock(mutex_);
  link.last_request_ns = mono_ns();
  modbus_reply(link.ctx, query, length, link.mapping);
  requests_.fetch_add(1, std::memory_order_relaxed);
  after_write(index, query, modbus_get_header_length(link.ctx));
}

void ModbusSimServer::serve_rtu(Link& link, std::size_t index) noexcept {
  std::uint8_t query[MODBUS_RTU_MAX_ADU_LENGTH];
  while (!stop_.load(std::memory_order_acquire)) {
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(link.pty_master, &readable);
    timeval timeout{0, 50'000};
    if (select(link.pty_master + 1, &readable, nullptr, nullptr, &timeout) <= 0) continue;
    const int rc = modbus_receive(link.ctx, query);  // a whole frame, CRC checked, our unit only
    if (rc > 0)
      handle(link, index, query, rc);
    else if (rc == -1)
      modbus_flush(link.ctx);  // a broken frame: drop what is buffered
  }
}

std::array<std::uint16_t, kFingerCount> ModbusSimServer::output_words() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::array<std::uint16_t, kFingerCount> w{};
  if (links_.empty()) return w;
  for (std::size_t c = 0; c < kFingerCount; ++c) w[c] = *output_register(c);
  return w;
}

double ModbusSimServer::plant_output_kPa(std::size_t channel) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return plants_.at(channel).output_kPa();
}

}  // namespace palprig
