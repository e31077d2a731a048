#include "controller/fault_recorder.hpp"

#include <ctime>
#include <sstream>

#include "controller/telemetry_writer.hpp"
#include "io/checked_output.hpp"

namespace palprig {

std::vector<TelemetryRecord> FaultRecorder::records() const {
  std::vector<TelemetryRecord> out;
  out.reserve(size());
  const std::uint64_t first = next_ - size();
  for (std::uint64_t i = first; i < next_; ++i) out.push_back(ring_[i % ring_.size()]);
  return out;
}

void write_fault_record(const std::filesystem::path& path, const FaultRecorder& recorder, const Fault& fault,
                        const std::string& what_ran) {
  CheckedOutputFile file(path);
  std::ostream& out = file.stream();
  out << "# palprig fault record: " << what_ran << "\n";
  out << "# fault: " << fault.describe() << "; every channel vented\n";
  out << "# the last " << recorder.size() << " ticks before it, oldest first (the columns of run --telemetry)\n";
  write_telemetry_csv_header(out);
  for (const TelemetryRecord& r : recorder.records()) write_telemetry_csv_row(out, r);
  file.commit();
}

std::filesystem::path fault_record_path(const std::filesystem::path& telemetry_file,
                                        const std::filesystem::path& folder) {
  if (!telemetry_file.empty()) {
    std::filesystem::path p = telemetry_file;
    return p.replace_extension(".fault.csv");
  }
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
  std::filesystem::path p = folder / ("palprig-fault-" + std::string(stamp) + ".csv");
  for (int n = 2; std::filesystem::exists(p); ++n)
    p = folder / ("palprig-fault-" + std::string(stamp) + "-" + std::to_string(n) + ".csv");
  return p;
}

std::string save_fault_record(const FaultRecorder& recorder, const Fault& fault, const std::string& what_ran,
                              const std::filesystem::path& telemetry_file, const std::filesystem::path& folder,
                              std::filesystem::path* written) {
  const std::filesystem::path path = fault_record_path(telemetry_file, folder);
  try {
    write_fault_record(path, recorder, fault, what_ran);
  } catch (const std::exception& e) {
    return std::string("the ticks before it could not be kept: ") + e.what();
  }
  if (written) *written = path;
  std::ostringstream line;
  line << "the last " << recorder.size() << " ticks before it: " << path.string();
  return line.str();
}

}  // namespace palprig
