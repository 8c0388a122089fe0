#include "scene/SceneLoader.h"
#include "scene/Overrides.h"
#include "scene/Sections.h"
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cellphase::scene
{

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides)
{
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError("cannot read scene file '" + path + "': it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError("cannot read scene file '" + path + "': " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    throw SceneError("cannot read scene file '" + path + "': read error");
  return parse_scene(text.str(), path, overrides);
}

Scene parse_scene(const std::string& yaml_text, const std::string& source,
                  const std::vector<std::string>& overrides)
{
  YAML::Node root;
  try
  {
    root = YAML::Load(yaml_text);
  }
  catch (const YAML::Exception& e)
  {
    const std::string where = e.mark.is_null() ? source
                                               : source + ":" + std::to_string(e.mark.line + 1)
                                                     + ":" + std::to_string(e.mark.column + 1);
    throw SceneError(where + ": YAML syntax error: " + e.msg);
  }
  const std::string sections = "domain, cells, phase_field, numerics and optionally boundary, "
                               "numbers or units, flow, interaction, reaction_diffusion, polar_gel, output";
  if (!root.IsDefined() || root.IsNull())
    throw SceneError(source + ": the scene file is empty; expected a mapping with the sections "
                     + sections);
  if (!root.IsMap())
    throw SceneError(source + ": the scene file must be a mapping of sections (" + sections
                     + "), found "
                     + (root.IsSequence() ? std::string("a list") : "the text \"" + root.Scalar() + "\""));

  try
  {
    yaml::Origin origin{source, apply_overrides(root, overrides, source)};
    const yaml::Section top = yaml::Section::root(origin, root);
    top.allow_only({"domain", "boundary", "cells", "phase_field", "numbers", "units",
                    "numerics", "flow", "output", "interaction", "reaction_diffusion",
                    "polar_gel"});
    Scene s;
    s.source = source;
    s.overrides = overrides;
    s.resolved_yaml = YAML::Dump(root);
    read_domain(top, s);
    read_phase_field(top, s);
    read_boundary(top, s);
    read_numbers(top, s);
    read_numerics(top, s);
    read_cells(top, s);
    read_interaction(top, s);
    read_flow(top, s);
    read_reaction_diffusion(top, s);
    read_polar_gel(top, s);
    check_coupling(top, s);
    if (!s.numerics.mesh.refine_inside)
      s.numerics.mesh.refine_inside = s.numerics.mesh.adaptive && s.polar_gel.has_value();
    read_output(top, s);
    check_geometry(top, s);
    check_split(top, s);
    return s;
  }
  catch (const SceneError&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    // Not expected: the readers check before converting. Never let it escape unexplained.
    throw SceneError(source + ": invalid scene: " + e.what());
  }
}

} // namespace cellphase::scene
