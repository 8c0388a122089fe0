// A 2D triangle mesh with named facet tags, read from an XDMF file (the layout written by
// python/msh_to_xdmf.py: a grid "mesh" of triangles and a grid "facet_tags" of lines with
// their tag numbers and one <Information Name="NAME" Value="NUMBER"/> per tag). Plain C++
// (pugixml), so that `cellphase check` validates mesh domains without DOLFINx.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cellphase::scene
{
struct MeshData
{
  std::vector<double> points;        ///< 3 coordinates per node (z = 0 in 2D)
  std::vector<std::int64_t> cells;   ///< 3 node numbers per triangle
  std::vector<std::int64_t> facets;  ///< 2 node numbers per tagged facet
  std::vector<int> facet_tags;       ///< tag number of each tagged facet
  std::map<std::string, int> tags;   ///< tag name -> number
  std::size_t num_nodes() const { return points.size() / 3; }
  std::size_t num_cells() const { return cells.size() / 3; }
};

/// Reads the file; throws std::runtime_error with a message that says what is wrong
/// (missing file, not XDMF, no triangles, a node number out of range, ...).
MeshData read_mesh_file(const std::string& path);
} // namespace cellphase::scene
