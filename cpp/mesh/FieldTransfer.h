// Moving the fields to a new mesh with phi's integral (the cell volumes, 3.10) kept.
#pragma once
#include "compat/Dolfinx.h"
#include "physics/PhaseFieldModule.h"

namespace cellphase
{
struct TransferReport
{
  double volume_change_interpolated = 0; ///< relative change of int phi~ by interpolation alone
  double volume_change_corrected = 0;    ///< the same after the correction
};

/// New P2 space on `mesh` (the space every field lives in).
std::shared_ptr<Space> create_p2_space(std::shared_ptr<Mesh> mesh, int dim);

/// New vector P2 space on `mesh` (the flow velocity).
std::shared_ptr<Space> create_vector_p2_space(std::shared_ptr<const Mesh> mesh, int dim);

/// Interpolate all fields onto V, then correct phi by c (1 - phi^2) so that int phi is
/// the old one: the correction acts only in the interface and keeps phi = -1 outside.
FieldMap transfer_fields(const FieldMap& old, std::shared_ptr<Space> V, TransferReport& report);

/// After phi was interpolated from phi_old: add c (1 - phi^2) so that int phi equals
/// int phi_old + shift (the correction acts only in the interface); fills the report.
/// The shift is |old mesh| - |new mesh| when the meshes cover different regions (a cell's
/// own patch), so that int (1 + phi), the cell's volume, is kept.
void restore_integral(std::shared_ptr<const Function> phi_old, std::shared_ptr<Function> phi,
                      TransferReport& report, double shift = 0);

/// Add c (1 - phi^2) to phi with c such that int phi grows by `amount`: a change of the
/// cell's volume placed in its interface, phi = -1 outside stays.
void add_in_interface(std::shared_ptr<Function> phi, double amount);

/// int phi dx of a P2 field.
double integral_of(std::shared_ptr<const Function> f);

/// |mesh| of a P2 space: int 1 dx.
double mesh_volume(std::shared_ptr<const Space> V);
} // namespace cellphase
