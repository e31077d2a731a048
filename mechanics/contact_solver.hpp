#pragma once
// One finite-element problem on GetFEM: large-deformation hyperelastic bodies in 2D (plane
// strain or plane stress), frictionless large-sliding contact between a slave and a master
// boundary, prescribed displacements and follower air pressures, solved step by step with
// Newton and a line search. This header keeps GetFEM out of its users (its templates are heavy:
// only contact_solver.cpp compiles them).
//
// Units: mm, kPa (forces per unit thickness in kPa mm = N/m).
//
// What is computed for a solved state:
// - the contact stress along the slave boundary read the way ABAQUS's CPRESS reports it: the
//   Cauchy normal stress (the contact multiplier, a nominal traction, divided by the surface's
//   area ratio da/dA0 = J |F^-T N|), smoothed by a lumped L2 projection on the boundary's
//   quadratic nodes (each node's value is the stress averaged over its neighbouring element
//   sides with its shape function's weight), not a raw multiplier value;
// - the total contact force; the reaction on a boundary held by a one-component condition;
// - the deformed mesh with each element's von Mises stress (at its centre).
#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mechanics/quad_mesh.hpp"
#include "mechanics/strain_energy.hpp"
#include "models/material_law.hpp"

namespace palprig::mechanics {

// A boundary held in both directions at a prescribed displacement (set per load state by name).
struct HeldBoundary {
  std::string boundary;
};
// A boundary whose normal displacement is prescribed (rollers), with the normal reaction kept.
struct RollerBoundary {
  std::string boundary;
};
struct ContactPair {
  std::string slave, master;
  double augmentation_kPa_per_mm = 10.0;  // GetFEM's augmentation parameter r
  double release_distance_mm = 3.0;       // contact is searched within this distance
};
// An air pressure on a boundary, following it as it deforms (set per load state by name).
struct PressureBoundary {
  std::string boundary;
};

struct ProblemSpec {
  QuadMesh mesh;
  std::vector<MaterialLaw> materials;  // indexed by QuadElement::material
  PlaneMode plane = PlaneMode::plane_strain;
  std::vector<HeldBoundary> held;
  std::vector<RollerBoundary> rollers;
  std::optional<ContactPair> contact;
  std::vector<PressureBoundary> pressures;
};

struct LoadState {
  std::map<std::string, std::array<double, 2>> held_mm;  // per held boundary: (ux, uy); absent: (0, 0)
  std::map<std::string, double> roller_mm;               // per roller: outward normal displacement; absent: 0
  std::map<std::string, double> pressure_kPa;            // per pressure boundary; absent: 0
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  std::string failure;  // why not, when not
};

struct ContactNode {
  double s_mm = 0;            // signed arc position along the undeformed slave boundary
  double x_mm = 0, y_mm = 0;  // where it is now
  double pressure_kPa = 0;    // Cauchy contact stress (CPRESS), compressive positive
};

struct DeformedMesh {
  std::vector<MeshNode> nodes;        // deformed positions, indexed like QuadMesh::nodes
  std::vector<double> von_mises_kPa;  // per element, at its centre
};

class ContactSolver {
 public:
  // Throws palprig::Error when GetFEM refuses the problem (a bug in the meshers: the mesh came
  // from this folder).
  explicit ContactSolver(ProblemSpec spec);
  ~ContactSolver();
  ContactSolver(const ContactSolver&) = delete;
  ContactSolver& operator=(const ContactSolver&) = delete;

  // Newton from the present state to the state of `load`. On failure the state is put back
  // as it was, so the caller can cut the step.
  NewtonReport solve(const LoadState& load, int max_iterations = 40);

  std::vector<ContactNode> contact_profile() const;                  // along the slave boundary, by s_mm
  std::array<double, 2> contact_force_per_mm() const;                // on the slave body (kPa mm)
  double roller_reaction_per_mm(const std::string& boundary) const;  // normal force on it
  DeformedMesh deformed() const;
  const QuadMesh& mesh() const;
  std::size_t unknowns() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace palprig::mechanics
