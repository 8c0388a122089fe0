#include "physics/PhaseFieldModule.h"
#include <chrono>
#include <cmath>

namespace cellphase
{
using namespace dolfinx;
using scene::Model;

namespace
{
double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::shared_ptr<Constant> constant(double v) { return std::make_shared<Constant>(v); }

/// Assemble a bilinear form into a new PETSc matrix, with identity rows for the BCs.
std::unique_ptr<la::petsc::Matrix> assemble_matrix(const Form& a, const BCs& bcs,
                                                   la::petsc::Matrix* reuse)
{
  std::unique_ptr<la::petsc::Matrix> A;
  if (!reuse)
    A = std::make_unique<la::petsc::Matrix>(fem::petsc::create_matrix(a), false);
  Mat m = reuse ? reuse->mat() : A->mat();
  MatZeroEntries(m);
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(m, ADD_VALUES), a, bcs);
  // BC rows and columns are skipped above, so ADD of the diagonal needs no flush.
  fem::set_diagonal<T>(la::petsc::Matrix::set_fn(m, ADD_VALUES), *a.function_spaces()[0], bcs);
  MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY);
  return A;
}

void assemble_rhs(la::Vector<T>& b, const Form& L, const std::shared_ptr<const Form>& a,
                  const BCs& bcs)
{
  b.set(0.0);
  fem::assemble_vector(b.mutable_array(), L);
  fem::apply_lifting<T>(b.mutable_array(), {a}, {bcs}, {}, 1.0);
  b.scatter_rev(std::plus<T>());
  fem::set_bc<T>(b.mutable_array(), bcs);
}
} // namespace

PhaseFieldModule::PhaseFieldModule(const scene::Scene& scene, MPI_Comm comm)
    : scene_(scene), comm_(comm), forms_(model_forms(scene.phase_field.model, scene.domain.dim)),
      names_(scene::model_fields(scene.phase_field.model)),
      stabilised_(scene.numerics.linearisation == scene::Linearisation::stabilised),
      domain_volume_(scene.domain.volume())
{
  const auto& pf = scene.phase_field;
  const auto& nu = scene.numerics;
  dt_ = constant(nu.dt);
  lam_v_ = constant(0.0);
  lam_a_ = constant(0.0);
  constants_ = {{"dt", dt_},
                {"eps", constant(nu.epsilon)},
                {"gamma", constant(pf.mobility)},
                {"Be", constant(scene.numbers.Be)},
                {"H0", constant(pf.spontaneous_curvature)},
                {"S", constant(nu.stabilisation)},
                {"lam_v", lam_v_},
                {"lam_a", lam_a_}};
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

  // V dof -> W dof for each field, matched through the cell-local dof order (the
  // sub-elements of W are V's element).
  to_mixed_.assign(names_.size(), std::vector<std::int32_t>(V_->dofmap()->index_map->size_local()
                                                            + V_->dofmap()->index_map->num_ghosts()));
  const std::int32_t ncells = mesh->topology().index_map(mesh->topology().dim())->size_local()
                              + mesh->topology().index_map(mesh->topology().dim())->num_ghosts();
  for (std::size_t i = 0; i < names_.size(); ++i)
  {
    auto sub = names_.size() > 1 ? W_->sub({int(i)}) : W_;
    for (std::int32_t c = 0; c < ncells; ++c)
    {
      auto vd = V_->dofmap()->cell_dofs(c);
      auto wd = sub->dofmap()->cell_dofs(c);
      for (std::size_t k = 0; k < vd.size(); ++k)
        to_mixed_[i][vd[k]] = wd[k];
    }
  }

  u0_ = std::make_shared<Function>(W_);
  bcs_.clear();
  if (scene_.phi_boundary == scene::PhiBoundary::dirichlet)
  {
    // phi = -1 on the boundary (2.19); the other fields have natural conditions.
    // The value lives in the collapsed space V for a mixed W, in W itself otherwise
    // (their dof numberings differ).
    boundary_value_ = std::make_shared<Function>(names_.size() > 1 ? V_ : W_);
    boundary_value_->x()->set(-1.0);
    if (names_.size() > 1)
      bcs_.push_back(std::make_shared<DirichletBC>(
          boundary_value_, compat::boundary_dofs(*W_, 0, *V_), W_->sub({0})));
    else
      bcs_.push_back(std::make_shared<DirichletBC>(boundary_value_, compat::boundary_dofs(*W_)));
  }

  bind_forms();
  A_.reset();
  matrix_current_ = false;
  solver_ = std::make_unique<LinearSolver>(comm_, "phasefield_", scene_.numerics.petsc);
  b_ = std::make_unique<la::Vector<T>>(W_->dofmap()->index_map, W_->dofmap()->index_map_bs());
  x_ = std::make_unique<la::Vector<T>>(W_->dofmap()->index_map, W_->dofmap()->index_map_bs());
  if (load_v_)
  {
    x_v_ = std::make_unique<la::Vector<T>>(W_->dofmap()->index_map, W_->dofmap()->index_map_bs());
    x_a_ = std::make_unique<la::Vector<T>>(W_->dofmap()->index_map, W_->dofmap()->index_map_bs());
  }

  if (forms_.a_mu && fields.find("mu") == fields.end())
    compute_mu_from_phi();
}

void PhaseFieldModule::bind_forms()
{
  CoefficientMap coeffs{{"u0", u0_}};
  auto mesh = W_->mesh();
  const ufcx_form& a = stabilised_ ? *forms_.a_stab : *forms_.a;
  const ufcx_form& L = stabilised_ ? *forms_.L_stab : *forms_.L;
  a_ = compat::create_form(a, {W_, W_}, coeffs, constants_);
  L_ = compat::create_form(L, {W_}, coeffs, constants_);
  auto functional = [&](ufcx_form* f) -> std::shared_ptr<Form>
  { return f ? compat::create_form(*f, {}, coeffs, constants_, mesh) : nullptr; };
  dW_integral_ = functional(forms_.dW_integral);
  auto obs = observable_forms(scene_.domain.dim);
  CoefficientMap phi_only{{"phi", fields_.at("phi")}};
  phi_integral_ = compat::create_form(*obs.phi_integral, {}, phi_only, constants_, mesh);
  energy_ch_ = compat::create_form(*obs.energy_ch, {}, phi_only, constants_, mesh);
  if (forms_.load_v)
  {
    load_v_ = compat::create_form(*forms_.load_v, {W_}, coeffs, constants_);
    load_a_ = compat::create_form(*forms_.load_a, {W_}, coeffs, constants_);
    delta_ = std::make_shared<Function>(V_);
    delta_integral_ = compat::create_form(*obs.phi_integral, {}, {{"phi", delta_}}, constants_, mesh);
    // phi^n is the linearisation point of E_CH: bound to the standalone field, which
    // holds phi^n until the step is complete.
    delta_area_variation_ = compat::create_form(
        *obs.area_variation, {}, {{"phi", fields_.at("phi")}, {"delta", delta_}}, constants_, mesh);
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
  auto M = assemble_matrix(*a, {}, nullptr);
  la::Vector<T> b(V_->dofmap()->index_map, 1);
  assemble_rhs(b, *L, a, {});
  LinearSolver mass(comm_, "mass_", {});
  mass.set_operator(M->mat());
  mass.solve(b, *fields_.at("mu")->x(), "the initial mu projection");
}

void PhaseFieldModule::update_multipliers(double dt)
{
  const auto& pf = scene_.phase_field;
  const double theta = pf.constraint_relaxation;
  const double g = pf.mobility / scene_.numbers.Be;
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
  case Model::helfrich_penalty:
    lam_v_->value[0] = pf.penalty_volume * (integral(phi_integral_) - targets_.volume); // (3.32)
    lam_a_->value[0] = pf.penalty_area * (integral(energy_ch_) - targets_.area);
    break;
  case Model::helfrich_hm1:
    lam_a_->value[0] = pf.penalty_area * (integral(energy_ch_) - targets_.area); // (3.35)
    break;
  default:
    break;
  }
}

void PhaseFieldModule::extract_phi(const la::Vector<T>& x, Function& phi) const
{
  auto in = x.array();
  auto out = phi.x()->mutable_array();
  for (std::size_t d = 0; d < to_mixed_[0].size(); ++d)
    out[d] = in[to_mixed_[0][d]];
}

void PhaseFieldModule::apply_implicit_multipliers()
{
  // Unit loads are homogeneous at Dirichlet rows (scale 0): phi^{n+1} keeps its BC value.
  for (auto [form, x] : {std::pair{load_v_, x_v_.get()}, std::pair{load_a_, x_a_.get()}})
  {
    b_->set(0.0);
    fem::assemble_vector(b_->mutable_array(), *form);
    b_->scatter_rev(std::plus<T>());
    fem::set_bc<T>(b_->mutable_array(), bcs_, 0.0);
    solver_->solve(*b_, *x, "the multiplier loads of helfrich_lagrange");
  }
  // Volume (3.10) and first-order area (3.11) of phi_0 + lam_v phi_v + lam_a phi_a:
  //   int phi_0 + lam_v int phi_v + lam_a int phi_a = V0
  //   A(phi^n) + dA[phi_0 - phi^n] + lam_v dA[phi_v] + lam_a dA[phi_a] = A0
  auto phi_n = fields_.at("phi");
  std::array<double, 3> vol, darea;
  const std::array<const la::Vector<T>*, 3> xs{x_.get(), x_v_.get(), x_a_.get()};
  for (int k = 0; k < 3; ++k)
  {
    extract_phi(*xs[k], *delta_);
    if (k == 0)
    {
      auto d = delta_->x()->mutable_array();
      auto p = phi_n->x()->array();
      vol[0] = integral(delta_integral_);
      for (std::size_t i = 0; i < d.size(); ++i)
        d[i] -= p[i];
      darea[0] = integral(delta_area_variation_);
    }
    else
    {
      vol[k] = integral(delta_integral_);
      darea[k] = integral(delta_area_variation_);
    }
  }
  const double r1 = targets_.volume - vol[0];
  const double r2 = targets_.area - integral(energy_ch_) - darea[0];
  const double det = vol[1] * darea[2] - vol[2] * darea[1];
  const double lv = (r1 * darea[2] - vol[2] * r2) / det;
  const double la = (vol[1] * r2 - darea[1] * r1) / det;
  lam_v_->value[0] = lv;
  lam_a_->value[0] = la;
  auto x = x_->mutable_array();
  auto xv = x_v_->array(), xa = x_a_->array();
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] += lv * xv[i] + la * xa[i];
}

void PhaseFieldModule::gather_state()
{
  auto u = u0_->x()->mutable_array();
  for (std::size_t i = 0; i < names_.size(); ++i)
  {
    auto f = fields_.at(names_[i])->x()->array();
    for (std::size_t d = 0; d < to_mixed_[i].size(); ++d)
      u[to_mixed_[i][d]] = f[d];
  }
}

void PhaseFieldModule::scatter_state()
{
  auto x = x_->array();
  for (std::size_t i = 0; i < names_.size(); ++i)
  {
    auto f = fields_.at(names_[i])->x()->mutable_array();
    for (std::size_t d = 0; d < to_mixed_[i].size(); ++d)
      f[d] = x[to_mixed_[i][d]];
  }
}

StepTimings PhaseFieldModule::step(double dt)
{
  StepTimings t;
  auto t0 = std::chrono::steady_clock::now();
  if (dt != dt_->value[0])
  {
    dt_->value[0] = dt;
    matrix_current_ = false;
  }
  gather_state();
  update_multipliers(dt);

  // Taylor linearisation: the matrix depends on phi^n and is rebuilt every step (the
  // sparsity pattern and MUMPS' symbolic analysis are kept). Stabilised: built once.
  const bool rebuild = !stabilised_ || !matrix_current_;
  if (rebuild)
  {
    if (A_)
      assemble_matrix(*a_, bcs_, A_.get());
    else
      A_ = assemble_matrix(*a_, bcs_, nullptr);
  }
  assemble_rhs(*b_, *L_, a_, bcs_);
  t.assemble = seconds_since(t0);
  if (rebuild)
  {
    t.factorise = solver_->set_operator(A_->mat());
    matrix_current_ = true;
  }
  auto t1 = std::chrono::steady_clock::now();
  solver_->solve(*b_, *x_, std::string("phase field (") + scene::to_string(scene_.phase_field.model) + ")");
  if (load_v_)
    apply_implicit_multipliers();
  scatter_state();
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
  case Model::helfrich_lagrange:
    return helfrich;                                           // (3.25) on the constraint set
  case Model::helfrich_penalty:                                // (3.30)
    return helfrich + pf.penalty_volume / (2 * Be) * std::pow(phi_integral - targets_.volume, 2)
           + pf.penalty_area / (2 * Be) * std::pow(energy_ch - targets_.area, 2);
  case Model::helfrich_hm1:                                    // (3.33)
    return helfrich + pf.penalty_area / (2 * Be) * std::pow(energy_ch - targets_.area, 2);
  }
  return energy_ch;
}
} // namespace cellphase
