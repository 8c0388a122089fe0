#include "scene/InteractionPairs.h"
#include <algorithm>

namespace cellphase::scene
{
std::vector<InteractionPotential> interaction_potentials(const Interaction& in)
{
  std::vector<InteractionPotential> potentials{in.potential};
  for (const auto& pair : in.pairs)
    if (std::find(potentials.begin(), potentials.end(), pair.potential) == potentials.end())
      potentials.push_back(pair.potential);
  return potentials;
}

PairInteraction pair_interaction(const Interaction& in, const std::string& a,
                                 const std::string& b)
{
  const auto potentials = interaction_potentials(in);
  for (const auto& pair : in.pairs)
    if ((pair.first == a && pair.second == b) || (pair.first == b && pair.second == a))
    {
      const auto k = std::find(potentials.begin(), potentials.end(), pair.potential);
      return {std::size_t(k - potentials.begin()), pair.In};
    }
  return {0, in.In};
}
} // namespace cellphase::scene
