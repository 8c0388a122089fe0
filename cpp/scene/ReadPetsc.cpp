#include "scene/MumpsControl.h"
#include "scene/Sections.h"

namespace cellphase::scene
{
using namespace yaml;

namespace
{
/// mat_mumps_icntl_<i> and mat_mumps_cntl_<i>: an index that MUMPS has and a value of its type.
void check_mumps_control(const Value& v, const std::string& key, const std::string& value)
{
  const MumpsControl c = read_mumps_control(key, value);
  const std::string last = std::to_string(c.last_index());
  if (c.status == MumpsControl::Status::bad_index)
    v.fail("MUMPS has " + std::string(c.integer ? "ICNTL" : "CNTL") + "(1) to (" + last
           + "): write " + c.stem() + "<1.." + last + ">");
  if (c.status == MumpsControl::Status::bad_value)
    v.fail("found " + v.found() + ", expected " + (c.integer ? "an integer" : "a number"));
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

Numerics::Solver read_solver(const Section& s, Numerics::Solver fallback)
{
  return s.choice("solver", fallback,
                  {{"direct", Numerics::Solver::direct}, {"reuse", Numerics::Solver::reuse}});
}
} // namespace cellphase::scene
