#include "controller/telemetry_writer.hpp"

#include <boost/lockfree/spsc_queue.hpp>
#include <chrono>
#include <cstring>
#include <fstream>

#include "models/parse_error.hpp"

namespace palprig {

namespace {
constexpr char kMagic[8] = {'P', 'A', 'L', 'P', 'R', 'I', 'G', 'T'};
constexpr std::uint32_t kTelemetryVersion = 1;
}  // namespace

TelemetryFormat telemetry_format_for(const std::filesystem::path& path) {
  const auto ext = path.extension().string();
  return ext == ".bin" || ext == ".ptl" ? TelemetryFormat::binary : TelemetryFormat::csv;
}

TelemetryWriter::TelemetryWriter(std::filesystem::path path, TelemetryFormat format, std::size_t capacity)
    : path_(std::move(path)), format_(format),
      queue_(std::make_unique<boost::lockfree::spsc_queue<TelemetryRecord>>(capacity)) {
  {  // Fail now, before anything moves, if the file cannot be created.
    std::ofstream probe(path_, std::ios::binary | std::ios::trunc);
    if (!probe) throw InputError(path_.string(), "telemetry", "a writable file path (cannot create it)");
  }
  thread_ = std::thread([this] { run(); });
}

TelemetryWriter::~TelemetryWriter() {
  done_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
}

bool TelemetryWriter::try_push(const TelemetryRecord& r) noexcept {
  if (queue_->push(r)) return true;
  dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

void TelemetryWriter::push_wait(const TelemetryRecord& r) noexcept {
  while (!queue_->push(r)) {
    if (failed()) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    std::this_thread::yield();
  }
}

std::string TelemetryWriter::failure() const { return failed() ? failure_ : std::string(); }

void TelemetryWriter::run() noexcept {
  try {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot open " + path_.string());
    if (format_ == TelemetryFormat::binary) {
      out.write(kMagic, sizeof kMagic);
      const std::uint32_t header[2] = {kTelemetryVersion, static_cast<std::uint32_t>(sizeof(TelemetryRecord))};
      out.write(reinterpret_cast<const char*>(header), sizeof header);
    } else {
      write_telemetry_csv_header(out);
    }
    TelemetryRecord batch[256];
    for (;;) {
      const bool finishing = done_.load(std::memory_order_acquire);
      const std::size_t n = queue_->pop(batch, 256);
      for (std::size_t i = 0; i < n; ++i) {
        if (format_ == TelemetryFormat::binary) out.write(reinterpret_cast<const char*>(&batch[i]), sizeof batch[i]);
        else write_telemetry_csv_row(out, batch[i]);
      }
      written_.fetch_add(n, std::memory_order_relaxed);
      if (!out) throw std::runtime_error("write failed on " + path_.string() + " (disk full?)");
      if (n == 0) {
        if (finishing) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
    }
    out.flush();
    if (!out) throw std::runtime_error("write failed on " + path_.string());
  } catch (const std::exception& e) {
    failure_ = e.what();
    failed_.store(true, std::memory_order_release);
  }
}

void TelemetryWriter::finish() {
  done_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  if (failed()) throw std::runtime_error("telemetry writer: " + failure_);
}

void write_telemetry_csv_header(std::ostream& out) {
  out << "tick,t_s,x_mm,y_mm,force_N";
  for (const char* col : {"stiffness", "target_kPa", "setpoint_kPa", "monitor_kPa"})
    for (int i = 1; i <= kFingerCount; ++i) out << ',' << col << '_' << i;
  out << ",wake_latency_us,io_us,fault,flags\n";
}

void write_telemetry_csv_row(std::ostream& out, const TelemetryRecord& r) {
  char buf[512];
  int n = std::snprintf(buf, sizeof buf, "%llu,%.6f,%.3f,%.3f,%.4f", static_cast<unsigned long long>(r.tick), r.t_s,
                        r.x_mm, r.y_mm, r.force_N);
  const float* cols[4] = {r.stiffness, r.target_kPa, r.setpoint_kPa, r.monitor_kPa};
  for (const float* c : cols)
    for (int i = 0; i < kFingerCount; ++i) n += std::snprintf(buf + n, sizeof buf - n, ",%.4f", c[i]);
  n += std::snprintf(buf + n, sizeof buf - n, ",%.1f,%.1f,%d,%d\n", r.wake_latency_us, r.io_us, int(r.fault), int(r.flags));
  out.write(buf, n);
}

std::uint64_t convert_telemetry_to_csv(const std::filesystem::path& binary, const std::filesystem::path& csv) {
  std::ifstream in(binary, std::ios::binary);
  if (!in) throw InputError(binary.string(), "file", "a readable telemetry file");
  char magic[8];
  std::uint32_t header[2];
  in.read(magic, sizeof magic);
  in.read(reinterpret_cast<char*>(header), sizeof header);
  if (!in || std::memcmp(magic, kMagic, sizeof magic) != 0)
    throw InputError(binary.string(), "header", "a palprig binary telemetry file (magic PALPRIGT)");
  if (header[0] != kTelemetryVersion || header[1] != sizeof(TelemetryRecord))
    throw InputError(binary.string(), "header",
                     "telemetry version " + std::to_string(kTelemetryVersion) + " with " +
                         std::to_string(sizeof(TelemetryRecord)) + "-byte records, got version " +
                         std::to_string(header[0]) + " with " + std::to_string(header[1]));
  std::ofstream out(csv);
  if (!out) throw InputError(csv.string(), "file", "a writable CSV path");
  write_telemetry_csv_header(out);
  TelemetryRecord r;
  std::uint64_t n = 0;
  while (in.read(reinterpret_cast<char*>(&r), sizeof r)) {
    write_telemetry_csv_row(out, r);
    ++n;
  }
  if (in.gcount() != 0)
    throw InputError(binary.string(), "record " + std::to_string(n), "a whole record (file is truncated)");
  return n;
}

}  // namespace palprig
