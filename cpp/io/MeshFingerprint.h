// A 64-bit fingerprint of a mesh's geometry and cells on all ranks, so that a remesh that
// rebuilds the same mesh is recognised and the output refers to the mesh already written.
#pragma once
#include "compat/Dolfinx.h"
#include <cstdint>

namespace cellphase
{
/// Equal on every rank; equal for two meshes with the same nodes (bitwise) and cells on
/// every rank, different otherwise (up to a 2^-64 chance).
std::uint64_t mesh_fingerprint(const Mesh& mesh);
} // namespace cellphase
