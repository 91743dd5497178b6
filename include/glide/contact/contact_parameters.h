#pragma once

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <string>
#include <vector>

namespace glide
{
  /// How a contact pair's constraint is enforced (P2.3).
  enum class Enforcement
  {
    hard,   ///< Lagrange multiplier per slave node, semismooth NCP in KINSOL
    penalty ///< p = eps max(0, -g), no extra unknowns
  };

  /// The kinds of master surface.
  enum class MasterType
  {
    surface,      ///< a surface of a deformable body (not available yet)
    rigid_plane,  ///< analytical rigid line (2D) or plane (3D)
    rigid_circle, ///< analytical rigid circle (2D) or cylinder along z (3D)
    rigid_sphere  ///< analytical rigid sphere (3D; a circle in 2D)
  };

  /**
   * One contact pair of a scene, declared in `subsection Contact pair
   * <name>` (R1.3, R3, R5, P1.4). The slave is a surface `<body>.<surface>`
   * or a node set; the master is a body surface or an analytical rigid
   * surface moved by a prescribed rigid motion.
   */
  struct ContactPairParameters
  {
    std::string name;
    std::string slave;
    MasterType  master_type = MasterType::rigid_plane;
    std::string master; ///< master surface, for MasterType::surface

    // Rigid master geometry (reference configuration) and motion.
    std::vector<double> point{0., 0., 0.};  ///< plane point / circle center
    std::vector<double> normal{0., 1., 0.}; ///< plane normal, towards the slave
    double              radius       = 1.;
    bool                slave_inside = false; ///< slave inside circle/sphere
    std::string         translation;          ///< u(t), ';'-separated
    std::string         rotation = "0";       ///< angle(t) in radians
    std::vector<double> rotation_center{0., 0., 0.};
    std::array<double, 3> rotation_axis{{0., 0., 1.}}; ///< unit vector

    std::string formulation = "node to surface";
    std::string sliding     = "finite";
    double      smoothing   = 0.2;
    Enforcement enforcement = Enforcement::hard;
    /// Penalty stiffness (stress per length); 0: 1000 E_max / h.
    double penalty_stiffness = 0.;
    bool   symmetrized       = false;
    /// Small sliding: user normals at master nodes (R8.1), per node set.
    std::vector<std::pair<std::string, std::vector<double>>> master_normals;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &name,
                     const unsigned int        dim);
  };
} // namespace glide
