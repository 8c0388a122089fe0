#include "physics/FlowModule.h"
#include "solve/Assemble.h"
#include "util/Clock.h"
#include <dolfinx/common/log.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cellphase
{
using namespace dolfinx;

namespace
{
std::shared_ptr<Constant> constant(double v) { return std::make_shared<Constant>(v); }

std::shared_ptr<Constant> vector_constant(const std::array<double, 3>& v, int dim)
{
  return std::make_shared<Constant>(std::span<const T>(v.data(), std::size_t(dim)));
}

int axis_of(Side s) { return int(s) / 2; }
bool is_upper(Side s) { return int(s) % 2 == 1; }

bool same(const std::vector<T>& remembered, const Function& f)
{
  auto now = f.x()->array();
  return std::equal(now.begin(), now.end(), remembered.begin(), remembered.end());
}

std::vector<T> copy_of(const Function& f)
{
  auto a = f.x()->array();
  return std::vector<T>(a.begin(), a.end());
}
} // namespace

FlowModule::FlowModule(const FlowParameters& parameters, MPI_Comm comm, FlowForms forms)
    : params_(parameters), comm_(comm), forms_(forms)
{
  const auto& p = params_;
  dt_ = constant(1.0);
  constants_ = {{"dt", dt_},
                {"Re", constant(p.Re)},
                {"convection", constant(p.convection ? 1.0 : 0.0)},
                {"rho0", constant(p.density[0])},
                {"rho1", constant(p.density[1])},
                {"eta0", constant(p.viscosity[0])},
                {"eta1", constant(p.viscosity[1])},
                {"mobility", constant(p.mobility)},
                {"degenerate", constant(p.degenerate_mobility ? 1.0 : 0.0)},
                {"capillary", constant(p.capillary)},
                {"one", constant(1.0)}};
  bdf_.add_to(constants_);
  const Inextensibility& in = p.inextensibility;
  if (in.enabled)
  {
    if (!(in.epsilon > 0) || !(in.xi > 0))
      throw std::invalid_argument("flow: inextensibility needs eps > 0 and xi > 0");
    constants_["eps"] = constant(in.epsilon);
    constants_["xi"] = constant(in.xi);
    constants_["xi2"] = constant(in.xi2);
    area_source_ = constant(0.0);
    constants_["area_source"] = area_source_;
  }
}

std::int64_t FlowModule::num_dofs() const { return compat::num_global_dofs(*W_); }

void FlowModule::attach(std::shared_ptr<const Mesh> mesh, std::shared_ptr<const Function> phi,
                        std::shared_ptr<const Function> mu,
                        std::shared_ptr<const Function> velocity, MembraneFields membrane,
                        PreviousFlowState previous)
{
  for (const auto& f : {phi, mu, velocity, membrane.phi_cells, membrane.concentration,
                        membrane.viscosity, previous.velocity, previous.phi, previous.mu})
    if (f && f->function_space()->mesh() != mesh)
      throw std::invalid_argument("flow: phi, mu and the velocity must live on the flow's mesh"
                                  " (transfer them after a remesh)");
  mesh_ = mesh;
  const int dim = mesh->topology().dim();
  const bool inextensible = params_.inextensibility.enabled;
  if (!forms_.a)
    forms_ = flow_forms(dim, inextensible);
  if (inextensible != forms_.has_multiplier)
    throw std::invalid_argument("flow: the forms do not match the inextensibility setting");
  constants_["gravity"] = vector_constant(params_.gravity, dim);
  constants_["force"] = vector_constant(params_.force, dim);

  W_ = compat::create_space(forms_.space, "v_0", mesh);
  Vv_ = compat::collapse(*W_, {0});
  Q_ = compat::collapse(*W_, {1});
  // Defaults for a flow without a phase field: all surrounding fluid.
  if (!phi || !mu)
  {
    auto V = compat::create_space(forms_.space, "phi", mesh);
    if (!phi)
    {
      auto f = std::make_shared<Function>(V);
      f->x()->set(-1.0);
      phi = f;
    }
    if (!mu)
    {
      auto f = std::make_shared<Function>(V);
      f->x()->set(0.0);
      mu = f;
    }
  }
  phi_ = phi;
  mu_ = mu;
  viscosity_ = membrane.viscosity;
  // Second order: the forms read phi*, mu*; phi^{n-1}, mu^{n-1} are kept as given (moved
  // from the last mesh, from a checkpoint) or start as phi^n, mu^n (no history yet).
  phi_in_ = phi;
  mu_in_ = mu;
  phi_cells_in_ = nullptr;
  phi_star_ = mu_star_ = phi_prev_ = mu_prev_ = velocity_prev_ = nullptr;
  if (params_.second_order)
  {
    auto copy_or = [](std::shared_ptr<const Function> given, std::shared_ptr<const Function> f)
    {
      auto c = std::make_shared<Function>(std::const_pointer_cast<Space>(f->function_space()));
      c->x()->set(0.0);
      c->interpolate(given ? *given : *f);
      return c;
    };
    if (params_.extrapolate_phase)
    {
      phi_star_ = copy_or(nullptr, phi);
      phi_prev_ = copy_or(previous.phi, phi);
      phi_prev_->name = "flow_phi_prev";
      phi_in_ = phi_star_;
    }
    if (params_.extrapolate_phase && params_.extrapolate_potential)
    {
      mu_star_ = copy_or(nullptr, mu);
      mu_prev_ = copy_or(previous.mu, mu);
      mu_prev_->name = "flow_potential_prev";
      mu_in_ = mu_star_;
    }
  }
  if (inextensible)
  {
    Lambda_ = compat::collapse(*W_, {2});
    phi_cells_ = membrane.phi_cells ? membrane.phi_cells : phi;
    // One cell: phi_cells is phi, extrapolated with it (several: phi_cells^n).
    phi_cells_in_ = phi_cells_ == phi ? phi_in_ : phi_cells_;
    if (!membrane.concentration)
    {
      auto one = std::make_shared<Function>(compat::create_space(forms_.space, "phi", mesh));
      one->x()->set(1.0);
      membrane.concentration = one;
    }
    concentration_ = membrane.concentration;
    multiplier_ = std::make_shared<Function>(Lambda_.space);
    multiplier_->name = "lambda";
    multiplier_->x()->set(0.0);
  }
  velocity_ = std::make_shared<Function>(Vv_.space);
  velocity_->name = "v";
  velocity_->x()->set(0.0);
  if (velocity)
    velocity_->interpolate(*velocity); // same element and mesh: a copy in our dof order
  if (params_.second_order)
  {
    velocity_prev_ = std::make_shared<Function>(Vv_.space);
    velocity_prev_->name = "flow_v_prev";
    velocity_prev_->x()->set(0.0);
    velocity_prev_->interpolate(previous.velocity ? *previous.velocity : *velocity_);
  }
  pressure_ = std::make_shared<Function>(Q_.space);
  pressure_->name = "p";
  pressure_->x()->set(0.0);
  membrane_force_ = std::make_shared<Function>(Vv_.space);
  membrane_force_->x()->set(0.0);

  build_bcs();
  bind_forms();
  // The BC dofs (walls, the pinned pressure) stay Dirichlet dofs, never slaves.
  const auto box = compat::bounding_box(*mesh_);
  periodic_ = std::make_unique<PeriodicConstraint>(W_, box[0], box[1], params_.periodic, bcs_);
  A_ = std::make_unique<la::petsc::Matrix>(periodic_->create_matrix(*a_));
  b_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  x_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  lifting_ = std::make_unique<la::Vector<T>>(periodic_->create_vector());
  // Without the transport terms (v^n.grad) v and (J.grad) v the matrix of forms/flow.py
  // (and of flow_inextensible.py) is symmetric: L D L^T instead of LU.
  const bool symmetric = params_.Re == 0 || !params_.convection;
  solver_ = std::make_unique<LinearSolver>(comm_, "flow_", params_.petsc,
                                           symmetric ? Symmetry::symmetric : Symmetry::general);
  if (params_.reuse_factorisations)
    solver_->reuse_factorisations(1e-10, 30, 8);
  factorised_ = false;
}

void FlowModule::build_bcs()
{
  const int dim = mesh_->topology().dim();
  const auto box = compat::bounding_box(*mesh_);
  const std::array<double, 3> lo = box[0], hi = box[1];
  double extent = 0;
  for (int d = 0; d < dim; ++d)
    extent = std::max(extent, hi[d] - lo[d]);
  const double tol = 1e-8 * extent;

  bc_values_.clear();
  bcs_.clear();
  std::vector<bool> closed(2 * dim, false);
  // Free-slip first, then no-slip, then moving/prescribed: at shared dofs the last BC wins.
  auto rank = [](WallKind k)
  { return k == WallKind::free_slip ? 0 : k == WallKind::no_slip ? 1 : 2; };
  std::vector<Wall> walls = params_.walls;
  std::stable_sort(walls.begin(), walls.end(),
                   [&](const Wall& a, const Wall& b) { return rank(a.kind) < rank(b.kind); });
  // A periodic side closes the box too: what leaves through it comes back in.
  for (int a : params_.periodic)
    closed.at(2 * a) = closed.at(2 * a + 1) = true;
  for (const Wall& wall : walls)
  {
    const bool tagged = bool(wall.facets);
    const int axis = tagged ? wall.normal_axis : axis_of(wall.side);
    std::vector<std::int32_t> facets;
    if (tagged)
      facets = wall.facets(*mesh_);
    else
    {
      if (axis >= dim)
        throw std::invalid_argument("flow: front/back walls need a 3D mesh");
      if (std::count(params_.periodic.begin(), params_.periodic.end(), axis))
        throw std::invalid_argument("flow: a wall on a side of a periodic axis");
      closed[int(wall.side)] = true;
      const double plane = is_upper(wall.side) ? hi[axis] : lo[axis];
      facets = compat::boundary_facets(
          *mesh_, [=](double x, double y, double z)
          { return std::abs(std::array<double, 3>{x, y, z}[axis] - plane) < tol; });
    }

    if (wall.kind == WallKind::free_slip)
    {
      if (axis < 0)
        throw std::invalid_argument("flow: free slip on a wall that is not perpendicular to an axis");
      // Only the normal component is fixed (v.n = 0); the tangential stress vanishes
      // naturally.
      auto component = compat::collapse(*W_, {0, axis});
      auto zero = std::make_shared<Function>(component.space);
      zero->x()->set(0.0);
      bc_values_.push_back(zero);
      bcs_.push_back(std::make_shared<DirichletBC>(zero, compat::facet_dofs(component, facets),
                                                   component.sub));
      continue;
    }
    auto g = std::make_shared<Function>(Vv_.space);
    if (wall.kind == WallKind::no_slip)
      g->x()->set(0.0);
    else if (wall.kind == WallKind::moving)
    {
      auto u = wall.velocity;
      if (axis >= 0)
        u[axis] = 0; // the wall moves in its plane
      compat::interpolate_vector(*g, [u](double, double, double) { return u; });
    }
    else
    {
      if (!wall.profile)
        throw std::invalid_argument("flow: a prescribed wall needs a velocity profile");
      compat::interpolate_vector(*g, wall.profile);
    }
    bc_values_.push_back(g);
    bcs_.push_back(std::make_shared<DirichletBC>(g, compat::facet_dofs(Vv_, facets), Vv_.sub));
  }

  // With v.n prescribed on every side the pressure is determined up to a constant only.
  // MUMPS could factorise the singular matrix with null-pivot detection (ICNTL(24)) and a
  // PETSc null space, but that depends on a pivot threshold; pinning one pressure dof makes
  // the matrix regular. This is exact: with v.n = 0 (or zero net flux) on the boundary the
  // dropped continuity row is the sum of the others. The mean is removed after the solve.
  // Periodic axes: the pinned dof is at the lower corner, on the min faces, which hold
  // the masters; the constraint keeps Dirichlet dofs out of the slaves anyway.
  // Tagged walls: the scene knows whether they close the boundary, and names a vertex.
  pinned_ = params_.tagged_walls ? params_.pressure_pin.has_value()
                                 : std::all_of(closed.begin(), closed.end(), [](bool c) { return c; });
  if (pinned_)
  {
    const std::array<double, 3> pin = params_.tagged_walls ? *params_.pressure_pin : lo;
    auto corner = compat::dofs_at(Q_, [&](double x, double y, double z)
                                  {
                                    const std::array<double, 3> p{x, y, z};
                                    for (int d = 0; d < dim; ++d)
                                      if (std::abs(p[d] - pin[d]) > tol)
                                        return false;
                                    return true;
                                  });
    int found = corner[0].empty() ? 0 : 1;
    MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPI_INT, MPI_MAX, comm_);
    if (!found)
      throw std::runtime_error("flow: no pressure node at the pinned point (the lower corner of "
                               "the box, or the mesh vertex chosen for a closed mesh domain)");
    auto zero = std::make_shared<Function>(Q_.space);
    zero->x()->set(0.0);
    bc_values_.push_back(zero);
    bcs_.push_back(std::make_shared<DirichletBC>(zero, std::move(corner), Q_.sub));
  }
}

void FlowModule::bind_forms()
{
  // The system reads phi_in_, mu_in_ (phi*, mu* at second order); the observables the
  // fields themselves.
  CoefficientMap system{{"v0", velocity_},
                        {"phi", phi_in_},
                        {"mu", mu_in_},
                        {"f_membrane", membrane_force_},
                        {"p_h", pressure_}};
  CoefficientMap observed = system;
  observed["phi"] = phi_;
  observed["mu"] = mu_;
  if (velocity_prev_)
    system["v1"] = velocity_prev_;
  if (viscosity_)
    system["eta_cells"] = observed["eta_cells"] = viscosity_;
  if (multiplier_)
  {
    system["phi_cells"] = phi_cells_in_;
    observed["phi_cells"] = phi_cells_;
    system["conc"] = observed["conc"] = concentration_;
    system["lam_h"] = observed["lam_h"] = multiplier_;
  }
  // Stokes (Re = 0) skips the inertial terms instead of multiplying them by 0.
  const bool stokes = params_.Re == 0 && forms_.a_stokes;
  // With the cells' own viscosities the viscous term takes eta_cells (7.12).
  ufcx_form* a = viscosity_ ? (stokes ? forms_.a_stokes_cells : forms_.a_cells)
                            : (stokes ? forms_.a_stokes : forms_.a);
  a_ = compat::create_form(*a, {W_, W_}, system, constants_);
  L_ = compat::create_form(*(stokes ? forms_.L_stokes : forms_.L), {W_}, system, constants_);
  a_bdf2_ = L_bdf2_ = nullptr;
  if (params_.second_order && !stokes)
  {
    if (!forms_.a_bdf2 || !forms_.L_bdf2 || viscosity_)
      throw std::logic_error("flow: no second-order forms for this flow");
    a_bdf2_ = compat::create_form(*forms_.a_bdf2, {W_, W_}, system, constants_);
    L_bdf2_ = compat::create_form(*forms_.L_bdf2, {W_}, system, constants_);
  }
  auto functional = [&](ufcx_form* f) -> std::shared_ptr<Form>
  { return f ? compat::create_form(*f, {}, observed, constants_, mesh_) : nullptr; };
  kinetic_ = functional(forms_.kinetic_energy);
  divergence_ = functional(forms_.divergence_sq);
  phase_weight_ = functional(forms_.phase_weight);
  pressure_integral_ = functional(forms_.pressure_integral);
  phase_velocity_.clear();
  for (int d = 0; d < mesh_->topology().dim(); ++d)
    phase_velocity_.push_back(functional(forms_.phase_velocity[d]));
  domain_volume_ = compat::assemble_scalar(*functional(forms_.domain_volume));
  membrane_delta_ = functional(forms_.membrane_delta);
  energy_ch_ = functional(forms_.energy_ch);
  lambda_dissipation_ = functional(forms_.lambda_dissipation);
  lambda_membrane_ = functional(forms_.lambda_membrane);
}

bool FlowModule::matrix_outdated(double dt) const
{
  // Decided together: a rank whose part of phi changed makes all ranks refactorise.
  int outdated = local_matrix_outdated(dt) ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &outdated, 1, MPI_INT, MPI_MAX, comm_);
  return outdated != 0;
}

bool FlowModule::local_matrix_outdated(double dt) const
{
  if (!factorised_)
    return true;
  // Which inputs enter the matrix of forms/flow.py for these parameters.
  const auto& p = params_;
  const bool inertia = p.Re != 0;
  const bool transport = inertia && p.convection;
  const bool variable_density = p.density[0] != p.density[1];
  const bool variable_viscosity = p.viscosity[0] != p.viscosity[1];
  if (inertia && dt != factorised_dt_)
    return true;
  // BDF2's c0 and v* depend on the step ratio and v^{n-1}
  if (inertia && (second_order_step_ != factorised_second_order_
                  || (second_order_step_ && bdf_.w() != factorised_w_)))
    return true;
  if ((variable_viscosity || (inertia && variable_density)) && !same(factorised_phi_, *phi_in_))
    return true;
  if (transport && variable_density && p.mobility != 0 && !same(factorised_mu_, *mu_in_))
    return true;
  // delta_phi P_phi and phi^2 of (3.67)-(3.68) move with the membrane
  if (phi_cells_in_ && !same(factorised_phi_cells_, *phi_cells_in_))
    return true;
  if (viscosity_ && !same(factorised_eta_, *viscosity_))
    return true;
  if (transport && second_order_step_ && !same(factorised_v_prev_, *velocity_prev_))
    return true;
  return transport && !same(factorised_v_, *velocity_);
}

void FlowModule::remember_matrix_inputs(double dt)
{
  factorised_ = true;
  factorised_dt_ = dt;
  factorised_w_ = bdf_.w();
  factorised_second_order_ = second_order_step_;
  factorised_phi_ = copy_of(*phi_in_);
  factorised_mu_ = copy_of(*mu_in_);
  factorised_v_ = copy_of(*velocity_);
  if (velocity_prev_)
    factorised_v_prev_ = copy_of(*velocity_prev_);
  if (phi_cells_in_)
    factorised_phi_cells_ = copy_of(*phi_cells_in_);
  if (viscosity_)
    factorised_eta_ = copy_of(*viscosity_);
}

double FlowModule::area_source(double dt) const
{
  if (!params_.inextensibility.global_area)
    return 0;
  if (!(area_target_ > 0))
    throw std::logic_error("flow: the global area constraint needs set_area_target");
  // E_CH = 2 sqrt2/3 |Gamma| (3.11); the r = 1 row of (3.68) sets d|Gamma|/dt =
  // int delta P : grad v = area_source int delta_phi.
  const double missing = 3 / (2 * std::sqrt(2.0)) * (area_target_ - compat::assemble_scalar(*energy_ch_));
  return missing / (dt * compat::assemble_scalar(*membrane_delta_));
}

FlowTimings FlowModule::step(double dt)
{
  FlowTimings t;
  auto t0 = Clock::now();
  dt_->value[0] = dt;
  if (multiplier_)
    area_source_->value[0] = area_source(dt);
  second_order_step_ = prepare_second_order(dt);
  // Stokes has no d_t v: its forms serve both schemes
  const bool bdf2_forms = second_order_step_ && a_bdf2_;
  const auto& a = bdf2_forms ? a_bdf2_ : a_;
  t.factorised = matrix_outdated(dt);
  if (t.factorised)
  {
    periodic_->assemble_matrix(A_->mat(), *a, bcs_);
    // The wall values do not change on a mesh, so neither does -A g while A stays.
    periodic_->lifting(*lifting_, a, bcs_);
  }
  periodic_->assemble_vector(*b_, bdf2_forms ? *L_bdf2_ : *L_, *lifting_, bcs_);
  keep_previous(dt);
  t.assemble = seconds_since(t0);
  if (t.factorised)
  {
    t.factorise = solver_->set_operator(A_->mat());
    factorisations_ += !params_.reuse_factorisations; // with reuse: those made (below)
    remember_matrix_inputs(dt);
    LOG(INFO) << "flow: factorisation " << factorisations_ << " (" << t.factorise << " s)";
  }
  auto t1 = Clock::now();
  solver_->solve(*b_, *x_, "the flow");
  const auto [factorised, iterations] = solver_->take_counts();
  factorisations_ += params_.reuse_factorisations ? factorised : 0;
  krylov_iterations_ += iterations;
  periodic_->backsubstitute(*x_); // slave values from their masters
  store_solution();
  t.solve = seconds_since(t1);
  return t;
}

bool FlowModule::prepare_second_order(double dt)
{
  if (!params_.second_order)
    return false;
  // Variable-step BDF2, w = dt_n / dt_{n-1} (forms/cellphase_ufl.py, bdf2_constants); the
  // first step (no history) is backward Euler driven by phi^n, mu^n.
  const bool bdf2 = history_.have;
  const double w = bdf2 ? dt / history_.dt_prev : 0.0;
  bdf_.set(w);
  // phi*, mu* node by node (phi and mu share the phase field's space)
  if (phi_star_)
    extrapolate(phi_->x()->array(), phi_prev_->x()->array(), w, phi_star_->x()->mutable_array());
  if (mu_star_)
    extrapolate(mu_->x()->array(), mu_prev_->x()->array(), w, mu_star_->x()->mutable_array());
  return bdf2;
}

void FlowModule::keep_previous(double dt)
{
  if (!params_.second_order)
    return;
  // After the assembly, before the solve overwrites v^n.
  auto keep = [](const Function& now, Function& before)
  {
    auto n = now.x()->array();
    std::copy(n.begin(), n.end(), before.x()->mutable_array().begin());
  };
  if (phi_prev_)
    keep(*phi_, *phi_prev_);
  if (mu_prev_)
    keep(*mu_, *mu_prev_);
  keep(*velocity_, *velocity_prev_);
  history_ = {true, dt};
}

void FlowModule::store_solution()
{
  auto x = x_->array();
  auto v = velocity_->x()->mutable_array();
  auto p = pressure_->x()->mutable_array();
  if (v.size() != Vv_.to_parent.size() || p.size() != Q_.to_parent.size())
    throw std::logic_error("flow: collapsed dof maps do not match the velocity/pressure");
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = x[Vv_.to_parent[i]];
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = x[Q_.to_parent[i]];
  if (multiplier_)
  {
    auto l = multiplier_->x()->mutable_array();
    for (std::size_t i = 0; i < l.size(); ++i)
      l[i] = x[Lambda_.to_parent[i]];
  }
  if (pinned_)
  {
    // Zero mean instead of the arbitrary value at the pinned node.
    const double mean = compat::assemble_scalar(*pressure_integral_) / domain_volume_;
    for (auto& pi : p)
      pi -= mean;
  }
}

FlowObservables FlowModule::observables() const
{
  FlowObservables o;
  o.kinetic_energy = compat::assemble_scalar(*kinetic_);
  o.divergence_l2 = std::sqrt(compat::assemble_scalar(*divergence_));
  const double weight = compat::assemble_scalar(*phase_weight_);
  // No cell (phi~ = 0 everywhere): the mean velocity is undefined, report 0.
  if (weight > 1e-12 * domain_volume_)
    for (std::size_t d = 0; d < phase_velocity_.size(); ++d)
      o.cell_velocity[d] = compat::assemble_scalar(*phase_velocity_[d]) / weight;
  if (multiplier_)
  {
    const double length = compat::assemble_scalar(*membrane_delta_);
    if (length > 0)
      o.tension_mean = compat::assemble_scalar(*lambda_membrane_) / length;
    o.lambda_dissipation = compat::assemble_scalar(*lambda_dissipation_);
  }
  return o;
}
} // namespace cellphase
