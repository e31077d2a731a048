#pragma once
// The finite-element model's figures as a reader of paper 002 knows them, each as PNG and SVG:
// - the contact stress along the fingertip (fig. 10 and 13): one curve per case or step;
// - the peak contact stress against the load, with its fitted line (fig. 12);
// - the deformed mesh coloured by von Mises stress (fig. 9 and 11).
//
// The curves go through the line chart of chart_png.hpp. The deformed mesh is painted here with
// QPainter, element by element (each nine-node element's outline through its eight edge nodes,
// filled with its von Mises colour, on a blue-to-red scale like ABAQUS's with a colour bar): a
// plotting library's colour map is a regular grid (QCustomPlot's QCPColorMap, for one), and a
// deformed unstructured mesh is not one; resampling it onto a grid would blur the element edges
// and the contact's outline, which are what the figure is for.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mechanics/contact_problems.hpp"

namespace palprig::charts {

struct ProfileCurve {
  std::string label;
  const mechanics::ContactStep* step = nullptr;
};

// stem.png and stem.svg: the contact stress (1 mm average) against where the surface is now
// (x, mm). Returns the files written.
std::vector<std::filesystem::path> write_contact_stress_figure(const std::filesystem::path& stem,
                                                               const std::string& title,
                                                               const std::vector<ProfileCurve>& curves);

struct PeakSeries {
  std::string label;
  std::vector<double> load, peak_kPa;
  std::optional<mechanics::StressLine> line;  // drawn as a line over the series' load range
};
std::vector<std::filesystem::path> write_peak_figure(const std::filesystem::path& stem, const std::string& title,
                                                     const std::string& x_label, const std::vector<PeakSeries>& series);

// The run's last deformed mesh around the contact (the fingertip and what lies within 12 mm of
// it), coloured by von Mises stress up to `max_kPa` (0: the 99th percentile of what is shown).
std::vector<std::filesystem::path> write_deformed_mesh_figure(const std::filesystem::path& stem,
                                                              const std::string& title,
                                                              const mechanics::ContactRun& run, double max_kPa = 0);

}  // namespace palprig::charts
