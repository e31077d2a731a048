#include "sessions/session_telemetry.hpp"

#include <string>
#include <system_error>

#include "core/input_error.hpp"

namespace palprig {

void refuse_unusable_telemetry_file(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::exists(file, ec) &&
      (!std::filesystem::is_regular_file(file, ec) || std::filesystem::file_size(file, ec) > 0)) {
    throw InputError(file.string(), "telemetry",
                     "a new file (this one exists and is not empty, e.g. an earlier attempt's recording; nothing is "
                     "overwritten: choose another name)");
  }
  const std::filesystem::path folder = std::filesystem::absolute(file).parent_path();
  if (!std::filesystem::is_directory(folder, ec)) {
    throw InputError(file.string(), "telemetry",
                     "a file in an existing folder (" + folder.string() + " does not exist)");
  }
}

std::string telemetry_summary(const SessionEnd& end) {
  if (end.telemetry_file.empty()) return "";
  std::string line = "telemetry: " + std::to_string(end.telemetry_records) + " ticks in " + end.telemetry_file.string();
  if (end.telemetry_dropped > 0)
    line += " (" + std::to_string(end.telemetry_dropped) + " dropped: the disk fell behind)";
  return line;
}

SessionTelemetry::SessionTelemetry(const std::filesystem::path& file, RigStimulus& output, const SessionClock& clock)
    : file_(file), output_(output) {
  if (file_.empty()) return;
  writer_ = std::make_unique<TelemetryWriter>(file_, telemetry_format_for(file_));
  output_.record_to(writer_.get(), !clock.real_time());
}

SessionTelemetry::~SessionTelemetry() {
  if (writer_) output_.record_to(nullptr, false);  // the writer goes first: never leave it pointed to
}

void SessionTelemetry::finish(SessionEnd& end) {
  if (!writer_) return;
  output_.record_to(nullptr, false);
  end.telemetry_file = file_;
  try {
    writer_->finish();
  } catch (const std::exception& e) {
    if (end.fault.empty()) end.fault = std::string("telemetry: ") + e.what();
  }
  end.telemetry_records = writer_->written();
  end.telemetry_dropped = writer_->dropped();
}

}  // namespace palprig
