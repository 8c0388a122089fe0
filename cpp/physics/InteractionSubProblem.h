// Interaction between the cells' phase fields, section 7.1.2: before the phase fields step,
// the sums over the other cells w_sum_i = sum_{j != i} (In / In_ij) w_j and B_sum_i =
// sum_{j != i} (In / In_ij) B(phi_j) at the P2 nodes, one pair of sums per potential (pairs
// may have their own, interaction.pairs), from which each cell's equation takes its
// source (7.11). Only
// pairs whose diffuse bands (|phi| < 1) have overlapping bounding boxes are summed, so the
// cost grows with the number of neighbours, not with N^2. Also observes, for any scene with
// several phase fields, the interaction energy (7.5) and the largest overlap
// max_x min((1 + phi_i)/2, (1 + phi_j)/2) of two cells.
#pragma once
#include "compat/Resample.h"
#include "core/SubProblem.h"
#include "physics/InteractionFunction.h"
#include "scene/InteractionPairs.h"
#include "scene/Plan.h"
#include <array>
#include <memory>
#include <optional>

namespace cellphase
{
class InteractionSubProblem : public SubProblem
{
public:
  InteractionSubProblem(scene::PlanStep step, const scene::Scene& scene, MPI_Comm comm);

  std::vector<std::string> attach_reads() const override { return phis_; }
  void declare(FieldRegistry& fields) override;
  void attach(FieldRegistry& fields) override;
  StepTimings step(double dt) override;
  /// interaction.refresh: the sums again from every cell's phi^{n+1}, before the phase
  /// fields' finish_step puts the source of this state into their w.
  StepTimings finish_step() override;
  void observe(Observation& row) override;

private:
  /// Bounding box (min x, y, z, max x, y, z) over all ranks of the nodes where a phase
  /// field's interaction does not vanish (phi > reach_level_); empty (min > max) if none.
  std::array<double, 6> band_box(const Function& phi) const;
  static std::array<double, 6> common_box(const std::array<double, 6>& a,
                                          const std::array<double, 6>& b);
  /// phi_j at the nodes of phi_i's mesh: all nodes when they share the mesh; with own
  /// meshes the nodes inside phi_j's band box, where phi_j is evaluated on its own mesh
  /// (elsewhere |phi_j| >= 1 - 1e-12, where w_j vanishes and B(phi_j) is below 1e-24/eps).
  struct Samples
  {
    std::vector<std::int32_t> nodes;
    std::vector<double> values;
  };
  Samples sample(std::size_t i, std::size_t j, const std::array<double, 6>& box_j) const;
  static bool boxes_meet(const std::array<double, 6>& a, const std::array<double, 6>& b);
  /// The sums w_sum, B_sum of every cell from the phase fields now; sets boxes_.
  void update_sums();
  /// band_box of every phase field, in the order of phis_.
  std::vector<std::array<double, 6>> band_boxes() const;

  MPI_Comm comm_;
  scene::Domain domain_; ///< its periodic axes: the band boxes of two cells a period apart meet
  double eps_;
  std::optional<scene::Interaction> interaction_;
  std::vector<scene::CellGroup> groups_;
  std::vector<std::string> phis_;
  FieldRegistry* fields_ = nullptr;
  std::vector<InteractionShape> potentials_; ///< scene::interaction_potentials
  std::vector<std::vector<scene::PairInteraction>> pairs_; ///< [i][j]: of groups i and j
  /// [i][k]: the sums of group i over the other cells with potential k
  std::vector<std::vector<std::shared_ptr<Function>>> w_sum_, B_sum_;
  std::vector<std::shared_ptr<Form>> energy_; ///< (7.5) of each group and potential
  bool own_; ///< each phase field on its own mesh (numerics.mesh.cell_meshes: own)
  double reach_level_; ///< phi at the distance beyond which w_j and B(phi_j) vanish
  std::vector<PointEvaluator> evaluate_;    ///< own meshes: phi_j, -1 beyond its mesh
  std::vector<std::vector<double>> nodes_;  ///< own meshes: node coordinates of phi_i's space
  std::vector<std::array<double, 6>> boxes_; ///< band boxes of the last update_sums
};
} // namespace cellphase
