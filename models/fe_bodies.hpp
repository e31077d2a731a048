#pragma once
// The three bodies of paper 002's finite-element study (section 2.3), as plain data: what the
// fingertip, tissue and actuator files hold once validated (formats/fe_body_files.hpp), and what
// mechanics/ meshes and solves. 2D cross-sections; lengths in mm, moduli in kPa. Defaults are
// the shipped files' (paper 002 and, where it is silent, the assumption the docs state:
// docs/finite-element.md).
#include <string>
#include <vector>

#include "models/material_law.hpp"

namespace palprig {

// The fingertip's cross-section: a super-ellipse outline (16 x 12 mm, paper 002), a skin band
// of constant thickness inside it, the distal phalanx as an elliptic bone, the nail filling the
// skin band over its width on the dorsal side. Coordinates: x across, y up, the outline's lowest
// point at (0, 0).
struct FingertipBody {
  double width_mm = 16.0;
  double height_mm = 12.0;
  double outline_exponent = 2.0;  // 2: an ellipse; larger: blunter
  double skin_thickness_mm = 0.8;
  double bone_width_mm = 7.0;
  double bone_height_mm = 4.0;
  double bone_centre_height_mm = 7.5;  // above the lowest point of the outline
  double nail_width_mm = 10.0;         // 0: no nail
  MaterialLaw skin = table1::skin();
  MaterialLaw tissue = table1::finger_tissue();
  MaterialLaw nail = table1::nail();
  MaterialLaw bone = table1::bone();
};

// A circular inclusion (the cross-section of a nodule) in the tissue block.
struct BlockInclusion {
  std::string name;
  double x_mm = 0;              // from the block's middle
  double centre_depth_mm = 10;  // below the block's top surface
  double diameter_mm = 10;
  MaterialLaw law = table1::tumor();
  double top_depth_mm() const noexcept { return centre_depth_mm - diameter_mm / 2; }
};

// How the block's sides are held (paper 002 does not say): free, or on rollers (no sideways
// motion, free to slide up and down). Its bottom is fixed.
enum class BlockSides { free, rollers };
const char* to_string(BlockSides s) noexcept;

// The soft-tissue block (30 x 100 mm, paper 002) with its inclusions. Its top surface is at
// y = 0, its middle at x = 0.
struct TissueBlock {
  std::string name;
  double width_mm = 30.0;
  double height_mm = 100.0;
  MaterialLaw tissue = table1::soft_tissue();
  BlockSides sides = BlockSides::free;
  std::vector<BlockInclusion> inclusions;
};

// The pneumatic actuator's cross-section (paper 002 fig. 2): a rigid substrate with an air
// chamber, the membrane bonded over it, the soft silicone layer on top. The air pressure acts on
// the membrane's underside across the chamber; elsewhere the membrane is bonded to the
// substrate. Top surface at y = 0, middle at x = 0.
struct ActuatorBody {
  std::string name;
  double width_mm = 24.0;         // the modelled width of the layers (the fingertip is 16 mm)
  double chamber_width_mm = 4.0;  // the cavity's diameter
  // Read and checked, but not modelled: the air is a pressure on the membrane's underside over the
  // chamber's width and the substrate below it is not meshed, so a membrane pressed deeper than
  // the chamber would not be stopped (no check; docs/finite-element.md's assumptions).
  double chamber_depth_mm = 2.0;
  double membrane_thickness_mm = 0.25;
  MaterialLaw membrane = table1::membrane();  // E from Shore A 40 (paper 002 eq. 3-4)
  // How the membrane's underside meets the substrate beside the chamber: bonded (held in both
  // directions, the paper's adhesive) or sliding (held only vertically: a frictionless rigid
  // substrate, ABAQUS's default contact; the layers' sides are then held horizontally so the
  // actuator cannot slide away). Paper 002 does not say which its model used.
  bool membrane_slides = false;
  double layer_thickness_mm = 3.0;
  MaterialLaw layer = table1::silicone_layer();
};

}  // namespace palprig
