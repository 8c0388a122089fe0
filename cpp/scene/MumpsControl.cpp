#include "scene/MumpsControl.h"
#include <cstdlib>

namespace cellphase::scene
{
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
} // namespace

MumpsControl read_mumps_control(const std::string& key, const std::string& value)
{
  MumpsControl c;
  for (const bool integer : {true, false})
  {
    c.integer = integer;
    if (key.rfind(c.stem(), 0) != 0)
      continue;
    const std::string index = key.substr(c.stem().size());
    c.index = is_integer(index) ? std::atoi(index.c_str()) : 0;
    if (c.index < 1 || c.index > c.last_index())
      c.status = MumpsControl::Status::bad_index;
    else if (integer ? !is_integer(value) : !is_number(value))
      c.status = MumpsControl::Status::bad_value;
    else
    {
      c.status = MumpsControl::Status::ok;
      c.value = integer ? double(std::atoi(value.c_str())) : std::strtod(value.c_str(), nullptr);
    }
    return c;
  }
  return c;
}
} // namespace cellphase::scene
