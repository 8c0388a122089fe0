#include "io/XmlIndex.h"
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace cellphase::xml_index
{
std::string numbered(const char* stem, int step)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s-%08d", stem, step);
  return buf;
}

std::string time_text(double t)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", t);
  return buf;
}

pugi::xml_document load(const std::string& path)
{
  pugi::xml_document doc;
  if (!doc.load_file(path.c_str()))
    throw std::runtime_error("cannot read '" + path + "' just written by DOLFINx");
  return doc;
}

bool load_to_resume(pugi::xml_document& doc, const std::string& path, bool resume)
{
  if (resume && std::filesystem::exists(path) && doc.load_file(path.c_str()))
    return true;
  doc.reset();
  return false;
}

void save_atomically(const pugi::xml_document& doc, const std::string& path)
{
  const std::string tmp = path + ".tmp";
  if (!doc.save_file(tmp.c_str(), "  "))
    throw std::runtime_error("cannot write '" + tmp + "'");
  std::filesystem::rename(tmp, path);
}
} // namespace cellphase::xml_index
