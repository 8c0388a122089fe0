// `--set key.path=value` overrides, applied to the YAML tree before validation so that
// overridden values go through exactly the same checks as values in the file.
#pragma once
#include <map>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

namespace cellphase::scene
{
/// Applies each "dotted.key=value" (value parsed as YAML) to `root`, creating missing
/// sections; list entries are addressed by index (cells.0.radius). Returns the dotted key
/// -> override text, for messages. Throws SceneError for malformed overrides.
std::map<std::string, std::string> apply_overrides(YAML::Node& root,
                                                   const std::vector<std::string>& overrides,
                                                   const std::string& source);
} // namespace cellphase::scene
