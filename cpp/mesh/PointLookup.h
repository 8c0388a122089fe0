// Finds stored points again by their coordinates. Meshes rebuilt from the same base mesh
// have the same vertices, cell centroids and P2 nodes whatever the number of MPI ranks,
// but not the same local numbering, so checkpoints identify cells and dofs by position.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace cellphase
{
class PointLookup
{
public:
  /// `points` holds N points as rows of 3; `tolerance` is far below the distance between
  /// two distinct points and far above round-off.
  PointLookup(std::span<const double> points, double tolerance) : points_(points), tol_(tolerance)
  {
    for (std::size_t i = 0; i < points.size() / 3; ++i)
      bins_.emplace(key(bin(points[3 * i]), bin(points[3 * i + 1]), bin(points[3 * i + 2])),
                    std::int64_t(i));
  }

  /// Index of the stored point within the tolerance of p, or -1.
  std::int64_t find(const double* p) const
  {
    const std::int64_t b[3] = {bin(p[0]), bin(p[1]), bin(p[2])};
    // A point near a bin boundary may have been stored in the neighbouring bin.
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
        {
          auto [lo, hi] = bins_.equal_range(key(b[0] + dx, b[1] + dy, b[2] + dz));
          for (auto it = lo; it != hi; ++it)
          {
            const double* q = &points_[3 * it->second];
            if (std::abs(q[0] - p[0]) <= tol_ && std::abs(q[1] - p[1]) <= tol_
                && std::abs(q[2] - p[2]) <= tol_)
              return it->second;
          }
        }
    return -1;
  }

private:
  std::int64_t bin(double x) const { return std::int64_t(std::floor(x / tol_)); }
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    // Mixing hash of the three bin indices; collisions are resolved by equal_range.
    std::uint64_t h = std::uint64_t(i) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(j) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= std::uint64_t(k) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h;
  }

  std::span<const double> points_;
  double tol_;
  std::unordered_multimap<std::uint64_t, std::int64_t> bins_;
};
} // namespace cellphase
