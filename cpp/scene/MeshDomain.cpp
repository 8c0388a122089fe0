#include "scene/MeshDomain.h"
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace cellphase::scene
{
/// Uniform grid over the mesh's bounding box; each item (a triangle or segment) is
/// listed in the grid cells its bounding box touches, so that a query looks at a few
/// items instead of all.
class MeshDomain::Buckets
{
public:
  Buckets(const std::array<double, 3>& lo, const std::array<double, 3>& hi, std::size_t items)
      : lo_(lo)
  {
    const double dx = hi[0] - lo[0], dy = hi[1] - lo[1];
    const double cell = std::sqrt(dx * dy / std::max<std::size_t>(items, 1)) + 1e-300;
    n_ = {std::max(1, int(std::ceil(dx / cell))), std::max(1, int(std::ceil(dy / cell)))};
    n_[0] = std::min(n_[0], 4096), n_[1] = std::min(n_[1], 4096);
    h_ = {dx / n_[0] + 1e-300, dy / n_[1] + 1e-300};
    lists_.resize(std::size_t(n_[0]) * n_[1]);
  }
  void add(int item, double x0, double y0, double x1, double y1, double pad)
  {
    for_range(x0 - pad, y0 - pad, x1 + pad, y1 + pad,
              [&](std::vector<int>& l) { l.push_back(item); });
  }
  /// Items listed in the grid cell of p.
  const std::vector<int>& at(const double* p) const
  {
    static const std::vector<int> none;
    const int i = index(p[0], 0), j = index(p[1], 1);
    if (i < 0 || j < 0)
      return none;
    return lists_[std::size_t(j) * n_[0] + i];
  }

private:
  int index(double x, int axis) const
  {
    const int i = int(std::floor((x - lo_[axis]) / h_[axis]));
    if (i < -1 || i > n_[axis])
      return -1;
    return std::clamp(i, 0, n_[axis] - 1);
  }
  template <typename F>
  void for_range(double x0, double y0, double x1, double y1, F&& f)
  {
    auto clampi = [&](double x, int axis)
    { return std::clamp(int(std::floor((x - lo_[axis]) / h_[axis])), 0, n_[axis] - 1); };
    for (int j = clampi(y0, 1); j <= clampi(y1, 1); ++j)
      for (int i = clampi(x0, 0); i <= clampi(x1, 0); ++i)
        f(lists_[std::size_t(j) * n_[0] + i]);
  }
  std::array<double, 3> lo_;
  std::array<int, 2> n_;
  std::array<double, 2> h_;
  std::vector<std::vector<int>> lists_;
};

namespace
{
double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

/// Distance from p to the segment [a, b].
double segment_distance(const double* p, const double* a, const double* b)
{
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double len2 = ex * ex + ey * ey;
  double t = len2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey);
}
} // namespace

MeshDomain::MeshDomain(MeshData data, std::string path) : data_(std::move(data)), path_(std::move(path))
{
  const auto& x = data_.points;
  lower_ = {x[0], x[1], 0};
  upper_ = lower_;
  for (std::size_t i = 0; i < x.size(); i += 3)
    for (int d = 0; d < 2; ++d)
      lower_[d] = std::min(lower_[d], x[i + d]), upper_[d] = std::max(upper_[d], x[i + d]);
  tol_ = 1e-9 * std::max(upper_[0] - lower_[0], upper_[1] - lower_[1]);

  // Area, longest edge, and the edges that belong to one triangle only (the boundary),
  // each with the triangle's third node for the inward normal.
  std::map<std::pair<std::int64_t, std::int64_t>, std::pair<int, std::int64_t>> edges;
  const std::size_t nc = data_.num_cells();
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int64_t* v = &data_.cells[3 * c];
    const double* p0 = &x[3 * v[0]];
    const double* p1 = &x[3 * v[1]];
    const double* p2 = &x[3 * v[2]];
    area_ += 0.5 * std::abs(cross(p1[0] - p0[0], p1[1] - p0[1], p2[0] - p0[0], p2[1] - p0[1]));
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = v[k], b = v[(k + 1) % 3];
      longest_edge_ = std::max(longest_edge_, std::hypot(x[3 * b] - x[3 * a], x[3 * b + 1] - x[3 * a + 1]));
      auto& e = edges[{std::min(a, b), std::max(a, b)}];
      e.first += 1;
      e.second = v[(k + 2) % 3];
    }
  }
  cell_buckets_ = std::make_unique<Buckets>(lower_, upper_, nc);
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int64_t* v = &data_.cells[3 * c];
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (int k = 0; k < 3; ++k)
    {
      x0 = std::min(x0, x[3 * v[k]]), x1 = std::max(x1, x[3 * v[k]]);
      y0 = std::min(y0, x[3 * v[k] + 1]), y1 = std::max(y1, x[3 * v[k] + 1]);
    }
    cell_buckets_->add(int(c), x0, y0, x1, y1, tol_);
  }

  // Tagged file facets, bucketed for the midpoint lookup.
  const std::size_t nf = data_.facet_tags.size();
  tag_buckets_ = std::make_unique<Buckets>(lower_, upper_, nf);
  for (std::size_t f = 0; f < nf; ++f)
  {
    const double* a = &x[3 * data_.facets[2 * f]];
    const double* b = &x[3 * data_.facets[2 * f + 1]];
    tag_buckets_->add(int(f), std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[0], b[0]),
                      std::max(a[1], b[1]), 2 * tol_);
  }
  auto file_tags_at = [&](const double* m)
  {
    std::vector<int> t;
    for (int f : tag_buckets_->at(m))
      if (segment_distance(m, &x[3 * data_.facets[2 * f]], &x[3 * data_.facets[2 * f + 1]]) < tol_
          && std::find(t.begin(), t.end(), data_.facet_tags[f]) == t.end())
        t.push_back(data_.facet_tags[f]);
    return t;
  };

  for (const auto& [key, e] : edges)
  {
    if (e.first != 1)
      continue;
    Edge b;
    const double* pa = &x[3 * key.first];
    const double* pb = &x[3 * key.second];
    const double* po = &x[3 * e.second];
    b.a = {pa[0], pa[1]};
    b.b = {pb[0], pb[1]};
    const double len = std::hypot(pb[0] - pa[0], pb[1] - pa[1]);
    b.n = {-(pb[1] - pa[1]) / len, (pb[0] - pa[0]) / len};
    if (b.n[0] * (po[0] - pa[0]) + b.n[1] * (po[1] - pa[1]) < 0)
      b.n = {-b.n[0], -b.n[1]};
    const double m[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])};
    b.tags = file_tags_at(m);
    boundary_.push_back(b);
  }
}

MeshDomain::~MeshDomain() = default;

std::vector<std::string> MeshDomain::tag_names() const
{
  std::vector<std::string> names;
  for (const auto& [name, number] : data_.tags)
    names.push_back(name);
  return names;
}

bool MeshDomain::contains(const double* p) const
{
  const auto& x = data_.points;
  for (int c : cell_buckets_->at(p))
  {
    const std::int64_t* v = &data_.cells[3 * c];
    const double* a = &x[3 * v[0]];
    const double* b = &x[3 * v[1]];
    const double* q = &x[3 * v[2]];
    const double area = cross(b[0] - a[0], b[1] - a[1], q[0] - a[0], q[1] - a[1]);
    // Barycentric signs, with a tolerance so that points on shared edges count.
    const double s = area > 0 ? 1 : -1, eps = tol_ * std::sqrt(std::abs(area)) * 2;
    const double l0 = s * cross(b[0] - p[0], b[1] - p[1], q[0] - p[0], q[1] - p[1]);
    const double l1 = s * cross(q[0] - p[0], q[1] - p[1], a[0] - p[0], a[1] - p[1]);
    const double l2 = s * cross(a[0] - p[0], a[1] - p[1], b[0] - p[0], b[1] - p[1]);
    if (l0 >= -eps && l1 >= -eps && l2 >= -eps)
      return true;
  }
  return false;
}

bool MeshDomain::near_boundary(const double* p, double r) const
{
  // Boundary edges are few (the square root of the cells); a plain loop is fast enough
  // for the scene checks.
  for (const Edge& e : boundary_)
    if (segment_distance(p, e.a.data(), e.b.data()) < r)
      return true;
  return false;
}

bool MeshDomain::on_tags(const double* m, const std::vector<int>& tags) const
{
  const auto& x = data_.points;
  const bool want_untagged = std::count(tags.begin(), tags.end(), untagged) > 0;
  bool on_any = false;
  for (int f : tag_buckets_->at(m))
    if (segment_distance(m, &x[3 * data_.facets[2 * f]], &x[3 * data_.facets[2 * f + 1]]) < tol_)
    {
      on_any = true;
      if (std::count(tags.begin(), tags.end(), data_.facet_tags[f]))
        return true;
    }
  return want_untagged && !on_any;
}

double MeshDomain::tag_length(int tag) const
{
  double length = 0;
  for (const Edge& e : boundary_)
    if (std::count(e.tags.begin(), e.tags.end(), tag) || (tag == untagged && e.tags.empty()))
      length += std::hypot(e.b[0] - e.a[0], e.b[1] - e.a[1]);
  return length;
}

int MeshDomain::normal_axis(const std::vector<int>& tags) const
{
  int axis = -2; // none seen yet
  for (const Edge& e : boundary_)
  {
    bool mine = false;
    for (int t : tags)
      mine = mine || std::count(e.tags.begin(), e.tags.end(), t) > 0
             || (t == untagged && e.tags.empty());
    if (!mine)
      continue;
    const int a = std::abs(e.n[1]) < 1e-12 ? 0 : std::abs(e.n[0]) < 1e-12 ? 1 : -1;
    if (a < 0 || (axis != -2 && a != axis))
      return -1;
    axis = a;
  }
  return axis < 0 ? -1 : axis;
}
} // namespace cellphase::scene
