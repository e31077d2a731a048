#pragma once
// Split a numeric CSV column by a group column, for the two-group tests and describe --by.
// Groups keep the order in which they first appear in the file, unless the caller lists the
// groups it wants (then that order, and rows of other groups are not read at all).
#include <string>
#include <string_view>
#include <vector>

#include "statistics/csv_table.hpp"

namespace palprig {

struct NumericGroup {
  std::string label;
  std::vector<double> values;
};

// Throws InputError for a missing column, a missing label, a missing or non-numeric value in a
// used row (with its line), or a selected group that does not occur.
std::vector<NumericGroup> group_numbers(const CsvTable& table, std::string_view value_column,
                                        std::string_view group_column,
                                        const std::vector<std::string>& selected_groups = {});

// Exactly two groups for a two-sample test: the selected ones, or the only two in the file.
// Throws InputError naming the groups found otherwise.
std::vector<NumericGroup> two_groups(const CsvTable& table, std::string_view value_column,
                                     std::string_view group_column,
                                     const std::vector<std::string>& selected_groups = {});

// What a test of one value per trial should be told about a table before it runs: several rows
// of the same trial (palprig's trials_long.csv has one row per finger value or tumor: a
// participant, session and trial repeated), and practice trials (a `practice` column with 1s).
// One sentence each, naming the file; empty when there is nothing to say (a table without those
// columns is taken as it is).
std::vector<std::string> one_value_per_trial_warnings(const CsvTable& table);

}  // namespace palprig
