#include "io/MeshFingerprint.h"
#include "util/Mpi.h"
#include <vector>

namespace cellphase
{
namespace
{
/// FNV-1a over raw bytes.
std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t h)
{
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i)
    h = (h ^ p[i]) * 1099511628211ull;
  return h;
}
constexpr std::uint64_t fnv_offset = 14695981039346656037ull;
} // namespace

std::uint64_t mesh_fingerprint(const Mesh& mesh)
{
  const auto& x = mesh.geometry().x();
  const auto& cells = mesh.geometry().dofmap().array();
  std::uint64_t local = fnv1a(x.data(), x.size() * sizeof(double), fnv_offset);
  local = fnv1a(cells.data(), cells.size() * sizeof(cells[0]), local);
  // Order matters (rank r's part is rank r's): hash the list of the ranks' hashes.
  std::vector<std::uint64_t> all(size_of(mesh.comm()));
  MPI_Allgather(&local, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, mesh.comm());
  return fnv1a(all.data(), all.size() * sizeof(std::uint64_t), fnv_offset);
}
} // namespace cellphase
