#include "statistics/csv_groups.hpp"

#include <algorithm>

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

}  // namespace palprig
