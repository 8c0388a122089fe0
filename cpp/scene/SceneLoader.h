// Reading a scene file: YAML -> validated Scene, with `--set key=value` overrides.
#pragma once
#include "scene/Scene.h"
#include <stdexcept>
#include <string>
#include <vector>

namespace cellphase::scene
{
/// Any problem with a scene. The message names the file, the key (dotted path) or cell,
/// what was found and what is allowed.
struct SceneError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Load and validate a scene file; overrides are "dotted.key=value" strings applied to
/// the YAML before validation (cells are addressed as cells.0.radius).
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

/// Same from YAML text; source names the text in messages.
Scene parse_scene(const std::string& yaml_text, const std::string& source,
                  const std::vector<std::string>& overrides = {});
} // namespace cellphase::scene
