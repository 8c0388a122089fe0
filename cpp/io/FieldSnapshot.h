// Fields in a checkpoint, independent of the number of ranks: every owned dof is stored
// with the position of its node, and read back into a space on the same (rebuilt) mesh by
// looking its node up (mesh/PointLookup.h). Lagrange nodes of a conforming mesh are distinct.
#pragma once
#include "compat/Dolfinx.h"
#include "io/CheckpointFile.h"
#include <string>

namespace cellphase
{
/// Gather u's owned values and node positions to rank 0 into data (entries "<key>.x",
/// "<key>.values"); other ranks add nothing.
void save_field(const Function& u, const std::string& key, CheckpointData& data);

/// Fill u (owned and ghost dofs) from the entries of save_field. Throws CheckpointError if
/// a node of u's space is not among the stored ones (the mesh differs).
void restore_field(const CheckpointData& data, const std::string& key, Function& u);

/// Gather a rank-local array of doubles to rank 0 (result empty on other ranks).
std::vector<double> gather_to_root(MPI_Comm comm, const std::vector<double>& local);
} // namespace cellphase
