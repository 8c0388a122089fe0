// A MUMPS control written as a PETSc option: mat_mumps_icntl_<1..60> with an integer,
// mat_mumps_cntl_<1..15> with a number. One reader for the scene's checks
// (scene/ReadPetsc.cpp) and for the solver that hands the controls to MUMPS
// (solve/LinearSolver.cpp).
#pragma once
#include <string>

namespace cellphase::scene
{
struct MumpsControl
{
  enum class Status
  {
    not_a_control, ///< the key names another option
    ok,
    bad_index,     ///< no such ICNTL/CNTL in MUMPS
    bad_value      ///< not an integer (ICNTL) or not a number (CNTL)
  };
  Status status = Status::not_a_control;
  bool integer = false; ///< ICNTL (integer) or CNTL (real)
  int index = 0;        ///< 1-based, as in the MUMPS user guide
  double value = 0;
  int last_index() const { return integer ? 60 : 15; }
  std::string stem() const { return integer ? "mat_mumps_icntl_" : "mat_mumps_cntl_"; }
};

MumpsControl read_mumps_control(const std::string& key, const std::string& value);
} // namespace cellphase::scene
