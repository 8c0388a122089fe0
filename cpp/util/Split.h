// Splitting comma-separated text: observables.csv rows and headers, checkpoint name lists.
#pragma once
#include <sstream>
#include <string>
#include <vector>

namespace cellphase
{
/// The pieces of `text` between the separators (a trailing separator adds no empty piece).
inline std::vector<std::string> split(const std::string& text, char separator = ',')
{
  std::vector<std::string> pieces;
  std::istringstream in(text);
  for (std::string piece; std::getline(in, piece, separator);)
    pieces.push_back(piece);
  return pieces;
}
} // namespace cellphase
