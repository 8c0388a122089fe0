// The L2 projection of a linear form onto a finite element space: out = M^-1 b(L) with the
// space's mass matrix M, factorised once per mesh (it is positive definite, so L D L^T).
// The explicit forces on the flow (interface, protrusion, orientation) and the chemical
// potentials that enter other sub-problems as coefficients are made this way.
//
// On a vector space (block size k) the mass matrix of inner(u, w) dx is k copies of the
// scalar one, one per component, with nothing between components. Then only the scalar
// matrix is factorised, and the k components are solved with it as k right-hand sides:
// a factorisation of a k-times smaller matrix with about k^2 times fewer entries.
//
// On a periodic domain the projection is made under the periodic constraint: the loads
// hold weak derivatives (eps Lap phi, the Frank term of P#), which are only right at a
// periodic face with both sides' elements. Unconstrained, the face saw one side, as if it
// were a wall, and a polar-gel cell crossing it changed its speed by up to 15 %.
#pragma once
#include "compat/Dolfinx.h"
#include "compat/Periodic.h"
#include "scene/Scene.h"
#include "solve/LinearSolver.h"
#include <memory>
#include <string>
#include <vector>

namespace cellphase
{
class L2Projection
{
public:
  /// `mass` is the bilinear form of M on V (with its constants); V is periodic along the
  /// domain's periodic axes; `prefix` names the solver.
  L2Projection(const Form& mass, const scene::Domain& domain, MPI_Comm comm,
               const std::string& prefix);
  ~L2Projection();

  /// out = M^-1 (sum of the linear forms); `what` names the projection in an error.
  void project(const std::vector<const Form*>& forms, Function& out, const std::string& what);
  void project(const Form& form, Function& out, const std::string& what)
  {
    project(std::vector<const Form*>{&form}, out, what);
  }

  /// Components solved with one scalar mass matrix (1: the matrix of the whole space).
  int components() const { return components_; }

private:
  std::unique_ptr<PeriodicConstraint> periodic_; ///< plain assembly without periodic axes
  std::unique_ptr<dolfinx::la::petsc::Matrix> mass_;
  std::unique_ptr<LinearSolver> solver_;
  int components_ = 1;
};
} // namespace cellphase
