#include "scene/Plan.h"
#include "scene/Sections.h"
#include <algorithm>

namespace cellphase::scene
{
using namespace yaml;

void read_output(const Section& top, Scene& s)
{
  const Section o = top.section("output");
  o.allow_only({"directory", "format", "every", "fields", "progress", "checkpoints"});
  Output& out = s.output;
  out.directory = o.string("directory", out.directory);
  if (out.directory.empty())
    o.fail("directory", "is empty; give a directory name such as output");
  out.format = o.choice("format", out.format,
                        {{"xdmf", OutputFormat::xdmf}, {"vtk", OutputFormat::vtk}});
  out.every = o.integer("every", out.every, non_negative());
  out.progress = o.boolean("progress", out.progress);
  const Section c = o.section("checkpoints");
  c.allow_only({"every", "keep"});
  out.checkpoints.every = c.integer("every", out.checkpoints.every, non_negative());
  out.checkpoints.keep = c.integer("keep", out.checkpoints.keep, closed(1, 1000));
  if (!o.has("fields"))
    return;

  std::vector<std::string> allowed = model_fields(s.phase_field.model);
  if (s.flow)
  {
    allowed.push_back("v"); // velocity and pressure of the flow
    allowed.push_back("p");
    if (s.flow->inextensibility || cell_groups(s).size() > 1)
      allowed.push_back("phi_cells"); // max_i phi_i (7.14), the flow's phase
    if (s.flow->inextensibility)
    {
      allowed.push_back("lambda"); // multiplier of (3.67)
      if (s.flow->inextensibility->concentration)
        allowed.push_back("c"); // concentration of (3.70)
    }
  }
  if (s.reaction_diffusion)
    for (const auto& sp : s.reaction_diffusion->species)
      allowed.push_back(sp.name); // c1, c2, C of forms/gtpase.py
  if (s.polar_gel)
    allowed.insert(allowed.end(), {"P", "P_sharp"}); // orientation field and its potential
  out.fields = o.strings("fields");
  const Value v = o.value("fields");
  for (std::size_t i = 0; i < out.fields.size(); ++i)
  {
    const std::string& f = out.fields[i];
    if (std::find(allowed.begin(), allowed.end(), f) == allowed.end())
      v.element(i).fail("field \"" + f + "\" is not solved for by model "
                        + to_string(s.phase_field.model) + (s.flow ? " and the flow" : "")
                        + "; allowed: " + join(allowed));
    if (std::find(out.fields.begin(), out.fields.begin() + i, f) != out.fields.begin() + i)
      v.element(i).fail("field \"" + f + "\" is listed twice");
  }
}

} // namespace cellphase::scene
