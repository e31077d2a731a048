#pragma once
// The finite-element table beyond paper 002 (models/fe_stress_table.hpp): one indentation solve
// per nodule (cover x diameter x contrast x offset), each giving the peak at every indentation
// step, plus the healthy block's. The nodule is the block's own law made `contrast` times
// stiffer (same locking stretch); the fingertip presses at x = 0 and the nodule's centre sits
// `offset` to the side. The block is widened where the widest offset needs it, so that every
// nodule fits with the block's side 8 mm beyond it (the healthy peaks come from that block too).
//
// Solves run in `workers` child processes: GetFEM (Debian's build, without OpenMP) keeps
// process-wide caches that threads would share unsynchronised, so each worker is a fork that
// sends its results back through a pipe. Nothing is written to disk here: caching the table
// by its inputs' hash is the command's job (cli/fe_table_command.cpp).
#include <cstddef>

#include "mechanics/contact_problems.hpp"
#include "models/fe_bodies.hpp"
#include "models/fe_stress_table.hpp"

namespace palprig::mechanics {

struct TableBuildOptions {
  SolveOptions solve;
  int workers = 2;
};

struct TableBuild {
  FeStressTable table;
  std::size_t solves = 0;
  double wall_s = 0;
  int workers = 1;
  double block_width_mm = 0;  // after widening
};

// The block the table's solves use (widened for the offsets; its inclusions dropped).
TissueBlock table_block(const TissueBlock& tissue, const FeTableAxes& axes);

// axes.indentation_mm are the steps of each solve (increasing, from the first to the deepest).
// Throws palprig::Error when a solve fails (naming the nodule) or a worker dies.
TableBuild build_stress_table(const FingertipBody& finger, const TissueBlock& tissue, const FeTableAxes& axes,
                              const TableBuildOptions& options, const ProgressFn& progress = {});

}  // namespace palprig::mechanics
