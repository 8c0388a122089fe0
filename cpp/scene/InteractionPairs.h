// Which interaction each pair of phase fields has, (7.5) and (7.11): the scene's In and
// potential, or those of its entry in interaction.pairs. The distinct potentials are
// numbered, the scene's first, so that every cell needs one source term per potential
// (forms/helfrich_hm1.py: load_int) and not one per pair.
#pragma once
#include "scene/Scene.h"
#include <cstddef>
#include <string>
#include <vector>

namespace cellphase::scene
{
/// The distinct potentials: [0] the scene's, then those of pairs, in the order listed.
std::vector<InteractionPotential> interaction_potentials(const Interaction& in);

struct PairInteraction
{
  std::size_t potential; ///< index into interaction_potentials
  double In;             ///< In_ij = In_ji
};
/// The interaction of the phase fields of groups `a` and `b` (a != b).
PairInteraction pair_interaction(const Interaction& in, const std::string& a,
                                 const std::string& b);
} // namespace cellphase::scene

namespace cellphase::scene
{
/// The registry name of a group's sum over the other cells with potential k, `sum` being
/// "w_sum" or "B_sum": interaction.<group>.w_sum for the scene's potential, .w_sum<k> else.
inline std::string interaction_sum_field(const std::string& group, const std::string& sum,
                                         std::size_t k)
{
  return "interaction." + group + "." + sum + (k == 0 ? "" : std::to_string(k));
}
} // namespace cellphase::scene
