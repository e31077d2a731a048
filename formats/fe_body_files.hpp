#pragma once
// The three files of the finite-element model (JSON, versioned), read into models/fe_bodies.hpp:
//
//   fingertip  {"version": 1, "kind": "fingertip", "name",
//               "outline": {"width_mm", "height_mm", "exponent"}, "skin_thickness_mm",
//               "bone": {"width_mm", "height_mm", "centre_height_mm"}, "nail": {"width_mm"},
//               "materials": {"skin", "tissue", "nail", "bone": MATERIAL}}   (Table 1 when absent)
//   tissue     {"version": 1, "kind": "tissue", "name",
//               "block": {"width_mm", "height_mm", "sides": "free"|"rollers"}, "material": MATERIAL,
//               "inclusions": [{"name", "x_mm", "centre_depth_mm", "diameter_mm", "material"}]}
//   actuator   {"version": 1, "kind": "actuator", "name", "width_mm",
//               "chamber": {"width_mm", "depth_mm"},
//               "membrane": {"thickness_mm", "material"}, "layer": {"thickness_mm", "material"}}
//   MATERIAL   {"law": "ogden", "mu_kPa", "alpha"} | {"law": "arruda_boyce", "mu_kPa",
//               "locking_stretch"} | {"law": "linear_elastic", "youngs_kPa" | "shore_a" |
//               "shore_d", "poisson"}, each with an optional "density_kg_m3"
//
// Every key is documented in docs/scene-authoring.md ("Finite-element files"). A refused file
// names the file, the field and what was expected (InputError), including shapes that cannot be
// meshed: a bone outside the tissue, a nodule through the block's surface, two nodules that
// overlap, a chamber wider than the actuator.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "formats/json_file.hpp"
#include "models/fe_bodies.hpp"

namespace palprig {

inline constexpr int kFeBodyFileVersion = 1;

FingertipBody load_fingertip_file(const std::filesystem::path& path);
TissueBlock load_tissue_file(const std::filesystem::path& path);
ActuatorBody load_actuator_file(const std::filesystem::path& path);

// The same from parsed JSON (`file` names it in refusals): the fuzz targets and the table
// builder, which reads a tissue file once and varies its nodule.
FingertipBody parse_fingertip(const nlohmann::json& doc, const std::string& file);
TissueBlock parse_tissue(const nlohmann::json& doc, const std::string& file);
ActuatorBody parse_actuator(const nlohmann::json& doc, const std::string& file);

// A MATERIAL object (see above).
MaterialLaw parse_material(const JsonObject& o);

// The file's "kind" when it is one of the three ("fingertip", "tissue", "actuator"), else "".
std::string fe_body_kind(const nlohmann::json& doc);

}  // namespace palprig
