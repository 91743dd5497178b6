#include <glide/base/quiet_parse.h>
#include <glide/contact/rigid_master.h>
#include <glide/mechanics/rotation.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    std::unique_ptr<FunctionParser<1>>
    parse(const std::string &expression,
          const unsigned int n,
          const std::string &parameter)
    {
      auto              f     = std::make_unique<FunctionParser<1>>(n);
      const std::string error = parse_quietly([&]() {
        // Functions of the load factor only: the variable is 't'.
        f->initialize("t",
                      Utilities::split_string_list(expression, ';'),
                      {{"pi", numbers::PI}},
                      false);
        Vector<double> v(n);
        f->vector_value(Point<1>(0.), v);
      });
      if (!error.empty())
        throw InputError("Parameter '" + parameter + "' = '" + expression +
                         "' is not a valid function of t: " + error + ".");
      return f;
    }
  } // namespace

  template <int dim>
  RigidMaster<dim>::RigidMaster(const ContactPairParameters &p,
                                const std::string           &path)
    : type(p.master_type)
    , inside(p.slave_inside)
    , radius(p.radius)
  {
    for (unsigned int d = 0; d < dim; ++d)
      {
        reference_point[d]  = p.point[d];
        reference_normal[d] = p.normal[d];
        rotation_center[d]  = p.rotation_center[d];
      }
    for (unsigned int d = 0; d < 3; ++d)
      axis[d] = p.rotation_axis[d];
    if (!std::isfinite(axis.norm()) || !(axis.norm() > 0.))
      throw InputError("Parameter '" + path +
                       "/Rigid master/Rotation axis' has no finite, "
                       "non-zero length; only its direction counts, so "
                       "scale it (e.g. '0, 0, 1').");
    axis /= axis.norm();
    reference_normal /= reference_normal.norm();
    if (!p.translation.empty())
      translation =
        parse(p.translation, dim, path + "/Rigid master/Translation");
    rotation         = parse(p.rotation, 1, path + "/Rigid master/Rotation");
    this->path       = path + "/Rigid master";
    translation_text = p.translation;
    rotation_text    = p.rotation;
    // The motion at the last load factor too, so that a motion that is
    // not finite there is an input error before anything is written.
    set_time(1.);
    set_time(0.);
  }

  template <int dim>
  std::pair<Tensor<1, dim>, double>
  RigidMaster<dim>::motion(const double t) const
  {
    Tensor<1, dim> u;
    if (translation)
      for (unsigned int d = 0; d < dim; ++d)
        u[d] = translation->value(Point<1>(t), d);
    const double theta = rotation->value(Point<1>(t));
    // A motion that is not a finite number (a division by zero, the root
    // of a negative number, an overflow) is an input error; glide never
    // computes with it (as CheckedFunction for the other functions).
    if (!std::isfinite(u.norm()) || !std::isfinite(theta))
      {
        std::ostringstream s;
        s << "Parameter '" << path << "/"
          << (std::isfinite(theta) ? "Translation' = '" + translation_text :
                                     "Rotation' = '" + rotation_text)
          << "' is not a finite number at t = " << t << " (translation " << u
          << ", rotation " << theta
          << "); every value must be finite. Check the expression for a "
             "division by zero, the root or logarithm of a negative "
             "number, or an overflow at that load factor.";
        throw InputError(s.str());
      }
    return {u, theta};
  }

  template <int dim>
  Point<dim>
  RigidMaster<dim>::move(const Point<dim> &y,
                         const double      from,
                         const double      to) const
  {
    // x(X, t) = c + u(t) + R(theta(t)) (X - c): back to X, forward to t.
    const auto [u0, theta0] = motion(from);
    const auto [u1, theta1] = motion(to);
    const Tensor<1, dim> X_minus_c =
      rotate<dim>(y - rotation_center - u0, axis, -theta0);
    return rotation_center + u1 + rotate<dim>(X_minus_c, axis, theta1);
  }

  template <int dim>
  Point<dim>
  RigidMaster<dim>::centre_at(const double t) const
  {
    const auto [u, theta] = motion(t);
    // Rotation about 'Rotation axis' (z in 2D).
    return rotation_center + u +
           rotate<dim>(reference_point - rotation_center, axis, theta);
  }

  template <int dim>
  void
  RigidMaster<dim>::set_time(const double t)
  {
    const auto theta = motion(t).second;
    point            = centre_at(t);
    // A cylinder's axis (z in the reference configuration) turns with the
    // master.
    normal = rotate<dim>(reference_normal, axis, theta);
    if constexpr (dim == 3)
      cylinder_axis = rotate<dim>(Tensor<1, dim>({0., 0., 1.}), axis, theta);
    if (!std::isfinite(Tensor<1, dim>(point).norm()) ||
        !std::isfinite(normal.norm()))
      {
        std::ostringstream s;
        s << "Parameter '" << path << "': the rigid master placed at t = " << t
          << " is not finite (its point " << point
          << "): 'Point', 'Rotation center', 'Translation' or 'Rotation' "
             "overflow double precision. Use lengths of the scene's size.";
        throw InputError(s.str());
      }
  }

  template <int dim>
  typename RigidMaster<dim>::Projection
  RigidMaster<dim>::project(const Point<dim> &x) const
  {
    Projection p;
    if (type == MasterType::rigid_plane)
      {
        p.gap           = (x - point) * normal;
        p.normal        = normal;
        p.closest_point = x - p.gap * normal;
        return p;
      }
    // Circle, cylinder (in 3D along its current axis) or sphere.
    Tensor<1, dim> d = x - point;
    Tensor<2, dim> P = unit_symmetric_tensor<dim>();
    if (dim == 3 && type == MasterType::rigid_circle)
      {
        d -= (d * cylinder_axis) * cylinder_axis;
        P -= outer_product(cylinder_axis, cylinder_axis);
      }
    const double r = d.norm();
    // At the centre (or on the axis) the normal is undefined. A node
    // there in the initial configuration lies a whole radius inside the
    // circle: most often a 'Radius' far beyond the scene (1e20 with the
    // centre next to the slave) or a misplaced centre, so the set-up's
    // message names them (Contact::check_initial_overclosure()). During a
    // step it is an increment too large for the master's size.
    if (!(r > 1e-12 * radius))
      {
        std::ostringstream text;
        text << std::setprecision(4) << "Parameter '" << path
             << "': the slave node at (";
        for (unsigned int k = 0; k < dim; ++k)
          text << (k ? ", " : "") << x[k];
        text << ") lies at the "
             << (dim == 3 && type == MasterType::rigid_circle ? "axis" :
                                                                "centre")
             << " of the rigid master (" << r
             << " from it, less than 1e-12 of 'Radius' = " << radius
             << "), where its normal is undefined";
        throw UndefinedNormal(text.str());
      }
    const Tensor<1, dim> e          = d / r;
    const Tensor<2, dim> tangential = (P - outer_product(e, e)) / r;
    const double         sign       = inside ? -1. : 1.;
    p.gap                           = sign * (r - radius);
    p.normal                        = sign * e;
    p.curvature                     = sign * tangential;
    p.closest_point                 = x - (r - radius) * e;
    return p;
  }

  template <int dim>
  std::string
  RigidMaster<dim>::misplaced(const UndefinedNormal &e) const
  {
    return std::string(e.what()) + ": the slave " +
           (inside ? "is there" : "starts a whole radius inside the master") +
           ". Check 'Point' (the centre), 'Radius' and 'Slave inside'.";
  }

  template <int dim>
  double
  RigidMaster<dim>::passage_depth(const Point<dim> &x_old,
                                  const double      t_old,
                                  const Point<dim> &x_new,
                                  const double      t_new,
                                  const double      clearance) const
  {
    if (type == MasterType::rigid_plane || inside)
      return 0.;
    // Both points in the reference frame, relative to the reference centre
    // (a cylinder's reference axis is z).
    const auto relative = [&](const Point<dim> &x, const double t) {
      const auto [u, theta] = motion(t);
      Tensor<1, dim> d = rotate<dim>(x - rotation_center - u, axis, -theta) +
                         (rotation_center - reference_point);
      if (dim == 3 && type == MasterType::rigid_circle)
        d[dim - 1] = 0.;
      return d;
    };
    const Tensor<1, dim> a = relative(x_old, t_old);
    const Tensor<1, dim> b = relative(x_new, t_new);
    // In contact (or inside) at the end: a passage only if the point ended
    // on the far side of the centre (axis) from where it started, pushed
    // out through the master's far side (checked after the path below).
    const bool closed_at_end = !(b.norm() > radius + clearance);
    if (closed_at_end && !(a * b < 0.))
      return 0.;
    // The closest approach to the centre (axis) along the path: the node
    // moves straight from x_old to x_new while the master moves by its
    // prescribed motion. Without a turn in the increment the path in the
    // master's frame is the straight segment from a to b; with one it is
    // followed in steps (a chord between its ends would cut into a circle
    // that only spins about its centre under a node in contact).
    const auto [u_old, theta_old] = motion(t_old);
    const auto [u_new, theta_new] = motion(t_new);
    double closest                = std::min(a.norm(), b.norm());
    if (theta_old == theta_new)
      {
        const Tensor<1, dim> ab = b - a;
        const double         s  = ab.norm_square() > 0. ?
                                    std::clamp(-(a * ab) / ab.norm_square(), 0., 1.) :
                                    0.;
        closest                 = (a + s * ab).norm();
      }
    else
      {
        // Steps of at most a sixteenth of the radius along the path (and
        // at least 64), so that a passage deeper than a slave facet is not
        // stepped over.
        const double length =
          (b - a).norm() + (x_new - x_old).norm() +
          std::abs(theta_new - theta_old) * (a.norm() + b.norm());
        const unsigned int n = static_cast<unsigned int>(
          std::clamp(std::ceil(16. * length / radius), 64., 65536.));
        const auto distance = [&](const double s) {
          return relative(x_old + s * (x_new - x_old),
                          t_old + s * (t_new - t_old))
            .norm();
        };
        unsigned int best = 0;
        for (unsigned int k = 1; k < n; ++k)
          if (const double d = distance(static_cast<double>(k) / n);
              d < closest)
            {
              closest = d;
              best    = k;
            }
        // The minimum between the neighbours of the closest step.
        if (best > 0)
          {
            double lo = (best - 1.) / n, hi = (best + 1.) / n;
            for (unsigned int i = 0; i < 60; ++i)
              {
                const double m1 = lo + (hi - lo) / 3., m2 = hi - (hi - lo) / 3.;
                if (distance(m1) < distance(m2))
                  hi = m2;
                else
                  lo = m1;
              }
            closest = std::min(closest, distance(0.5 * (lo + hi)));
          }
      }
    // In contact at the end on the far side: a passage only where the path
    // ran through the inner half of the master. A node that slides round
    // it in contact by more than a quarter turn in one increment (a sheet
    // drawn over a small die radius) keeps its chord at R cos(turn / 2)
    // from the centre, more than R / 2 for turns up to 120 degrees.
    if (closed_at_end && !(closest < 0.5 * radius))
      return 0.;
    // Relative to the start's depth: a closed node that the master leaves
    // (or a penalty node that started deep inside) has gone no deeper.
    return std::max(0., radius - closest - std::max(0., radius - a.norm()));
  }

  template class RigidMaster<2>;
  template class RigidMaster<3>;
} // namespace glide
