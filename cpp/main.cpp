// cellphase: phase-field simulations of vesicles and cells.
//   cellphase run SCENE [--set key=value ...] [--restart RUNDIR]
//   cellphase check SCENE [--set key=value ...]
#include "app/Simulation.h"
#include "scene/Check.h"
#include "scene/SceneLoader.h"
#include "solve/LinearSolver.h"
#include <dolfinx/common/log.h>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
const char* usage = R"(cellphase - finite-element phase-field simulations of vesicles and cells

Usage:
  cellphase run SCENE [--set KEY=VALUE ...]    run the experiment described by SCENE
  cellphase run SCENE --restart RUNDIR [--set KEY=VALUE ...]
                                               continue the run in RUNDIR from its newest
                                               valid checkpoint (any number of MPI ranks)
  cellphase check SCENE [--set KEY=VALUE ...]  validate SCENE and print the derived numbers,
                                               mesh resolution, expected size and the
                                               operator split (what each sub-problem
                                               reads and writes), then exit
  cellphase --help                             this text
  cellphase --version

SCENE is a YAML file (see docs/scenes.md). --set overrides one key of the scene, with the
value written as in YAML, for example:
  cellphase run demos/vesicle-relaxation/scene.yaml --set numerics.epsilon=0.02 \
      --set output.directory=eps002
Cells are addressed by index: --set cells.0.radius=0.8.

A run writes into output.directory:
  observables.csv   one row per step: time, volume, membrane length/area, energies,
                    centre of mass, circularity, dofs, wall time per part of the step;
                    with several cells also per-cell columns (<cell>.volume, ...),
                    interaction_energy and overlap_max; with reaction_diffusion the
                    species' amounts (rd_mass, ...) and the front and rear of c1;
                    with polar_gel the orientation energy and mean (polar_energy, ...)
  fields.xdmf       the fields every output.every steps, one grid per time holding every
                    field (open in ParaView; data in fields/, where each step-<n>.xdmf
                    opens on its own); output.format: vtk writes fields.pvd instead
                    (second-order cells); a restart continues the index; with own
                    cell meshes also cell.<name>.xdmf, each cell on its mesh
  checkpoints/      checkpoint-<step>.cpk every output.checkpoints.every steps and at the
                    end (the newest output.checkpoints.keep are kept)
Ctrl-C, SIGTERM or SIGUSR1 (a queue's time limit) stops the run after the current step
with a checkpoint and prints the command that continues it; a second Ctrl-C stops at once.
Under mpirun send SIGUSR1 to mpirun (it forwards it to every rank; SIGTERM makes it kill
the ranks at once), e.g. #SBATCH --signal=B:USR1@300 with Slurm.
A run that fails numerically (NaN, diverging solver, phi beyond numerics.limits.phi_bound,
volume drift beyond numerics.limits.volume_drift) writes its last good state as a
checkpoint and as fields, and stops. numerics.stop_when_settled ends a run before
end_time once an observable has settled (its final state written and checkpointed).
Run in parallel with: mpirun -n 2 -x OPENBLAS_NUM_THREADS=1 cellphase run SCENE
(one BLAS thread per rank). A rank with a CPU to spare assembles part of the Helfrich step
on a second thread (same results); OMP_NUM_THREADS=1 keeps it on one.

Exit status: 0 success (end_time reached or settled), 2 invalid scene or arguments (or no valid checkpoint to restart
from), 3 numerical failure, 4 other errors (for example an output directory that cannot be
written), 5 stopped by SIGINT, SIGTERM or SIGUSR1 after writing a checkpoint.
)";

struct Arguments
{
  std::string command, scene;
  std::vector<std::string> overrides;
  std::string restart_dir; ///< empty: a new run
};

/// Parse argv; returns false with a message for bad usage.
bool parse(int argc, char** argv, Arguments& args, std::string& error)
{
  if (argc < 2)
  {
    error = "missing command (run or check)";
    return false;
  }
  args.command = argv[1];
  for (int i = 2; i < argc; ++i)
  {
    std::string a = argv[i];
    if (a == "--set")
    {
      if (i + 1 >= argc || std::strchr(argv[i + 1], '=') == nullptr)
      {
        error = "--set needs KEY=VALUE, for example --set numerics.dt=1e-3";
        return false;
      }
      args.overrides.push_back(argv[++i]);
    }
    else if (a.rfind("--set=", 0) == 0)
      args.overrides.push_back(a.substr(6));
    else if (a == "--restart" || a.rfind("--restart=", 0) == 0)
    {
      if (a == "--restart" && (i + 1 >= argc || argv[i + 1][0] == '-'))
      {
        error = "--restart needs the run directory to continue, for example --restart output";
        return false;
      }
      args.restart_dir = a == "--restart" ? argv[++i] : a.substr(10);
      if (args.restart_dir.empty())
      {
        error = "--restart needs the run directory to continue, for example --restart output";
        return false;
      }
    }
    else if (a.rfind("-", 0) == 0)
    {
      error = "unknown option '" + a + "' (allowed: --set KEY=VALUE, --restart RUNDIR)";
      return false;
    }
    else if (args.scene.empty())
      args.scene = a;
    else
    {
      error = "more than one scene file given ('" + args.scene + "' and '" + a + "')";
      return false;
    }
  }
  if (args.command != "run" && args.command != "check")
  {
    error = "unknown command '" + args.command + "' (allowed: run, check)";
    return false;
  }
  if (args.scene.empty())
  {
    error = "missing scene file after '" + args.command + "'";
    return false;
  }
  if (!args.restart_dir.empty() && args.command != "run")
  {
    error = "--restart goes with 'run', not with '" + args.command + "'";
    return false;
  }
  return true;
}

/// Rank given by the MPI launcher's environment (0 when not started by mpirun).
int launcher_rank()
{
  for (const char* var : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* v = std::getenv(var))
      return std::atoi(v);
  return 0;
}

/// sim.run(), stopping every rank at once on an unexpected error. The errors the program
/// raises on purpose (numerical failure, interruption, bad scene or restart, solver
/// failure) are raised on every rank and pass through. Any other may be one rank's alone:
/// the others then wait in a collective call, and so would the simulation's destructors
/// (MUMPS and PETSc objects free collectively), so the run would hang without a word.
void run_or_abort(cellphase::Simulation& sim, int rank)
{
  try
  {
    sim.run();
  }
  catch (const cellphase::NumericalFailure&) { throw; }
  catch (const cellphase::Interrupted&) { throw; }
  catch (const cellphase::scene::SceneError&) { throw; }
  catch (const cellphase::RestartError&) { throw; }
  catch (const cellphase::SolverError&) { throw; }
  catch (const std::exception& e)
  {
    int ranks;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (ranks == 1)
      throw;
    std::fprintf(stderr, "error on rank %d: %s\n", rank, e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 4);
  }
}

int run(const cellphase::scene::Scene& scene, bool restart)
{
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int status = 0;
  try
  {
    cellphase::Simulation sim(scene, MPI_COMM_WORLD, restart);
    run_or_abort(sim, rank);
  }
  catch (const cellphase::NumericalFailure& e)
  {
    if (rank == 0)
      std::fprintf(stderr, "error: %s\n", e.what());
    status = 3;
  }
  catch (const cellphase::Interrupted& e)
  {
    if (rank == 0)
      std::printf("cellphase: %s\n", e.what());
    status = 5;
  }
  catch (const cellphase::scene::SceneError& e) // found once the run knows its columns
  {
    if (rank == 0)
      std::fprintf(stderr, "error: %s\n", e.what());
    status = 2;
  }
  catch (const cellphase::RestartError& e)
  {
    if (rank == 0)
      std::fprintf(stderr, "error: %s\n", e.what());
    status = 2;
  }
  catch (const cellphase::SolverError& e)
  {
    if (rank == 0)
      std::fprintf(stderr, "error: numerical failure: %s\n", e.what());
    status = 3;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "error: %s\n", e.what());
    status = 4;
  }
  return status;
}
} // namespace

int main(int argc, char** argv)
{
  // --help anywhere (cellphase run --help, cellphase check SCENE -h) prints the usage.
  auto asks_for_help = [](const char* a)
  { return !std::strcmp(a, "--help") || !std::strcmp(a, "-h"); };
  if (argc >= 2 && (std::any_of(argv + 1, argv + argc, asks_for_help)
                    || !std::strcmp(argv[1], "help")))
  {
    std::fputs(usage, stdout);
    return 0;
  }
  if (argc >= 2 && !std::strcmp(argv[1], "--version"))
  {
    std::puts("cellphase 0.1 (DOLFINx 0.5)");
    return 0;
  }
  Arguments args;
  std::string error;
  if (!parse(argc, argv, args, error))
  {
    std::fprintf(stderr, "error: %s\nRun 'cellphase --help' for usage.\n", error.c_str());
    return 2;
  }

  cellphase::scene::Scene scene;
  try
  {
    // A restart continues in its run directory: that is where output goes.
    if (!args.restart_dir.empty())
    {
      args.overrides.push_back("output.directory=" + args.restart_dir);
      if (!std::filesystem::is_directory(args.restart_dir))
        throw cellphase::scene::SceneError("cannot restart: '" + args.restart_dir
                                           + "' is not a directory");
    }
    scene = cellphase::scene::load_scene(args.scene, args.overrides);
  }
  catch (const cellphase::scene::SceneError& e)
  {
    // The scene is read before MPI starts; under mpirun only the first rank reports.
    if (launcher_rank() == 0)
      std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  if (args.command == "check")
  {
    std::fputs(cellphase::scene::check_report(scene).c_str(), stdout);
    return 0;
  }

  // Only a run needs MPI and PETSc; DOLFINx objects are destroyed inside run().
  int provided;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  dolfinx::init_logging(argc, argv); // DOLFINx logs warnings only
  PetscInitializeNoArguments();
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr); // errors become messages, not aborts
  // Output piped into a reader that stops early (cellphase run ... | head) must not abort
  // the run through PETSc's signal handler: a closed pipe only drops the log lines.
  std::signal(SIGPIPE, SIG_IGN);
  const int status = run(scene, !args.restart_dir.empty());
  PetscFinalize();
  MPI_Finalize();
  return status;
}
