#pragma once

#include <glide/scene/scene.h>

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/tria.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace glide
{
  /**
   * The bodies of a scene in one distributed triangulation (P1.3), told
   * apart by material id (= body index), with named surfaces. Each body's
   * mesh is built (or read) on its own, its boundary ids are renumbered so
   * that they are unique over the scene, and the bodies are put into one
   * coarse mesh; bodies never share vertices, even where they touch.
   * Refinement then happens per body on the distributed triangulation.
   */
  template <int dim>
  class Mesh
  {
  public:
    /// Build every body of @p scene into @p tria. Throws InputError for
    /// unreadable files and impossible geometry.
    void
    build(const Scene                                       &scene,
          dealii::parallel::distributed::Triangulation<dim> &tria);

    /// Boundary ids of the surface @p name (`<body>.<surface>`); throws an
    /// InputError that lists the known surfaces if there is none such.
    /// @p parameter names the scene parameter, for the message.
    const std::set<dealii::types::boundary_id> &
    surface(const std::string &name, const std::string &parameter) const;

    /// True if the surface exists.
    bool
    has_surface(const std::string &name) const;

    /// All surface names with their boundary ids.
    const std::map<std::string, std::set<dealii::types::boundary_id>> &
    surfaces() const
    {
      return surface_ids;
    }

    /// The names of all surfaces, comma-separated, followed by the node sets
    /// read from mesh files (for messages and logs).
    std::string
    surface_list() const;

    /// Characteristic size of the whole scene (bounding-box diagonal).
    double
    scene_size() const
    {
      return size;
    }

    /// Warnings about the mesh as built: a body whose 'Local refinements'
    /// found no cell to refine at some level (its 'Refinement point' off the
    /// body, or beyond 'Refinement radius' of every cell).
    const std::vector<std::string> &
    notes() const
    {
      return refinement_notes;
    }

  private:
    std::map<std::string, std::set<dealii::types::boundary_id>> surface_ids;
    std::vector<std::string> refinement_notes;
    double                   size = 1.;
    /// Node sets of mesh files (<body>.<set>), for the list of surfaces.
    std::vector<std::string> file_node_sets;
    /// Node sets of mesh files that are not node sets of a body, with the
    /// reason, for the message when the scene names one.
    std::map<std::string, std::string> unavailable;
  };

  /**
   * Build the coarse mesh of one body in @p tria, with surfaces as boundary
   * ids and their names in @p names (without the body prefix): the faces
   * with one boundary id belong to every surface named for it (faces of a
   * mesh file can be in several surfaces). Curved boundaries get manifold
   * ids and manifolds. Exposed for unit tests.
   */
  template <int dim>
  void
  build_body_mesh(
    const MeshParameters                                           &parameters,
    const std::string                                              &body_name,
    dealii::Triangulation<dim>                                     &tria,
    std::map<dealii::types::boundary_id, std::vector<std::string>> &names);
} // namespace glide
