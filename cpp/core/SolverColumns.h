// The observables columns of a sub-problem whose solver reuses factorisations
// (numerics.solver: reuse): <prefix>_factorisations, the factorisations made so far, and
// <prefix>_krylov_iterations, the GMRES iterations since the last row.
#pragma once
#include "core/SubProblem.h"
#include <string>

namespace cellphase
{
class SolverColumns
{
public:
  explicit SolverColumns(std::string prefix) : prefix_(std::move(prefix)) {}
  /// Append the two columns for the totals `factorisations`, `iterations` of the solver.
  void add(Observation& row, int factorisations, int iterations)
  {
    row.extra.push_back({prefix_ + "_factorisations", double(factorisations)});
    row.extra.push_back({prefix_ + "_krylov_iterations", double(iterations - last_iterations_)});
    last_iterations_ = iterations;
  }

private:
  std::string prefix_;
  int last_iterations_ = 0;
};
} // namespace cellphase
