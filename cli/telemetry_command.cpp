// palprig telemetry to-csv: convert a compact binary telemetry file to CSV.
#include <iostream>

#include "cli/commands.hpp"
#include "controller/telemetry_writer.hpp"

void register_telemetry_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("telemetry", "Work with telemetry files");
  sub->require_subcommand(1);
  auto in = std::make_shared<std::string>(), out = std::make_shared<std::string>();
  CLI::App* conv = sub->add_subcommand("to-csv", "Convert a binary telemetry file (.bin) to CSV");
  conv->add_option("input", *in, "Binary telemetry file")->required()->check(CLI::ExistingFile);
  conv->add_option("output", *out, "CSV file to write")->required();
  conv->callback([=]() {
    const auto n = palprig::convert_telemetry_to_csv(*in, *out);
    std::cout << "wrote " << n << " records to " << *out << "\n";
  });
}
