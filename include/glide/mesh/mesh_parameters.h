#pragma once

#include <glide/mesh/mesh_file.h>

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <string>
#include <vector>

namespace glide
{
  /**
   * How the mesh of one body is made: a built-in builder with its geometric
   * parameters, or a mesh file, plus refinement of that body. Declared inside
   * the body's subsection of the scene.
   */
  struct MeshParameters
  {
    /// One of the names in builder_names(), or "file".
    std::string type = "block";
    /// Mesh file (Gmsh .msh or Abaqus .inp) for type "file"; relative paths
    /// are taken relative to the scene file.
    std::string file;
    /// The body's cells in the file: an element set (Abaqus *ELSET, Gmsh
    /// physical group) and/or an Abaqus part or instance; empty: all.
    std::string element_set;
    std::string part;
    /// The body as read from the file when the scene was read (null for
    /// built-in meshes; build_body_mesh() reads the file if it is null).
    std::shared_ptr<const ImportedMesh> imported;

    // Block
    std::vector<double>       lower_corner{0., 0., 0.};
    std::vector<double>       upper_corner{1., 1., 1.};
    std::vector<unsigned int> subdivisions{1, 1, 1};

    // Round shapes (cylinder, half cylinder, hertz, ring, sphere octant)
    std::vector<double> center{0., 0., 0.};
    double              radius       = 1.;
    double              inner_radius = 0.5;
    double              length       = 1.; // extent along z in 3D

    /// Set by the scene: the analysis is axisymmetric ('hertz' then builds
    /// the meridian section of a sphere).
    bool axisymmetric = false;

    // Refinement of this body after the bodies have been put together.
    unsigned int        global_refinements = 0;
    unsigned int        local_refinements  = 0;
    std::vector<double> refinement_point;
    double              refinement_radius         = 0.;
    double              minimum_refinement_radius = 0.;

    /// Lower-case extension of the mesh file (".msh", ".inp", ...).
    std::string
    extension() const;
    /// True for a Gmsh file.
    bool
    is_gmsh() const;

    /// Names of the built-in builders, '|'-separated, for Patterns::Selection.
    static std::string
    builder_names();

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    /// @p path is the subsection path, for error messages.
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &path,
                     const std::string        &scene_directory,
                     const unsigned int        dim);
    /// Check that every point has @p dim components; @p path names the
    /// body's subsection in messages.
    void
    check_sizes(const unsigned int dim, const std::string &path) const;
  };
} // namespace glide
