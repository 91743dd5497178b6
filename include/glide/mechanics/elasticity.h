#pragma once

#include <glide/material/material.h>
#include <glide/mesh/mesh.h>
#include <glide/scene/scene.h>
#include <glide/study/manufactured_solution.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace glide
{
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  /// If @p failure is non-empty on any process, throw std::runtime_error
  /// with the first such message on every process (so that no process is
  /// left waiting in a collective call).
  void
  throw_on_any_process(const std::string &failure, MPI_Comm comm);
  using MatrixType = dealii::TrilinosWrappers::SparseMatrix;

  /**
   * The elastic bodies of a scene: mesh, finite element, DoFs,
   * constraints, and the residual F(U) = f_int(U) - f_ext(t) with its
   * Jacobian (P1.1, P1.2, P1.5). Plane strain, axisymmetric and 3D
   * analyses share one assembly in which every kinematic quantity is a 3x3
   * tensor: plane strain has zero out-of-plane gradient, axisymmetric
   * analysis (x = r, y = z) adds the hoop term u_r / r and integrates with
   * 2 pi r. A geometrically linear scene evaluates only the linear elastic
   * law; the neo-Hookean law, and with it F, J and F^{-1}, exists only in
   * geometrically nonlinear scenes (P4.2).
   *
   * Dirichlet conditions (fixed, displacement, XSYMM/YSYMM/ZSYMM, and
   * u_r = 0 on the axis of axisymmetric scenes) are imposed on U itself:
   * constraints_at(t) holds the values at load factor t, and the Newton
   * system uses the homogeneous constraints, so every Newton update
   * keeps them.
   */
  template <int dim>
  class Elasticity
  {
  public:
    Elasticity(const Scene &scene, MPI_Comm comm, dealii::TimerOutput &timer);

    /// Mesh, DoFs, boundary conditions; checks every surface name and
    /// function of the scene (InputError) before anything is computed.
    void
    setup();

    /// Constraints and the sparsity pattern of the whole system: the
    /// displacement DoFs plus the @p extra unknowns (contact multipliers,
    /// numbered after the displacements); @p add_couplings adds their
    /// couplings to the pattern. @p ghosts: DoFs of other processes that
    /// the couplings reach (contact with a master surface on another
    /// process): their rows are assembled here and sent to their owners,
    /// and their constraints are brought from the owners.
    void
    setup_system(const dealii::IndexSet &extra = dealii::IndexSet(),
                 const std::function<void(dealii::DynamicSparsityPattern &)>
                                        &add_couplings = {},
                 const dealii::IndexSet &ghosts        = dealii::IndexSet());

    /// The displacement part of @p U with ghost entries, for evaluation
    /// on cells.
    VectorType
    ghosted_displacement(const VectorType &U) const;

    /// Vertices of a node set or of surfaces (comma-separated
    /// <body>.<surface>), with their DoFs; only vertices with owned DoFs if
    /// @p owned_only, else also those of ghost cells. Throws InputError for
    /// node-set points that match no vertex.
    std::vector<std::pair<std::array<dealii::types::global_dof_index, dim>,
                          dealii::Point<dim>>>
    find_nodes(const std::string &surface,
               const std::string &parameter,
               const bool         owned_only) const;

    /// Constraints with the prescribed values at load factor @p t.
    dealii::AffineConstraints<double>
    constraints_at(const double t) const;

    /// F(U) at load factor @p t (condensed: zero on constrained rows).
    void
    residual(const VectorType &U, const double t, VectorType &F) const;

    /// Jacobian dF/dU at @p U.
    void
    jacobian(const VectorType &U, MatrixType &J) const;

    /// F(U) + K(U) D at load factor @p t, condensed like residual(): the
    /// right-hand side of the tangent predictor, with @p D the change of
    /// the prescribed values over the step (nonzero on constrained DoFs
    /// only). K(U) D is formed cell by cell, before condensation, so that
    /// the free rows see the prescribed increment.
    void
    predictor_residual(const VectorType &U,
                       const VectorType &D,
                       const double      t,
                       VectorType       &F) const;

    /// Total reaction force of each Dirichlet boundary condition (by its
    /// name): the unconstrained residual summed over the DoFs it
    /// constrains (a DoF shared by two conditions counts for both), plus
    /// @p contact_forces there if given (Contact::nodal_forces(): a slave
    /// or master node whose displacement is prescribed passes its contact
    /// force to its support).
    std::map<std::string, dealii::Tensor<1, dim>>
    reactions(const VectorType &U,
              const double      t,
              const VectorType *contact_forces = nullptr) const;

    /// L2 and H1-seminorm errors against the manufactured solution.
    std::pair<double, double>
    errors(const VectorType &U) const;

    /// Near-null-space vectors for AMG: translations, and rotations
    /// except in axisymmetric analysis.
    std::vector<VectorType>
    rigid_body_modes() const;

    /// The largest Young's modulus of the deformable bodies (of all bodies
    /// if every one is rigid): the stiffness scale of the scene.
    double
    youngs_modulus_scale() const
    {
      return max_youngs_modulus;
    }

    /// The smallest Young's modulus of the deformable bodies.
    double
    softest_youngs_modulus() const
    {
      return min_youngs_modulus;
    }

    /// Scaling of residual rows so that the tolerance is unit-free: 1 /
    /// (E_min A_ref), A_ref the mean boundary-face measure, E_min the
    /// softest deformable body's modulus. The forces a scene carries are
    /// set by its softest body (a stiff body pressed into a soft one sees
    /// the soft one's pressures): with E_max instead, the equilibrium of a
    /// body 1e6 times softer was resolved to 1e-4 only, and with each
    /// body's own modulus the load on the stiff one sat at the tolerance.
    double
    residual_scale() const
    {
      return 1. / (min_youngs_modulus * reference_area);
    }

    /// The scaled residual (units of residual_scale()) that round-off
    /// alone can leave: 10 machine epsilons times the largest P-wave
    /// modulus lambda + 2 mu of the deformable bodies over E_min, or times
    /// the largest scaled nodal load if that is larger (loads that strain
    /// the bodies by hundreds; after check_inputs()). A stress
    /// lambda ln J (or lambda tr eps) is computed from a volume change that
    /// carries round-off of a few epsilon, so a nearly incompressible or a
    /// much stiffer body leaves residual noise of about that size (3D
    /// ironing, a die with E = 1000 and nu = 0.499 on a slab with E = 1:
    /// the residual stalled at 1.1e-10 to 1.6e-10, floor 3.7e-10).
    double
    round_off_floor() const;

    /// Whether the loads, not the stiffest body, set round_off_floor().
    bool
    round_off_floor_from_loads() const;

    /// How much the scene's loads and prescribed displacements strain its
    /// bodies (after check_inputs()): the largest scaled nodal load
    /// (units of residual_scale(), a strain) or the largest prescribed
    /// displacement over the scene's size, whichever is larger, at the
    /// first and the last load factor; 0 if neither loads nor moves.
    double
    driving_strain() const
    {
      return driving_strain_;
    }

    /// Young's modulus of body @p b, +infinity for a rigid body.
    double
    youngs_modulus_of_body(const unsigned int b) const;

    /// Length that makes displacements unit-free (scene size).
    double
    length_scale() const
    {
      return mesh.scene_size();
    }

    /**
     * Input checks that need the mesh and the constraints, before anything
     * is written (InputError): every deformable body is held against each
     * rigid-body motion by a Dirichlet condition or is in a contact pair;
     * every function of the scene is finite at the first and the last load
     * factor; the moduli and penalty stiffnesses stay within what double
     * precision resolves together.
     */
    void
    check_inputs();

    /// Warnings about the scene's conditions for the log, from
    /// check_inputs() (conditions that prescribe different values for the
    /// same DoF).
    const std::vector<std::string> &
    condition_warnings() const
    {
      return condition_notes;
    }

    /// For a failed load step: bodies that only contact holds, with the
    /// motions nothing else stops (empty if every body is held).
    std::string
    holding_hint() const;

    /// A rigid-body motion of a body that no Dirichlet condition stops.
    struct FreeMotion
    {
      /// For people: "translation in x", "rotation about z around (1,
      /// 0.5)".
      std::string text;
      /// A rotation (not a translation): about `axis` (unit; z in 2D)
      /// through `point`. A translation: along `axis` (unit).
      bool                 rotation = false;
      dealii::Point<dim>   point;
      dealii::Tensor<1, 3> axis;
    };

    /// The free motions of each body; empty for a held body and for rigid
    /// bodies.
    std::vector<std::vector<FreeMotion>>
    free_motions() const;

    /// The connected parts of the bodies: cells of one body that share no
    /// vertex, even through other cells, are separate parts (a mesh file
    /// may hold several). On every process.
    struct Parts
    {
      std::vector<unsigned int>       part_of_coarse_cell;
      std::vector<unsigned int>       body;   ///< of each part
      std::vector<dealii::Point<dim>> center; ///< of each part's box
    };
    Parts
    parts() const;

    /// Of the surfaces @p names (<body>.<surface>, on any process), those
    /// that are round about the rotation @p m: the velocity of the turn
    /// has no component along any face normal beyond 1 % of its size
    /// (every face normal points at the axis, e.g. a cylinder's curved
    /// surface and a turn about its centre). Frictionless contact on such
    /// a surface does not resist the turn. The axis is the one through
    /// m.point: where translations across it are free too, the axis of a
    /// free turn is not unique, and a surface round about another,
    /// parallel axis is not found. Collective.
    std::vector<std::string>
    round_about(const std::vector<std::string> &names,
                const FreeMotion               &m) const;

    /// The list of effects this scene computes (P4.2), for the log.
    std::vector<std::string>
    active_effects() const;

    const dealii::DoFHandler<dim> &
    get_dof_handler() const
    {
      return dof_handler;
    }
    const dealii::Mapping<dim> &
    get_mapping() const
    {
      return *mapping;
    }
    /// Unknowns of the whole system owned by this process.
    const dealii::IndexSet &
    locally_owned() const
    {
      return owned_total;
    }
    /// Displacement DoFs owned by this process.
    const dealii::IndexSet &
    displacement_owned() const
    {
      return owned;
    }
    /// Displacement DoFs this process needs (owned and ghost).
    const dealii::IndexSet &
    displacement_relevant() const
    {
      return relevant;
    }
    /// The Jacobian's sparsity pattern (displacements and any extra
    /// unknowns): a matrix is set up from it by reinit(matrix_pattern()).
    /// Only the pattern is kept, no values: a matrix's worth of memory
    /// (a seventh of a 3D contact scene's peak with AMG).
    const dealii::TrilinosWrappers::SparsityPattern &
    matrix_pattern() const
    {
      return pattern;
    }
    const Scene &
    get_scene() const
    {
      return scene;
    }
    const dealii::parallel::distributed::Triangulation<dim> &
    get_triangulation() const
    {
      return triangulation;
    }
    /// Hanging-node and homogeneous Dirichlet constraints of the Newton
    /// updates.
    const dealii::AffineConstraints<double> &
    update_constraints() const
    {
      return homogeneous_constraints;
    }
    /// Hanging-node constraints alone.
    const dealii::AffineConstraints<double> &
    hanging_constraints() const
    {
      return hanging_node_constraints;
    }
    /// The named surfaces.
    const Mesh<dim> &
    get_mesh() const
    {
      return mesh;
    }
    /// The material law of body @p b (fresh object).
    std::unique_ptr<Material>
    material(const unsigned int b) const;

    /// Boundary conditions whose surfaces carry symmetry type @p component
    /// (0: XSYMM, 1: YSYMM, 2: ZSYMM), for contact.
    const std::vector<dealii::types::boundary_id> &
    symmetry_boundary_ids(const unsigned int component) const
    {
      return symmetry_ids[component];
    }

  private:
    struct Load
    {
      const BoundaryConditionParameters   *parameters;
      std::set<dealii::types::boundary_id> ids;
      /// True if the condition acts on node sets (then `nodes` holds this
      /// process's vertices of them, possibly none); `ids` holds the
      /// surfaces of the same condition's list, if any.
      bool on_node_set = false;
      /// For conditions on node sets: vertex DoFs and positions.
      std::vector<std::pair<std::array<dealii::types::global_dof_index, dim>,
                            dealii::Point<dim>>>
                                                   nodes;
      std::unique_ptr<dealii::FunctionParser<dim>> function;
    };
    /// A meshed rigid body: its DoFs (owned and ghost) with their
    /// component and reference support point, and its motion.
    struct RigidBody
    {
      std::unique_ptr<dealii::FunctionParser<dim>> translation; ///< or null
      std::unique_ptr<dealii::FunctionParser<dim>> rotation;
      dealii::Point<dim>                           center;
      dealii::Tensor<1, 3>                         axis;
      std::vector<std::tuple<dealii::types::global_dof_index,
                             unsigned int,
                             dealii::Point<dim>>>
        dofs;
    };
    std::vector<RigidBody> rigid_bodies;

    struct PointForce
    {
      std::string                                  path; ///< of the condition
      std::unique_ptr<dealii::FunctionParser<dim>> function;
      /// Vertex DoFs (locally owned) per component, with their positions.
      std::vector<std::pair<std::array<dealii::types::global_dof_index, dim>,
                            dealii::Point<dim>>>
        nodes;
    };

    /// Residual and/or Jacobian, condensed with @p constraints; with
    /// @p increment, F also gains K(U) times it (before condensation).
    void
    assemble(const VectorType                        &U,
             const double                             t,
             VectorType                              *F,
             MatrixType                              *J,
             const dealii::AffineConstraints<double> &constraints,
             const VectorType *increment = nullptr) const;


    /// The displacement components a Dirichlet condition prescribes.
    dealii::ComponentMask
    component_mask(const BoundaryConditionParameters &bc) const;

    std::unique_ptr<dealii::FunctionParser<dim>>
    parse_function(const std::string &expression,
                   const unsigned int n_components,
                   const std::string &parameter) const;

    const Scene                                      &scene;
    MPI_Comm                                          comm;
    dealii::TimerOutput                              &timer;
    dealii::parallel::distributed::Triangulation<dim> triangulation;
    Mesh<dim>                                         mesh;
    dealii::FESystem<dim>                             fe;
    std::unique_ptr<dealii::Mapping<dim>>             mapping;
    dealii::DoFHandler<dim>                           dof_handler;
    dealii::IndexSet                                  owned, relevant;
    dealii::IndexSet owned_total, relevant_total;
    /// Are there DoFs of other processes in relevant_total (besides the
    /// usual ghosts) whose constraints the owners must send?
    bool                                      consistent_constraints = false;
    dealii::AffineConstraints<double>         homogeneous_constraints;
    dealii::AffineConstraints<double>         hanging_node_constraints;
    dealii::TrilinosWrappers::SparsityPattern pattern;
    std::vector<Load>                         dirichlet, surface_loads;
    std::vector<PointForce>                   point_forces;
    std::vector<std::unique_ptr<dealii::FunctionParser<dim>>> body_forces;
    std::unique_ptr<ManufacturedSolution<dim>>                exact;
    std::vector<dealii::types::boundary_id>                   symmetry_ids[3];
    std::map<std::string, const NodeSetParameters *>          scene_node_sets;
    std::vector<std::string>                                  holding_hints;
    std::vector<std::string>                                  condition_notes;

    /// Collective, at load factor @p t: conditions that prescribe
    /// different values for the same DoF (the first in 'Boundary
    /// conditions' holds there, as deal.II keeps a DoF's first
    /// constraint). A condition that holds none of its DoFs and differs
    /// from an earlier one, and a radial displacement other than 0 on the
    /// axis of an axisymmetric scene, are input errors; a partial overlap
    /// (a corner shared by two surfaces) is a warning.
    void
    check_conditions(const double t);
    /// free_motions() of groups of cells: @p group gives a cell's group,
    /// @p body_of each group's body.
    std::vector<std::vector<FreeMotion>>
    free_motions_of(
      const std::function<unsigned int(
        const typename dealii::DoFHandler<dim>::active_cell_iterator &)> &group,
      const std::vector<unsigned int> &body_of) const;
    double max_youngs_modulus = 1., min_youngs_modulus = 1.,
           reference_area = 1.;
    /// The largest nodal load at the first and the last load factor, in
    /// units of residual_scale() (set by check_inputs()).
    double largest_scaled_load = 0.;
    /// See driving_strain().
    double driving_strain_ = 0.;
    bool   axisymmetric;
  };
} // namespace glide
