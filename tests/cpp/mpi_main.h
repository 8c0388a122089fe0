// main() of the GoogleTest executables that use DOLFINx: MPI and PETSc around the tests.
#pragma once
#include <gtest/gtest.h>
#include <dolfinx/common/log.h>
#include <petscsys.h>

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  dolfinx::init_logging(argc, argv); // warnings only
  PetscInitialize(&argc, &argv, nullptr, nullptr);
  const int status = RUN_ALL_TESTS();
  PetscFinalize();
  return status;
}
