// SIGINT, SIGTERM and SIGUSR1 (Ctrl-C, a cluster queue's time limit) ask the run to stop
// after the current step with a checkpoint. A second signal stops the process at once.
// Under mpirun send SIGUSR1 (mpirun forwards it to all ranks; on SIGINT/SIGTERM it kills
// them) or signal the ranks themselves, as batch systems do.
#pragma once
#include <mpi.h>

namespace cellphase::stop_signal
{
/// Install the handlers (once per process).
void install();
/// Whether any rank has received a signal; collective over comm so that all stop together.
bool requested(MPI_Comm comm);
/// Name of the signal received ("SIGINT", "SIGTERM"), or "" if none.
const char* name();
} // namespace cellphase::stop_signal
