#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace glide
{
  /// Kinds of boundary condition, named as an engineer knows them.
  enum class BoundaryConditionType
  {
    fixed,        ///< all displacement components zero
    displacement, ///< prescribed displacement components u(x, t)
    traction,     ///< traction vector t(x, t) per unit reference area
    pressure,     ///< pressure p(x, t) along the inward normal
    force,        ///< concentrated force on every node of a node set
    xsymm,        ///< symmetry about a plane x = const: u_x = 0
    ysymm,        ///< symmetry about a plane y = const: u_y = 0
    zsymm         ///< symmetry about a plane z = const: u_z = 0 (3D only)
  };

  /**
   * One boundary condition of the scene, declared in
   * `subsection Boundary condition <name>`. The surface (or node set) is
   * named as `<body>.<surface>`; functions are ';'-separated vector
   * expressions in x, y, (z,) t where t is the load factor of the step.
   */
  struct BoundaryConditionParameters
  {
    std::string           name;
    std::string           surface;
    BoundaryConditionType type = BoundaryConditionType::fixed;
    std::vector<bool>     components{true, true, true};
    std::string           function;

    /// True for XSYMM, YSYMM and ZSYMM.
    bool
    is_symmetry() const;
    /// True for conditions that prescribe displacements (rows of U).
    bool
    is_dirichlet() const;
    /// The displacement component a symmetry condition fixes.
    unsigned int
    symmetry_component() const;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &name,
                     const unsigned int        dim);
  };

  /**
   * A named node set: the mesh vertices closest to given points (each point
   * must find a vertex within the tolerance). Every surface is a node set
   * too, under its own name. Node sets of mesh files (`<body>.<set>`) are
   * added by the scene with the coordinates of their nodes and @p body set,
   * so that they never pick a vertex of another body at the same place.
   */
  struct NodeSetParameters
  {
    std::string                      name;
    std::vector<std::vector<double>> points;
    double                           tolerance = 1e-8;
    /// The body (index) whose vertices the set selects; all bodies if
    /// invalid (node sets declared in the scene).
    unsigned int body = static_cast<unsigned int>(-1);

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &name,
                     const unsigned int        dim);
  };
} // namespace glide
