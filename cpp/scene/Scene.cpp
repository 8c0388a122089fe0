// Names and small queries on the scene data model.
#include "scene/Scene.h"

namespace cellphase::scene
{

double Domain::volume() const
{
  double v = 1;
  for (int i = 0; i < dim; ++i)
    v *= upper[i] - lower[i];
  return v;
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

bool is_helfrich(Model m)
{
  return m == Model::helfrich_lagrange || m == Model::helfrich_penalty
         || m == Model::helfrich_hm1;
}

} // namespace cellphase::scene
