#include <glide/base/collective_failure.h>
#include <glide/base/quiet_parse.h>
#include <glide/mechanics/checked_function.h>
#include <glide/mechanics/elasticity.h>
#include <glide/mechanics/rotation.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>

namespace glide
{
  using namespace dealii;

  void
  throw_on_any_process(const std::string &failure, MPI_Comm comm)
  {
    throw_first_failure<std::runtime_error>(failure, comm);
  }

  void
  throw_input_error_on_any_process(const std::string &failure, MPI_Comm comm)
  {
    throw_first_failure<InputError>(failure, comm);
  }

  namespace
  {
    /// Embed a dim-dimensional displacement gradient into 3x3, adding the
    /// hoop term u_r / r in axisymmetric analysis.
    template <int dim>
    Tensor2
    embed(const Tensor<2, dim> &grad, const double hoop)
    {
      Tensor2 H;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          H[i][j] = grad[i][j];
      if (dim == 2)
        H[2][2] = hoop;
      return H;
    }
  } // namespace

  template <int dim>
  Elasticity<dim>::Elasticity(const Scene &scene,
                              MPI_Comm     comm,
                              TimerOutput &timer)
    : scene(scene)
    , comm(comm)
    , timer(timer)
    , triangulation(comm,
                    typename Triangulation<dim>::MeshSmoothing(
                      Triangulation<dim>::limit_level_difference_at_vertices))
    , fe(FE_Q<dim>(scene.degree), dim)
    , dof_handler(triangulation)
    , axisymmetric(scene.analysis == AnalysisType::axisymmetric)
  {}

  template <int dim>
  std::unique_ptr<FunctionParser<dim>>
  Elasticity<dim>::parse_function(const std::string &expression,
                                  const unsigned int n_components,
                                  const std::string &parameter) const
  {
    auto              f = std::make_unique<CheckedFunction<dim>>(n_components,
                                                    parameter,
                                                    expression);
    const std::string vars  = (dim == 2 ? "x,y,t" : "x,y,z,t");
    const std::string error = parse_quietly([&]() {
      f->initialize(vars,
                    Utilities::split_string_list(expression, ';'),
                    {{"pi", numbers::PI}},
                    true);
      // muparser compiles lazily. The unchecked value: the origin need
      // not be a point of the body (the values are checked where they
      // are used).
      for (unsigned int c = 0; c < n_components; ++c)
        f->FunctionParser<dim>::value(Point<dim>(), c);
    });
    if (!error.empty())
      throw InputError("Parameter '" + parameter + "' = '" + expression +
                       "' is not a valid expression in " + vars + ": " + error +
                       ".");
    return f;
  }

  template <int dim>
  std::unique_ptr<Material>
  Elasticity<dim>::material(const unsigned int b) const
  {
    return create_material(scene.bodies[b].material,
                           scene.geometric_nonlinearity);
  }

  template <int dim>
  std::vector<std::pair<std::array<types::global_dof_index, dim>, Point<dim>>>
  Elasticity<dim>::find_nodes(const std::string &surface,
                              const std::string &parameter,
                              const bool         owned_only) const
  {
    // A list that mixes node sets and surfaces: the union of the nodes of
    // its items.
    {
      const auto items = Utilities::split_string_list(surface, ',');
      if (items.size() > 1 &&
          std::any_of(items.begin(), items.end(), [&](const std::string &n) {
            return scene_node_sets.count(n) > 0;
          }))
        {
          std::vector<
            std::pair<std::array<types::global_dof_index, dim>, Point<dim>>>
                                            nodes;
          std::set<types::global_dof_index> seen;
          for (const auto &item : items)
            for (const auto &n : find_nodes(item, parameter, owned_only))
              if (seen.insert(n.first[0]).second)
                nodes.push_back(n);
          return nodes;
        }
    }
    std::vector<std::vector<double>> points;
    double                           tol = 0;
    std::set<types::boundary_id>     ids;
    unsigned int                     body = numbers::invalid_unsigned_int;
    if (scene_node_sets.count(surface))
      {
        points = scene_node_sets.at(surface)->points;
        tol    = scene_node_sets.at(surface)->tolerance;
        body   = scene_node_sets.at(surface)->body;
      }
    else
      for (const auto &name : Utilities::split_string_list(surface, ','))
        for (const auto id : mesh.surface(name, parameter))
          ids.insert(id);

    std::vector<std::pair<std::array<types::global_dof_index, dim>, Point<dim>>>
                                      nodes;
    std::set<types::global_dof_index> seen;
    std::vector<unsigned int>         found(points.size(), 0);
    // Per point, the distinct vertices (their first DoF) within the
    // tolerance that this process owns: each vertex counts once.
    std::vector<std::set<types::global_dof_index>> owned_hits(points.size());
    // Distance to the nearest vertex of each point, for the message when
    // none is within the tolerance.
    std::vector<double> nearest(points.size(),
                                std::numeric_limits<double>::max());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if ((cell->is_locally_owned() || (!owned_only && cell->is_ghost())) &&
          (body == numbers::invalid_unsigned_int ||
           cell->material_id() == body))
        for (const auto v : cell->vertex_indices())
          {
            const Point<dim> x   = cell->vertex(v);
            bool             hit = false;
            for (unsigned int i = 0; i < points.size(); ++i)
              {
                Point<dim> p;
                for (unsigned int d = 0; d < dim; ++d)
                  p[d] = points[i][d];
                nearest[i] = std::min(nearest[i], x.distance(p));
                if (x.distance(p) <= tol)
                  {
                    hit = true;
                    ++found[i];
                    if (owned.is_element(cell->vertex_dof_index(v, 0)))
                      owned_hits[i].insert(cell->vertex_dof_index(v, 0));
                  }
              }
            if (!ids.empty())
              for (const auto f : cell->face_indices())
                if (cell->face(f)->at_boundary() &&
                    ids.count(cell->face(f)->boundary_id()))
                  for (const auto fv : cell->face(f)->vertex_indices())
                    if (cell->face(f)->vertex_index(fv) ==
                        cell->vertex_index(v))
                      hit = true;
            if (!hit)
              continue;
            std::array<types::global_dof_index, dim> dofs;
            for (unsigned int c = 0; c < dim; ++c)
              dofs[c] = cell->vertex_dof_index(v, c);
            if ((!owned_only || owned.is_element(dofs[0])) &&
                seen.insert(dofs[0]).second)
              nodes.emplace_back(dofs, x);
          }
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        if (Utilities::MPI::sum(found[i], comm) > 0)
          continue;
        std::ostringstream p;
        for (unsigned int d = 0; d < points[i].size(); ++d)
          p << (d == 0 ? "" : ", ") << points[i][d];
        std::ostringstream why;
        why << "Node set '" << surface << "': no mesh vertex within " << tol
            << " of its point " << i + 1 << " of " << points.size() << " ("
            << p.str() << "); the nearest vertex"
            << (body == numbers::invalid_unsigned_int ?
                  std::string() :
                  " of body '" + scene.bodies[body].name + "'")
            << " is " << Utilities::MPI::min(nearest[i], comm)
            << " away. Check 'Node set " << surface
            << "/Points' or raise its 'Tolerance'.";
        throw InputError(why.str());
      }
    // Each point selects one vertex: a tolerance wider than the mesh
    // spacing (or a point where two bodies' vertices coincide) would apply
    // a concentrated force several times.
    for (unsigned int i = 0; i < points.size(); ++i)
      if (const unsigned int n =
            Utilities::MPI::sum(static_cast<unsigned int>(owned_hits[i].size()),
                                comm);
          n > 1)
        {
          std::ostringstream p;
          for (unsigned int d = 0; d < points[i].size(); ++d)
            p << (d == 0 ? "" : ", ") << points[i][d];
          std::ostringstream why;
          why << "Node set '" << surface << "': " << n
              << " mesh vertices lie within 'Tolerance' = " << tol
              << " of its point " << i + 1 << " (" << p.str()
              << "); each point must select one vertex (a force on the node "
                 "set would act on each of them). Lower 'Node set "
              << surface
              << "/Tolerance' below the mesh spacing there (where vertices "
                 "of two bodies coincide at the point, no tolerance tells "
                 "them apart: choose another point).";
          throw InputError(why.str());
        }
    require(Utilities::MPI::sum(static_cast<unsigned int>(nodes.size()), comm) >
              0,
            "Parameter '" + parameter + "' = '" + surface +
              "' selects no node.");
    return nodes;
  }

  template <int dim>
  void
  Elasticity<dim>::setup()
  {
    {
      TimerOutput::Scope t(timer, "mesh");
      mesh.build(scene, triangulation);
    }
    TimerOutput::Scope t(timer, "setup");
    mapping = std::make_unique<MappingQ<dim>>(scene.degree);

    // E_max over the deformable bodies (a rigid body's material does not
    // matter), over all if every body is rigid.
    max_youngs_modulus = 0;
    for (const auto &b : scene.bodies)
      if (!b.rigid)
        max_youngs_modulus =
          std::max(max_youngs_modulus, b.material.youngs_modulus);
    if (max_youngs_modulus == 0)
      for (const auto &b : scene.bodies)
        max_youngs_modulus =
          std::max(max_youngs_modulus, b.material.youngs_modulus);
    min_youngs_modulus = max_youngs_modulus;
    for (const auto &b : scene.bodies)
      if (!b.rigid)
        min_youngs_modulus =
          std::min(min_youngs_modulus, b.material.youngs_modulus);

    if (scene.manufactured_solution != "none")
      {
        const auto &m = scene.bodies[0].material;
        for (const auto &b : scene.bodies)
          require(b.material.youngs_modulus == m.youngs_modulus &&
                    b.material.poissons_ratio == m.poissons_ratio,
                  "Parameter 'Verification/Manufactured solution' needs the "
                  "same material in every body.");
        exact = std::make_unique<ManufacturedSolution<dim>>(axisymmetric,
                                                            m.lambda(),
                                                            m.mu());
      }
    for (const auto &b : scene.bodies)
      body_forces.push_back(
        b.body_force.empty() ?
          nullptr :
          parse_function(b.body_force, dim, "Body " + b.name + "/Body force"));

    for (const auto &ns : scene.node_sets)
      scene_node_sets[ns.name] = &ns;

    dof_handler.distribute_dofs(fe);
    owned = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);

    // Meshed rigid bodies: every DoF of their cells (owned and ghost, at its
    // support point) follows the prescribed rigid motion.
    for (unsigned int b = 0; b < scene.bodies.size(); ++b)
      {
        const auto &body = scene.bodies[b];
        if (!body.rigid)
          continue;
        const std::string path = "Body " + body.name + "/Rigid body";
        // A rigid body moves as a whole: its motion is a function of the
        // load factor only, as an analytical master's is (until 2026-12-06
        // x and y were accepted and read at the origin, in silence).
        for (const auto &[expression, n, entry] :
             {std::make_tuple(body.rigid_translation,
                              unsigned(dim),
                              "Translation"),
              std::make_tuple(body.rigid_rotation, 1u, "Rotation")})
          if (!expression.empty())
            {
              FunctionParser<1> f(n);
              const std::string error = parse_quietly([&]() {
                f.initialize("t",
                             Utilities::split_string_list(expression, ';'),
                             {{"pi", numbers::PI}},
                             false);
                Vector<double> v(n);
                f.vector_value(Point<1>(0.), v);
              });
              if (!error.empty())
                throw InputError(
                  "Parameter '" + path + "/" + entry + "' = '" + expression +
                  "' is not a valid function of t: " + error +
                  ". A rigid body moves as a whole, so its motion depends "
                  "on the load factor t only.");
            }
        RigidBody r;
        r.translation =
          body.rigid_translation.empty() ?
            nullptr :
            parse_function(body.rigid_translation, dim, path + "/Translation");
        r.rotation = parse_function(body.rigid_rotation, 1, path + "/Rotation");
        for (unsigned int d = 0; d < dim; ++d)
          r.center[d] = body.rigid_center[d];
        for (unsigned int d = 0; d < 3; ++d)
          r.axis[d] = body.rigid_axis[d];
        const auto &unit_points = fe.get_unit_support_points();
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        std::set<types::global_dof_index>    seen;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial() && cell->material_id() == b)
            {
              cell->get_dof_indices(dofs);
              for (unsigned int k = 0; k < dofs.size(); ++k)
                if (seen.insert(dofs[k]).second)
                  r.dofs.emplace_back(
                    dofs[k],
                    fe.system_to_component_index(k).first,
                    mapping->transform_unit_to_real_cell(cell, unit_points[k]));
            }
        rigid_bodies.push_back(std::move(r));
      }

    for (const auto &bc : scene.boundary_conditions)
      {
        const std::string path = "Boundary condition " + bc.name;
        for (const auto &name : Utilities::split_string_list(bc.surface, ','))
          for (const auto &body : scene.bodies)
            require(!body.rigid || name.rfind(body.name + ".", 0) != 0,
                    "Parameter '" + path + "/Surface' = '" + name +
                      "' is a surface of the rigid body '" + body.name +
                      "'; a rigid body moves only by its 'Rigid body' "
                      "motion (remove the condition, or set 'Rigid = "
                      "false').");
        if (bc.type == BoundaryConditionType::force)
          {
            PointForce pf;
            pf.path     = path;
            pf.function = parse_function(bc.function, dim, path + "/Function");
            pf.nodes    = find_nodes(bc.surface, path + "/Surface", true);
            point_forces.push_back(std::move(pf));
            continue;
          }

        Load load;
        load.parameters = &bc;
        // The list may mix node sets (their vertices) and surfaces (all
        // DoFs on their faces, mid-side nodes included).
        std::string sets;
        for (const auto &name : Utilities::split_string_list(bc.surface, ','))
          if (scene_node_sets.count(name))
            {
              require(bc.is_dirichlet(),
                      "Parameter '" + path + "/Surface' = '" + name +
                        "' is a node set; a " +
                        std::string(bc.type == BoundaryConditionType::pressure ?
                                      "pressure" :
                                      "traction") +
                        " needs a surface <body>.<surface>.");
              sets += (sets.empty() ? "" : ",") + name;
            }
          else
            for (const auto id : mesh.surface(name, path + "/Surface"))
              load.ids.insert(id);
        if (!sets.empty())
          {
            // Every process needs the constraints of its ghost DoFs too.
            load.nodes       = find_nodes(sets, path + "/Surface", false);
            load.on_node_set = true;
          }
        if (bc.type == BoundaryConditionType::displacement && !exact)
          load.function = parse_function(bc.function, dim, path + "/Function");
        if (bc.type == BoundaryConditionType::traction)
          load.function = parse_function(bc.function, dim, path + "/Function");
        if (bc.type == BoundaryConditionType::pressure)
          load.function = parse_function(bc.function, 1, path + "/Function");
        if (bc.is_symmetry())
          for (const auto id : load.ids)
            symmetry_ids[bc.symmetry_component()].push_back(id);
        if (bc.is_dirichlet())
          dirichlet.push_back(std::move(load));
        else
          surface_loads.push_back(std::move(load));
      }

    // Reference area of a boundary face (per unit thickness in plane strain,
    // times 2 pi r in axisymmetric analysis).
    double area = 0, count = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              area +=
                face->measure() *
                (axisymmetric ? 2 * numbers::PI *
                                  std::max(face->center()[0], face->measure()) :
                                1.);
              count += 1;
            }
    reference_area =
      Utilities::MPI::sum(area, comm) / Utilities::MPI::sum(count, comm);
  }

  template <int dim>
  double
  Elasticity<dim>::youngs_modulus_of_body(const unsigned int b) const
  {
    AssertIndexRange(b, scene.bodies.size());
    return scene.bodies[b].rigid ? std::numeric_limits<double>::infinity() :
                                   scene.bodies[b].material.youngs_modulus;
  }

  template <int dim>
  ComponentMask
  Elasticity<dim>::component_mask(const BoundaryConditionParameters &bc) const
  {
    ComponentMask mask(dim, true);
    if (bc.is_symmetry())
      {
        mask = ComponentMask(dim, false);
        mask.set(bc.symmetry_component(), true);
      }
    else if (bc.type == BoundaryConditionType::displacement)
      for (unsigned int i = 0; i < dim; ++i)
        mask.set(i, bc.components[i]);
    return mask;
  }

  template <int dim>
  void
  Elasticity<dim>::setup_system(
    const IndexSet                                      &extra,
    const std::function<void(DynamicSparsityPattern &)> &add_couplings,
    const IndexSet                                      &ghosts)
  {
    TimerOutput::Scope t(timer, "setup");
    // The unknowns: displacement DoFs, then any extra unknowns (contact
    // multipliers) that other parts own.
    owned_total = IndexSet(
      std::max<types::global_dof_index>(dof_handler.n_dofs(), extra.size()));
    owned_total.add_indices(owned);
    owned_total.add_indices(extra);
    relevant_total = IndexSet(owned_total.size());
    relevant_total.add_indices(relevant);
    relevant_total.add_indices(extra);
    if (ghosts.size() > 0)
      relevant_total.add_indices(ghosts);
    consistent_constraints =
      Utilities::MPI::max(ghosts.n_elements() > 0 ? 1 : 0, comm) > 0;

    hanging_node_constraints.reinit(relevant_total);
    DoFTools::make_hanging_node_constraints(dof_handler,
                                            hanging_node_constraints);
    hanging_node_constraints.close();
    homogeneous_constraints = constraints_at(0.);
    for (const auto &i : homogeneous_constraints.get_lines())
      homogeneous_constraints.set_inhomogeneity(i.index, 0.);

    DynamicSparsityPattern dsp(relevant_total);
    DoFTools::make_sparsity_pattern(dof_handler,
                                    dsp,
                                    homogeneous_constraints,
                                    false);
    if (add_couplings)
      add_couplings(dsp);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               owned_total,
                                               comm,
                                               relevant_total);
    pattern.reinit(owned_total, owned_total, dsp, comm);
  }

  template <int dim>
  VectorType
  Elasticity<dim>::ghosted_displacement(const VectorType &U) const
  {
    VectorType ghosted(owned, relevant, comm);
    // Global sizes: the choice must be the same on every process, since
    // the import below is collective.
    if (owned_total.size() == owned.size())
      ghosted = U;
    else
      {
        VectorType displacement(owned, comm);
        for (const auto i : owned)
          displacement[i] = U[i];
        displacement.compress(VectorOperation::insert);
        ghosted = displacement;
      }
    return ghosted;
  }

  template <int dim>
  AffineConstraints<double>
  Elasticity<dim>::constraints_at(const double t) const
  {
    AffineConstraints<double> c;
    c.reinit(relevant_total);
    DoFTools::make_hanging_node_constraints(dof_handler, c);
    // A function of the scene that is not finite at a point of this
    // process: every process must hear of it (collective callers).
    std::string input_failure;
    try
      {
        for (const auto &d : dirichlet)
          {
            const auto         &bc   = *d.parameters;
            const ComponentMask mask = component_mask(bc);
            std::map<types::boundary_id, const Function<dim> *> functions;
            Functions::ZeroFunction<dim>                        zero(dim);
            const Function<dim>                                *f = &zero;
            if (bc.type == BoundaryConditionType::displacement)
              {
                if (exact)
                  f = exact.get();
                else
                  {
                    d.function->set_time(t);
                    f = d.function.get();
                  }
              }
            if (d.on_node_set)
              {
                Vector<double> value(dim);
                for (const auto &[node_dofs, x] : d.nodes)
                  {
                    f->vector_value(x, value);
                    for (unsigned int comp = 0; comp < dim; ++comp)
                      if (mask[comp] && c.can_store_line(node_dofs[comp]) &&
                          !c.is_constrained(node_dofs[comp]))
                        {
                          c.add_line(node_dofs[comp]);
                          c.set_inhomogeneity(node_dofs[comp], value[comp]);
                        }
                  }
              }
            if (d.ids.empty())
              continue;
            for (const auto id : d.ids)
              functions[id] = f;
            VectorTools::interpolate_boundary_values(
              *mapping, dof_handler, functions, c, mask);
          }
        for (const auto &r : rigid_bodies)
          {
            Tensor<1, dim> T;
            if (r.translation)
              {
                r.translation->set_time(t);
                Vector<double> v(dim);
                r.translation->vector_value(Point<dim>(), v);
                for (unsigned int d = 0; d < dim; ++d)
                  T[d] = v[d];
              }
            r.rotation->set_time(t);
            const double theta = r.rotation->value(Point<dim>());
            std::map<types::global_dof_index, double> target;
            for (const auto &[dof, comp, X] : r.dofs)
              {
                const Tensor<1, dim> x =
                  r.center + T + rotate<dim>(X - r.center, r.axis, theta);
                target[dof] = x[comp] - X[comp];
              }
            for (const auto &[dof, comp, X] : r.dofs)
              {
                if (!c.can_store_line(dof))
                  continue;
                if (!c.is_constrained(dof))
                  {
                    c.add_line(dof);
                    c.set_inhomogeneity(dof, target[dof]);
                    continue;
                  }
                // A hanging node, u_h = sum w_j u_j: on a curved surface it
                // does not lie on the straight edge between its parents, so
                // the parents' rigid motion does not move it rigidly under a
                // rotation (measured 5e-3 on the rigid sphere of
                // hertz-3d-elastic.prm turned by pi/2). The inhomogeneity
                // makes it exact: u_h = sum w_j u_j + (u_h* - sum w_j u_j*).
                const auto *entries = c.get_constraint_entries(dof);
                if (!entries || entries->empty())
                  continue;
                double interpolated = 0.;
                bool   all          = true;
                for (const auto &[j, w] : *entries)
                  {
                    const auto it = target.find(j);
                    all           = all && it != target.end();
                    if (it != target.end())
                      interpolated += w * it->second;
                  }
                if (all)
                  c.set_inhomogeneity(dof, target[dof] - interpolated);
              }
          }
        if (axisymmetric)
          {
            // u_r = 0 on the axis r = 0: regularity of a solid of revolution.
            const double tol = 1e-10 * mesh.scene_size();
            std::vector<types::global_dof_index> dofs(fe.n_dofs_per_face());
            for (const auto &cell : dof_handler.active_cell_iterators())
              if (!cell->is_artificial())
                for (const auto f : cell->face_indices())
                  {
                    const auto face    = cell->face(f);
                    bool       on_axis = true;
                    for (const auto v : face->vertex_indices())
                      on_axis = on_axis && std::abs(face->vertex(v)[0]) < tol;
                    if (!on_axis)
                      continue;
                    face->get_dof_indices(dofs);
                    for (unsigned int i = 0; i < dofs.size(); ++i)
                      if (fe.face_system_to_component_index(i).first == 0 &&
                          c.can_store_line(dofs[i]) &&
                          !c.is_constrained(dofs[i]))
                        c.add_line(dofs[i]);
                  }
          }
      }
    catch (const InputError &e)
      {
        input_failure = e.what();
      }
    throw_input_error_on_any_process(input_failure, comm);
    // DoFs of other processes that contact reaches (a master surface
    // there): their owners know their constraints (Dirichlet, symmetry,
    // hanging), this process does not.
    if (consistent_constraints)
      c.make_consistent_in_parallel(owned_total, relevant_total, comm);
    c.close();
    return c;
  }

  template <int dim>
  bool
  Elasticity<dim>::round_off_floor_from_loads() const
  {
    return 10. * std::numeric_limits<double>::epsilon() * largest_scaled_load >=
           round_off_floor();
  }

  template <int dim>
  double
  Elasticity<dim>::round_off_floor() const
  {
    double p_wave = 0.;
    for (const auto &b : scene.bodies)
      if (!b.rigid)
        {
          const double E  = b.material.youngs_modulus,
                       nu = b.material.poissons_ratio;
          p_wave =
            std::max(p_wave, E * (1. - nu) / ((1. + nu) * (1. - 2. * nu)));
        }
    // Round-off is relative to the largest terms of the residual: the
    // stresses of the stiffest body, or the loads where they are larger
    // (a linear block loaded to a strain of 5e5 stalled at 1.8e-10).
    return 10. * std::numeric_limits<double>::epsilon() *
           std::max(p_wave / min_youngs_modulus, largest_scaled_load);
  }

  template <int dim>
  void
  Elasticity<dim>::residual(const VectorType &U,
                            const double      t,
                            VectorType       &F) const
  {
    TimerOutput::Scope s(timer, "assembly: residual");
    assemble(U, t, &F, nullptr, homogeneous_constraints);
  }

  template <int dim>
  void
  Elasticity<dim>::jacobian(const VectorType &U, MatrixType &J) const
  {
    TimerOutput::Scope s(timer, "assembly: Jacobian");
    assemble(U, 0., nullptr, &J, homogeneous_constraints);
  }

  template <int dim>
  void
  Elasticity<dim>::predictor_residual(const VectorType &U,
                                      const VectorType &D,
                                      const double      t,
                                      VectorType       &F) const
  {
    TimerOutput::Scope s(timer, "assembly: residual");
    assemble(U, t, &F, nullptr, homogeneous_constraints, &D);
  }

  template <int dim>
  void
  Elasticity<dim>::assemble(const VectorType                &U,
                            const double                     t,
                            VectorType                      *F,
                            MatrixType                      *J,
                            const AffineConstraints<double> &constraints,
                            const VectorType                *increment) const
  {
    const VectorType U_ghost = ghosted_displacement(U);
    VectorType       D_ghost;
    if (increment)
      D_ghost = ghosted_displacement(*increment);
    // The tangent is needed for J and for the product with the increment.
    const bool tangent = J || (F && increment);
    if (F)
      *F = 0;
    if (J)
      *J = 0;

    const QGauss<dim>     quadrature(scene.degree + 1);
    const QGauss<dim - 1> face_quadrature(scene.degree + 1);
    FEValues<dim>         fe_values(*mapping,
                            fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
    FEFaceValues<dim>     fe_face(*mapping,
                              fe,
                              face_quadrature,
                              update_values | update_quadrature_points |
                                update_JxW_values | update_normal_vectors);

    const unsigned int n = fe.n_dofs_per_cell(), nq = quadrature.size();
    FullMatrix<double> cell_matrix(n, n);
    Vector<double>     cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<Tensor<2, dim>>          grads(nq);
    std::vector<Tensor<1, dim>>          values(nq);
    const FEValuesExtractors::Vector     u(0);

    std::vector<std::unique_ptr<Material>> materials;
    for (unsigned int b = 0; b < scene.bodies.size(); ++b)
      materials.push_back(material(b));
    for (const auto &f : body_forces)
      if (f)
        f->set_time(t);
    for (const auto &l : surface_loads)
      l.function->set_time(t);

    std::vector<unsigned int> component(n);
    for (unsigned int k = 0; k < n; ++k)
      component[k] = fe.system_to_component_index(k).first;
    std::vector<Tensor2> G(n), AG(n);
    Tensor2              P;
    Vector<double>       load(dim);

    // A failure on one process (an inverted element) must not leave the
    // others waiting in compress(): finish the loop, then agree.
    std::string failure, input_failure;
    for (const auto &cell : dof_handler.active_cell_iterators())
      try
        {
          if (!cell->is_locally_owned() || !input_failure.empty())
            continue;
          fe_values.reinit(cell);
          cell_matrix   = 0;
          cell_rhs      = 0;
          Material &law = *materials[cell->material_id()];
          fe_values[u].get_function_gradients(U_ghost, grads);
          if (axisymmetric)
            fe_values[u].get_function_values(U_ghost, values);
          const auto *body_force = body_forces[cell->material_id()].get();

          for (unsigned int q = 0; q < nq; ++q)
            {
              const Point<dim> &x = fe_values.quadrature_point(q);
              const double      r = x[0];
              const double      w =
                fe_values.JxW(q) * (axisymmetric ? 2 * numbers::PI * r : 1.);
              try
                {
                  law.evaluate(embed<dim>(grads[q],
                                          axisymmetric ? values[q][0] / r : 0.),
                               P);
                }
              catch (const std::exception &e)
                {
                  failure = e.what();
                  P       = 0;
                }

              Tensor<1, dim> b;
              if (exact)
                b = exact->body_force(x);
              else if (body_force)
                {
                  body_force->vector_value(x, load);
                  for (unsigned int d = 0; d < dim; ++d)
                    b[d] = load[d];
                }

              for (unsigned int k = 0; k < n; ++k)
                {
                  const unsigned int   c    = component[k];
                  const Tensor<1, dim> dphi = fe_values.shape_grad(k, q);
                  const double         phi  = fe_values.shape_value(k, q);
                  const double hoop = (axisymmetric && c == 0) ? phi / r : 0.;
                  if (F)
                    {
                      double v = 0;
                      for (unsigned int j = 0; j < dim; ++j)
                        v += P[c][j] * dphi[j];
                      if (dim == 2)
                        v += P[2][2] * hoop;
                      cell_rhs(k) += (v - b[c] * phi) * w;
                    }
                  if (tangent)
                    {
                      G[k] = 0;
                      for (unsigned int j = 0; j < dim; ++j)
                        G[k][c][j] = dphi[j];
                      if (dim == 2)
                        G[k][2][2] = hoop;
                    }
                }
              if (tangent)
                {
                  for (unsigned int l = 0; l < n; ++l)
                    AG[l] = law.tangent(G[l]);
                  for (unsigned int k = 0; k < n; ++k)
                    {
                      const unsigned int c = component[k];
                      for (unsigned int l = 0; l < n; ++l)
                        {
                          double v = 0;
                          for (unsigned int j = 0; j < dim; ++j)
                            v += AG[l][c][j] * G[k][c][j];
                          if (dim == 2)
                            v += AG[l][2][2] * G[k][2][2];
                          cell_matrix(k, l) += v * w;
                        }
                    }
                }
            }

          // Tractions and pressures (dead loads on the reference surface).
          if (F && !surface_loads.empty())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                for (const auto &l : surface_loads)
                  if (l.ids.count(cell->face(f)->boundary_id()))
                    {
                      fe_face.reinit(cell, f);
                      for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                        {
                          const Point<dim> &x = fe_face.quadrature_point(q);
                          const double      w =
                            fe_face.JxW(q) *
                            (axisymmetric ? 2 * numbers::PI * x[0] : 1.);
                          Tensor<1, dim> tr;
                          if (l.parameters->type ==
                              BoundaryConditionType::pressure)
                            tr =
                              -l.function->value(x) * fe_face.normal_vector(q);
                          else
                            {
                              l.function->vector_value(x, load);
                              for (unsigned int d = 0; d < dim; ++d)
                                tr[d] = load[d];
                            }
                          for (unsigned int k = 0; k < n; ++k)
                            cell_rhs(k) -=
                              tr[component[k]] * fe_face.shape_value(k, q) * w;
                        }
                    }

          cell->get_dof_indices(dofs);
          if (F && increment)
            {
              Vector<double> d(n), Kd(n);
              for (unsigned int k = 0; k < n; ++k)
                d(k) = D_ghost[dofs[k]];
              cell_matrix.vmult(Kd, d);
              cell_rhs += Kd;
            }
          if (F && J)
            constraints.distribute_local_to_global(
              cell_matrix, cell_rhs, dofs, *J, *F);
          else if (F)
            constraints.distribute_local_to_global(cell_rhs, dofs, *F);
          else
            constraints.distribute_local_to_global(cell_matrix, dofs, *J);
        }
      catch (const InputError &e)
        {
          // A function of the scene that is not finite here: finish the
          // loop (the other processes wait in compress()), then agree.
          input_failure = e.what();
        }

    // Concentrated forces at vertices.
    if (F && input_failure.empty())
      for (const auto &pf : point_forces)
        try
          {
            pf.function->set_time(t);
            for (const auto &[node_dofs, x] : pf.nodes)
              {
                pf.function->vector_value(x, load);
                std::vector<types::global_dof_index> idx(node_dofs.begin(),
                                                         node_dofs.end());
                Vector<double>                       f(dim);
                for (unsigned int d = 0; d < dim; ++d)
                  f[d] = -load[d];
                constraints.distribute_local_to_global(f, idx, *F);
              }
          }
        catch (const InputError &e)
          {
            input_failure = e.what();
          }

    if (F)
      F->compress(VectorOperation::add);
    if (J)
      J->compress(VectorOperation::add);
    throw_input_error_on_any_process(input_failure, comm);
    throw_on_any_process(failure, comm);
  }

  template <int dim>
  std::map<std::string, Tensor<1, dim>>
  Elasticity<dim>::reactions(const VectorType &U,
                             const double      t,
                             const VectorType *contact_forces) const
  {
    // Condense hanging nodes only: then the residual vanishes at every DoF
    // but the Dirichlet ones, where it is the reaction.
    VectorType F(owned_total, comm);
    assemble(U, t, &F, nullptr, hanging_node_constraints);
    if (contact_forces)
      F += *contact_forces;
    std::map<std::string, Tensor<1, dim>> result;
    for (const auto &d : dirichlet)
      {
        const std::string &name = d.parameters->name;
        // Only the components this condition constrains.
        const ComponentMask               mask = component_mask(*d.parameters);
        Tensor<1, dim>                    sum;
        std::set<types::global_dof_index> counted;
        if (d.on_node_set)
          {
            // Node sets: their owned vertex DoFs.
            for (const auto &[node_dofs, x] : d.nodes)
              for (unsigned int c = 0; c < dim; ++c)
                if (mask[c] && owned.is_element(node_dofs[c]) &&
                    counted.insert(node_dofs[c]).second)
                  sum[c] += F(node_dofs[c]);
          }
        if (d.ids.empty())
          {
            result[name] = Utilities::MPI::sum(sum, comm);
            continue;
          }
        const IndexSet dofs =
          DoFTools::extract_boundary_dofs(dof_handler, mask, d.ids);
        std::vector<types::global_dof_index> local_dofs(fe.n_dofs_per_cell());
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(local_dofs);
              for (unsigned int i = 0; i < local_dofs.size(); ++i)
                if (owned.is_element(local_dofs[i]) &&
                    dofs.is_element(local_dofs[i]) &&
                    counted.insert(local_dofs[i]).second)
                  sum[fe.system_to_component_index(i).first] +=
                    F(local_dofs[i]);
            }
        result[name] = Utilities::MPI::sum(sum, comm);
      }
    return result;
  }

  template <int dim>
  std::pair<double, double>
  Elasticity<dim>::errors(const VectorType &U) const
  {
    Assert(exact, ExcInternalError());
    const VectorType  U_ghost = ghosted_displacement(U);
    Vector<float>     cellwise(triangulation.n_active_cells());
    const QGauss<dim> q(scene.degree + 2);
    VectorTools::integrate_difference(*mapping,
                                      dof_handler,
                                      U_ghost,
                                      *exact,
                                      cellwise,
                                      q,
                                      VectorTools::L2_norm);
    const double l2 = VectorTools::compute_global_error(triangulation,
                                                        cellwise,
                                                        VectorTools::L2_norm);
    VectorTools::integrate_difference(*mapping,
                                      dof_handler,
                                      U_ghost,
                                      *exact,
                                      cellwise,
                                      q,
                                      VectorTools::H1_seminorm);
    const double h1 =
      VectorTools::compute_global_error(triangulation,
                                        cellwise,
                                        VectorTools::H1_seminorm);
    return {l2, h1};
  }

  template <int dim>
  std::vector<VectorType>
  Elasticity<dim>::rigid_body_modes() const
  {
    const unsigned int      n_modes = axisymmetric ? dim : dim * (dim + 1) / 2;
    std::vector<VectorType> modes(n_modes, VectorType(owned_total, comm));
    const auto             &points = fe.get_unit_support_points();
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned.is_element(dofs[i]))
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                const Point<dim>   x =
                  mapping->transform_unit_to_real_cell(cell, points[i]);
                modes[c](dofs[i]) = 1.;
                if (axisymmetric)
                  continue;
                if (dim == 2)
                  modes[2](dofs[i]) = (c == 0 ? -x[1] : x[0]);
                else
                  {
                    // rotations about z, x, y
                    const unsigned int a[3][2] = {{0, 1}, {1, 2}, {2, 0}};
                    for (unsigned int m = 0; m < 3; ++m)
                      {
                        const unsigned int p = a[m][0], q = a[m][1];
                        if (c == p)
                          modes[dim + m](dofs[i]) = -x[q];
                        else if (c == q)
                          modes[dim + m](dofs[i]) = x[p];
                      }
                  }
              }
        }
    for (auto &m : modes)
      m.compress(VectorOperation::insert);
    return modes;
  }

  template <int dim>
  std::vector<std::string>
  Elasticity<dim>::active_effects() const
  {
    std::vector<std::string> e;
    e.push_back(std::string(scene.geometric_nonlinearity ?
                              "finite-strain neo-Hookean" :
                              "small-strain linear elastic") +
                " bodies (" + scene.analysis_name() + ", Q" +
                std::to_string(scene.degree) + ")");
    for (unsigned int b = 0; b < scene.bodies.size(); ++b)
      if (scene.bodies[b].rigid)
        e.push_back("meshed rigid body " + scene.bodies[b].name +
                    " (prescribed rigid motion)");
    if (!dirichlet.empty() || axisymmetric)
      e.push_back(
        "prescribed displacements" +
        std::string(axisymmetric ? " (with u_r = 0 on the axis)" : ""));
    bool traction = false, pressure = false;
    for (const auto &l : surface_loads)
      (l.parameters->type == BoundaryConditionType::pressure ? pressure :
                                                               traction) = true;
    if (traction)
      e.push_back("surface tractions");
    if (pressure)
      e.push_back("pressures");
    if (!point_forces.empty())
      e.push_back("concentrated forces");
    for (const auto &f : body_forces)
      if (f)
        {
          e.push_back("body forces");
          break;
        }
    if (symmetry_ids[0].size() + symmetry_ids[1].size() +
          symmetry_ids[2].size() >
        0)
      e.push_back("symmetry conditions");
    if (exact)
      e.push_back("manufactured solution (" + scene.manufactured_solution +
                  ")");
    return e;
  }


  namespace
  {
    /// Numbers for messages: short, and -0 printed as 0.
    std::string
    short_number(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(4) << (std::abs(x) < 1e-12 ? 0. : x);
      return s.str();
    }

    /// A physical quantity for messages (a modulus, a force, an area):
    /// short, and not rounded to 0 however small ('Young's modulus (0)'
    /// was printed for 1e-99).
    std::string
    quantity(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(4) << x;
      return s.str();
    }

    /**
     * A basis of the null space of the symmetric positive semi-definite
     * matrix @p G (at most 6 x 6), from its reduced row echelon form with
     * relative pivot tolerance @p tolerance: one vector per free column,
     * with 1 there. Columns are eliminated in their order, so later
     * columns (rotations) become the free ones and each free vector names
     * one rotation together with the translations that make it a rotation
     * about a point; a zero column (a translation nothing stops) gives a
     * pure translation.
     */
    std::vector<std::vector<double>>
    null_space(FullMatrix<double> G, const double tolerance)
    {
      const unsigned int n     = G.m();
      double             scale = 0;
      for (unsigned int i = 0; i < n; ++i)
        scale = std::max(scale, std::abs(G(i, i)));
      std::vector<int> pivot_of_column(n, -1);
      unsigned int     row = 0;
      for (unsigned int col = 0; col < n && row < n; ++col)
        {
          unsigned int best = row;
          for (unsigned int r = row; r < n; ++r)
            if (std::abs(G(r, col)) > std::abs(G(best, col)))
              best = r;
          if (!(std::abs(G(best, col)) > tolerance * scale))
            continue;
          for (unsigned int k = 0; k < n; ++k)
            std::swap(G(row, k), G(best, k));
          const double p = G(row, col);
          for (unsigned int k = 0; k < n; ++k)
            G(row, k) /= p;
          for (unsigned int r = 0; r < n; ++r)
            if (r != row && G(r, col) != 0.)
              {
                const double f = G(r, col);
                for (unsigned int k = 0; k < n; ++k)
                  G(r, k) -= f * G(row, k);
              }
          pivot_of_column[col] = row++;
        }
      std::vector<std::vector<double>> basis;
      for (unsigned int free = 0; free < n; ++free)
        if (pivot_of_column[free] < 0)
          {
            std::vector<double> v(n, 0.);
            v[free] = 1.;
            for (unsigned int col = 0; col < n; ++col)
              if (pivot_of_column[col] >= 0)
                v[col] = -G(pivot_of_column[col], free);
            basis.push_back(v);
          }
      return basis;
    }
  } // namespace

  template <int dim>
  std::vector<std::vector<typename Elasticity<dim>::FreeMotion>>
  Elasticity<dim>::free_motions() const
  {
    std::vector<unsigned int> body_of(scene.bodies.size());
    std::iota(body_of.begin(), body_of.end(), 0u);
    return free_motions_of(
      [](const typename DoFHandler<dim>::active_cell_iterator &cell) {
        return static_cast<unsigned int>(cell->material_id());
      },
      body_of);
  }

  template <int dim>
  std::vector<std::vector<typename Elasticity<dim>::FreeMotion>>
  Elasticity<dim>::free_motions_of(
    const std::function<unsigned int(
      const typename DoFHandler<dim>::active_cell_iterator &)> &group,
    const std::vector<unsigned int>                            &body_of) const
  {
    // The rigid-body motions of a body: translations, and rotations
    // about its center c scaled by its size L (so that every mode is of
    // order 1 on the body): 2D x, y, z-rotation; axisymmetric only the
    // axial translation (a radial "translation" strains the hoops); 3D x,
    // y, z and rotations about x, y, z. A motion is free if no Dirichlet
    // constraint (fixed, displacement, symmetry, u_r = 0 on the axis, a
    // meshed rigid body) acts against it: the null space of the Gram
    // matrix G = sum over the body's constrained vertex DoFs of m m^T,
    // with m the values of the modes there.
    const unsigned int  n_bodies = body_of.size(); // groups of cells
    const unsigned int  n_modes  = axisymmetric ? 1 : dim * (dim + 1) / 2;
    std::vector<double> lower(n_bodies * dim,
                              std::numeric_limits<double>::max()),
      upper(n_bodies * dim, -std::numeric_limits<double>::max());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto v : cell->vertex_indices())
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int k = group(cell) * dim + d;
              lower[k]             = std::min(lower[k], cell->vertex(v)[d]);
              upper[k]             = std::max(upper[k], cell->vertex(v)[d]);
            }
    Utilities::MPI::min(lower, comm, lower);
    Utilities::MPI::max(upper, comm, upper);

    const auto mode_values = [&](const unsigned int b,
                                 const Point<dim>  &x,
                                 const unsigned int c) {
      std::vector<double> m(n_modes, 0.);
      if (axisymmetric)
        {
          m[0] = (c == 1);
          return m;
        }
      Tensor<1, dim> r;
      double         L = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double center = 0.5 * (lower[b * dim + d] + upper[b * dim + d]);
          r[d]                = x[d] - center;
          L = std::max(L, 0.5 * (upper[b * dim + d] - lower[b * dim + d]));
        }
      r /= (L > 0 ? L : 1.);
      m[c] = 1.;
      if (dim == 2)
        m[2] = (c == 0 ? -r[1] : r[0]);
      else
        {
          // omega x r for omega = e_x, e_y, e_z
          const unsigned int next[3] = {1, 2, 0}, prev[3] = {2, 0, 1};
          for (unsigned int a = 0; a < 3; ++a)
            {
              if (c == next[a])
                m[dim + a] = -r[prev[a]];
              else if (c == prev[a])
                m[dim + a] = r[next[a]];
            }
        }
      return m;
    };

    std::vector<double> gram(n_bodies * n_modes * n_modes, 0.);
    std::vector<bool>   seen(owned.n_elements(), false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto v : cell->vertex_indices())
          for (unsigned int c = 0; c < dim; ++c)
            {
              const auto i = cell->vertex_dof_index(v, c);
              if (!owned.is_element(i) || seen[owned.index_within_set(i)])
                continue;
              seen[owned.index_within_set(i)] = true;
              if (!homogeneous_constraints.is_constrained(i))
                continue;
              const auto *entries =
                homogeneous_constraints.get_constraint_entries(i);
              if (entries && !entries->empty())
                continue; // a hanging node, not a support
              const auto m = mode_values(group(cell), cell->vertex(v), c);
              double    *G = &gram[group(cell) * n_modes * n_modes];
              for (unsigned int a = 0; a < n_modes; ++a)
                for (unsigned int b = 0; b < n_modes; ++b)
                  G[a * n_modes + b] += m[a] * m[b];
            }
    Utilities::MPI::sum(gram, comm, gram);

    const char                          *axis[] = {"x", "y", "z"};
    std::vector<std::vector<FreeMotion>> result(n_bodies);
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        if (scene.bodies[body_of[b]].rigid)
          continue;
        FullMatrix<double> G(n_modes, n_modes);
        for (unsigned int i = 0; i < n_modes; ++i)
          for (unsigned int j = 0; j < n_modes; ++j)
            G(i, j) = gram[(b * n_modes + i) * n_modes + j];
        // Relative pivot tolerance: a single constrained vertex stops a
        // translation with a pivot of order 1; rounding is 1e-16.
        for (const auto &v : null_space(G, 1e-10))
          {
            FreeMotion motion;
            if (axisymmetric)
              {
                motion.text    = "translation along the axis (y)";
                motion.axis[1] = 1.;
                result[b].push_back(motion);
                continue;
              }
            Point<dim> center;
            double     L = 0;
            for (unsigned int d = 0; d < dim; ++d)
              {
                center[d] = 0.5 * (lower[b * dim + d] + upper[b * dim + d]);
                L =
                  std::max(L, 0.5 * (upper[b * dim + d] - lower[b * dim + d]));
              }
            L = (L > 0 ? L : 1.);
            Tensor<1, dim> t;
            for (unsigned int d = 0; d < dim; ++d)
              t[d] = v[d];
            Tensor<1, 3> w; // the rotation rate, physical units
            for (unsigned int a = dim; a < n_modes; ++a)
              w[dim == 2 ? 2 : a - dim] = v[a] / L;
            if (w.norm() * L < 1e-8 * t.norm())
              {
                t /= t.norm();
                for (unsigned int d = 0; d < dim; ++d)
                  motion.axis[d] = t[d];
                unsigned int nonzero = 0, along = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  if (std::abs(t[d]) > 1e-8)
                    {
                      ++nonzero;
                      along = d;
                    }
                if (nonzero == 1)
                  motion.text = std::string("translation in ") + axis[along];
                else
                  {
                    std::string direction;
                    for (unsigned int d = 0; d < dim; ++d)
                      direction += (d ? ", " : "") + short_number(t[d]);
                    motion.text = "translation along (" + direction + ")";
                  }
                result[b].push_back(motion);
                continue;
              }
            // The points that do not move: t + w x (x - c) = 0, i.e.
            // x = c + (w x t) / |w|^2 on the axis along w.
            Tensor<1, 3> t3;
            for (unsigned int d = 0; d < dim; ++d)
              t3[d] = t[d];
            const Tensor<1, 3> p = cross_product_3d(w, t3) / (w * w);
            std::string        point;
            for (unsigned int d = 0; d < dim; ++d)
              {
                point += (d ? ", " : "") + short_number(center[d] + p[d]);
                motion.point[d] = center[d] + p[d];
              }
            motion.rotation = true;
            motion.axis     = w / w.norm();
            if (dim == 2)
              motion.text = "rotation about z around (" + point + ")";
            else
              {
                std::string direction;
                for (unsigned int d = 0; d < 3; ++d)
                  direction += (d ? ", " : "") + short_number(motion.axis[d]);
                motion.text = "rotation about the axis along (" + direction +
                              ") through (" + point + ")";
              }
            result[b].push_back(motion);
          }
      }
    return result;
  }

  template <int dim>
  typename Elasticity<dim>::Parts
  Elasticity<dim>::parts() const
  {
    // Connected parts on the coarse mesh, which every process holds
    // whole (refinement does not change what is connected): coarse cells
    // of one body that share a vertex are one part (union-find).
    std::vector<unsigned int> root(triangulation.n_vertices());
    std::iota(root.begin(), root.end(), 0u);
    const auto find = [&](unsigned int v) {
      while (root[v] != v)
        v = root[v] = root[root[v]];
      return v;
    };
    for (const auto &cell : triangulation.cell_iterators_on_level(0))
      for (const auto v : cell->vertex_indices())
        root[find(cell->vertex_index(v))] = find(cell->vertex_index(0));
    Parts                                                         result;
    std::map<std::pair<unsigned int, unsigned int>, unsigned int> number;
    std::vector<Point<dim>>                                       lower, upper;
    result.part_of_coarse_cell.resize(triangulation.n_cells(0));
    for (const auto &cell : triangulation.cell_iterators_on_level(0))
      {
        const auto key =
          std::make_pair(static_cast<unsigned int>(cell->material_id()),
                         find(cell->vertex_index(0)));
        const auto [it, added] =
          number.emplace(key, static_cast<unsigned int>(result.body.size()));
        if (added)
          {
            result.body.push_back(key.first);
            lower.push_back(cell->vertex(0));
            upper.push_back(cell->vertex(0));
          }
        const unsigned int part                   = it->second;
        result.part_of_coarse_cell[cell->index()] = part;
        for (const auto v : cell->vertex_indices())
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[part][d] = std::min(lower[part][d], cell->vertex(v)[d]);
              upper[part][d] = std::max(upper[part][d], cell->vertex(v)[d]);
            }
      }
    for (unsigned int p = 0; p < lower.size(); ++p)
      result.center.push_back(Point<dim>(0.5 * (lower[p] + upper[p])));
    return result;
  }

  template <int dim>
  std::vector<std::string>
  Elasticity<dim>::round_about(const std::vector<std::string> &names,
                               const FreeMotion               &m) const
  {
    // Per surface: the largest |v . n| and |v| over its faces, v = axis x
    // (x - point) the turn's velocity at the face's centre and n the
    // normal of the face's straight chord (the perpendicular bisector of a
    // chord of a circle passes through its centre, so a cylinder's facets
    // give 0 up to round-off).
    std::vector<double> normal_part(names.size(), 0.), size(names.size(), 0.);
    for (unsigned int k = 0; k < names.size(); ++k)
      {
        const auto &ids = mesh.surface(names[k], "Contact pairs");
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  ids.count(cell->face(f)->boundary_id()))
                {
                  const auto       face = cell->face(f);
                  Tensor<1, 3>     n, r;
                  const Point<dim> x = face->center();
                  if constexpr (dim == 2)
                    {
                      const Tensor<1, dim> t =
                        face->vertex(1) - face->vertex(0);
                      n[0] = t[1];
                      n[1] = -t[0];
                    }
                  else
                    {
                      const Tensor<1, dim> d1 =
                        face->vertex(3) - face->vertex(0);
                      const Tensor<1, dim> d2 =
                        face->vertex(2) - face->vertex(1);
                      n = cross_product_3d(Tensor<1, 3>(d1), Tensor<1, 3>(d2));
                    }
                  if (!(n.norm() > 0.))
                    continue;
                  n /= n.norm();
                  for (unsigned int d = 0; d < dim; ++d)
                    r[d] = x[d] - m.point[d];
                  const Tensor<1, 3> v = cross_product_3d(m.axis, r);
                  normal_part[k] = std::max(normal_part[k], std::abs(v * n));
                  size[k]        = std::max(size[k], v.norm());
                }
      }
    Utilities::MPI::max(normal_part, comm, normal_part);
    Utilities::MPI::max(size, comm, size);
    std::vector<std::string> round;
    for (unsigned int k = 0; k < names.size(); ++k)
      if (size[k] > 0. && normal_part[k] <= 0.01 * size[k])
        round.push_back(names[k]);
    return round;
  }

  template <int dim>
  void
  Elasticity<dim>::check_conditions(const double t)
  {
    condition_notes.clear();
    if (exact)
      return;
    const double tol = 1e-12 * mesh.scene_size();
    // Per DoF: the value and the condition (index in `dirichlet`) that
    // holds it. The axis of an axisymmetric scene counts as a condition
    // u_r = 0 after all others, as constraints_at() applies it.
    std::map<types::global_dof_index, std::pair<double, unsigned int>> held;
    const unsigned int n  = dirichlet.size();
    const unsigned int nc = n + 1; // + the axis
    // For each pair (earlier, later): DoFs with different values, and an
    // example; for each condition: DoFs it holds.
    std::vector<unsigned int> differ(nc * nc, 0), holds(nc, 0);
    std::vector<std::string>  example(nc * nc);
    // The first DoF of each pair with different values, and the values.
    std::map<unsigned int, std::tuple<types::global_dof_index, double, double>>
               first;
    const auto record = [&](const types::global_dof_index i,
                            const double                  value,
                            const unsigned int            k) {
      if (!owned.is_element(i))
        return;
      const auto it = held.find(i);
      if (it == held.end())
        {
          held[i] = {value, k};
          ++holds[k];
          return;
        }
      const auto [v0, k0] = it->second;
      if (std::abs(value - v0) <=
          tol + 1e-9 * std::max(std::abs(value), std::abs(v0)))
        return;
      if (differ[k0 * nc + k]++ == 0)
        first[k0 * nc + k] = {i, v0, value};
    };
    {
      for (unsigned int k = 0; k < n; ++k)
        {
          const auto                  &d    = dirichlet[k];
          const auto                  &bc   = *d.parameters;
          const ComponentMask          mask = component_mask(bc);
          Functions::ZeroFunction<dim> zero(dim);
          const Function<dim>         *f = &zero;
          if (bc.type == BoundaryConditionType::displacement)
            {
              d.function->set_time(t);
              f = d.function.get();
            }
          if (d.on_node_set)
            {
              Vector<double> value(dim);
              for (const auto &[node_dofs, x] : d.nodes)
                {
                  f->vector_value(x, value);
                  for (unsigned int c = 0; c < dim; ++c)
                    if (mask[c])
                      record(node_dofs[c], value[c], k);
                }
            }
          if (d.ids.empty())
            continue;
          std::map<types::boundary_id, const Function<dim> *> functions;
          for (const auto id : d.ids)
            functions[id] = f;
          std::map<types::global_dof_index, double> values;
          VectorTools::interpolate_boundary_values(
            *mapping, dof_handler, functions, values, mask);
          for (const auto &[i, v] : values)
            record(i, v, k);
        }
      if (axisymmetric)
        {
          const double tol_axis = 1e-10 * mesh.scene_size();
          std::vector<types::global_dof_index> dofs(fe.n_dofs_per_face());
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const auto f : cell->face_indices())
                {
                  const auto face    = cell->face(f);
                  bool       on_axis = true;
                  for (const auto v : face->vertex_indices())
                    on_axis =
                      on_axis && std::abs(face->vertex(v)[0]) < tol_axis;
                  if (!on_axis)
                    continue;
                  face->get_dof_indices(dofs);
                  for (unsigned int i = 0; i < dofs.size(); ++i)
                    if (fe.face_system_to_component_index(i).first == 0)
                      record(dofs[i], 0., n);
                }
        }
    }
    if (!first.empty())
      {
        // Where those DoFs are: their cells' support points.
        std::map<types::global_dof_index, std::pair<unsigned int, Point<dim>>>
                                             where;
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        for (const auto &[p, v] : first)
          where[std::get<0>(v)] = {0, Point<dim>()};
        const auto &unit = fe.get_unit_support_points();
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              for (unsigned int j = 0; j < dofs.size(); ++j)
                if (const auto w = where.find(dofs[j]); w != where.end())
                  w->second = {fe.system_to_component_index(j).first,
                               mapping->transform_unit_to_real_cell(cell,
                                                                    unit[j])};
            }
        for (const auto &[p, v] : first)
          {
            const auto &[i, v0, v1] = v;
            const auto &[c, x]      = where[i];
            std::ostringstream text;
            text << std::setprecision(4) << "component "
                 << "xyz"[c] << " at (";
            for (unsigned int d = 0; d < dim; ++d)
              text << (d ? ", " : "") << x[d];
            text << "): " << v0 << " and " << v1;
            example[p] = text.str();
          }
      }
    for (auto *v : {&differ, &holds})
      MPI_Allreduce(MPI_IN_PLACE,
                    v->data(),
                    static_cast<int>(v->size()),
                    MPI_UNSIGNED,
                    MPI_SUM,
                    comm);
    // An example for each pair, from the first process that has one.
    for (unsigned int p = 0; p < nc * nc; ++p)
      if (differ[p] > 0)
        for (const auto &e : Utilities::MPI::all_gather(comm, example[p]))
          if (!e.empty())
            {
              example[p] = e;
              break;
            }
    const auto name = [&](const unsigned int k) {
      return "'Boundary condition " + dirichlet[k].parameters->name + "'";
    };
    for (unsigned int k0 = 0; k0 < n; ++k0)
      if (differ[k0 * nc + n] > 0)
        throw InputError(
          "In scene file '" + scene.file + "': " + name(k0) +
          " prescribes a radial displacement other than 0 on the axis of "
          "the axisymmetric scene (r = 0; " +
          example[k0 * nc + n] +
          "), where u_r = 0 holds for a solid of revolution. Leave the "
          "radial component free there ('Components'), or move the "
          "condition off the axis.");
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int k0 = 0; k0 < n; ++k0)
        if (differ[k0 * nc + k] > 0)
          {
            if (holds[k] == 0)
              throw InputError(
                "In scene file '" + scene.file + "': " + name(k) +
                " has no effect: " + name(k0) +
                ", earlier in 'Boundary conditions', prescribes its DoFs "
                "with other values (" +
                std::to_string(differ[k0 * nc + k]) + " DoF(s), e.g. " +
                example[k0 * nc + k] +
                "), and the first condition of a DoF holds. Remove one of "
                "the two, or put them on different surfaces or "
                "components.");
            condition_notes.push_back(
              name(k0) + " and " + name(k) +
              " prescribe different values for " +
              std::to_string(differ[k0 * nc + k]) +
              " DoF(s) they share (e.g. " + example[k0 * nc + k] + "); " +
              name(k0) +
              ", earlier in 'Boundary conditions', holds there. Check that "
              "this is meant (e.g. a corner shared by two surfaces).");
          }
  }

  template <int dim>
  void
  Elasticity<dim>::check_inputs()
  {
    const std::string file = "In scene file '" + scene.file + "': ";

    // A scene that neither loads nor moves anything has the solution 0;
    // that is almost certainly a scene whose loads were forgotten.
    bool loaded =
      !scene.contact_pairs.empty() || scene.manufactured_solution != "none";
    for (const auto &bc : scene.boundary_conditions)
      loaded = loaded ||
               !(bc.type == BoundaryConditionType::fixed || bc.is_symmetry());
    for (const auto &b : scene.bodies)
      loaded = loaded || !b.body_force.empty() || b.rigid;
    require(loaded,
            file +
              "The scene has nothing that loads or moves its bodies (no "
              "displacement, traction, pressure, force or body force, no "
              "rigid-body motion, no contact pair): its solution is zero. Add "
              "a load in a 'Boundary condition' subsection (see 'Boundary "
              "conditions').");


    // Bodies in a contact pair: contact may hold them (if it closes).
    std::set<std::string>                           in_contact;
    std::map<std::string, std::vector<std::string>> contact_surfaces;
    std::set<types::boundary_id>                    contact_ids;
    bool                                            node_set_slave = false;
    for (const auto &cp : scene.contact_pairs)
      for (const auto &list : {cp.slave, cp.master})
        for (const auto &surface : Utilities::split_string_list(list, ','))
          {
            if (scene_node_sets.count(surface))
              node_set_slave = true;
            const auto dot = surface.find('.');
            if (dot != std::string::npos)
              {
                const auto body = surface.substr(0, dot);
                in_contact.insert(body);
                auto &names = contact_surfaces[body];
                if (mesh.has_surface(surface) &&
                    std::find(names.begin(), names.end(), surface) ==
                      names.end())
                  names.push_back(surface);
                if (mesh.has_surface(surface))
                  for (const auto id :
                       mesh.surface(surface, "Contact pair " + cp.name))
                    contact_ids.insert(id);
              }
          }
    const auto motions = free_motions();
    holding_hints.clear();
    for (unsigned int b = 0; b < scene.bodies.size(); ++b)
      {
        if (motions[b].empty())
          continue;
        std::string list;
        for (unsigned int i = 0; i < motions[b].size(); ++i)
          list += (i == 0                     ? "" :
                   i + 1 == motions[b].size() ? " and " :
                                                ", ") +
                  motions[b][i].text;
        const std::string &name = scene.bodies[b].name;
        if (in_contact.count(name) || node_set_slave)
          {
            std::string hint =
              "body '" + name + "' is held against its " + list +
              " only by contact: while that contact is open nothing holds "
              "it, and the Newton systems are singular. Let the contact "
              "close from the first load step (start in contact or move "
              "the body into it by a prescribed displacement), or add a "
              "boundary condition that stops these motions (e.g. a "
              "symmetry condition).";
            // A turn that frictionless contact cannot resist even when it
            // is closed: every contact force on a round surface points at
            // its axis (doc/theory/nonlinear-solution.md, "A round body
            // turning about its centre").
            for (const auto &m : motions[b])
              if (m.rotation)
                for (const auto &surface :
                     round_about(contact_surfaces[name], m))
                  hint +=
                    " Frictionless contact cannot hold its " + m.text +
                    " firmly even where it is closed: its contact surface '" +
                    surface +
                    "' is round about that axis, so every contact force on "
                    "it points at the axis but for the deformation of the "
                    "contact zone and the facets of the mesh, which resist "
                    "the turn weakly and unevenly; Newton may wander and "
                    "cycle (most with a faceted or quadratic master "
                    "surface). Hold the turn, e.g. with a symmetry or "
                    "displacement condition on a node set of one more point "
                    "on the axis.";
            holding_hints.push_back(hint);
            continue;
          }
        throw InputError(
          file + "Body '" + name + "' is not held: nothing stops its " + list +
          " (no fixed, displacement or symmetry condition acts against "
          "them, and the body is in no contact pair), so the equilibrium "
          "has no unique solution. Add a boundary condition that holds it, "
          "e.g. 'Type = fixed' on one surface of '" +
          name + "', or symmetry conditions.");
      }

    // A body of separate parts (a mesh file may hold several): each part
    // must be held on its own. The test above sees the whole body only: a
    // second, unsupported square in a body's mesh file ran with exit 0 and
    // a singular matrix (the part's displacement whatever the solver made
    // of it).
    {
      const auto                p = parts();
      std::vector<unsigned int> n_parts(scene.bodies.size(), 0);
      for (const auto b : p.body)
        ++n_parts[b];
      if (*std::max_element(n_parts.begin(), n_parts.end()) > 1)
        {
          const auto part_of =
            [&](const typename DoFHandler<dim>::active_cell_iterator &cell) {
              // Its coarse ancestor (deal.II 9.4 keeps the map from
              // coarse cell id to index private).
              typename Triangulation<dim>::cell_iterator c = cell;
              while (c->level() > 0)
                c = c->parent();
              return p.part_of_coarse_cell[c->index()];
            };
          const auto part_motions = free_motions_of(part_of, p.body);
          // The parts with a face on a contact surface: contact may hold
          // those, not a part of the same body that no pair touches (until
          // 2026-12-06 any part of a body in a pair counted as held by
          // contact, and an unheld one ran, or failed with a note that
          // blamed open contact).
          std::vector<unsigned int> touches(p.body.size(), 0);
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const auto f : cell->face_indices())
                if (cell->at_boundary(f) &&
                    contact_ids.count(cell->face(f)->boundary_id()) > 0)
                  touches[part_of(cell)] = 1;
          MPI_Allreduce(MPI_IN_PLACE,
                        touches.data(),
                        static_cast<int>(touches.size()),
                        MPI_UNSIGNED,
                        MPI_MAX,
                        comm);
          for (unsigned int k = 0; k < p.body.size(); ++k)
            {
              const unsigned int b = p.body[k];
              if (n_parts[b] < 2 || part_motions[k].empty() ||
                  !motions[b].empty())
                continue;
              std::string list, center;
              for (unsigned int i = 0; i < part_motions[k].size(); ++i)
                list += (i == 0                          ? "" :
                         i + 1 == part_motions[k].size() ? " and " :
                                                           ", ") +
                        part_motions[k][i].text;
              for (unsigned int d = 0; d < dim; ++d)
                center += (d ? ", " : "") + short_number(p.center[k][d]);
              const std::string &name = scene.bodies[b].name;
              const std::string  what =
                "body '" + name + "' has " + std::to_string(n_parts[b]) +
                " separate parts (cells that share no vertex, e.g. meshed "
                "apart in its mesh file), and its part around (" +
                center + ")";
              if (touches[k] > 0 || node_set_slave)
                {
                  holding_hints.push_back(
                    what + " is held against its " + list +
                    " only by contact: while that contact is open nothing "
                    "holds it. Hold each part by a boundary condition, or "
                    "make it a body of its own.");
                  continue;
                }
              throw InputError(
                file + "B" + what.substr(1) +
                " is not held: nothing stops its " + list +
                " (no fixed, displacement or symmetry condition acts on "
                "that part" +
                (in_contact.count(name) ? ", and no contact pair touches it" :
                                          "") +
                "). Hold each part with a boundary condition on a "
                "surface of it, join the parts in the mesh, or make each "
                "part a body of its own.");
            }
        }
    }

    // Every function of the scene is finite at the first and the last
    // load factor (CheckedFunction throws otherwise), before anything is
    // written; the values in between are checked as they are used.
    const double first = 1. / scene.load_stepping.number_of_steps;
    // Their sizes too: the largest nodal load (the residual at U = 0) and
    // the largest prescribed displacement, at the last load factor.
    double largest_load = 0., largest_displacement = 0.;
    for (const double t : {first, 1.})
      {
        const auto c = constraints_at(t);
        VectorType U(owned_total, comm), F(owned_total, comm);
        residual(U, t, F);
        largest_load = std::max(largest_load, F.linfty_norm());
        for (const auto &line : c.get_lines())
          if (owned.is_element(line.index))
            largest_displacement =
              std::max(largest_displacement, std::abs(line.inhomogeneity));
      }
    largest_displacement = Utilities::MPI::max(largest_displacement, comm);
    largest_scaled_load  = largest_load * residual_scale();

    // Stiffnesses that double precision cannot resolve together.
    double      E_min = std::numeric_limits<double>::infinity(), E_max = 0;
    std::string soft, stiff;
    for (const auto &b : scene.bodies)
      if (!b.rigid)
        {
          if (b.material.youngs_modulus < E_min)
            {
              E_min = b.material.youngs_modulus;
              soft  = b.name;
            }
          if (b.material.youngs_modulus > E_max)
            {
              E_max = b.material.youngs_modulus;
              stiff = b.name;
            }
        }
    // 1e12: the forces in the softest body are then 1e-12 of those in the
    // stiffest; with 16 digits in double precision the solver tolerance
    // (1e-8 and finer) can no longer be met for both. Make the stiff body
    // rigid instead ('Rigid body/Rigid = true').
    constexpr double maximum_stiffness_ratio = 1e12;
    require(!(E_max > maximum_stiffness_ratio * E_min),
            file + "Young's moduli of 'Body " + stiff + "' (" +
              short_number(E_max) + ") and 'Body " + soft + "' (" +
              short_number(E_min) + ") differ by more than a factor of " +
              short_number(maximum_stiffness_ratio) +
              ": double precision cannot resolve both bodies' forces. Make "
              "the stiff body rigid ('Rigid body/Rigid = true') instead.");
    const double L = mesh.scene_size();
    // Loads and prescribed displacements that would move the bodies by
    // more than 1e8 times the scene's size: positions X + u then keep no
    // digit of the mesh's geometry (u carries 16 digits, X is 1e-8 of it),
    // and beyond about 1e150 the residual's norm overflows. Almost always
    // units that do not match (a load in N against moduli in GPa, or a
    // displacement in mm in a scene in m), or an expression gone wrong.
    // The load's measure: a nodal force over the stiffest body's modulus
    // and the mean boundary face area, the strain it would cause there.
    constexpr double maximum_motion = 1e8;
    if (E_max > 0.)
      {
        const double strain = largest_load / (E_max * reference_area);
        require(std::isfinite(strain) && !(strain > maximum_motion),
                file +
                  "The loads ('Function' of the traction, pressure and "
                  "force conditions, 'Body force') reach a nodal force "
                  "of " +
                  quantity(largest_load) + ", " + quantity(strain) +
                  " times the stiffest body's Young's modulus (" +
                  quantity(E_max) + ") on a face of mean area " +
                  quantity(reference_area) +
                  ": they would deform the bodies by more than " +
                  short_number(maximum_motion) +
                  " times their size, which double precision cannot "
                  "represent against the meshes' coordinates. Check that "
                  "the loads, the moduli and the lengths are in one system "
                  "of units (N, MPa, mm or N, Pa, m).");
        // Below that limit a step that fails where the loads strain the
        // bodies by hundreds is most likely a mistake of units, and no
        // material takes such strains: a failed step's note says so.
        if (strain > 100.)
          holding_hints.push_back(
            "the loads reach a nodal force of " + quantity(largest_load) +
            ", " + quantity(strain) +
            " times the stiffest body's Young's modulus (" + quantity(E_max) +
            ") on a face of mean area " + quantity(reference_area) +
            ": strains of that size are beyond any material, and a "
            "geometrically nonlinear body folds under them. Check that the "
            "loads, "
            "the moduli and the lengths are in one system of units (N, MPa, "
            "mm or N, Pa, m).");
      }
    require(std::isfinite(largest_displacement) &&
              !(largest_displacement > maximum_motion * L),
            file +
              "The prescribed displacements ('Function' of the "
              "displacement conditions, a rigid body's 'Translation' "
              "and 'Rotation' about its 'Rotation center') reach " +
              short_number(largest_displacement) + ", more than " +
              short_number(maximum_motion) + " times the scene's size (" +
              short_number(L) +
              "): positions then keep no digit of the meshes' geometry. "
              "Check the displacements' units and the rigid bodies' "
              "'Rotation center'.");
    driving_strain_ = std::max(largest_scaled_load, largest_displacement / L);
    // A radial force on a node of the axis acts on nothing: u_r = 0 holds
    // there, and its reaction takes the force (until 2026-12-06 a force of
    // 1000 in r on the axis nodes gave zero displacement and exit 0).
    if (axisymmetric)
      for (const auto &pf : point_forces)
        {
          std::string example;
          for (const double t : {first, 1.})
            {
              pf.function->set_time(t);
              for (const auto &[node_dofs, x] : pf.nodes)
                if (example.empty() && std::abs(x[0]) < 1e-10 * L &&
                    pf.function->value(x, 0) != 0.)
                  example = "(" + short_number(x[0]) + ", " +
                            short_number(x[1]) + ") at load factor " +
                            short_number(t) + ": " +
                            short_number(pf.function->value(x, 0));
            }
          for (const auto &e : Utilities::MPI::all_gather(comm, example))
            if (!e.empty())
              throw InputError(
                file + "'" + pf.path +
                "' applies a radial force to a node on the axis of the "
                "axisymmetric scene (r = 0; " +
                e +
                "), where u_r = 0 holds for a solid of revolution: the "
                "force would act on nothing. Give it no radial component "
                "there (its first expression 0; a force on the axis acts "
                "along it, in y), or apply it off the axis.");
        }
    check_conditions(1.);
    for (const auto &cp : scene.contact_pairs)
      if (cp.enforcement == Enforcement::penalty && cp.penalty_stiffness > 0)
        require(!(cp.penalty_stiffness * L >
                  maximum_stiffness_ratio * (E_max > 0 ? E_max : E_min)),
                file + "Parameter 'Contact pair " + cp.name +
                  "/Penalty stiffness' = " +
                  short_number(cp.penalty_stiffness) + " is more than " +
                  short_number(maximum_stiffness_ratio) +
                  " times the stiffness of the bodies (Young's modulus " +
                  short_number(E_max) + " / scene size " + short_number(L) +
                  "): double precision cannot resolve the bodies next to "
                  "it. Use 0 (automatic), or hard contact ('Enforcement = "
                  "hard').");
    // The other end: a penalty so soft that the bodies pass through each
    // other with (almost) no contact force, in silence.
    for (const auto &cp : scene.contact_pairs)
      if (cp.enforcement == Enforcement::penalty && cp.penalty_stiffness > 0 &&
          std::isfinite(E_min))
        require(!(cp.penalty_stiffness * L * maximum_stiffness_ratio < E_min),
                file + "Parameter 'Contact pair " + cp.name +
                  "/Penalty stiffness' = " +
                  // short_number() writes tiny numbers as 0
                  (std::ostringstream()
                   << std::setprecision(4) << cp.penalty_stiffness)
                    .str() +
                  " is less than 1e-12" +
                  " times the stiffness of the bodies (Young's modulus " +
                  short_number(E_min) + " / scene size " + short_number(L) +
                  "): the bodies would pass through each other with no "
                  "contact force. Use 0 (automatic: 1000 E / h), or hard "
                  "contact ('Enforcement = hard').");
  }

  template <int dim>
  std::string
  Elasticity<dim>::holding_hint() const
  {
    std::string hint;
    for (const auto &h : holding_hints)
      hint += "\nNote: " + h;
    return hint;
  }

  template class Elasticity<2>;
  template class Elasticity<3>;
} // namespace glide
