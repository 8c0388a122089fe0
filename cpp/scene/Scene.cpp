// Names and small queries on the scene data model.
#include "scene/Scene.h"
#include "scene/MeshDomain.h"
#include <cmath>
#include <algorithm>

namespace cellphase::scene
{

double Domain::volume() const
{
  if (mesh)
    return mesh->area();
  double v = 1;
  for (int i = 0; i < dim; ++i)
    v *= upper[i] - lower[i];
  return v;
}

double Domain::largest_extent() const
{
  double extent = 0;
  for (int a = 0; a < dim; ++a)
    extent = std::max(extent, upper[a] - lower[a]);
  return extent;
}

bool Domain::is_periodic(int axis) const
{
  return std::find(periodic.begin(), periodic.end(), axis) != periodic.end();
}

std::array<double, 3> Domain::into_period(double x, double y, double z) const
{
  std::array<double, 3> p{x, y, z};
  for (int a : periodic)
  {
    const double L = upper[a] - lower[a], round_off = 1e-9 * L;
    // The sides and round-off around them stay: a node of the shared mesh keeps its own
    // coordinates (its random start, PolarGelSubProblem, is hashed from them).
    if (p[a] > upper[a] + round_off || p[a] < lower[a] - round_off)
      p[a] -= std::floor((p[a] - lower[a]) / L) * L;
  }
  return p;
}

const char* to_string(Model m)
{
  switch (m)
  {
  case Model::allen_cahn: return "allen_cahn";
  case Model::allen_cahn_volume: return "allen_cahn_volume";
  case Model::cahn_hilliard: return "cahn_hilliard";
  case Model::helfrich_lagrange: return "helfrich_lagrange";
  case Model::helfrich_penalty: return "helfrich_penalty";
  case Model::helfrich_hm1: return "helfrich_hm1";
  }
  return "unknown";
}

const char* to_string(Linearisation l)
{
  switch (l)
  {
  case Linearisation::taylor: return "taylor";
  case Linearisation::stabilised: return "stabilised";
  }
  return "unknown";
}

std::vector<std::string> model_fields(Model m)
{
  switch (m)
  {
  case Model::allen_cahn:
  case Model::allen_cahn_volume: return {"phi"};
  case Model::cahn_hilliard:
  case Model::helfrich_lagrange:
  case Model::helfrich_penalty: return {"phi", "mu"};
  case Model::helfrich_hm1: return {"phi", "mu", "w"};
  }
  return {"phi"};
}

std::vector<std::string> history_fields(const Scene& s)
{
  const bool bdf2 = s.numerics.time_scheme == Numerics::TimeScheme::bdf2;
  if (!bdf2 && !s.numerics.adaptive_dt) // the error estimate extrapolates from phi^{n-1}
    return {};
  std::vector<std::string> out{"phi_prev"};
  if (bdf2 && s.phase_field.model != Model::allen_cahn
      && s.phase_field.model != Model::allen_cahn_volume)
    out.push_back("mu_prev"); // the extrapolated mu* of the Taylor linearisation
  return out;
}

bool is_helfrich(Model m)
{
  return m == Model::helfrich_lagrange || m == Model::helfrich_penalty
         || m == Model::helfrich_hm1;
}

const char* to_string(WallType w)
{
  switch (w)
  {
  case WallType::no_slip: return "no_slip";
  case WallType::moving: return "moving";
  case WallType::free_slip: return "free_slip";
  case WallType::open: return "open";
  case WallType::prescribed: return "prescribed";
  }
  return "unknown";
}

const char* to_string(OutputFormat f)
{
  return f == OutputFormat::vtk ? "vtk" : "xdmf";
}

bool couples_to_flow(Model m) { return m == Model::cahn_hilliard || is_helfrich(m); }

double flow_reynolds(const Scene& s)
{
  return s.flow && s.flow->equations == FlowEquations::navier_stokes ? s.numbers.Re : 0.0;
}

Numerics::Solver flow_solver(const Scene& s)
{
  return s.flow && s.flow->solver ? *s.flow->solver : s.numerics.solver;
}

Numerics::Solver reaction_diffusion_solver(const Scene& s)
{
  return s.reaction_diffusion && s.reaction_diffusion->solver ? *s.reaction_diffusion->solver
                                                              : s.numerics.solver;
}

Numerics::Solver polar_gel_solver(const Scene& s)
{
  return s.polar_gel && s.polar_gel->solver ? *s.polar_gel->solver : s.numerics.solver;
}

double flow_capillary(const Scene& s)
{
  if (is_helfrich(s.phase_field.model))
    return 1.0;
  if (s.flow && s.flow->surface_tension)
    return 3 * *s.flow->surface_tension / (2 * std::sqrt(2.0));
  return 1 / s.numbers.Ca;
}

} // namespace cellphase::scene
