#include "controller/telemetry_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/lockfree/spsc_queue.hpp>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "io/checked_output.hpp"
#include "core/input_error.hpp"
#include "io/regular_file.hpp"

namespace palprig {

namespace {
constexpr char kMagic[8] = {'P', 'A', 'L', 'P', 'R', 'I', 'G', 'T'};
constexpr std::uint32_t kTelemetryVersion = kTelemetryFileVersion;
}  // namespace

TelemetryFormat telemetry_format_for(const std::filesystem::path& path) {
  const auto ext = path.extension().string();
  return ext == ".bin" || ext == ".ptl" ? TelemetryFormat::binary : TelemetryFormat::csv;
}

TelemetryWriter::TelemetryWriter(std::filesystem::path path, TelemetryFormat format, std::size_t capacity,
                                 TelemetryLimits limits)
    : path_(std::move(path)),
      format_(format),
      limits_(limits),
      queue_(std::make_unique<boost::lockfree::spsc_queue<TelemetryRecord>>(capacity)) {
  {  // Fail now, before anything moves, if the file cannot be created. Only a regular file (or
     // a new one) is taken: opening a FIFO for writing waits for a reader, for ever, before
     // the signal handlers that vent on SIGTERM are even installed; a device is no log.
    const std::string expected = "a regular file (or a new path) to write telemetry to";
    std::error_code ec;
    const auto status = std::filesystem::status(path_, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
      throw InputError(path_.string(), "telemetry",
                       expected + ", got " + regular_file_problem(path_, ~std::uintmax_t(0)));
    }
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0644);
    if (fd < 0)
      throw InputError(path_.string(), "telemetry", expected + " (cannot create it: " + std::strerror(errno) + ")");
    struct stat st {};
    const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
    const bool truncated = regular && ::ftruncate(fd, 0) == 0;
    const int error = errno;
    ::close(fd);
    if (!regular) throw InputError(path_.string(), "telemetry", expected + ", got not a regular file");
    if (!truncated)
      throw InputError(path_.string(), "telemetry", expected + " (cannot truncate it: " + std::strerror(error) + ")");
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

namespace {
std::string size_text(std::uint64_t bytes) {
  return bytes >= (1u << 20) ? std::to_string(bytes >> 20) + " MiB" : std::to_string(bytes >> 10) + " KiB";
}
}  // namespace

void TelemetryWriter::check_room(std::uint64_t more) {
  if (bytes_ + more > limits_.max_bytes)
    throw Error("telemetry stopped at " + size_text(bytes_) + " in " + path_.string() + ": the budget of " +
                size_text(limits_.max_bytes) + " per file is reached");
  if (bytes_ + more - bytes_at_space_check_ < kMiB && bytes_ != 0) return;
  bytes_at_space_check_ = bytes_ + more;
  std::error_code ec;
  const auto dir = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  const std::filesystem::space_info room = std::filesystem::space(dir, ec);
  if (!ec && room.available < limits_.min_free_bytes + more)
    throw Error("telemetry stopped at " + size_text(bytes_) + " in " + path_.string() + ": the disk has " +
                size_text(room.available) + " free and " + size_text(limits_.min_free_bytes) + " are kept free");
}

std::string TelemetryWriter::failure() const { return failed() ? failure_ : std::string(); }

void TelemetryWriter::run() noexcept {
  try {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot open " + path_.string());
    std::ostringstream chunk;  // one batch, so its size is known before it reaches the disk
    if (format_ == TelemetryFormat::binary) {
      chunk.write(kMagic, sizeof kMagic);
      const std::uint32_t header[2] = {kTelemetryVersion, static_cast<std::uint32_t>(sizeof(TelemetryRecord))};
      chunk.write(reinterpret_cast<const char*>(header), sizeof header);
    } else {
      write_telemetry_csv_header(chunk);
    }
    TelemetryRecord batch[256];
    for (;;) {
      const bool finishing = done_.load(std::memory_order_acquire);
      const std::size_t n = queue_->pop(batch, 256);
      for (std::size_t i = 0; i < n; ++i) {
        if (format_ == TelemetryFormat::binary)
          chunk.write(reinterpret_cast<const char*>(&batch[i]), sizeof batch[i]);
        else
          write_telemetry_csv_row(chunk, batch[i]);
      }
      const std::string bytes = std::move(chunk).str();  // C++20: the buffer moves out, no copy
      chunk.str({});  // NOLINT(bugprone-use-after-move): str() after the move resets the stream, as the standard says
      if (!bytes.empty()) {
        check_room(bytes.size());
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        bytes_ += bytes.size();
      }
      written_.fetch_add(n, std::memory_order_relaxed);
      if (!out) throw Error("write failed on " + path_.string() + " (disk full?)");
      if (n == 0) {
        if (finishing) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
    }
    out.flush();
    if (!out) throw Error("write failed on " + path_.string());
  } catch (const std::exception& e) {
    failure_ = e.what();
    failed_.store(true, std::memory_order_release);
  }
}

void TelemetryWriter::finish() {
  done_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  if (failed()) throw Error("telemetry writer: " + failure_);
}

void write_telemetry_csv_header(std::ostream& out) {
  out << "tick,t_s,x_mm,y_mm,force_N";
  for (const char* col : {"stiffness", "target_kPa", "setpoint_kPa", "monitor_kPa"})
    for (int i = 1; i <= kFingerCount; ++i) out << ',' << col << '_' << i;
  out << ",wake_latency_us,io_us,fault,flags";
  for (const char* col : {"finger_x_mm", "finger_y_mm", "finger_force_N", "finger_vent", "drag_x_mm", "drag_y_mm"})
    for (int i = 1; i <= kFingerCount; ++i) out << ',' << col << '_' << i;
  out << '\n';
}

namespace {

// Appends one printf-formatted field to `row`. The field's length is whatever snprintf says
// it needs (a float of 3e38 printed with %.4f is 45 characters, a double of 1e308 with %.6f is
// 316), so no value a file or a run can hold writes past a buffer.
template <typename... Args>
void append_field(std::string& row, const char* format, Args... args) {
  char field[64];
  const int n = std::snprintf(field, sizeof field, format, args...);
  if (n < 0) return;
  if (static_cast<std::size_t>(n) < sizeof field) {
    row.append(field, static_cast<std::size_t>(n));
    return;
  }
  const std::size_t at = row.size();
  row.resize(at + static_cast<std::size_t>(n) + 1);
  std::snprintf(row.data() + at, static_cast<std::size_t>(n) + 1, format, args...);
  row.resize(at + static_cast<std::size_t>(n));
}

}  // namespace

void write_telemetry_csv_row(std::ostream& out, const TelemetryRecord& r) {
  std::string row;
  row.reserve(256);
  append_field(row, "%llu", static_cast<unsigned long long>(r.tick));
  append_field(row, ",%.6f", r.t_s);
  append_field(row, ",%.3f", double(r.x_mm));
  append_field(row, ",%.3f", double(r.y_mm));
  append_field(row, ",%.4f", double(r.force_N));
  const float* cols[4] = {r.stiffness, r.target_kPa, r.setpoint_kPa, r.monitor_kPa};
  for (const float* c : cols)
    for (int i = 0; i < kFingerCount; ++i) append_field(row, ",%.4f", double(c[i]));
  append_field(row, ",%.1f", double(r.wake_latency_us));
  append_field(row, ",%.1f", double(r.io_us));
  append_field(row, ",%d,%d", int(r.fault), int(r.flags));
  const float* fingers[3] = {r.finger_x_mm, r.finger_y_mm, r.finger_force_N};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < kFingerCount; ++i) append_field(row, k < 2 ? ",%.3f" : ",%.4f", double(fingers[k][i]));
  for (int i = 0; i < kFingerCount; ++i) append_field(row, ",%d", int(r.finger_vent[i]));
  for (const float* c : {r.drag_x_mm, r.drag_y_mm})
    for (int i = 0; i < kFingerCount; ++i) append_field(row, ",%.3f", double(c[i]));
  row += '\n';
  out.write(row.data(), static_cast<std::streamsize>(row.size()));
}

std::uint64_t convert_telemetry_to_csv(const std::filesystem::path& binary, const std::filesystem::path& csv) {
  std::ifstream in = open_regular_file(binary, kMaxTelemetryFileBytes, "palprig binary telemetry");
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
  // Written whole or not at all: a truncated input or a full disk leaves no CSV that looks done.
  CheckedOutputFile out(csv);
  write_telemetry_csv_header(out.stream());
  TelemetryRecord r;
  std::uint64_t n = 0;
  while (in.read(reinterpret_cast<char*>(&r), sizeof r)) {
    write_telemetry_csv_row(out.stream(), r);
    ++n;
    if ((n & 0xffff) == 0 && !out.stream()) break;  // the disk is full: stop converting, commit() says so
  }
  if (out.stream() && in.gcount() != 0)
    throw InputError(binary.string(), "record " + std::to_string(n), "a whole record (file is truncated)");
  out.commit();
  return n;
}

}  // namespace palprig
