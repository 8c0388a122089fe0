#include "core/FieldRegistry.h"
#include "mesh/FieldTransfer.h"
#include <algorithm>
#include <stdexcept>

namespace cellphase
{
void FieldRegistry::declare(const FieldInfo& info)
{
  if (info_.count(info.name))
    throw std::logic_error("field " + info.name + " is declared twice (by " + info.owner
                           + " and " + info_.at(info.name).owner + ")");
  if (!by_label(info.label).empty())
    throw std::logic_error("output label " + info.label + " of " + info.name
                           + " is already used by " + by_label(info.label));
  info_[info.name] = info;
  order_.push_back(info.name);
}

void FieldRegistry::set(const std::string& name, std::shared_ptr<Function> f)
{
  if (!info_.count(name))
    throw std::logic_error("field " + name + " is set but was never declared");
  functions_[name] = std::move(f);
}

std::shared_ptr<Function> FieldRegistry::get(const std::string& name) const
{
  auto f = find(name);
  if (!f)
    throw std::out_of_range("field " + name + (declared(name) ? " has no value yet"
                                                              : " is not declared by any sub-problem"));
  return f;
}

std::shared_ptr<Function> FieldRegistry::find(const std::string& name) const
{
  auto it = functions_.find(name);
  return it == functions_.end() ? nullptr : it->second;
}

std::shared_ptr<Function> FieldRegistry::take(const std::string& name,
                                              std::shared_ptr<const Space> V, bool& fresh)
{
  auto f = find(name);
  fresh = !f;
  if (!f)
    f = std::make_shared<Function>(V);
  else if (f->function_space() != V)
  {
    auto copy = std::make_shared<Function>(V);
    copy->interpolate(*f); // same element and mesh: a copy in V's dof order
    f = copy;
  }
  f->name = info(name).label;
  set(name, f);
  return f;
}

const FieldInfo& FieldRegistry::info(const std::string& name) const
{
  auto it = info_.find(name);
  if (it == info_.end())
    throw std::out_of_range("field " + name + " is not declared by any sub-problem");
  return it->second;
}

std::string FieldRegistry::by_label(const std::string& label) const
{
  for (const auto& name : order_)
    if (info_.at(name).label == label)
      return name;
  return "";
}

double FieldRegistry::scalar(const std::string& name) const
{
  auto it = scalars_.find(name);
  if (it == scalars_.end())
    throw std::out_of_range("scalar " + name + " is not published by any sub-problem");
  return it->second;
}

void FieldRegistry::set_mesh(const std::string& key, std::shared_ptr<Mesh> mesh,
                             std::optional<std::array<double, 6>> cut)
{
  meshes_[key] = {mesh, nullptr, nullptr, cut};
}

std::shared_ptr<Mesh> FieldRegistry::mesh(const std::string& key) const
{
  auto it = meshes_.find(key);
  if (it == meshes_.end())
    throw std::out_of_range("no mesh " + (key.empty() ? std::string("(shared)") : key)
                            + " is set");
  return it->second.mesh;
}

std::shared_ptr<Space> FieldRegistry::space(const std::string& key, FieldSpace kind)
{
  mesh(key); // names a missing mesh
  MeshEntry& e = meshes_[key];
  const int dim = e.mesh->topology().dim();
  if (kind == FieldSpace::scalar_p2)
    return e.scalar ? e.scalar : e.scalar = create_p2_space(e.mesh, dim);
  if (kind == FieldSpace::vector_p2)
    return e.vector ? e.vector : e.vector = create_vector_p2_space(e.mesh, dim);
  throw std::logic_error("fields of space 'other' are built by their owners");
}

std::vector<std::string> FieldRegistry::mesh_keys() const
{
  std::vector<std::string> keys{""};
  for (const auto& name : order_)
  {
    const std::string& key = info_.at(name).mesh;
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      keys.push_back(key);
  }
  return keys;
}
} // namespace cellphase
