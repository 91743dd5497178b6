#include <glide/contact/formulation.h>
#include <glide/contact/mortar.h>
#include <glide/contact/node_to_surface.h>
#include <glide/contact/small_sliding.h>
#include <glide/contact/small_sliding_formulation.h>
#include <glide/scene/input_error.h>

#include <sstream>

namespace glide
{
  using namespace dealii;

  template <int dim>
  Formulation<dim>::Formulation(const PairContext<dim>             &context,
                                std::unique_ptr<RigidMaster<dim>>   master,
                                std::unique_ptr<MasterSurface<dim>> surface)
    : context(context)
    , master(std::move(master))
    , surface(std::move(surface))
  {}

  template <int dim>
  void
  Formulation<dim>::setup(const std::vector<SlaveNode<dim>> &slave_nodes)
  {
    nodes = &slave_nodes;
    slip_length.assign(slave_nodes.size(), 0.);
    slip_parts.assign(slave_nodes.size(), {{0., 0.}});
  }

  template <int dim>
  void
  Formulation<dim>::set_time(const double t)
  {
    time = t;
    if (master)
      master->set_time(t);
  }

  template <int dim>
  void
  Formulation<dim>::move(const VectorType &U) const
  {
    if (!surface)
      return;
    const auto start = std::chrono::steady_clock::now();
    surface->set_displacement(U, true);
    searching += std::chrono::steady_clock::now() - start;
  }

  template <int dim>
  void
  Formulation<dim>::couplings(const unsigned int,
                              const VectorType &,
                              std::vector<types::global_dof_index> &)
  {}

  template <int dim>
  void
  Formulation<dim>::read_dofs(std::vector<types::global_dof_index> &dofs) const
  {
    if (surface)
      {
        for (const auto &node : surface->get_nodes())
          dofs.insert(dofs.end(), node.dofs.begin(), node.dofs.end());
        // A distributed surface: the own facets' nodes, whose motion
        // decides when to gather again (Contact::follow()).
        dofs.insert(dofs.end(),
                    surface->own_dofs().begin(),
                    surface->own_dofs().end());
      }
  }

  template <int dim>
  void
  Formulation<dim>::regather(
    const VectorType                            &U,
    const std::vector<dealii::BoundingBox<dim>> &regions)
  {
    std::vector<std::uint64_t> old_keys;
    for (unsigned int i = 0; i < surface->get_pieces().size(); ++i)
      old_keys.push_back(surface->piece_key(i));
    surface->gather_near(U, regions);
    renumber_pieces(old_keys);
  }

  template <int dim>
  bool
  Formulation<dim>::outside_pattern(const unsigned int,
                                    const Constraint<dim> &) const
  {
    return false;
  }

  template <int dim>
  int
  Formulation<dim>::holdable_piece(const Constraint<dim> &) const
  {
    return -1;
  }

  template <int dim>
  void
  Formulation<dim>::hold(const unsigned int, const int, const int)
  {}

  template <int dim>
  void
  Formulation<dim>::release_holds()
  {}

  template <int dim>
  unsigned int
  Formulation<dim>::n_held() const
  {
    return 0;
  }

  template <int dim>
  std::vector<typename Formulation<dim>::HeldGap>
  Formulation<dim>::held_gaps(const std::vector<Constraint<dim>> &) const
  {
    return {};
  }

  template <int dim>
  unsigned int
  Formulation<dim>::n_fallbacks() const
  {
    return 0;
  }

  template <int dim>
  void
  Formulation<dim>::distribute(
    const unsigned int   i,
    const double         lambda,
    std::vector<double> &nodal,
    std::vector<std::pair<types::global_dof_index, double>> &) const
  {
    nodal[i] += lambda;
  }

  template <int dim>
  void
  Formulation<dim>::accumulate_slip(const unsigned int    i,
                                    const Tensor<1, dim> &normal,
                                    const Tensor<1, dim> &relative)
  {
    slip_length[i] += (relative - (relative * normal) * normal).norm();
    const auto tangents = contact_tangents<dim>(normal);
    for (unsigned int a = 0; a < dim - 1; ++a)
      slip_parts[i][a] += relative * tangents[a];
  }

  template <int dim>
  Point<dim>
  Formulation<dim>::position(const unsigned int i, const VectorType &U) const
  {
    const auto &node = (*nodes)[i];
    Point<dim>  x    = node.X;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] += U[node.dofs[d]];
    return x;
  }

  template <int dim>
  void
  Formulation<dim>::report_failed(const std::vector<Constraint<dim>> &s,
                                  const std::string &what) const
  {
    // The reference positions of the constraints that @p pick selects.
    const auto positions = [&](const auto &pick) {
      std::vector<std::string> list;
      for (unsigned int i = 0; i < s.size(); ++i)
        if (pick(s[i]))
          {
            std::ostringstream text;
            text << "(" << (*nodes)[i].X << ")";
            list.push_back(text.str());
          }
      return list;
    };
    const std::string pair =
      "warning: contact pair '" + context.parameters.name + "': " + what;
    context.report(positions([](const Constraint<dim> &c) {
                     return c.outcome == Outcome::failed;
                   }),
                   pair + " did not converge for ",
                   " slave node(s), which count as open in this step (node "
                   "positions in the reference configuration)");
    context.report(positions([](const Constraint<dim> &c) {
                     return c.found() && c.projection.incomplete;
                   }),
                   pair +
                     " did not converge on some of the master pieces near ",
                   " slave node(s); they are in contact with the closest "
                   "point found on the others, and a closer one may have "
                   "been missed (node positions in the reference "
                   "configuration)");
  }

  template <int dim>
  std::unique_ptr<Formulation<dim>>
  make_formulation(const PairContext<dim>             &context,
                   std::unique_ptr<RigidMaster<dim>>   master,
                   std::unique_ptr<MasterSurface<dim>> surface)
  {
    const auto &p = context.parameters;
    // The formulations by name: 'Formulation' and 'Sliding' of the pair.
    const std::string name = p.formulation + ", " + p.sliding + " sliding";
    if (name == "node to surface, finite sliding")
      return std::make_unique<NodeToSurfaceFinite<dim>>(context,
                                                        std::move(master),
                                                        std::move(surface));
    if (name == "node to surface, small sliding" ||
        name == "surface to surface, small sliding")
      return std::make_unique<SmallSlidingFormulation<dim>>(
        context,
        std::move(master),
        std::move(surface),
        p.formulation == "surface to surface");
    if (name == "mortar, finite sliding")
      {
        // R14.7: in 3D the facets are bilinear quadrilaterals; the dual
        // basis of serendipity or biquadratic quadrilaterals is not
        // implemented.
        require(dim == 2 || context.scene.degree == 1,
                "Parameter '" + context.path +
                  "/Formulation' = 'mortar': mortar in 3D needs Element "
                  "degree = 1; the dual basis of quadratic quadrilateral "
                  "facets is not implemented. Use 'Element degree = 1' or "
                  "'Formulation = node to surface'.");
        require(surface != nullptr,
                "Parameter '" + context.path +
                  "/Formulation' = 'mortar' needs a master surface of a body "
                  "(deformable or meshed rigid), not the analytical '" +
                  p.master + "'; use 'node to surface' with it.");
        return std::make_unique<Mortar<dim>>(context, std::move(surface));
      }
    throw InputError("Parameter '" + context.path + "/Formulation' = '" +
                     p.formulation + "' with 'Sliding' = '" + p.sliding +
                     "': glide has no such formulation; surface to surface "
                     "needs 'Sliding = small'.");
  }

  template class Formulation<2>;
  template class Formulation<3>;
  template std::unique_ptr<Formulation<2>>
  make_formulation<2>(const PairContext<2> &,
                      std::unique_ptr<RigidMaster<2>>,
                      std::unique_ptr<MasterSurface<2>>);
  template std::unique_ptr<Formulation<3>>
  make_formulation<3>(const PairContext<3> &,
                      std::unique_ptr<RigidMaster<3>>,
                      std::unique_ptr<MasterSurface<3>>);
} // namespace glide
