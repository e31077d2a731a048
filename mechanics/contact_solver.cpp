// The one file that compiles GetFEM's headers (about 40 s of CPU: they are template-heavy), so
// the rest of palprig includes contact_solver.hpp only. See the header for what is solved.
#include "mechanics/contact_solver.hpp"

#include <getfem/getfem_contact_and_friction_large_sliding.h>
#include <getfem/getfem_generic_assembly.h>
#include <getfem/getfem_interpolation.h>
#include <getfem/getfem_model_solvers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace palprig::mechanics {

namespace {

using getfem::size_type;

constexpr size_type kMaterialRegion = 1;                            // + material index: its elements
constexpr size_type kBoundaryRegion = 100;                          // + boundary index: its element sides
const char* const kElementMethod = "IM_GAUSS_PARALLELEPIPED(2,4)";  // 3 x 3 points for Q2
const char* const kContactMethod = "IM_GAUSS_PARALLELEPIPED(2,6)";  // 4 points per side

// GetFEM reports through std::cout / std::cerr and its own levels; a library must stay quiet.
struct QuietGetfem {
  QuietGetfem() {
    gmm::set_traces_level(0);
    gmm::set_warning_level(0);
  }
};

// A law's strain energy as a GetFEM nonlinear operator of Grad_u: its value, gradient and
// Hessian computed in C++ (strain_energy.hpp says why). Registered once per law and plane mode,
// under a name made of their parameters, in GetFEM's table of predefined operators.
struct StrainEnergyOperator : getfem::ga_nonlinear_operator {
  MaterialLaw law;
  PlaneMode mode;
  StrainEnergyOperator(const MaterialLaw& l, PlaneMode m) : law(l), mode(m) {}

  static std::array<double, 4> grad_u(const arg_list& args) {
    const getfem::base_tensor& t = *args[0];
    return {t[0], t[1], t[2], t[3]};
  }
  bool result_size(const arg_list& args, bgeot::multi_index& sizes) const override {
    if (args.size() != 1 || args[0]->sizes().size() != 2 || args[0]->size() != 4) return false;
    sizes.resize(0);  // a scalar
    return true;
  }
  void value(const arg_list& args, getfem::base_tensor& result) const override {
    result[0] = strain_energy(law, mode, grad_u(args)).value;
  }
  void derivative(const arg_list& args, size_type, getfem::base_tensor& result) const override {
    const SecondOrderDual w = strain_energy(law, mode, grad_u(args));
    for (std::size_t k = 0; k < 4; ++k) result[k] = w.gradient[k];
  }
  void second_derivative(const arg_list& args, size_type, size_type, getfem::base_tensor& result) const override {
    const SecondOrderDual w = strain_energy(law, mode, grad_u(args));
    for (std::size_t k = 0; k < 4; ++k)  // result(k, l) at k + 4 l; the Hessian is symmetric
      for (std::size_t l = 0; l < 4; ++l) result[k + 4 * l] = w.hessian[4 * k + l];
  }
};

// The weak-form term of a law: its operator and, for an incompressible law in plane strain, the
// pressure's term p (J - 1). One operator per distinct law and mode in the process, numbered in
// the order first met (a name must be an identifier; numbering, unlike a hash, cannot collide).
std::string strain_energy_term(const MaterialLaw& law, PlaneMode mode, const std::string& pressure) {
  std::ostringstream key;
  key << std::hexfloat << int(law.kind) << ' ' << int(mode) << ' ' << law.mu_kPa << ' ' << law.alpha << ' '
      << law.locking_stretch << ' ' << law.youngs_kPa << ' ' << law.poisson;
  std::string op;
  {
    static std::mutex registering;                    // GetFEM's table is a process-wide map
    static std::map<std::string, std::string> names;  // key -> operator name
    const std::lock_guard<std::mutex> lock(registering);
    auto [it, added] = names.try_emplace(key.str(), "Palprig_strain_energy_" + std::to_string(names.size()));
    if (added)
      dal::singleton<getfem::ga_predef_operator_tab>::instance(0).add_method(
          it->second, std::make_shared<StrainEnergyOperator>(law, mode));
    op = it->second;
  }
  std::string term = op + "(Grad_u)";
  if (needs_pressure(law, mode)) term += "+" + pressure + "*(Det(F)-1)";
  return term;
}

getfem::base_node point(const MeshNode& n) {
  getfem::base_node p(2);
  p[0] = n.x_mm;
  p[1] = n.y_mm;
  return p;
}

}  // namespace

struct ContactSolver::Impl {
  ProblemSpec spec;
  QuietGetfem quiet;
  getfem::mesh mesh;
  getfem::mesh_im mim{mesh}, mim_contact{mesh};
  getfem::mesh_fem mf_u{mesh}, mf_p{mesh}, mf_lambda{mesh}, mf_surface{mesh}, mf_surface2{mesh}, mf_centre{mesh},
      mf_roller{mesh};
  getfem::model md;
  std::map<std::string, size_type> region_of;
  std::vector<std::string> variables{"u"};
  bool has_pressure = false;
  int slave_body = -1;
  std::string slave_thickness_ratio = "1";  // J3 in da/dA0 = J3 |F^-T N| (build_contact)

  explicit Impl(ProblemSpec s) : spec(std::move(s)) { build(); }

  size_type region(const std::string& boundary) const {
    const auto it = region_of.find(boundary);
    if (it == region_of.end()) throw Error("finite-element model: no boundary named " + boundary);
    return it->second;
  }

  void build_mesh() {
    const bgeot::pgeometric_trans q2 = bgeot::geometric_trans_descriptor("GT_QK(2,2)");
    for (std::size_t i = 0; i < spec.mesh.nodes.size(); ++i) {
      const size_type id = mesh.add_point(point(spec.mesh.nodes[i]), -1.0);  // never merged by distance
      if (id != i) throw Error("finite-element model: GetFEM renumbered a node");
    }
    for (const QuadElement& e : spec.mesh.elements) {
      std::array<size_type, 9> ids{};
      std::copy(e.nodes.begin(), e.nodes.end(), ids.begin());
      const size_type cv = mesh.add_convex(q2, ids.begin());
      mesh.region(kMaterialRegion + size_type(e.material)).add(cv);
    }
    // Sides: the GetFEM face whose points are the side's three nodes.
    for (std::size_t b = 0; b < spec.mesh.boundaries.size(); ++b) {
      const auto& [name, sides] = spec.mesh.boundaries[b];
      const size_type rg = kBoundaryRegion + b;
      region_of[name] = rg;
      for (const MeshSide& s : sides) {
        const auto want = spec.mesh.side_nodes(s);
        const std::set<size_type> wanted(want.begin(), want.end());
        bool found = false;
        for (bgeot::short_type f = 0; f < 4 && !found; ++f) {
          const auto pts = mesh.ind_points_of_face_of_convex(s.element, f);
          if (std::set<size_type>(pts.begin(), pts.end()) == wanted) {
            mesh.region(rg).add(s.element, f);
            found = true;
          }
        }
        if (!found) throw Error("finite-element model: a side of boundary " + name + " is not an element face");
      }
    }
  }

  void build() {
    build_mesh();
    mim.set_integration_method(mesh.convex_index(), getfem::int_method_descriptor(kElementMethod));
    mim_contact.set_integration_method(mesh.convex_index(), getfem::int_method_descriptor(kContactMethod));
    mf_u.set_qdim(2);
    mf_u.set_classical_finite_element(mesh.convex_index(), 2);
    md.add_fem_variable("u", mf_u);
    md.add_macro("F", "(Id(2)+Grad_u)");
    md.add_macro("C", "(F'*F)");
    // The pressure field over the incompressible elements (plane strain only).
    dal::bit_vector incompressible;
    for (std::size_t i = 0; i < spec.mesh.elements.size(); ++i)
      if (needs_pressure(spec.materials.at(std::size_t(spec.mesh.elements[i].material)), spec.plane))
        incompressible.add(i);
    has_pressure = incompressible.card() > 0;
    if (has_pressure) {
      mf_p.set_classical_finite_element(incompressible, 1);
      md.add_fem_variable("p", mf_p);
      variables.push_back("p");
    }
    for (std::size_t m = 0; m < spec.materials.size(); ++m) {
      if (mesh.region(kMaterialRegion + m).is_empty()) continue;
      getfem::add_nonlinear_term(md, mim, strain_energy_term(spec.materials[m], spec.plane, "p"), kMaterialRegion + m,
                                 true, false, "material " + std::to_string(m));
    }
    for (std::size_t i = 0; i < spec.held.size(); ++i) {
      const std::string data = "held_" + std::to_string(i);
      md.add_initialized_fixed_size_data(data, getfem::base_vector(2));
      getfem::add_Dirichlet_condition_with_simplification(md, "u", region(spec.held[i].boundary), data);
    }
    if (!spec.rollers.empty()) mf_roller.set_classical_finite_element(mesh.convex_index(), 1);
    for (std::size_t i = 0; i < spec.rollers.size(); ++i) {
      const std::string data = "roller_" + std::to_string(i), mult = "roller_force_" + std::to_string(i);
      md.add_initialized_scalar_data(data, 0.0);
      md.add_multiplier(mult, mf_roller, region(spec.rollers[i].boundary), "u");
      getfem::add_normal_Dirichlet_condition_with_multipliers(md, mim, "u", mult, region(spec.rollers[i].boundary),
                                                              data);
      variables.push_back(mult);
    }
    for (std::size_t i = 0; i < spec.pressures.size(); ++i) {
      const std::string data = "pressure_" + std::to_string(i);
      md.add_initialized_scalar_data(data, 0.0);
      // A follower load: the air pushes along the deformed surface's normal over its deformed
      // length (Nanson: da n = J F^-T N dA0). The residual is internal minus external work.
      getfem::add_nonlinear_term(md, mim, data + "*Det(F)*((Inv(F)')*Normal).Test_u",
                                 region(spec.pressures[i].boundary), false, false, "air pressure");
    }
    if (spec.contact) build_contact();
    // Centre values (von Mises) and the smoothed contact stress on the slave body's nodes.
    mf_centre.set_classical_discontinuous_finite_element(mesh.convex_index(), 0);
  }

  void build_contact() {
    const ContactPair& c = *spec.contact;
    const size_type slave = region(c.slave), master = region(c.master);
    slave_body = spec.mesh.elements.at(spec.mesh.boundary(c.slave).front().element).body;
    dal::bit_vector slave_elements;
    for (std::size_t i = 0; i < spec.mesh.elements.size(); ++i)
      if (spec.mesh.elements[i].body == slave_body) slave_elements.add(i);
    // da/dA0 = |Det(F) Inv(F)' N| (the surface's stretch) times the thickness stretch. In plane
    // strain that is exactly |Det(F) Inv(F)' N|, whatever the law (the discrete J of a weakly
    // incompressible solution is not exactly 1, and at the skin's surface the difference is a
    // few per cent); in plane stress an incompressible slave's thickness stretch is 1/Det(F),
    // which cancels Det(F). (A compressible slave in plane stress is read with its thickness
    // change left out: none of the shipped fingertips has one.)
    slave_thickness_ratio = spec.plane == PlaneMode::plane_strain ? "Det(F)" : "1";
    mf_lambda.set_qdim(2);
    // Quadratic multipliers, as the displacements: with linear ones (one per element corner) the
    // contact holds only on average over each side, and over the hard nodule the soft skin's
    // mid-side nodes wrinkled into the block (a zig-zag of 0.2 mm and stresses alternating
    // by 30 % node to node) until Newton stalled; quadratic ones converge in 4-5 iterations a
    // step there and leave the healthy case's peak unchanged.
    mf_lambda.set_classical_finite_element(slave_elements, 2);
    md.add_filtered_fem_variable("lambda", mf_lambda, slave);
    variables.push_back("lambda");
    md.add_initialized_scalar_data("contact_r", c.augmentation_kPa_per_mm);
    md.add_initialized_scalar_data("friction", 0.0);
    const size_type brick = getfem::add_integral_large_sliding_contact_brick_raytracing(
        md, "contact_r", c.release_distance_mm, "friction", "1", false, false);
    getfem::add_contact_boundary_to_large_sliding_contact_brick(md, brick, mim_contact, slave, false, true, "u",
                                                                "lambda", "");
    getfem::add_contact_boundary_to_large_sliding_contact_brick(md, brick, mim_contact, master, true, false, "u", "",
                                                                "");
    mf_surface.set_classical_finite_element(slave_elements, 2);
    mf_surface2.set_qdim(2);
    mf_surface2.set_classical_finite_element(slave_elements, 2);
  }

  void apply(const LoadState& load) {
    for (std::size_t i = 0; i < spec.held.size(); ++i) {
      const auto it = load.held_mm.find(spec.held[i].boundary);
      auto& v = md.set_real_variable("held_" + std::to_string(i));
      v[0] = it == load.held_mm.end() ? 0.0 : it->second[0];
      v[1] = it == load.held_mm.end() ? 0.0 : it->second[1];
    }
    for (std::size_t i = 0; i < spec.rollers.size(); ++i) {
      const auto it = load.roller_mm.find(spec.rollers[i].boundary);
      md.set_real_variable("roller_" + std::to_string(i))[0] = it == load.roller_mm.end() ? 0.0 : it->second;
    }
    for (std::size_t i = 0; i < spec.pressures.size(); ++i) {
      const auto it = load.pressure_kPa.find(spec.pressures[i].boundary);
      md.set_real_variable("pressure_" + std::to_string(i))[0] = it == load.pressure_kPa.end() ? 0.0 : it->second;
    }
  }

  // Assemble an expression (order 0) over a region.
  double integral(const std::string& expr, size_type rg) const {
    getfem::ga_workspace ws(md);
    ws.add_expression(expr, mim_contact, rg, 0);
    ws.assembly(0);
    return ws.assembled_potential();
  }
};

ContactSolver::ContactSolver(ProblemSpec spec) {
  try {
    impl_ = std::make_unique<Impl>(std::move(spec));
  } catch (const palprig::Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(std::string("finite-element model: GetFEM refused the problem: ") + e.what());
  }
}

ContactSolver::~ContactSolver() = default;

NewtonReport ContactSolver::solve(const LoadState& load, int max_iterations) {
  Impl& m = *impl_;
  std::vector<getfem::model_real_plain_vector> saved;
  for (const auto& v : m.variables) saved.push_back(m.md.real_variable(v));
  NewtonReport report;
  gmm::iteration iter(1e-9, 0, size_type(max_iterations));
  try {
    m.apply(load);
    getfem::simplest_newton_line_search ls;
    getfem::standard_solve(m.md, iter, getfem::rselect_linear_solver(m.md, "mumps"), ls);
    report.converged = iter.converged();
    if (!report.converged)
      report.failure = "Newton did not converge in " + std::to_string(max_iterations) + " iterations";
  } catch (const std::exception& e) {
    report.failure = std::string("GetFEM: ") + e.what();
  }
  report.iterations = int(iter.get_iteration());
  if (report.converged)
    for (const auto& v : m.variables)
      for (double x : m.md.real_variable(v))
        if (!std::isfinite(x)) {
          report.converged = false;
          report.failure = "a non-finite " + v;
          break;
        }
  if (!report.converged)
    for (std::size_t i = 0; i < m.variables.size(); ++i) gmm::copy(saved[i], m.md.set_real_variable(m.variables[i]));
  return report;
}

std::vector<ContactNode> ContactSolver::contact_profile() const {
  const Impl& m = *impl_;
  if (!m.spec.contact) return {};
  const size_type slave = m.region(m.spec.contact->slave);
  // da/dA0 = J3 |F^-T N|; the Cauchy normal stress is the multiplier's normal component over it
  // (compressive positive: the multiplier is the traction on the slave surface, pointing in).
  const std::string n = "Normalized(Inv(F)'*Normal)";
  const std::string cpress = "(-(lambda." + n + ")/(" + m.slave_thickness_ratio + "*Norm(Inv(F)'*Normal)))";
  const size_type nd = m.mf_surface.nb_dof();
  getfem::base_vector weighted(nd), weights(nd);
  // A workspace of its own, with the solution as constants and the surface field as its only
  // variable: the assembled vector is that field's.
  auto assemble = [&](const std::string& expr, getfem::base_vector& out) {
    getfem::ga_workspace ws;
    const getfem::model_real_plain_vector dummy(nd);
    ws.add_fem_constant("u", m.mf_u, m.md.real_variable("u"));
    ws.add_fem_constant("lambda", m.md.mesh_fem_of_variable("lambda"), m.md.real_variable("lambda"));
    ws.add_fem_variable("t", m.mf_surface, gmm::sub_interval(0, nd), dummy);
    ws.add_macro("F", "(Id(2)+Grad_u)");
    ws.set_assembled_vector(out);
    ws.add_expression(expr, m.mim_contact, slave, 1);
    ws.assembly(1);
  };
  assemble(cpress + "*Test_t", weighted);
  assemble("Test_t", weights);
  getfem::base_vector us(m.mf_surface2.nb_dof());
  getfem::interpolation(m.mf_u, m.mf_surface2, m.md.real_variable("u"), us);
  // Arc position: sort the surface nodes by angle about the slave body's centre, then measure.
  double cx = 0, cy = 0, count = 0;
  for (size_type i = 0; i < nd; ++i)
    if (weights[i] > 1e-12) {
      const auto p = m.mf_surface.point_of_basic_dof(i);
      cx += p[0];
      cy += p[1];
      ++count;
    }
  if (count == 0) return {};
  cx /= count;
  cy /= count;
  struct Entry {
    double angle;
    getfem::base_node ref;
    ContactNode node;
  };
  std::vector<Entry> entries;
  double lowest_y = 1e300, lowest_angle = 0;
  for (size_type i = 0; i < nd; ++i) {
    if (!(weights[i] > 1e-12)) continue;
    const auto p = m.mf_surface.point_of_basic_dof(i);
    Entry e;
    e.ref = p;
    // Angle from straight down, positive to the right.
    e.angle = std::atan2(p[0] - cx, -(p[1] - cy));
    e.node.x_mm = p[0] + us[2 * i];
    e.node.y_mm = p[1] + us[2 * i + 1];
    e.node.pressure_kPa = weighted[i] / weights[i];
    if (p[1] < lowest_y) {
      lowest_y = p[1];
      lowest_angle = e.angle;
    }
    entries.push_back(e);
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.angle < b.angle; });
  std::vector<ContactNode> out;
  out.reserve(entries.size());
  double s = 0;
  std::size_t origin = 0;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (k > 0) s += gmm::vect_dist2(entries[k].ref, entries[k - 1].ref);
    entries[k].node.s_mm = s;
    if (std::abs(entries[k].angle - lowest_angle) < std::abs(entries[origin].angle - lowest_angle)) origin = k;
  }
  const double s0 = entries[origin].node.s_mm;
  for (auto& e : entries) {
    e.node.s_mm -= s0;
    out.push_back(e.node);
  }
  return out;
}

std::array<double, 2> ContactSolver::contact_force_per_mm() const {
  const Impl& m = *impl_;
  if (!m.spec.contact) return {0, 0};
  const size_type slave = m.region(m.spec.contact->slave);
  return {m.integral("lambda(1)", slave), m.integral("lambda(2)", slave)};
}

double ContactSolver::roller_reaction_per_mm(const std::string& boundary) const {
  const Impl& m = *impl_;
  for (std::size_t i = 0; i < m.spec.rollers.size(); ++i)
    if (m.spec.rollers[i].boundary == boundary)
      return m.integral("roller_force_" + std::to_string(i), m.region(boundary));
  throw Error("finite-element model: no roller boundary named " + boundary);
}

DeformedMesh ContactSolver::deformed() const {
  const Impl& m = *impl_;
  DeformedMesh out;
  out.nodes = m.spec.mesh.nodes;
  const auto& u = m.md.real_variable("u");
  for (std::size_t cv = 0; cv < m.spec.mesh.elements.size(); ++cv) {
    const auto dofs = m.mf_u.ind_basic_dof_of_element(cv);
    const auto& e = m.spec.mesh.elements[cv];
    for (std::size_t k = 0; k < 9; ++k) {
      MeshNode& node = out.nodes[e.nodes[k]];
      const MeshNode& ref = m.spec.mesh.nodes[e.nodes[k]];
      node.x_mm = ref.x_mm + u[dofs[2 * k]];
      node.y_mm = ref.y_mm + u[dofs[2 * k + 1]];
    }
  }
  std::array<getfem::base_vector, 4> g;
  const char* const components[4] = {"Grad_u(1,1)", "Grad_u(1,2)", "Grad_u(2,1)", "Grad_u(2,2)"};
  for (std::size_t k = 0; k < 4; ++k) {
    g[k].resize(m.mf_centre.nb_dof());
    getfem::ga_interpolation_Lagrange_fem(m.md, components[k], m.mf_centre, g[k]);
  }
  out.von_mises_kPa.resize(m.spec.mesh.elements.size());
  for (std::size_t cv = 0; cv < m.spec.mesh.elements.size(); ++cv) {
    const size_type d = m.mf_centre.ind_basic_dof_of_element(cv)[0];
    const std::array<double, 4> F = {1 + g[0][d], g[1][d], g[2][d], 1 + g[3][d]};
    out.von_mises_kPa[cv] =
        von_mises_kPa(m.spec.materials.at(std::size_t(m.spec.mesh.elements[cv].material)), m.spec.plane, F);
  }
  return out;
}

const QuadMesh& ContactSolver::mesh() const { return impl_->spec.mesh; }

std::size_t ContactSolver::unknowns() const { return impl_->md.nb_dof(); }

}  // namespace palprig::mechanics
