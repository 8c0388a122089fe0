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

inline int size_of(MPI_Comm comm)
{
  int n;
  MPI_Comm_size(comm, &n);
  return n;
}
} // namespace cellphase
