// Random values without generator state: a hash of the seed, a stream number and what is
// hashed (a node's snapped position, a turn's number). They depend on nothing else, so a
// restart or another partition into ranks gives the same values.
#pragma once
#include <cmath>
#include <cstdint>

namespace cellphase::random
{
/// splitmix64: a well-mixed 64-bit hash.
inline std::uint64_t mix(std::uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Uniform in [0, 1) from the seed, a stream number and a point (snapped by the caller).
inline double uniform(std::uint64_t seed, std::uint64_t stream, double x, double y, double z)
{
  std::uint64_t h = mix(seed ^ mix(stream));
  for (double c : {x, y, z})
    h = mix(h ^ std::uint64_t(std::llround(c * 1e9))); // c is snapped: no last-bit noise
  return double(h >> 11) * 0x1.0p-53;
}

/// Rounds a coordinate to 1e-12 of the domain's largest extent. DOLFINx interpolates cell by
/// cell, and a node shared by cells gets the coordinates its last cell computes, which differ
/// in the last bits between cells (and so between partitions); snapped, the node hashes to
/// one value on any number of ranks.
struct Snap
{
  /// extent: the domain's largest extent (scene::Domain::largest_extent).
  explicit Snap(double extent) : grid(1e-12 * extent) {}
  double operator()(double x) const { return std::round(x / grid) * grid; }
  double grid;
};
} // namespace cellphase::random
