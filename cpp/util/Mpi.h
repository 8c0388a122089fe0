// Small MPI conveniences.
#pragma once
#include <mpi.h>

namespace cellphase
{
inline int rank_of(MPI_Comm comm)
{
  int r;
  MPI_Comm_rank(comm, &r);
  return r;
}
} // namespace cellphase
