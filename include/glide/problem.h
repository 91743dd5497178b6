#pragma once

#include <glide/scene/scene.h>

#include <mpi.h>

namespace glide
{
  /**
   * One run of a scene (DESIGN.md, "How one solve flows"): set up the
   * bodies, then for each load step let KINSOL solve F(U) = 0, cutting the
   * step back when it fails, and after each converged step write the
   * statistics row and the VTU file. Returns normally when the last step
   * converged; throws std::runtime_error with the reason when a step fails
   * after all cut-backs, and InputError for mistakes in the scene.
   */
  template <int dim>
  void
  run_scene(const Scene &scene, MPI_Comm comm);
} // namespace glide
