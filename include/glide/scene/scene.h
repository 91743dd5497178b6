#pragma once

#include <glide/contact/contact_parameters.h>
#include <glide/material/material.h>
#include <glide/mechanics/boundary_conditions.h>
#include <glide/mesh/mesh_parameters.h>
#include <glide/output/output_parameters.h>
#include <glide/solver/solver_parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

namespace glide
{
  /// The analysis types of P1.1.
  enum class AnalysisType
  {
    plane_strain,
    axisymmetric,
    three_dimensional
  };

  /// One body: its mesh, its material, its body force.
  struct BodyParameters
  {
    std::string        name;
    MeshParameters     mesh;
    MaterialParameters material;
    /// Body force per unit reference volume, ';'-separated components.
    std::string body_force;
    /// Meshed rigid body (P1.4): every node follows the rigid motion
    /// x = c + T(t) + R(theta(t)) (X - c), R about the unit axis
    /// rigid_axis (z in 2D).
    bool                  rigid = false;
    std::string           rigid_translation; ///< ';'-separated, of t
    std::string           rigid_rotation;    ///< angle about rigid_axis, of t
    std::vector<double>   rigid_center;
    std::array<double, 3> rigid_axis{{0., 0., 1.}};
  };

  /**
   * A scene as read from a `.prm` file (P4.1). Reading happens in two
   * passes: the first reads the lists of names (bodies, boundary
   * conditions, node sets), the second declares one subsection per name and
   * reads the whole file strictly, so that a misspelt entry anywhere is an
   * error that names the file and line. All cross-checks (names that must
   * exist, combinations that are not supported) happen here, before
   * anything is computed or written.
   */
  class Scene
  {
  public:
    std::string  file;      ///< the scene file, as given
    std::string  directory; ///< its directory, for relative mesh paths
    std::string  name;      ///< the scene name (default: file name stem)
    unsigned int dimension              = 2;
    AnalysisType analysis               = AnalysisType::plane_strain;
    unsigned int degree                 = 1;
    bool         geometric_nonlinearity = false;

    std::vector<BodyParameters>              bodies;
    std::vector<BoundaryConditionParameters> boundary_conditions;
    std::vector<NodeSetParameters>           node_sets;
    std::vector<ContactPairParameters>       contact_pairs;
    /// Name of the manufactured solution for verification, or "none".
    std::string manufactured_solution = "none";
    /// Warnings for the log: entries the scene gives (other than their
    /// defaults) that its configuration does not use, each with the
    /// reason (a 'Function' of a fixed boundary, a 'Penalty stiffness'
    /// with hard enforcement, a rigid motion of a deformable body, ...).
    std::vector<std::string> unused;

    NonlinearSolverParameters nonlinear_solver;
    LinearSolverParameters    linear_solver;
    LoadSteppingParameters    load_stepping;
    OutputParameters          output;

    /**
     * Read and check @p filename. @p overrides are "path=value" strings
     * from the command line (`--set "Output/Directory=out"`), applied after
     * the file. Throws InputError on any mistake.
     */
    static Scene
    read(const std::string              &filename,
         const std::vector<std::string> &overrides = {});

    /// Print every parameter with default, pattern and documentation, with
    /// one example body, boundary condition and node set.
    static void
    print_parameters(std::ostream &out, const std::string &format);

    /// "plane strain", "axisymmetric" or "3d".
    std::string
    analysis_name() const;

    /// A lower bound of the bytes a mesh of @p cells cells needs: its cell
    /// data (@p bytes_per_cell, at least 200), the unknowns and the
    /// Jacobian's entries.
    double
    memory_lower_bound(double cells, double bytes_per_cell = 200.) const;

    /// Refuse (InputError) a refinement cycle of the mesh that would make
    /// @p cells cells of @p bytes_per_cell bytes (as measured on the mesh
    /// so far), more than this machine can hold; @p body and @p parameter
    /// ("Global refinements", "Local refinements") are named.
    void
    check_refinement_fits(double             cells,
                          double             bytes_per_cell,
                          const std::string &body,
                          const std::string &parameter) const;

  private:
    static void
    declare_parameters(dealii::ParameterHandler       &prm,
                       const std::vector<std::string> &bodies,
                       const std::vector<std::string> &boundary_conditions,
                       const std::vector<std::string> &node_sets,
                       const std::vector<std::string> &contact_pairs);
    void
    parse_parameters(dealii::ParameterHandler &prm);
    void
    check() const;
    /// The notes of #unused, from the parsed file @p prm and a handler
    /// @p defaults declared with the same names and nothing parsed.
    std::vector<std::string>
    unused_entries(const dealii::ParameterHandler &prm,
                   const dealii::ParameterHandler &defaults) const;
    /// Refuse a mesh that cannot fit in memory, before it is built.
    void
    check_size() const;
  };
} // namespace glide
