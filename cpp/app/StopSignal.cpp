#include "app/StopSignal.h"
#include <csignal>

namespace cellphase::stop_signal
{
namespace
{
volatile std::sig_atomic_t received = 0;

extern "C" void on_signal(int sig)
{
  received = sig;
  std::signal(sig, SIG_DFL); // a second Ctrl-C ends the process immediately
}
} // namespace

void install()
{
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGUSR1, on_signal); // Open MPI's mpirun forwards it to every rank
}

bool requested(MPI_Comm comm)
{
  int local = received != 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

const char* name()
{
  switch (received)
  {
  case SIGINT:
    return "SIGINT";
  case SIGTERM:
    return "SIGTERM";
  case SIGUSR1:
    return "SIGUSR1";
  default:
    return received ? "a signal" : "";
  }
}
} // namespace cellphase::stop_signal
