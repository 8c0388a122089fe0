// Every field of a run under one qualified name ("cell.phi", "flow.v", "membrane.c"),
// with what the time loop needs to know about it: which sub-problem owns it, how it moves
// to a new mesh, whether checkpoints and output hold it. Checkpoints, restarts, remesh
// transfer, field output and the NaN check all iterate over this table, so a new field is
// declared once, by its owner, and nothing else changes.
#pragma once
#include "compat/Dolfinx.h"
#include <array>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

namespace cellphase
{
/// Function space a field lives in; fields of one kind on one mesh share the space.
enum class FieldSpace
{
  scalar_p2, ///< phase fields, potentials, concentrations
  vector_p2, ///< velocities
  other      ///< a space its owner builds (pressure, multipliers): never transferred
};

/// How a field reaches a new mesh at a remesh.
enum class Transfer
{
  interpolate,    ///< point evaluation at the new nodes (rank-local, mesh/FieldTransfer)
  keep_integral,  ///< interpolation, then c (1 - phi^2) added so that int phi is kept (3.10)
  recompute       ///< not moved: its owner computes it again on the new mesh
};

struct FieldInfo
{
  std::string name;  ///< qualified: "<sub-problem group>.<field>"
  std::string label; ///< name in the output and in the scene's output.fields
  std::string owner; ///< the sub-problem that writes it
  FieldSpace space = FieldSpace::scalar_p2;
  Transfer transfer = Transfer::interpolate;
  bool checkpointed = true; ///< stored in checkpoints (the loop's history)
  /// The mesh it lives on: "" is the shared mesh (refined around all cells, the flow's);
  /// another key is a mesh of one cell's own (numerics.mesh.cell_meshes: own).
  std::string mesh = "";
  /// Its value outside its mesh (phi = -1 outside a cell's own patch).
  double outside = 0;
  /// Its mesh is refined around its zero level set (as around every keep_integral field).
  bool level_set = false;
  /// A two-step scheme's copy of a field at the step before: it moves to a new mesh as
  /// that field does but never shapes the mesh.
  bool history = false;
};

class FieldRegistry
{
public:
  /// Declare a field (once, before the first mesh). Throws std::logic_error on a second
  /// declaration of the same name or label.
  void declare(const FieldInfo& info);
  /// The function that currently holds the field (after every attach).
  void set(const std::string& name, std::shared_ptr<Function> f);
  /// The field's function; throws std::out_of_range naming it if it has none yet.
  std::shared_ptr<Function> get(const std::string& name) const;
  /// The field's function, or null if it is undeclared or has none yet.
  std::shared_ptr<Function> find(const std::string& name) const;
  /// The field's function in V, named by its label and set as the field's function: the
  /// one moved from the last mesh or restored (copied into V's dof order if it came in
  /// another space of V's element), or in a new run a zero function of V (`fresh` true).
  std::shared_ptr<Function> take(const std::string& name, std::shared_ptr<const Space> V,
                                 bool& fresh);
  bool declared(const std::string& name) const { return info_.count(name) > 0; }
  const FieldInfo& info(const std::string& name) const;
  /// Names in the order of declaration.
  const std::vector<std::string>& names() const { return order_; }
  /// The field whose output label is `label`, or "" if none.
  std::string by_label(const std::string& label) const;
  /// Drop all functions (before a new mesh); declarations stay.
  void clear_functions()
  {
    functions_.clear();
    supports_.clear();
  }
  /// The owned cells outside which a field holds its value outside (FieldInfo::outside)
  /// exactly, on this mesh: a cell's copy on the shared mesh of its field on its own mesh.
  /// Set by the owner after attach; forms that vanish with the field assemble there only.
  void set_support(const std::string& name, std::vector<std::int32_t> cells)
  {
    supports_[name] = std::move(cells);
  }
  /// The field's support, or null: it may differ from its outside value anywhere.
  const std::vector<std::int32_t>* support(const std::string& name) const
  {
    auto it = supports_.find(name);
    return it == supports_.end() ? nullptr : &it->second;
  }

  /// The meshes the fields live on, by the key of FieldInfo::mesh ("" the shared mesh);
  /// set by the time loop before every attach.
  /// `cut` is the box a cell's own mesh was cut around (its band grown by the margin).
  void set_mesh(const std::string& key, std::shared_ptr<Mesh> mesh,
                std::optional<std::array<double, 6>> cut = std::nullopt);
  /// The box mesh `key` was cut around, if it is a cell's own mesh.
  std::optional<std::array<double, 6>> cut_box(const std::string& key) const
  {
    auto it = meshes_.find(key);
    return it == meshes_.end() ? std::nullopt : it->second.cut;
  }
  /// Throws std::out_of_range naming the key if there is no such mesh.
  std::shared_ptr<Mesh> mesh(const std::string& key) const;
  /// The space of a kind (scalar_p2, vector_p2) on mesh `key`: built once per mesh and
  /// shared by the fields of that kind there.
  std::shared_ptr<Space> space(const std::string& key, FieldSpace kind);
  /// Keys of the meshes the declared fields live on ("" first, then in declaration order).
  std::vector<std::string> mesh_keys() const;
  /// The fields whose mesh is refined around their zero level set (see FieldInfo).
  bool shapes_mesh(const std::string& name) const
  {
    const FieldInfo& i = info(name);
    return !i.history && (i.level_set || i.transfer == Transfer::keep_integral);
  }

  /// Named scalars that sub-problems publish for others (e.g. a cell's area target for the
  /// flow's global area constraint); not checkpointed (their owners checkpoint them).
  void set_scalar(const std::string& name, double value) { scalars_[name] = value; }
  double scalar(const std::string& name) const;

private:
  std::map<std::string, FieldInfo> info_;
  std::vector<std::string> order_;
  std::map<std::string, std::shared_ptr<Function>> functions_;
  std::map<std::string, double> scalars_;
  std::map<std::string, std::vector<std::int32_t>> supports_;
  struct MeshEntry
  {
    std::shared_ptr<Mesh> mesh;
    std::shared_ptr<Space> scalar, vector;
    std::optional<std::array<double, 6>> cut;
  };
  std::map<std::string, MeshEntry> meshes_;
};
} // namespace cellphase
