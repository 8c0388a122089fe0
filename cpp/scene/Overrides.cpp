#include "scene/Overrides.h"
#include "scene/SceneLoader.h"
#include <cctype>

namespace cellphase::scene
{
namespace
{

std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

bool is_name(const std::string& s)
{
  if (s.empty())
    return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
      return false;
  return true;
}

bool is_index(const std::string& s, std::size_t& i)
{
  if (s.empty() || s.size() > 9)
    return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c)))
      return false;
  i = std::stoul(s);
  return true;
}

std::vector<std::string> split_dots(const std::string& key)
{
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true)
  {
    const auto dot = key.find('.', start);
    parts.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos)
      return parts;
    start = dot + 1;
  }
}

} // namespace

std::map<std::string, std::string> apply_overrides(YAML::Node& root,
                                                   const std::vector<std::string>& overrides,
                                                   const std::string& source)
{
  std::map<std::string, std::string> applied;
  for (const std::string& text : overrides)
  {
    auto bad = [&](const std::string& why)
    { throw SceneError(source + ": --set " + text + ": " + why); };

    const auto eq = text.find('=');
    if (eq == std::string::npos)
      bad("expected key.path=value, e.g. numerics.epsilon=0.02");
    const std::string key = trim(text.substr(0, eq));
    const std::vector<std::string> parts = split_dots(key);
    for (const std::string& p : parts)
      if (!is_name(p))
        bad("'" + key + "' is not a dotted key path such as numerics.epsilon or cells.0.radius");

    YAML::Node value;
    try
    {
      value = YAML::Load(text.substr(eq + 1));
    }
    catch (const YAML::Exception& e)
    {
      bad("the value is not valid YAML: " + e.msg);
    }

    // Walk down, creating absent sections; reset() rebinds (operator= would copy into).
    YAML::Node cur;
    cur.reset(root);
    std::string walked;
    for (std::size_t k = 0; k < parts.size(); ++k)
    {
      const std::string& part = parts[k];
      const bool last = k + 1 == parts.size();
      const std::string here = walked.empty() ? part : walked + "." + part;
      if (cur.IsSequence())
      {
        std::size_t i = 0;
        if (!is_index(part, i) || i >= cur.size())
          bad(walked + " is a list of " + std::to_string(cur.size())
              + (cur.size() == 1 ? " entry" : " entries") + "; address one by its index 0 to " + std::to_string(cur.size() - 1)
              + " (" + walked + ".0...)");
        if (last)
          cur[i] = value;
        else
          cur.reset(cur[i]);
      }
      else if (cur.IsMap() || cur.IsNull())
      {
        if (cur.IsNull())
          cur = YAML::Node(YAML::NodeType::Map);
        if (last)
          cur[part] = value;
        else
        {
          if (!cur[part].IsDefined() || cur[part].IsNull())
            cur[part] = YAML::Node(YAML::NodeType::Map);
          YAML::Node next = cur[part];
          cur.reset(next);
        }
      }
      else
        bad(walked + " is a value, not a section, so it has no key '" + part + "'");
      walked = here;
    }
    applied[key] = trim(text);
  }
  return applied;
}

} // namespace cellphase::scene
