#include "scene/Sections.h"
#include <tuple>
#include "scene/Shapes.h"
#include <algorithm>
#include <cmath>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
const std::vector<std::pair<std::string, ShapeKind>> shapes = {
    {"circle", ShapeKind::circle},
    {"ellipse", ShapeKind::ellipse},
    {"cassini", ShapeKind::cassini},
    {"expression", ShapeKind::expression},
    {"field", ShapeKind::field}};

/// Size keys of each shape (the other keys are common to all shapes).
std::vector<std::string> size_keys(ShapeKind k)
{
  switch (k)
  {
  case ShapeKind::circle: return {"radius"};
  case ShapeKind::ellipse: return {"semi_axes"};
  case ShapeKind::cassini: return {"a", "b"};
  case ShapeKind::expression: return {"distance"};
  case ShapeKind::field: return {"phi0"};
  }
  return {};
}

const char* shape_name(ShapeKind k)
{
  for (const auto& [name, kind] : shapes)
    if (kind == k)
      return name.c_str();
  return "?";
}

/// Rejects size keys of other shapes, then anything unknown.
void check_keys(const Section& c, ShapeKind kind)
{
  std::vector<std::string> allowed = {"name", "shape", "center", "rotation", "group", "Be",
                                      "spontaneous_curvature", "mobility", "penalty_area",
                                      "viscosity"};
  const std::vector<std::string> own = size_keys(kind);
  allowed.insert(allowed.end(), own.begin(), own.end());
  for (const std::string& key : c.keys())
    for (const auto& [name, other] : shapes)
    {
      const std::vector<std::string> theirs = size_keys(other);
      if (other != kind && std::find(theirs.begin(), theirs.end(), key) != theirs.end()
          && std::find(own.begin(), own.end(), key) == own.end())
        c.fail(key, "is a key of shape " + name + ", but this cell's shape is "
                        + shape_name(kind) + ", which takes " + join(own));
    }
  c.allow_only(allowed);
}

void require(const Section& c, const std::string& key, ShapeKind kind, const std::string& what)
{
  if (!c.has(key))
    c.fail(key, std::string("missing; shape ") + shape_name(kind) + " needs " + key + " ("
                    + what + ")");
}
/// The cell's group (its own phase field unless named) and its own parameters, which the
/// cells of a group must share.
void read_cell_phase_field(const Section& c, const Scene& s, Cell& cell)
{
  cell.group = c.string("group", cell.name);
  if (cell.group.empty() || cell.group.find_first_of(".,/ ") != std::string::npos)
    c.fail("group", "found \"" + cell.group + "\", expected a name without '.', ',', '/' or "
                    "spaces (it names the phase field's fields, e.g. phi_<group>)");
  if (c.has("Be"))
    cell.Be = c.number("Be", positive());
  if (c.has("spontaneous_curvature"))
    cell.spontaneous_curvature = c.number("spontaneous_curvature", any());
  if (c.has("mobility"))
    cell.mobility = c.number("mobility", positive());
  if (c.has("penalty_area"))
    cell.penalty_area = c.number("penalty_area", non_negative());
  if (c.has("viscosity"))
    cell.viscosity = c.number("viscosity", positive());
  for (const Cell& other : s.cells)
    if (other.group == cell.group)
      for (const auto& [key, mine, theirs] :
           {std::tuple{"Be", cell.Be, other.Be},
            std::tuple{"spontaneous_curvature", cell.spontaneous_curvature, other.spontaneous_curvature},
            std::tuple{"mobility", cell.mobility, other.mobility},
            std::tuple{"penalty_area", cell.penalty_area, other.penalty_area},
            std::tuple{"viscosity", cell.viscosity, other.viscosity}})
        if (mine != theirs)
          c.fail(key, std::string("differs from that of ") + other.name + " in group \"" + cell.group
                          + "\"; the cells of one group share one phase field and its parameters");
}
} // namespace

std::string cell_label(std::size_t i, const Cell& c)
{
  const std::string index = "cells[" + std::to_string(i) + "]";
  return c.name == index ? index : index + " (\"" + c.name + "\")";
}

void read_cells(const Section& top, Scene& s)
{
  if (!top.has("cells"))
    top.fail("cells", "missing; a scene needs at least one cell, e.g. "
                      "cells: [{shape: circle, center: [0, 0], radius: 1}]");
  const std::vector<Section> list = top.list_of_sections("cells");
  if (list.empty())
    top.value("cells").fail("is an empty list; give at least one cell");

  const int dim = s.domain.dim;
  const std::vector<std::size_t> n{std::size_t(dim)};
  s.cells.clear();
  for (std::size_t i = 0; i < list.size(); ++i)
  {
    Cell cell;
    const std::string index = "cells[" + std::to_string(i) + "]";
    cell.name = list[i].string("name", index);
    if (cell.name.empty())
      list[i].fail("name", "is empty; leave it out to use the default name " + index);
    for (std::size_t j = 0; j < i; ++j)
      if (s.cells[j].name == cell.name)
        list[i].fail("name", "\"" + cell.name + "\" is already the name of cells["
                                 + std::to_string(j) + "]; names must be unique");
    const Section c = list[i].relabel(cell_label(i, cell));

    cell.shape = c.choice<ShapeKind>("shape", ShapeKind::circle, shapes);
    check_keys(c, cell.shape);
    if (c.has("center"))
    {
      const auto v = c.numbers("center", n, any());
      std::copy(v.begin(), v.end(), cell.center.begin());
    }
    cell.rotation = c.number("rotation", 0, any()) * M_PI / 180;

    switch (cell.shape)
    {
    case ShapeKind::circle:
      require(c, "radius", cell.shape, "a number > 0");
      cell.radius = c.number("radius", positive());
      break;
    case ShapeKind::ellipse:
    {
      require(c, "semi_axes", cell.shape, "a list of " + std::to_string(dim) + " numbers > 0");
      const auto v = c.numbers("semi_axes", n, positive());
      std::copy(v.begin(), v.end(), cell.semi_axes.begin());
      break;
    }
    case ShapeKind::cassini:
      require(c, "a", cell.shape, "half the distance between the foci, a number > 0");
      require(c, "b", cell.shape, "product of the distances to the foci is b^2, a number > 0");
      cell.cassini_a = c.number("a", positive());
      cell.cassini_b = c.number("b", positive());
      break;
    case ShapeKind::expression:
    {
      require(c, "distance", cell.shape, "a signed distance in x, y, z, negative inside");
      cell.expression = c.value("distance").string();
      const std::string error = check_expression(cell.expression);
      if (!error.empty())
        c.value("distance").fail("cannot parse the expression \"" + cell.expression
                                 + "\": " + error + " (allowed variables: x, y, z)");
      break;
    }
    case ShapeKind::field:
    {
      // The initial phase field itself, not through the tanh profile of a distance.
      require(c, "phi0", cell.shape, "the initial phase field in x, y, z, in [-1, 1]");
      cell.expression = c.value("phi0").string();
      cell.field_epsilon = s.numerics.epsilon;
      const std::string error = check_expression(cell.expression);
      if (!error.empty())
        c.value("phi0").fail("cannot parse the formula \"" + cell.expression + "\": " + error
                             + " (allowed variables: x, y, z)");
      break;
    }
    }
    read_cell_phase_field(c, s, cell);
    s.cells.push_back(cell);
  }
}

} // namespace cellphase::scene
