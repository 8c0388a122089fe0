#include "physics/ConcentrationModule.h"
#include "util/Clock.h"
#include <stdexcept>

namespace cellphase
{
ConcentrationModule::ConcentrationModule(double diffusion, std::vector<int> periodic,
                                         MPI_Comm comm)
    : diffusion_(diffusion), periodic_(std::move(periodic)), comm_(comm)
{
  dt_ = std::make_shared<Constant>(1.0);
  constants_ = {{"dt", dt_},
                {"diffusion", std::make_shared<Constant>(diffusion_)}};
}

void ConcentrationModule::attach(std::shared_ptr<const Function> phi_cells,
                                 std::shared_ptr<const Function> initial)
{
  auto mesh = phi_cells->function_space()->mesh();
  if (!forms_.a)
    forms_ = concentration_forms(mesh->topology().dim());
  auto V = compat::create_space(forms_.space, "c", mesh);
  phi_cells_ = phi_cells;
  c_ = std::make_shared<Function>(V);
  c_->name = "c";
  c_->x()->set(1.0);
  if (initial)
    c_->interpolate(*initial); // same element and mesh: a copy in this dof order
  c_old_ = std::make_shared<Function>(V);
  a_.reset();
  L_.reset();
}

void ConcentrationModule::set_velocity(std::shared_ptr<const Function> velocity)
{
  auto V = c_->function_space();
  if (velocity->function_space()->mesh() != V->mesh())
    throw std::invalid_argument("concentration: the velocity must live on c's mesh");
  CoefficientMap coeffs{{"c0", c_old_}, {"phi", phi_cells_}, {"v", velocity}};
  a_ = compat::create_form(*forms_.a, {V, V}, coeffs, constants_);
  L_ = compat::create_form(*forms_.L, {V}, coeffs, constants_);
  const auto box = compat::bounding_box(*V->mesh());
  constraint_ = std::make_unique<PeriodicConstraint>(V, box[0], box[1], periodic_);
  A_ = std::make_unique<dolfinx::la::petsc::Matrix>(constraint_->create_matrix(*a_));
  b_ = std::make_unique<dolfinx::la::Vector<T>>(constraint_->create_vector());
  x_ = std::make_unique<dolfinx::la::Vector<T>>(constraint_->create_vector());
  solver_ = std::make_unique<LinearSolver>(comm_, "concentration_",
                                           std::map<std::string, std::string>{});
}

double ConcentrationModule::step(double dt)
{
  if (!a_)
    throw std::logic_error("concentration: step before set_velocity");
  auto t0 = Clock::now();
  dt_->value[0] = dt;
  auto from = c_->x()->array();
  std::copy(from.begin(), from.end(), c_old_->x()->mutable_array().begin());
  // The matrix holds v^{n+1} and phi^{n+1}: new every step.
  constraint_->assemble_matrix(A_->mat(), *a_, {});
  constraint_->assemble_vector(*b_, *L_, a_, {});
  solver_->set_operator(A_->mat());
  solver_->solve(*b_, *x_, "the membrane concentration (3.70)");
  constraint_->backsubstitute(*x_, *c_);
  return seconds_since(t0);
}
} // namespace cellphase
