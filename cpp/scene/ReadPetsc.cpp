#include "scene/Sections.h"
#include <cstdlib>

namespace cellphase::scene
{
using namespace yaml;

namespace
{
bool is_integer(const std::string& t)
{
  std::size_t i = (!t.empty() && (t[0] == '-' || t[0] == '+')) ? 1 : 0;
  if (i == t.size())
    return false;
  for (; i < t.size(); ++i)
    if (t[i] < '0' || t[i] > '9')
      return false;
  return t.size() < 10; // within MUMPS' 32-bit integers
}

bool is_number(const std::string& t)
{
  char* end = nullptr;
  std::strtod(t.c_str(), &end);
  return !t.empty() && end == t.c_str() + t.size();
}

/// mat_mumps_icntl_<i> and mat_mumps_cntl_<i>: an index that MUMPS has and a value of its type.
void check_mumps_control(const Value& v, const std::string& key, const std::string& value)
{
  for (const bool integer : {true, false})
  {
    const std::string stem = integer ? "mat_mumps_icntl_" : "mat_mumps_cntl_";
    if (key.rfind(stem, 0) != 0)
      continue;
    const std::string index = key.substr(stem.size());
    const int last = integer ? 60 : 15;
    if (!is_integer(index) || std::atoi(index.c_str()) < 1 || std::atoi(index.c_str()) > last)
      v.fail("MUMPS has " + std::string(integer ? "ICNTL" : "CNTL") + "(1) to ("
             + std::to_string(last) + "): write " + stem + "<1.." + std::to_string(last) + ">");
    if (integer ? !is_integer(value) : !is_number(value))
      v.fail("found " + v.found() + ", expected " + (integer ? "an integer" : "a number"));
  }
}
} // namespace

void read_petsc_options(const Section& p, std::map<std::string, std::string>& out)
{
  p.allow_only(p.keys()); // any names, but no duplicates or non-scalar keys
  for (const std::string& key : p.keys())
  {
    const Value v = p.value(key);
    if (key.empty() || key[0] == '-')
      v.fail("write PETSc option names without the leading '-' (e.g. ksp_type)");
    if (v.node.IsNull())
      out[key] = ""; // a flag option such as ksp_monitor
    else if (v.node.IsScalar())
      out[key] = v.node.Scalar();
    else
      v.fail("found " + v.found() + ", expected a single value (text, number or boolean)");
    check_mumps_control(v, key, out[key]);
  }
}
} // namespace cellphase::scene
