// Meshes refined around the zero level set of phi, always rebuilt from the same base mesh
// so that old and new meshes share their partition (point evaluation stays rank-local).
#pragma once
#include "compat/Dolfinx.h"
#include "scene/Scene.h"

namespace cellphase
{
class AdaptiveMesh
{
public:
  AdaptiveMesh(const scene::Scene& scene, MPI_Comm comm);
  /// The same refinement of another base mesh (a cell's patch of the scene's base mesh).
  AdaptiveMesh(const scene::Scene& scene, std::shared_ptr<Mesh> base);

  /// The base mesh refined `levels()` times wherever |phi| < threshold somewhere in a cell
  /// (with refine_inside wherever phi > -threshold, up to inside_coarser_by levels fewer).
  /// Periodic faces are refined alike. Records which cells it refined (see history()).
  std::shared_ptr<Mesh> build(const PointEvaluator& phi);
  /// The mesh of an earlier build() again, from its history (all ranks' centroids):
  /// the same cells whatever the number of ranks. Throws std::runtime_error if the
  /// history does not fit this base mesh.
  std::shared_ptr<Mesh> replay(const std::vector<std::vector<double>>& history);
  /// Centroids (rows of 3) of the local cells refined at each level by the last build.
  const std::vector<std::vector<double>>& history() const { return history_; }
  int levels() const { return levels_; }
  std::shared_ptr<Mesh> base() const { return base_; }

private:
  std::vector<std::int32_t> mark(const Mesh& mesh, const PointEvaluator& phi, double h,
                                 bool inside) const;
  /// mesh refined at `marked` and at the cells added to `marked` so that the refined
  /// periodic faces match (mesh/PeriodicFaces.h). Collective.
  std::shared_ptr<Mesh> refine_matching_faces(Mesh& mesh, std::vector<std::int32_t>& marked) const;

  std::shared_ptr<Mesh> base_;
  scene::Domain domain_; ///< its periodic axes and box, for refine_matching_faces
  int levels_;
  double h_base_;
  double threshold_;
  double band_; ///< width of the band |phi| < threshold
  bool inside_; ///< also refine where phi > -threshold (numerics.mesh.refine_inside)
  int inside_levels_; ///< levels refined inside: levels_ - numerics.mesh.inside_coarser_by
  std::vector<std::vector<double>> history_;
};
} // namespace cellphase
