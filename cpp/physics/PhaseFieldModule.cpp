#include "physics/PhaseFieldModule.h"
#include "mesh/BoundaryTags.h"
#include "solve/Assemble.h"
#include "util/Clock.h"
#include "util/Cpus.h"
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace cellphase
{
using namespace dolfinx;
using scene::Model;

namespace
{
std::shared_ptr<Constant> constant(double v) { return std::make_shared<Constant>(v); }

/// sigma = 1/Ca of the surface tension energy (3.78), 0 unless the scene asks for it.
double surface_tension(const scene::Scene& s)
{
  return s.phase_field.surface_tension ? 1 / s.numbers.Ca : 0.0;
}

/// Boundary facets on the sides of non-periodic axes: where phi = -1 (2.19) applies. A
/// mesh-file domain: the whole boundary, or the facets of boundary.phi_tags.
std::vector<std::int32_t> wall_facets(const Mesh& mesh, const scene::Scene& s)
{
  const scene::Domain& d = s.domain;
  if (d.mesh && !s.phi_tags.empty())
    return tagged_facets(mesh, *d.mesh, tag_numbers(*d.mesh, s.phi_tags));
  if (d.mesh)
    return compat::boundary_facets(mesh, [](double, double, double) { return true; });
  const double tol = 1e-8 * d.largest_extent();
  return compat::boundary_facets(mesh, [&d, tol](double x, double y, double z)
                                 {
                                   const std::array<double, 3> p{x, y, z};
                                   for (int a = 0; a < d.dim; ++a)
                                     if (!d.is_periodic(a)
                                         && (std::abs(p[a] - d.lower[a]) < tol
                                             || std::abs(p[a] - d.upper[a]) < tol))
                                       return true;
                                   return false;
                                 });
}

} // namespace

PhaseFieldModule::PhaseFieldModule(const scene::Scene& scene, MPI_Comm comm)
    : scene_(scene), comm_(comm), forms_(model_forms(scene.phase_field.model, scene.domain.dim)),
      names_(scene::model_fields(scene.phase_field.model)),
      stabilised_(scene.numerics.linearisation == scene::Linearisation::stabilised),
      symmetrisable_(stabilised_ && (scene.phase_field.model == Model::helfrich_lagrange
                                     || scene.phase_field.model == Model::helfrich_penalty)),
      bdf2_(scene.numerics.time_scheme == scene::Numerics::TimeScheme::bdf2),
      spare_cpu_(cpus_per_rank(comm) > 1), domain_volume_(scene.domain.volume())
{
  for (const auto& h : scene::history_fields(scene))
    history_names_.push_back(h);
  // The L2 flows' coupling stabilisation lives in forms of its own (forms/helfrich_l2.py).
  if (scene.flow && scene.flow->coupling_stabilisation > 0 && forms_.a_coupled)
  {
    forms_.a = forms_.a_coupled;
    forms_.L = forms_.L_coupled;
    forms_.a_bdf2 = forms_.a_bdf2_coupled;
    forms_.L_bdf2 = forms_.L_bdf2_coupled;
  }
  const auto& pf = scene.phase_field;
  const auto& nu = scene.numerics;
  dt_ = constant(nu.dt);
  lam_v_ = constant(0.0);
  lam_a_ = constant(0.0);
  own_mesh_ = constant(nu.mesh.cell_meshes == scene::Mesh::CellMeshes::own ? 1.0 : 0.0);
  constants_ = {{"dt", dt_},
                {"eps", constant(nu.epsilon)},
                {"gamma", constant(pf.mobility)},
                {"Be", constant(scene.numbers.Be)},
                {"H0", constant(pf.spontaneous_curvature)},
                {"S", constant(nu.stabilisation)},
                {"lam_v", lam_v_},
                {"lam_a", lam_a_},
                {"sigma", constant(surface_tension(scene))},
                // -eps/g with g = gamma/Be: the symmetric scaling of helfrich_l2.py
                {"row_psi", constant(symmetrisable_ ? -nu.epsilon * scene.numbers.Be / pf.mobility
                                                    : 1.0)},
                {"degenerate", constant(pf.degenerate_mobility ? 1.0 : 0.0)},
                // forms/helfrich_hm1.py: mobility on the step's change of w (0 without flow)
                {"beta_coupling", constant(scene.flow ? scene.flow->coupling_stabilisation : 0.0)},
                // advect phi + 1 on a cell's own mesh (forms/cellphase_ufl.py)
                {"own_mesh", own_mesh_},
                {"cos_theta", constant(scene.contact_angle_deg
                                           ? std::cos(*scene.contact_angle_deg * std::numbers::pi / 180)
                                           : 0.0)}};
  bdf_.add_to(constants_);
}

std::int64_t PhaseFieldModule::num_dofs() const { return compat::num_global_dofs(*W_); }

void PhaseFieldModule::attach(std::shared_ptr<Space> V, FieldMap fields)
{
  V_ = V;
  auto mesh = V->mesh();
  W_ = compat::create_space(forms_.space, "u0", mesh);
  fields_.clear();
  for (const auto& name : names_)
  {
    auto it = fields.find(name);
    fields_[name] = it != fields.end() ? it->second : std::make_shared<Function>(V_);
    fields_[name]->name = name;
  }
  // BDF2: the previous state moves with the present one (remesh, checkpoint); without it
  // (the start) the next step is a backward Euler step.
  for (const auto& name : history_names_)
  {
    auto it = fields.find(name);
    if (it == fields.end())
      history_.have = false;
    fields_[name] = it != fields.end() ? it->second : std::make_shared<Function>(V_);
    fields_[name]->name = name;
  }

  // V dof -> W dof for each field, matched through the cell-local dof order (the
  // sub-elements of W are V's element).
  to_mixed_.clear();
  for (std::size_t i = 0; i < names_.size(); ++i)
    to_mixed_.push_back(compat::dofs_in_sub_space(*V_, *(names_.size() > 1 ? W_->sub({int(i)}) : W_)));

  u0_ = std::make_shared<Function>(W_);
  u1_ = nullptr;
  if (bdf2_) // (an adaptive Euler step keeps phi_prev for its estimate only)
  {
    u1_ = std::make_shared<Function>(W_);
    u1_->x()->set(0.0); // slots of fields without history (w) stay zero
  }
  sources_.clear(); // built again on this mesh by set_interaction, set_orientation
  interaction_rhs_.clear();
  interaction_projection_.reset();
  dE_.reset();
  velocity_.reset();
  flowing_ = false;
  if (forms_.advected)
  {
    // Zero until the flow sets its velocity: the no-flow forms add exact zeros.
    auto v = std::make_shared<Function>(compat::create_space(forms_.space, "v", mesh));
    v->x()->set(0.0);
    velocity_ = v;
  }
  bcs_.clear();
  if (scene_.phi_boundary == scene::PhiBoundary::dirichlet)
  {
    // phi = -1 on the boundary (2.19); the other fields have natural conditions.
    // The value lives in the collapsed space V for a mixed W, in W itself otherwise
    // (their dof numberings differ).
    boundary_value_ = std::make_shared<Function>(names_.size() > 1 ? V_ : W_);
    boundary_value_->x()->set(-1.0);
    const auto facets = wall_facets(*mesh, scene_);
    if (names_.size() > 1)
      bcs_.push_back(std::make_shared<DirichletBC>(
          boundary_value_, compat::boundary_dofs(*W_, 0, *V_, facets), W_->sub({0})));
    else
      bcs_.push_back(
          std::make_shared<DirichletBC>(boundary_value_, compat::boundary_dofs(*W_, facets)));
  }
  periodic_ = std::make_unique<PeriodicConstraint>(W_, scene_.domain.lower, scene_.domain.upper,
                                                   scene_.domain.periodic, bcs_);

  bind_forms();
  A_.reset();
  matrix_current_ = false;
  solver_.reset();
  // From the constraint: with periodic axes their ghosts include remote masters.
  b_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  x_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  lifting_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  for (auto& load : loads_)
  {
    load.x = std::make_unique<la::Vector<T>>(periodic_->create_vector());
    load.b = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  }

  if (forms_.a_mu && fields.find("mu") == fields.end())
    compute_mu_from_phi();
}

std::shared_ptr<const Function> PhaseFieldModule::interface_potential()
{
  if (!forms_.L_dE)
    return fields_.at(scene_.phase_field.model == Model::helfrich_hm1 ? "w" : "mu");
  if (!dE_)
  {
    dE_ = std::make_shared<Function>(V_);
    dE_->name = "dE";
    CoefficientMap coeffs{{"phi_h", fields_.at("phi")}, {"mu_h", fields_.at("mu")}};
    dE_rhs_ = compat::create_form(*forms_.L_dE, {V_}, coeffs, constants_);
    dE_projection_ = std::make_unique<L2Projection>(
        *compat::create_form(*forms_.a_mu, {V_, V_}, {}, constants_), scene_.domain, comm_, "mass_");
    update_interface_potential();
  }
  return dE_;
}

void PhaseFieldModule::update_interface_potential()
{
  dE_projection_->project(*dE_rhs_, *dE_, "the projection of dE/dphi (3.84)");
}

void PhaseFieldModule::add_source(const ufcx_form* form, const std::string& term,
                                  CoefficientMap coefficients, const ConstantMap& parameters)
{
  if (!form)
    throw std::logic_error(std::string("model ") + scene::to_string(scene_.phase_field.model)
                           + " has no " + term + " term");
  ConstantMap constants = constants_;
  constants.insert(parameters.begin(), parameters.end());
  coefficients["u0"] = u0_;
  sources_.push_back(compat::create_form(*form, {W_}, coefficients, constants));
  source_b_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
}

void PhaseFieldModule::set_interaction(std::shared_ptr<const Function> w_sum,
                                       std::shared_ptr<const Function> B_sum,
                                       const ConstantMap& parameters, bool refresh,
                                       bool in_flow_force)
{
  if (in_flow_force)
    add_source(forms_.load_int, "interaction", {{"w_sum", w_sum}, {"B_sum", B_sum}}, parameters);
  if (!refresh && in_flow_force)
    return;
  ConstantMap constants = constants_;
  constants.insert(parameters.begin(), parameters.end());
  interaction_rhs_.push_back(compat::create_form(
      *forms_.L_int, {V_}, {{"phi_h", fields_.at("phi")}, {"w_sum", w_sum}, {"B_sum", B_sum}},
      constants));
  if (interaction_projection_)
    return; // one projection of the sum over the potentials
  interaction_projection_ = std::make_unique<L2Projection>(
      *compat::create_form(*forms_.a_mu, {V_, V_}, {}, constants_), scene_.domain, comm_, "interaction_");
  interaction_of_step_ = std::make_shared<Function>(V_);
  interaction_now_ = std::make_shared<Function>(V_);
  if (!in_flow_force) // gamma Lap(w + P(source)): w, which the flow reads, stays without it
    add_source(forms_.load_int_mobility, "interaction", {{"w_int", interaction_of_step_}}, {});
}

std::vector<const Form*> PhaseFieldModule::interaction_sources() const
{
  std::vector<const Form*> forms;
  for (const auto& form : interaction_rhs_)
    forms.push_back(form.get());
  return forms;
}

void PhaseFieldModule::refresh_interaction()
{
  if (interaction_rhs_.empty())
    return;
  interaction_projection_->project(interaction_sources(), *interaction_now_,
                                   "the interaction source (7.11) after the step");
  auto w = fields_.at("w")->x()->mutable_array();
  auto now = interaction_now_->x()->array();
  auto before = interaction_of_step_->x()->array();
  for (std::size_t i = 0; i < w.size(); ++i)
    w[i] += now[i] - before[i];
}

void PhaseFieldModule::set_patch_edges(bool cut)
{
  own_mesh_->value[0] = cut ? 1.0 : 0.0;
  matrix_current_ = false;
}

void PhaseFieldModule::set_orientation(std::shared_ptr<const Function> P,
                                       const ConstantMap& parameters)
{
  if (P->function_space()->mesh() != W_->mesh()) // the polar gel solves on phi's mesh
    throw std::invalid_argument("phase field: the orientation field must live on the current mesh");
  add_source(forms_.load_polar, "orientation-field", {{"P_polar", P}}, parameters);
}

void PhaseFieldModule::set_velocity(std::shared_ptr<const Function> v)
{
  if (!forms_.advected)
    throw std::logic_error(std::string("model ") + scene::to_string(scene_.phase_field.model)
                           + " has no advection term");
  if (v->function_space()->mesh() != W_->mesh())
    throw std::invalid_argument("phase field: the velocity must live on the current mesh");
  velocity_ = v;
  flowing_ = true;
  if (symmetrisable_)
    solver_.reset(); // advection makes the matrix unsymmetric: LU from now on
  bind_system_forms();
  matrix_current_ = false;
}

void PhaseFieldModule::bind_system_forms()
{
  CoefficientMap coeffs{{"u0", u0_}};
  if (velocity_)
    coeffs["v"] = velocity_;
  const ufcx_form& a = stabilised_ ? *forms_.a_stab : *forms_.a;
  const ufcx_form& L = stabilised_ ? *forms_.L_stab : *forms_.L;
  a_ = compat::create_form(a, {W_, W_}, coeffs, constants_);
  L_ = compat::create_form(L, {W_}, coeffs, constants_);
  if (bdf2_)
  {
    coeffs["u1"] = u1_;
    a_bdf2_ = compat::create_form(*forms_.a_bdf2, {W_, W_}, coeffs, constants_);
    L_bdf2_ = compat::create_form(*forms_.L_bdf2, {W_}, coeffs, constants_);
  }
}

void PhaseFieldModule::bind_forms()
{
  CoefficientMap coeffs{{"u0", u0_}};
  auto mesh = W_->mesh();
  bind_system_forms();
  auto functional = [&](ufcx_form* f) -> std::shared_ptr<Form>
  { return f ? compat::create_form(*f, {}, coeffs, constants_, mesh) : nullptr; };
  dW_integral_ = functional(forms_.dW_integral);
  auto obs = observable_forms(scene_.domain.dim);
  CoefficientMap phi_only{{"phi", fields_.at("phi")}};
  phi_integral_ = compat::create_form(*obs.phi_integral, {}, phi_only, constants_, mesh);
  energy_ch_ = compat::create_form(*obs.energy_ch, {}, phi_only, constants_, mesh);
  loads_.clear();
  if (forms_.load_a)
  {
    const auto& pf = scene_.phase_field;
    if (forms_.load_v)
      loads_.push_back({UnitLoad::volume, compat::create_form(*forms_.load_v, {W_}, coeffs, constants_),
                        nullptr, nullptr, nullptr, lam_v_, pf.penalty_volume});
    // With surface tension the L2 flow keeps only the volume (3.83)-(3.85): the membrane
    // area is free and the tension (1/Ca) kappa acts instead of the area multiplier.
    const bool area_free = pf.model == Model::helfrich_lagrange && pf.surface_tension;
    // BDF2 steps: the curvature of the area load at the extrapolated state (u0, u1).
    CoefficientMap with_history = coeffs;
    if (bdf2_)
      with_history["u1"] = u1_;
    if (!area_free)
      loads_.push_back({UnitLoad::area,
                        compat::create_form(*forms_.load_a, {W_}, coeffs, constants_),
                        bdf2_ ? compat::create_form(*forms_.load_a_bdf2, {W_}, with_history, constants_)
                              : nullptr,
                        nullptr, nullptr, lam_a_, pf.penalty_area});
    // phi^n is the linearisation point of E_CH: bound to the standalone field, which
    // holds phi^n until the step is complete.
    volume_weights_form_ = compat::create_form(*obs.volume_weights, {V_}, {}, constants_);
    area_weights_form_ = compat::create_form(*obs.area_weights, {V_}, phi_only, constants_);
    volume_weights_ = std::make_unique<la::Vector<T>>(V_->dofmap()->index_map, 1);
    area_weights_ = std::make_unique<la::Vector<T>>(V_->dofmap()->index_map, 1);
    volume_weights_->set(0.0);
    fem::assemble_vector(volume_weights_->mutable_array(), *volume_weights_form_);
    volume_weights_->scatter_rev(std::plus<T>());
  }
}

double PhaseFieldModule::integral(const std::shared_ptr<Form>& f) const
{
  return compat::assemble_scalar(*f);
}

void PhaseFieldModule::compute_mu_from_phi()
{
  // mu^0 = L2 projection of eps Lap phi - W0'(phi)/eps, (3.23)
  CoefficientMap coeffs{{"phi_init", fields_.at("phi")}};
  auto a = compat::create_form(*forms_.a_mu, {V_, V_}, {}, constants_);
  auto L = compat::create_form(*forms_.L_mu, {V_}, coeffs, constants_);
  // Under the periodic constraint: eps Lap phi is a weak derivative (see L2Projection.h).
  PeriodicConstraint periodic(V_, scene_.domain.lower, scene_.domain.upper, scene_.domain.periodic);
  la::petsc::Matrix M = periodic.create_matrix(*a);
  periodic.assemble_matrix(M.mat(), *a, {});
  auto b = periodic.create_vector(), x = periodic.create_vector();
  periodic.assemble_vector(b, *L, a, {});
  // One solve with the mass matrix: conjugate gradients with its diagonal converge in a few
  // dozen iterations whatever the mesh grading, where a factorisation took a third of the
  // start-up of a run.
  LinearSolver mass(comm_, "mu_projection_",
                    {{"ksp_type", "cg"}, {"pc_type", "jacobi"}, {"ksp_rtol", "1e-13"},
                     {"ksp_atol", "1e-300"}, {"ksp_max_it", "1000"}},
                    Symmetry::positive_definite);
  mass.set_operator(M.mat());
  mass.solve(b, x, "the initial mu projection");
  auto& mu = *fields_.at("mu");
  periodic.backsubstitute(x, mu);
  mu.x()->scatter_fwd();
}

void PhaseFieldModule::update_multipliers(double dt)
{
  const auto& pf = scene_.phase_field;
  const double theta = pf.constraint_relaxation;
  switch (pf.model)
  {
  case Model::allen_cahn_volume:
  {
    // (2.27) plus a relaxation of the accumulated drift, as the (1/2tau)(V - V0) of 5.3
    const double V = integral(phi_integral_);
    lam_v_->value[0] = (theta * (V - targets_.volume) / (pf.mobility * dt)
                        - integral(dW_integral_)) / domain_volume_;
    break;
  }
  case Model::helfrich_lagrange:
  case Model::helfrich_penalty:
  case Model::helfrich_hm1:
    // The base solve has no constraint forces; apply_constraint_loads() adds them.
    lam_v_->value[0] = lam_a_->value[0] = 0;
    break;
  default:
    break;
  }
}

double PhaseFieldModule::phi_dot(const la::Vector<T>& weights, const la::Vector<T>& x,
                                 bool minus_phi_n) const
{
  // Owned dofs only (the weights hold the assembled sums there), then over ranks.
  auto w = weights.array();
  auto xs = x.array();
  auto p = fields_.at("phi")->x()->array();
  const std::int32_t owned = V_->dofmap()->index_map->size_local();
  double sum = 0;
  for (std::int32_t d = 0; d < owned; ++d)
    sum += w[d] * (xs[to_mixed_[0][d]] - (minus_phi_n ? p[d] : 0.0));
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return sum;
}

void PhaseFieldModule::assemble_right_hand_sides(std::vector<const la::Vector<T>*>& rhs,
                                                 std::vector<la::Vector<T>*>& solutions)
{
  rhs = {b_.get()};
  solutions = {x_.get()};
  std::vector<UnitLoad*> stale;
  for (auto& load : loads_)
  {
    // The volume load does not depend on the state: with a matrix kept from the last
    // step (stabilised scheme) its solution is still valid.
    if (load.kind == UnitLoad::volume && load.current)
      continue;
    load.current = true;
    stale.push_back(&load);
    rhs.push_back(load.b.get());
    solutions.push_back(load.x.get());
  }
  // The loads' cell loops run beside the right-hand side's when a CPU is spare.
  auto local_loads = std::async(spare_cpu_ ? std::launch::async : std::launch::deferred,
                                [this, &stale]
                                {
                                  for (auto* load : stale)
                                    periodic_->assemble_local(
                                        *load->b, second_order_step_ && load->form_bdf2
                                                      ? *load->form_bdf2
                                                      : *load->form);
                                });
  periodic_->assemble_local(*b_, second_order_step_ ? *L_bdf2_ : *L_, lifting_.get());
  for (const auto& source : sources_)
  {
    // Explicit: added to the step's right-hand side before the ghost exchange.
    periodic_->assemble_local(*source_b_, *source);
    auto b = b_->mutable_array();
    auto extra = source_b_->array();
    for (std::size_t i = 0; i < b.size(); ++i)
      b[i] += extra[i];
  }
  local_loads.get();
  periodic_->finish(*b_, bcs_, 1.0);
  // Unit loads are homogeneous at Dirichlet rows (scale 0): phi^{n+1} keeps its BC value.
  for (auto* load : stale)
    periodic_->finish(*load->b, bcs_, 0.0);
}

void PhaseFieldModule::start_area_linearisation()
{
  // Both read only phi^n (the standalone field, unchanged until scatter_state()).
  auto assemble = [this]
  {
    area_weights_->set(0.0);
    fem::assemble_vector(area_weights_->mutable_array(), *area_weights_form_);
    return fem::assemble_scalar(*energy_ch_);
  };
  local_energy_ch_ = std::async(spare_cpu_ ? std::launch::async : std::launch::deferred, assemble);
}

void PhaseFieldModule::apply_constraint_loads()
{
  // phi^{n+1} = phi_0 + sum_j m_j phi_j. Its volume (3.10) is linear in m, its area
  // (3.11) is linearised about phi^n: A = A(phi^n) + dA[phi_0 - phi^n] + sum_j m_j dA[phi_j].
  const std::size_t K = loads_.size();
  double energy_ch = local_energy_ch_.get();
  area_weights_->scatter_rev(std::plus<T>());
  MPI_Allreduce(MPI_IN_PLACE, &energy_ch, 1, MPI_DOUBLE, MPI_SUM, comm_);
  std::vector<double> vol(K + 1), darea(K + 1);
  for (std::size_t j = 0; j <= K; ++j)
  {
    const auto& x = j == 0 ? *x_ : *loads_[j - 1].x;
    vol[j] = phi_dot(*volume_weights_, x, false);
    darea[j] = phi_dot(*area_weights_, x, j == 0);
  }
  darea[0] += energy_ch;
  // One row per load: multipliers hold g(phi^{n+1}) = target (3.28)-(3.29); penalties are
  // m = p (g(phi^{n+1}) - target) (3.32)/(3.35).
  const bool multipliers = scene_.phase_field.model == Model::helfrich_lagrange;
  std::array<std::array<double, 2>, 2> M{};
  std::array<double, 2> r{};
  for (std::size_t k = 0; k < K; ++k)
  {
    const auto& g = loads_[k].kind == UnitLoad::volume ? vol : darea;
    const double target = loads_[k].kind == UnitLoad::volume ? targets_.volume : targets_.area;
    const double p = loads_[k].penalty;
    for (std::size_t j = 0; j < K; ++j)
      M[k][j] = multipliers ? g[j + 1] : (k == j) - p * g[j + 1];
    r[k] = multipliers ? target - g[0] : p * (g[0] - target);
  }
  std::array<double, 2> m{};
  if (K == 1)
    m[0] = r[0] / M[0][0];
  else
  {
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    m[0] = (r[0] * M[1][1] - M[0][1] * r[1]) / det;
    m[1] = (M[0][0] * r[1] - M[1][0] * r[0]) / det;
  }
  auto x = x_->mutable_array();
  for (std::size_t k = 0; k < K; ++k)
  {
    loads_[k].value->value[0] = m[k];
    auto xk = loads_[k].x->array();
    for (std::size_t i = 0; i < x.size(); ++i)
      x[i] += m[k] * xk[i];
  }
}

void PhaseFieldModule::to_mixed(const std::vector<std::string>& names, std::span<T> mixed) const
{
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    auto f = fields_.at(names[i])->x()->array();
    for (std::size_t d = 0; d < to_mixed_[i].size(); ++d)
      mixed[to_mixed_[i][d]] = f[d];
  }
}

void PhaseFieldModule::from_mixed(std::span<const T> mixed, const std::vector<std::string>& names)
{
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    auto f = fields_.at(names[i])->x()->mutable_array();
    for (std::size_t d = 0; d < to_mixed_[i].size(); ++d)
      f[d] = mixed[to_mixed_[i][d]];
  }
}

void PhaseFieldModule::gather_state() { to_mixed(names_, u0_->x()->mutable_array()); }

void PhaseFieldModule::scatter_state() { from_mixed(x_->array(), names_); }

void PhaseFieldModule::gather_history() { to_mixed(history_names_, u1_->x()->mutable_array()); }

void PhaseFieldModule::keep_history() { from_mixed(u0_->x()->array(), history_names_); }

void PhaseFieldModule::estimate_time_error(double dt)
{
  time_error_ = -1;
  if (!history_.have)
    return;
  // phi(t^{n+1}) - phi* = phi'' dt (dt + dt_prev) / 2 + O(dt^3): scaled by dt / (dt + dt_prev)
  // to backward Euler's local error phi'' dt^2 / 2 (for BDF2 an upper bound).
  const double w = dt / history_.dt_prev;
  auto now = fields_.at("phi")->x()->array();
  auto before = fields_.at("phi_prev")->x()->array();
  auto u = u0_->x()->array();
  const std::int32_t owned = V_->dofmap()->index_map->size_local();
  double largest = 0;
  for (std::int32_t d = 0; d < owned; ++d)
  {
    largest = std::max(largest, std::abs(now[d] - extrapolate(u[to_mixed_[0][d]], before[d], w)));
  }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, comm_);
  time_error_ = largest * dt / (dt + history_.dt_prev);
}

void PhaseFieldModule::set_bdf2_coefficients(double dt)
{
  bdf_.set(dt / history_.dt_prev);
}

StepTimings PhaseFieldModule::step(double dt)
{
  StepTimings t;
  auto t0 = Clock::now();
  if (dt != dt_->value[0])
  {
    dt_->value[0] = dt;
    matrix_current_ = false;
  }
  gather_state();
  second_order_step_ = bdf2_ && history_.have;
  if (second_order_step_)
  {
    set_bdf2_coefficients(dt);
    gather_history();
  }
  update_multipliers(dt);
  if (!interaction_rhs_.empty()) // the part of w that this step's source makes (phi^n, sums now)
    interaction_projection_->project(interaction_sources(), *interaction_of_step_,
                                     "the interaction source (7.11)");

  // Taylor linearisation: the matrix depends on phi^n and is rebuilt every step (the
  // sparsity pattern and MUMPS' symbolic analysis are kept). Stabilised: built once,
  // unless the advection velocity (implicit term) changes every step.
  const bool rebuild = !stabilised_ || !matrix_current_ || flowing_;
  if (rebuild)
  {
    if (!A_) // the sparsity (and MUMPS' analysis) is kept until the next mesh
      A_ = std::make_unique<la::petsc::Matrix>(periodic_->create_matrix(*a_));
    const auto& a = second_order_step_ ? a_bdf2_ : a_; // the same sparsity
    periodic_->assemble_matrix(A_->mat(), *a, bcs_);
    periodic_->lifting(*lifting_, a, bcs_); // -A g, (phi = -1)
  }
  if (rebuild)
    for (auto& load : loads_)
      load.current = false;
  std::vector<const la::Vector<T>*> rhs;
  std::vector<la::Vector<T>*> solutions;
  assemble_right_hand_sides(rhs, solutions);
  t.assemble = seconds_since(t0);
  if (rebuild)
  {
    if (!solver_)
    {
      solver_ = std::make_unique<LinearSolver>(comm_, "phasefield_", scene_.numerics.petsc,
                                               symmetrisable_ && !flowing_ ? Symmetry::symmetric
                                                                           : Symmetry::general);
      reuse_ = scene_.numerics.solver == scene::Numerics::Solver::reuse;
      if (reuse_)
        solver_->reuse_factorisations(1e-10, 30, 8);
    }
    t.factorise = solver_->set_operator(A_->mat());
    factorisations_ += !reuse_; // with reuse: those the solver made (below)
    matrix_current_ = true;
  }
  auto t1 = Clock::now();
  if (!loads_.empty())
    start_area_linearisation();
  solver_->solve(rhs, solutions,
                 std::string("phase field (") + scene::to_string(scene_.phase_field.model) + ")");
  const auto [factorised, iterations] = solver_->take_counts();
  factorisations_ += reuse_ ? factorised : 0;
  krylov_iterations_ += iterations;
  // Slave values of every solution; the unit loads have zero Dirichlet values.
  for (std::size_t i = 0; i < solutions.size(); ++i)
    periodic_->backsubstitute(*solutions[i], i > 0);
  if (!loads_.empty())
    apply_constraint_loads();
  scatter_state();
  if (!history_names_.empty())
  {
    estimate_time_error(dt);
    keep_history(); // phi^n becomes phi^{n-1} of the next step
    history_ = {true, dt};
  }
  if (dE_)
    update_interface_potential(); // the flow's next step reads dE/dphi of this state
  t.solve = seconds_since(t1);
  return t;
}

double PhaseFieldModule::total_energy(double phi_integral, double energy_ch, double helfrich) const
{
  const auto& pf = scene_.phase_field;
  const double Be = scene_.numbers.Be;
  switch (pf.model)
  {
  case Model::allen_cahn:
  case Model::allen_cahn_volume:
  case Model::cahn_hilliard:
    return energy_ch;                                          // (2.22)
  case Model::helfrich_lagrange:                               // (3.25) on the constraint set
    return helfrich + surface_tension(scene_) * energy_ch;     // + (1/Ca) E_CH, (3.78)
  case Model::helfrich_penalty:                                // (3.30)
    return helfrich + pf.penalty_volume / (2 * Be) * std::pow(phi_integral - targets_.volume, 2)
           + pf.penalty_area / (2 * Be) * std::pow(energy_ch - targets_.area, 2)
           + surface_tension(scene_) * energy_ch;
  case Model::helfrich_hm1:                                    // (3.33)
    return helfrich + pf.penalty_area / (2 * Be) * std::pow(energy_ch - targets_.area, 2)
           + surface_tension(scene_) * energy_ch;
  }
  return energy_ch;
}
} // namespace cellphase
