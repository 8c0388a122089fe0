// Readers for the top-level sections of a scene file; each validates its keys and fills
// its part of the Scene. Called in the order of SceneLoader.cpp (later sections may use
// earlier ones, e.g. cells need the dimension).
#pragma once
#include "scene/Scene.h"
#include "scene/YamlRead.h"

namespace cellphase::scene
{
void read_domain(const yaml::Section& top, Scene& s);       ///< domain, boundary
void read_boundary(const yaml::Section& top, Scene& s);
void read_phase_field(const yaml::Section& top, Scene& s);  ///< phase_field
void read_numbers(const yaml::Section& top, Scene& s);      ///< numbers or units
void read_numerics(const yaml::Section& top, Scene& s);     ///< numerics
/// numerics.coupling needs a flow and time_scheme: bdf2 (after all sections are read)
void check_coupling(const yaml::Section& top, const Scene& s);
void read_cells(const yaml::Section& top, Scene& s);        ///< cells (shapes only)
void read_flow(const yaml::Section& top, Scene& s);         ///< flow (optional)
void read_interaction(const yaml::Section& top, Scene& s);  ///< interaction (after cells)
/// reaction_diffusion (optional, after cells and flow)
void read_reaction_diffusion(const yaml::Section& top, Scene& s);
/// polar_gel (optional, after cells, flow and reaction_diffusion)
void read_polar_gel(const yaml::Section& top, Scene& s);
void read_output(const yaml::Section& top, Scene& s);       ///< output (after flow)
/// numerics.petsc and flow.petsc: PETSc option names without the leading '-' and single
/// values, passed on as text; a MUMPS control (mat_mumps_icntl_<1..60>, mat_mumps_cntl_<1..15>)
/// must be an integer or a number.
void read_petsc_options(const yaml::Section& p, std::map<std::string, std::string>& out);
/// numerics.solver, flow.solver, reaction_diffusion.solver: `direct` or `reuse`.
Numerics::Solver read_solver(const yaml::Section& s, Numerics::Solver fallback);
/// How messages and reports name a cell: cells[1], or cells[1] ("rbc") if it has a name.
std::string cell_label(std::size_t i, const Cell& c);
/// Checks across sections: cells inside the domain and disjoint, mesh resolution reachable.
void check_geometry(const yaml::Section& top, const Scene& s);
/// numerics.split: names of the scene's sub-problems, each once, and a plan whose every
/// read field is written by a listed sub-problem or is initial data (scene/Plan.h).
void check_split(const yaml::Section& top, const Scene& s);
} // namespace cellphase::scene
