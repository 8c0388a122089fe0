// A cell's own mesh (numerics.mesh.cell_meshes: own, section 7.2): the patch of the base
// mesh around the cell's band, grown by a margin, refined around that cell's zero level set
// only. Its size does not depend on the other cells, so N cells cost N times one cell.
// Patches are cut from the same base mesh as the shared mesh (no redistribution), so
// fields move between them rank-locally, on any number of MPI ranks (compat/Patch.h).
#pragma once
#include "compat/Patch.h"
#include "mesh/AdaptiveMesh.h"

namespace cellphase
{
/// A cell's own mesh is cut around the nodes where its phi exceeds this (the band
/// |phi| < 0.9, 2.1 epsilon out from the zero level set), grown by numerics.mesh.own_margin.
/// Not closer to -1: the H^-1 flows exchange volume through the bulk, whose phi may shift
/// from -1 by about 1e-3 over the whole patch.
constexpr double own_band_level = -0.9;

class OwnMesh
{
public:
  /// `base` is the scene's base mesh (the shared mesh's).
  OwnMesh(const scene::Scene& scene, std::shared_ptr<Mesh> base);

  /// The patch of base cells meeting `band` (the box of the cell's band phi > own_band_level)
  /// grown by the margin, refined around the zero level set of phi. Across a periodic side
  /// the patch is wrapped: its part beyond the side lies a period up (compat::create_patch).
  std::shared_ptr<Mesh> build(const PointEvaluator& phi, const compat::Box& band);
  /// The mesh of an earlier build again (checkpoints): its patch box and history.
  std::shared_ptr<Mesh> replay(const compat::Box& patch_box,
                               const std::vector<std::vector<double>>& history);
  const compat::Box& patch_box() const { return box_; }
  const std::vector<std::vector<double>>& history() const { return refined_->history(); }
  int levels() const { return refined_ ? refined_->levels() : 0; }
  double margin() const { return margin_; }

private:
  const scene::Scene& scene_;
  std::shared_ptr<Mesh> base_;
  double margin_;
  compat::Box box_{};
  std::unique_ptr<AdaptiveMesh> refined_;
};

/// Whether a cut box covers the whole domain (a cell nearly as long as a periodic side,
/// OwnMesh::build): the "patch" is then the whole domain and has no cut edges.
bool covers_domain(const compat::Box& box, const scene::Domain& d);

/// Box of the nodes where f > level over all ranks (empty, min > max, if there are none).
/// On a mesh that spans a periodic axis, nodes on both sides of the periodic side give a
/// box across it: its upper end lies beyond the side.
compat::Box box_above(const Function& f, double level);

/// `box` moved by whole periods along the periodic axes to where it meets `near` or is
/// closest to it (the boxes of two cells, one of them on a wrapped patch).
compat::Box image_near(const compat::Box& box, const compat::Box& near, const scene::Domain& d);
} // namespace cellphase
