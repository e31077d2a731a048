#include "statistics/csv_groups.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <tuple>

#include "core/input_error.hpp"

namespace palprig {

std::vector<NumericGroup> group_numbers(const CsvTable& table, std::string_view value_column,
                                        std::string_view group_column,
                                        const std::vector<std::string>& selected_groups) {
  const std::size_t value_index = table.column(value_column);
  const std::size_t group_index = table.column(group_column);
  std::vector<NumericGroup> groups;
  groups.reserve(selected_groups.size());
  for (const auto& label : selected_groups) groups.push_back({label, {}});

  for (std::size_t row = 0; row < table.rows(); ++row) {
    const std::string& label = table.label(row, group_index);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const NumericGroup& g) { return g.label == label; });
    if (it == groups.end()) {
      if (!selected_groups.empty()) continue;  // a group nobody asked for: its values are not used
      groups.push_back({label, {}});
      it = groups.end() - 1;
    }
    it->values.push_back(table.number(row, value_index));
  }
  for (const auto& g : groups) {
    if (g.values.empty()) {
      throw InputError(table.source(), "column '" + std::string(group_column) + "'",
                       "rows of group '" + g.label + "' (none found)");
    }
  }
  return groups;
}

std::vector<NumericGroup> two_groups(const CsvTable& table, std::string_view value_column,
                                     std::string_view group_column, const std::vector<std::string>& selected_groups) {
  if (!selected_groups.empty() && selected_groups.size() != 2) {
    throw InputError(table.source(), "`groups`", "exactly two group labels");
  }
  auto groups = group_numbers(table, value_column, group_column, selected_groups);
  if (groups.size() != 2) {
    std::string found;
    for (const auto& g : groups) found += (found.empty() ? "" : ", ") + g.label;
    throw InputError(table.source(), "column '" + std::string(group_column) + "'",
                     "exactly two groups (found " + std::to_string(groups.size()) + ": " + found +
                         "); choose two with `groups` A,B");
  }
  return groups;
}

namespace {

std::optional<std::size_t> find_column(const CsvTable& table, std::string_view name) {
  const auto& h = table.header();
  const auto it = std::find(h.begin(), h.end(), name);
  if (it == h.end()) return std::nullopt;
  return static_cast<std::size_t>(it - h.begin());
}

}  // namespace

std::vector<std::string> one_value_per_trial_warnings(const CsvTable& table) {
  std::vector<std::string> out;
  const auto participant = find_column(table, "participant"), session = find_column(table, "session"),
             trial = find_column(table, "trial");
  if (trial) {
    std::set<std::tuple<std::string, std::string, std::string>> seen;
    std::size_t repeated = 0;
    for (std::size_t row = 0; row < table.rows(); ++row) {
      const auto key = std::make_tuple(participant ? table.text(row, *participant) : std::string(),
                                       session ? table.text(row, *session) : std::string(), table.text(row, *trial));
      if (!seen.insert(key).second) ++repeated;
    }
    if (repeated > 0) {
      out.push_back(table.source() + ": " + std::to_string(table.rows()) + " rows hold " + std::to_string(seen.size()) +
                    " trials (several rows per trial, as trials_long.csv's one row per finger value or tumor): a "
                    "test of one value per trial counts those trials several times; use trials.csv of palprig "
                    "export (one row per trial), or palprig stats trials on the store");
    }
  }
  if (const auto practice = find_column(table, "practice")) {
    std::size_t practice_rows = 0;
    for (std::size_t row = 0; row < table.rows(); ++row) practice_rows += table.text(row, *practice) == "1" ? 1 : 0;
    if (practice_rows > 0) {
      out.push_back(table.source() + ": " + std::to_string(practice_rows) +
                    " rows are practice trials (practice = 1), tested with the others; paper 002 and palprig stats "
                    "trials leave them out");
    }
  }
  return out;
}

}  // namespace palprig
