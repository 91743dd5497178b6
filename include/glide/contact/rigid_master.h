#pragma once

#include <glide/contact/contact_parameters.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <limits>
#include <memory>
#include <stdexcept>

namespace glide
{
  /// A slave point at the centre (on the axis) of a rigid circle, cylinder
  /// or sphere, where the normal is undefined (RigidMaster::project()). In
  /// the initial configuration a misplaced master (an input error:
  /// Contact::check_initial_overclosure()); during a load step an
  /// increment that moved the master by its radius against the slave (the
  /// step fails and is cut back).
  struct UndefinedNormal : std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  /**
   * An analytical rigid master surface (P1.4): a plane (a line in 2D), a
   * circle/cylinder (axis along z in 3D) or a sphere, moved by a prescribed
   * rigid motion x -> c + u(t) + R(theta(t)) (x - c). For a slave point x
   * it gives the gap g (positive when open), the contact normal n = dg/dx
   * (unit, pointing from the master towards the slave) and the curvature
   * term d2g/dx2 that the consistent Jacobian needs (zero for a plane,
   * (I - n n) / r for a circle or sphere of current distance r, projected
   * on the plane normal to the axis for a cylinder).
   */
  template <int dim>
  class RigidMaster
  {
  public:
    struct Projection
    {
      double                 gap;
      dealii::Tensor<1, dim> normal;
      dealii::Tensor<2, dim> curvature;
      dealii::Point<dim>     closest_point;
    };

    /// @p parameter_path names the pair in error messages.
    RigidMaster(const ContactPairParameters &parameters,
                const std::string           &parameter_path);

    /// Move the master to load factor @p t.
    void
    set_time(const double t);

    /// Where the centre ('Point', moved by 'Translation' and 'Rotation')
    /// is at load factor @p t.
    dealii::Point<dim>
    centre_at(const double t) const;

    /// Where the master's material point that is at @p y at load factor
    /// @p from is at load factor @p to (for the slip of a slave node).
    dealii::Point<dim>
    move(const dealii::Point<dim> &y, const double from, const double to) const;

    /// Gap, normal and curvature for the slave point @p x (current
    /// position). Throws UndefinedNormal where the normal is undefined
    /// (a slave point on the axis of a circle or at a sphere's center).
    Projection
    project(const dealii::Point<dim> &x) const;

    /// The input error for UndefinedNormal @p e in the initial
    /// configuration: the master is misplaced (its 'Point', 'Radius' or
    /// 'Slave inside').
    std::string
    misplaced(const UndefinedNormal &e) const;

    /**
     * How deep the straight path of a slave point relative to the master,
     * from @p x_old at load factor @p t_old to @p x_new at @p t_new (in
     * the master's own frame), goes into a circle, cylinder or sphere
     * that the point is outside of at its end, beyond the depth it started
     * at: the radius less the path's closest distance to the centre (the
     * axis; the point moving straight while the master moves by its
     * motion, followed in steps where it turns), less the start's depth if
     * it started inside (in contact, or
     * penetrating under penalty). 0 where the path stays outside, where the
     * point ends not more than @p clearance outside (in contact) on the
     * same side of the centre (axis) as it started, or on the far side with
     * its path no closer to the centre than R / 2 (it slid round in
     * contact), for a plane and for a
     * slave inside (a hole: a point outside at its end has never been
     * inside). A master that passed through a slave node within one
     * increment leaves it open at its end, whether it was open or in
     * contact before, or, where the master went only part of the way, in
     * contact on the master's far side, pushed out the wrong way (a circle
     * moved from above a node to below its top in one increment lifted the
     * block, exit 0, until 2026-12-07); Contact::passed_through() compares
     * this with the slave facet size.
     */
    double
    passage_depth(const dealii::Point<dim> &x_old,
                  const double              t_old,
                  const dealii::Point<dim> &x_new,
                  const double              t_new,
                  const double              clearance) const;

    /// The radius of curvature of the master's surface: 'Radius' for a
    /// circle, cylinder or sphere, infinite for a plane.
    double
    curvature_radius() const
    {
      return type == MasterType::rigid_plane ?
               std::numeric_limits<double>::infinity() :
               radius;
    }

  private:
    /// Translation and rotation angle at load factor @p t.
    std::pair<dealii::Tensor<1, dim>, double>
    motion(const double t) const;

    const MasterType       type;
    const bool             inside;
    const double           radius;
    dealii::Point<dim>     reference_point, point, rotation_center;
    dealii::Tensor<1, 3>   axis;          ///< of the prescribed rotation
    dealii::Tensor<1, dim> cylinder_axis; ///< 3D cylinder, current
    dealii::Tensor<1, dim> reference_normal, normal;
    std::unique_ptr<dealii::FunctionParser<1>> translation, rotation;
    /// For messages: "Contact pair <name>/Rigid master", and the motion's
    /// expressions.
    std::string path, translation_text, rotation_text;
  };
} // namespace glide
