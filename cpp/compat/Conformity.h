// A check that a mesh refined in parallel is conforming across the MPI ranks.
#pragma once
#include "compat/Dolfinx.h"
#include <cstdint>

namespace cellphase::compat
{
/// The number of hanging vertices, summed over the ranks: vertices of one rank that lie
/// at the midpoint of an edge of a cell on the rank boundary of another rank. 0 for a
/// conforming mesh. Collective.
std::int64_t hanging_vertices(Mesh& mesh);
} // namespace cellphase::compat
