// Geometry of a domain given as a mesh file (domain.mesh): extent, area, the inside test
// for the initial cells, and which named tag a boundary facet lies on. Facet tags are
// found geometrically (a facet carries the tags of the tagged file facets its midpoint
// lies on), so they hold on every refinement of the base mesh too: bisection puts new
// boundary vertices on the old (straight) boundary facets.
#pragma once
#include "scene/MeshFile.h"
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace cellphase::scene
{
class MeshDomain
{
public:
  /// `path` as resolved (for messages).
  MeshDomain(MeshData data, std::string path);
  ~MeshDomain();

  const MeshData& data() const { return data_; }
  const std::string& path() const { return path_; }
  const std::array<double, 3>& lower() const { return lower_; }
  const std::array<double, 3>& upper() const { return upper_; }
  double area() const { return area_; }
  double longest_edge() const { return longest_edge_; }
  double tolerance() const { return tol_; }
  /// Names of the facet tags, sorted.
  std::vector<std::string> tag_names() const;
  /// Tag number of a name; throws std::out_of_range for an unknown name.
  int tag(const std::string& name) const { return data_.tags.at(name); }

  /// Point (x, y) inside or on the boundary of the mesh.
  bool contains(const double* p) const;
  /// Distance from p to the mesh boundary is below r.
  bool near_boundary(const double* p, double r) const;
  /// The facet midpoint m lies on a file facet with one of the tag numbers; the number
  /// `untagged` stands for boundary facets of the file that carry no tag.
  bool on_tags(const double* m, const std::vector<int>& tags) const;
  static constexpr int untagged = -1;

  /// Boundary edges of the file's mesh: endpoints a, b and the unit normal n into the mesh.
  struct Edge
  {
    std::array<double, 2> a, b, n;
    std::vector<int> tags; ///< tags of the file facets it lies on (empty: untagged)
  };
  const std::vector<Edge>& boundary() const { return boundary_; }
  /// Total length of the boundary edges carrying the tag number.
  double tag_length(int tag) const;
  /// The axis (0, 1) every facet of these tags is perpendicular to, or -1 if there is none.
  int normal_axis(const std::vector<int>& tags) const;

private:
  class Buckets;
  MeshData data_;
  std::string path_;
  std::array<double, 3> lower_{0, 0, 0}, upper_{0, 0, 0};
  double area_ = 0, longest_edge_ = 0, tol_ = 0;
  std::vector<Edge> boundary_;
  std::unique_ptr<Buckets> cell_buckets_, tag_buckets_;
};
} // namespace cellphase::scene
