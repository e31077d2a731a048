// palprig fe table: the finite-element table beyond paper 002 (mechanics/stress_table_build.hpp):
// the fingertip's peak stress over indentation x nodule cover x diameter x stiffness contrast x
// lateral offset, solved in parallel worker processes, cached by the hash of the input files and
// the settings ($XDG_CACHE_HOME/palprig, else ~/.cache/palprig), written where a function scene's
// "fe_stress_table" can name it.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "cli/fe_arguments.hpp"
#include "formats/fe_body_files.hpp"
#include "formats/fe_result_files.hpp"
#include "mechanics/stress_table_build.hpp"
#include "io/checked_output.hpp"

using namespace palprig;
using namespace palprig::cli;

namespace {

struct TableArgs {
  std::string fingertip, tissue, out, cache;
  std::string depths = "1,2,3,4,5,6,7,8", covers = "1,3,6,10,15", diameters = "5,10,20", contrasts = "2,6,40",
              offsets = "0,5,10,20";
  int workers = 2;
  bool use_cache = true;
  FeAnalysisArgs analysis;
};

std::filesystem::path cache_folder(const TableArgs& a) {
  if (!a.cache.empty()) return a.cache;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "palprig";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "palprig";
  return {};
}

void run_table(const TableArgs& a) {
  const FingertipBody finger = load_fingertip_file(a.fingertip);
  const TissueBlock tissue = load_tissue_file(a.tissue);
  FeTableAxes axes;
  axes.indentation_mm = number_list(a.depths, "--depths-mm", 0.05, 20);
  axes.cover_mm = number_list(a.covers, "--cover-mm", 0.5, 80);
  axes.diameter_mm = number_list(a.diameters, "--diameter-mm", 0.5, 60);
  axes.contrast = number_list(a.contrasts, "--contrast", 1.01, 1e4);
  axes.offset_mm = number_list(a.offsets, "--offset-mm", 0, 100);
  try {  // the grid's own rules (increasing, in range), before any solve
    (void)FeStressTable(axes, std::vector<double>(axes.values(), 0.0), std::vector<double>(axes.indentation_mm.size()));
  } catch (const std::invalid_argument& e) {
    throw InputError("palprig fe table", "the grid", e.what());
  }
  std::ostringstream settings;
  settings << PALPRIG_VERSION << ' ' << plane_text(a.analysis) << ' ' << a.analysis.element_mm << ' ' << a.depths << ' '
           << a.covers << ' ' << a.diameters << ' ' << a.contrasts << ' ' << a.offsets;
  FeTableFile file;
  file.inputs = {a.fingertip,
                 a.tissue,
                 "",
                 fe_inputs_hash({a.fingertip, a.tissue}, settings.str()),
                 plane_text(a.analysis),
                 a.analysis.element_mm};
  std::cout << "palprig fe table: " << a.fingertip << " on " << a.tissue << ", " << plane_text(a.analysis) << ", "
            << a.analysis.element_mm << " mm elements; " << axes.cells() + 1 << " solves of "
            << axes.indentation_mm.size() << " steps, " << axes.values() << " values\n";
  const std::filesystem::path folder = a.use_cache ? cache_folder(a) : std::filesystem::path();
  const std::filesystem::path cached =
      folder.empty() ? std::filesystem::path() : folder / ("fe-table-" + file.inputs.hash + ".json");
  if (!cached.empty() && std::filesystem::is_regular_file(cached)) {
    FeTableFile hit = load_fe_table_file(cached);
    if (hit.inputs.hash == file.inputs.hash) {
      write_fe_table_file(a.out, hit);
      std::cout << "  from the cache (" << cached.string() << "), built in " << hit.wall_s << " s with " << hit.workers
                << " workers\n  wrote " << a.out << "\n";
      return;
    }
  }
  mechanics::TableBuildOptions o;
  o.solve = solve_options(a.analysis);
  o.workers = a.workers;
  FeProgress progress("fe table");
  const mechanics::TableBuild built = mechanics::build_stress_table(finger, tissue, axes, o, std::ref(progress));
  file.table = std::make_shared<const FeStressTable>(built.table);
  file.solves = built.solves;
  file.wall_s = built.wall_s;
  file.workers = built.workers;
  print_out("  %zu solves in %.0f s with %d workers (block %.0f mm wide)\n", built.solves, built.wall_s, built.workers,
            built.block_width_mm);
  const double deepest = axes.indentation_mm.back();
  print_out("  healthy peak at %.2f mm: %.3f kPa\n", deepest, file.table->healthy_kPa(deepest));
  std::cout << std::flush;
  if (!cached.empty()) {
    try {  // the cache is a convenience: a folder that cannot be written costs the next run the build
      std::filesystem::create_directories(folder);
      write_fe_table_file(cached, file);
      std::cout << "  cached as " << cached.string() << "\n";
    } catch (const std::exception& e) {
      std::cerr << "palprig fe table: not cached: " << e.what() << "\n";
    }
  }
  write_fe_table_file(a.out, file);
  std::cout << "  wrote " << a.out << "\n";
}

}  // namespace

void register_fe_table(CLI::App* fe) {
  auto a = std::make_shared<TableArgs>();
  CLI::App* sub = fe->add_subcommand("table", "Compute (or take from the cache) the table function scenes render from");
  sub->add_option("--fingertip", a->fingertip, "Fingertip file (JSON)")->required()->check(CLI::ExistingFile);
  sub->add_option("--tissue", a->tissue, "Tissue file: its block and material (its inclusions are not used)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->out, "Table file to write (JSON)")->required();
  sub->add_option("--depths-mm", a->depths, "Indentation depths (the steps of each solve)")->default_val(a->depths);
  sub->add_option("--cover-mm", a->covers, "Depths of the nodule's top")->default_val(a->covers);
  sub->add_option("--diameter-mm", a->diameters, "Nodule diameters")->default_val(a->diameters);
  sub->add_option("--contrast", a->contrasts, "Nodule-to-tissue modulus ratios (> 1)")->default_val(a->contrasts);
  sub->add_option("--offset-mm", a->offsets, "Fingertip-to-nodule distances across (the last where the rise dies out)")
      ->default_val(a->offsets);
  sub->add_option("--workers", a->workers, "Worker processes solving at once")
      ->default_val(2)
      ->check(CLI::Range(1, 64));
  sub->add_option("--cache", a->cache, "Cache folder (default $XDG_CACHE_HOME/palprig or ~/.cache/palprig)");
  sub->add_flag("!--no-cache", a->use_cache, "Neither read nor write the cache");
  add_fe_analysis_options(sub, a->analysis);
  sub->callback([a] { run_table(*a); });
}
