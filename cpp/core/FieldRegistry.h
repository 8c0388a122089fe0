// Every field of a run under one qualified name ("cell.phi", "flow.v", "membrane.c"),
// with what the time loop needs to know about it: which sub-problem owns it, how it moves
// to a new mesh, whether checkpoints and output hold it. Checkpoints, restarts, remesh
// transfer, field output and the NaN check all iterate over this table, so a new field is
// declared once, by its owner, and nothing else changes.
#pragma once
#include "compat/Dolfinx.h"
#include <map>
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
  bool declared(const std::string& name) const { return info_.count(name) > 0; }
  const FieldInfo& info(const std::string& name) const;
  /// Names in the order of declaration.
  const std::vector<std::string>& names() const { return order_; }
  /// The field whose output label is `label`, or "" if none.
  std::string by_label(const std::string& label) const;
  /// Drop all functions (before a new mesh); declarations stay.
  void clear_functions() { functions_.clear(); }

  /// Named scalars that sub-problems publish for others (e.g. a cell's area target for the
  /// flow's global area constraint); not checkpointed (their owners checkpoint them).
  void set_scalar(const std::string& name, double value) { scalars_[name] = value; }
  double scalar(const std::string& name) const;

private:
  std::map<std::string, FieldInfo> info_;
  std::vector<std::string> order_;
  std::map<std::string, std::shared_ptr<Function>> functions_;
  std::map<std::string, double> scalars_;
};
} // namespace cellphase
