// The time loop of one scene: initial mesh and fields, then step, remesh, observe, write.
#pragma once
#include "io/FieldWriter.h"
#include "io/ObservablesCsv.h"
#include "mesh/AdaptiveMesh.h"
#include "physics/Observables.h"
#include "physics/PhaseFieldModule.h"
#include "scene/Scene.h"
#include <memory>
#include <stdexcept>

namespace cellphase
{
/// A run that failed numerically (non-finite field); the message names field, step and time.
struct NumericalFailure : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

class Simulation
{
public:
  Simulation(const scene::Scene& scene, MPI_Comm comm);
  /// Run to the scene's end time; throws NumericalFailure or SolverError.
  void run();

private:
  void initialise();
  double remesh(double& volume_change);
  void record(int step, double time, const StepTimings& timings, double remesh_time,
              double volume_change);
  void log(const char* fmt, ...) const;

  const scene::Scene& scene_;
  MPI_Comm comm_;
  AdaptiveMesh adaptive_;
  PhaseFieldModule module_;
  std::unique_ptr<Observables> observables_;
  std::unique_ptr<ObservablesCsv> csv_;
  std::unique_ptr<FieldWriter> writer_;
};
} // namespace cellphase
