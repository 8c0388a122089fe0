// Periodic boundary conditions on a box through dolfinx_mpc 0.5: the dofs on the max face
// of each periodic axis are slaves of the matching points on the min face. The same object
// also does plain DOLFINx assembly when no axis is periodic, so a module switches between
// constrained and unconstrained systems by the list of axes alone.
#pragma once
#include "compat/Dolfinx.h"
#include "solve/RecordedAssembly.h"
#include <array>
#include <memory>
#include <vector>

namespace dolfinx_mpc
{
template <typename T>
class MultiPointConstraint;
}

namespace cellphase
{
class PeriodicConstraint
{
public:
  /// V: the root space of the system (scalar, vector, mixed of those, e.g. Taylor-Hood).
  /// Every scalar component of every sub-space is made periodic along `axes` (0, 1, 2 =
  /// x, y, z) of the box [lower, upper]. Dofs of `bcs` stay Dirichlet dofs, not slaves;
  /// pass the same bcs to the assembly. Their current values are also used where the
  /// faces do not match next to a Dirichlet face (a constant part of a slave). The faces
  /// may be refined differently. A periodic axis whose sides the mesh does not reach (a
  /// cell's own mesh inside the domain) constrains nothing. Collective.
  PeriodicConstraint(std::shared_ptr<const Space> V, const std::array<double, 3>& lower,
                     const std::array<double, 3>& upper, const std::vector<int>& axes,
                     const BCs& bcs = {});
  ~PeriodicConstraint();

  bool active() const { return mpc_ != nullptr; }
  /// Global number of constrained (slave) dofs.
  std::int64_t num_slaves() const { return num_slaves_; }

  /// Matrix with the sparsity of a (plus the slave -> master couplings).
  dolfinx::la::petsc::Matrix create_matrix(const Form& a) const;
  /// A <- a, with identity rows/columns for slave and Dirichlet dofs. A from create_matrix.
  void assemble_matrix(Mat A, const Form& a, const BCs& bcs) const;

  /// Vector for right-hand sides and solutions (its ghosts include remote masters).
  dolfinx::la::Vector<T> create_vector() const;
  /// b <- L with lifting of the Dirichlet values of bcs through a, scattered, BC values set.
  void assemble_vector(dolfinx::la::Vector<T>& b, const Form& L, std::shared_ptr<const Form> a,
                       const BCs& bcs) const;
  /// The same with the lifting from lifting(a, bcs), which stays valid while the matrix of
  /// a and the Dirichlet values do not change (a reused factorisation).
  void assemble_vector(dolfinx::la::Vector<T>& b, const Form& L,
                       const dolfinx::la::Vector<T>& lifting, const BCs& bcs) const;
  /// l <- the lifting -A g of the Dirichlet values g of bcs through a, before the ghost
  /// accumulation (for the overload above); l from create_vector.
  void lifting(dolfinx::la::Vector<T>& l, std::shared_ptr<const Form> a, const BCs& bcs) const;

  /// After a solve into x (from create_vector): slave values from their masters, then
  /// copied into u (a function on V).
  void backsubstitute(dolfinx::la::Vector<T>& x, Function& u) const;
  /// The same without the copy: x then holds the whole solution in V's numbering (prefix).
  /// `homogeneous`: x solves a load with zero Dirichlet values (no constant slave parts).
  void backsubstitute(dolfinx::la::Vector<T>& x, bool homogeneous = false) const;
  /// The two halves of assemble_vector, for vectors assembled on two threads:
  /// b <- L (+ lifting) on owned and ghost entries, no MPI, so any thread may call it; then,
  /// on the thread that calls MPI, the ghost accumulation and the Dirichlet values of bcs
  /// times bc_scale (1 for a right-hand side, 0 for a unit load).
  void assemble_local(dolfinx::la::Vector<T>& b, const Form& L,
                      const dolfinx::la::Vector<T>* lifting = nullptr) const;
  void finish(dolfinx::la::Vector<T>& b, const BCs& bcs, double bc_scale) const;
  /// b += L on owned and ghost entries (no ghost accumulation, no BC values): several
  /// loads summed into one right-hand side before finish().
  void add_load(dolfinx::la::Vector<T>& b, const Form& L) const;

private:
  /// b += -A g (the Dirichlet values of bcs and the constant slave parts through a).
  void add_lifting(dolfinx::la::Vector<T>& b, std::shared_ptr<const Form> a, const BCs& bcs) const;

  std::shared_ptr<const Space> V_;
  std::shared_ptr<dolfinx_mpc::MultiPointConstraint<T>> mpc_;
  /// Where each matrix' element entries go (assemble_matrix is const for its callers).
  std::unique_ptr<RecordedAssembly> recorded_ = std::make_unique<RecordedAssembly>();
  /// Slaves with Dirichlet masters: u_s = sum c u_m + constant (local slave, constant), and
  /// the constants as a Dirichlet condition on those slaves for the lifting.
  std::vector<std::pair<std::int32_t, T>> constants_;
  std::shared_ptr<const DirichletBC> constants_lift_;
  std::int64_t num_slaves_ = 0;
};
} // namespace cellphase
