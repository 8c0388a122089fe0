// Small helpers shared by the field writers: numbered file names, the time as text that
// reads back to the same double, and XML files replaced atomically (written under a
// temporary name, then renamed), so that a killed run leaves a complete index.
#pragma once
#include <pugixml.hpp>
#include <string>
#include <vector>

namespace cellphase::xml_index
{
/// "step-00000040" for ("step", 40).
std::string numbered(const char* stem, int step);
/// %.17g: the time as written reads back bit for bit.
std::string time_text(double t);
/// The XML file at `path`; throws naming the path if it cannot be parsed.
pugi::xml_document load(const std::string& path);
/// With `resume` (a restart), load the index at `path` into `doc` and return true if it
/// exists and parses; otherwise leave `doc` empty and return false.
bool load_to_resume(pugi::xml_document& doc, const std::string& path, bool resume);
/// Remove the children `name` of `parent` for which `drop(child)` holds.
template <typename Predicate>
void remove_children(pugi::xml_node parent, const char* name, Predicate drop)
{
  std::vector<pugi::xml_node> doomed;
  for (auto child : parent.children(name))
    if (drop(child))
      doomed.push_back(child);
  for (auto child : doomed)
    parent.remove_child(child);
}
/// Write `doc` to `path` through `path`.tmp and a rename.
void save_atomically(const pugi::xml_document& doc, const std::string& path);
} // namespace cellphase::xml_index
