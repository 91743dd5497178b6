#include <glide/mesh/mesh.h>
#include <glide/mesh/mesh_file.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    template <int dim>
    Point<dim>
    to_point(const std::vector<double> &v)
    {
      Point<dim> p;
      for (unsigned int d = 0; d < dim && d < v.size(); ++d)
        p[d] = v[d];
      return p;
    }

    /// Re-set the boundary ids of a round shape from the geometry of each
    /// boundary face: faces on the plane x_d = c_d get plane ids, faces on
    /// the circle/sphere/cylinder of radius r get the ids in @p radii.
    template <int dim>
    void
    label_round_boundary(
      Triangulation<dim>                                             &tria,
      const Point<dim>                                               &center,
      const std::vector<std::pair<double, types::boundary_id>>       &radii,
      const std::vector<std::pair<unsigned int, types::boundary_id>> &planes,
      const double                                                    length,
      const bool                                                      axis_is_z)
    {
      const double tol = 1e-6 * radii.back().first;
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              // A face lies on a plane or a round surface when all its
              // vertices do (independent of the manifolds attached so far).
              const Point<dim> p    = face->center(false);
              bool             done = false;
              if (dim == 3 && axis_is_z)
                {
                  if (std::abs(p[2] - center[2]) < tol)
                    {
                      face->set_boundary_id(10); // bottom
                      continue;
                    }
                  if (std::abs(p[2] - center[2] - length) < tol)
                    {
                      face->set_boundary_id(11); // top
                      continue;
                    }
                }
              auto all_vertices = [&](const auto &on_surface) {
                for (const auto v : face->vertex_indices())
                  if (!on_surface(face->vertex(v)))
                    return false;
                return true;
              };
              for (const auto &[d, id] : planes)
                if (!done && all_vertices([&, d = d](const Point<dim> &x) {
                      return std::abs(x[d] - center[d]) < tol;
                    }))
                  {
                    face->set_boundary_id(id);
                    done = true;
                  }
              for (const auto &[radius, id] : radii)
                if (!done &&
                    all_vertices([&, radius = radius](const Point<dim> &x) {
                      Tensor<1, dim> r = x - center;
                      if (dim == 3 && axis_is_z)
                        r[2] = 0;
                      return std::abs(r.norm() - radius) < tol;
                    }))
                  {
                    face->set_boundary_id(id);
                    done = true;
                  }
              AssertThrow(done,
                          ExcMessage(
                            "A boundary face of a built-in mesh matched "
                            "none of its surfaces."));
            }
    }

    template <int dim>
    void
    set_curved_faces(Triangulation<dim>                 &tria,
                     const std::set<types::boundary_id> &curved)
    {
      tria.set_all_manifold_ids(numbers::flat_manifold_id);
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && curved.count(face->boundary_id()))
            face->set_all_manifold_ids(0);
    }

    /// Disk (2D) or its extrusion along z (3D); @p half keeps the lower
    /// half (y <= center_y).
    template <int dim>
    void
    make_cylinder(const MeshParameters &m,
                  Triangulation<dim>   &tria,
                  const bool            half)
    {
      const Point<dim> c = to_point<dim>(m.center);
      Triangulation<2> disk;
      const Point<2>   c2(c[0], c[1]);
      if (half)
        {
          GridGenerator::half_hyper_ball(disk, Point<2>(), m.radius);
          GridTools::rotate(-numbers::PI / 2, disk);
          GridTools::shift(Tensor<1, 2>(c2), disk);
        }
      else
        GridGenerator::hyper_ball(disk, c2, m.radius);
      disk.set_all_manifold_ids(numbers::flat_manifold_id);

      if constexpr (dim == 2)
        tria.copy_triangulation(disk);
      else
        {
          const unsigned int slices = std::max(
            2u, static_cast<unsigned int>(std::round(m.length / m.radius)) + 1);
          Triangulation<2> flat;
          flat.copy_triangulation(disk);
          GridGenerator::extrude_triangulation(flat, slices, m.length, tria);
          Tensor<1, dim> shift;
          shift[2] = c[2];
          GridTools::shift(shift, tria);
        }
      // ids: 0 curved/outer, 1 flat (cut plane y = c_y), 10 bottom, 11 top
      label_round_boundary<dim>(
        tria,
        c,
        {{m.radius, 0}},
        half ?
          std::vector<std::pair<unsigned int, types::boundary_id>>{{1, 1}} :
          std::vector<std::pair<unsigned int, types::boundary_id>>{},
        m.length,
        true);
      set_curved_faces(tria, {0});
      if constexpr (dim == 2)
        tria.set_manifold(0, SphericalManifold<2>(c));
      else
        {
          Tensor<1, 3> axis;
          axis[2] = 1.;
          tria.set_manifold(0, CylindricalManifold<3>(axis, c));
        }
    }

    /// Put the vertex nearest to @p target exactly on it. Rotations leave
    /// round-off in coordinates; the lowest point of a Hertz body must be
    /// exactly where the analytical contact starts, or a force-driven body
    /// that should touch a flat at one node floats by 1e-17 and its
    /// stiffness matrix is singular.
    template <int dim>
    void
    snap_vertex(Triangulation<dim> &tria,
                const Point<dim>   &target,
                const double        tolerance)
    {
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto v : cell->vertex_indices())
          if (cell->vertex(v).distance(target) < tolerance)
            cell->vertex(v) = target;
    }
  } // namespace



  template <int dim>
  void
  build_body_mesh(const MeshParameters &m,
                  const std::string    &body_name,
                  Triangulation<dim>   &tria,
                  std::map<types::boundary_id, std::vector<std::string>> &names)
  {
    const Point<dim> c = to_point<dim>(m.center);
    names.clear();
    if (m.type == "block")
      {
        std::vector<unsigned int> reps(m.subdivisions.begin(),
                                       m.subdivisions.begin() + dim);
        GridGenerator::subdivided_hyper_rectangle(tria,
                                                  reps,
                                                  to_point<dim>(m.lower_corner),
                                                  to_point<dim>(m.upper_corner),
                                                  /*colorize=*/true);
        const char *n[] = {"left", "right", "bottom", "top", "back", "front"};
        for (unsigned int i = 0; i < 2 * dim; ++i)
          names[i] = {n[i]};
      }
    else if (m.type == "hertz" && (dim == 3 || m.axisymmetric))
      {
        // The lower part of a sphere, for Hertz point contact: in an
        // axisymmetric scene the quarter disk r >= 0, z <= center (its
        // meridian section), in 3D the octant x >= cx, y <= cy, z >= cz
        // (a quarter model with symmetry planes x0 and z0).
        GridGenerator::quarter_hyper_ball(tria, Point<dim>(), m.radius);
        if constexpr (dim == 2)
          GridTools::rotate(-numbers::PI / 2, tria); // (x, y) -> (y, -x)
        else
          {
            Tensor<1, 3> x_axis;
            x_axis[0] = 1.;
            GridTools::rotate(x_axis,
                              numbers::PI / 2,
                              tria); // (x, y, z) -> (x, -z, y)
          }
        GridTools::shift(Tensor<1, dim>(c), tria);
        std::vector<std::pair<unsigned int, types::boundary_id>> planes{{1, 1},
                                                                        {0, 2}};
        if (dim == 3)
          planes.emplace_back(2, 3);
        label_round_boundary<dim>(tria, c, {{m.radius, 0}}, planes, 0., false);
        set_curved_faces(tria, {0});
        tria.set_manifold(0, SphericalManifold<dim>(c));
        Point<dim> lowest = c;
        lowest[1] -= m.radius;
        snap_vertex(tria, lowest, 1e-8 * m.radius);
        names[0] = {"curved"};
        names[1] = {"flat"};
        names[2] = {dim == 2 ? "axis" : "x0"};
        if (dim == 3)
          names[3] = {"z0"};
      }
    else if (m.type == "cylinder" || m.type == "half cylinder" ||
             m.type == "hertz")
      {
        const bool half = (m.type != "cylinder");
        make_cylinder<dim>(m, tria, half);
        if (m.type == "hertz")
          {
            Point<dim> lowest = c;
            lowest[1] -= m.radius;
            snap_vertex(tria, lowest, 1e-8 * m.radius);
          }
        names[0] = {half ? "curved" : "outer"};
        if (half)
          names[1] = {"flat"};
        if (dim == 3)
          {
            names[10] = {"bottom"};
            names[11] = {"top"};
          }
      }
    else if (m.type == "half ring")
      {
        if constexpr (dim == 2)
          {
            GridGenerator::half_hyper_shell(tria,
                                            Point<2>(),
                                            m.inner_radius,
                                            m.radius);
            GridTools::rotate(-numbers::PI / 2, tria);
            GridTools::shift(Tensor<1, dim>(c), tria);
            label_round_boundary<dim>(tria,
                                      c,
                                      {{m.inner_radius, 0}, {m.radius, 1}},
                                      {{1, 2}},
                                      m.length,
                                      true);
            tria.set_all_manifold_ids(0);
            tria.set_manifold(0, SphericalManifold<2>(c));
            names[0] = {"inner"};
            names[1] = {"outer"};
            names[2] = {"ends"};
          }
        else
          throw InputError("Body '" + body_name +
                           "': 'Mesh = half ring' is available in 2D only.");
      }
    else if (m.type == "quarter ring")
      {
        if constexpr (dim == 2)
          {
            GridGenerator::quarter_hyper_shell(
              tria, c, m.inner_radius, m.radius, 3);
            label_round_boundary<dim>(tria,
                                      c,
                                      {{m.inner_radius, 0}, {m.radius, 1}},
                                      {{0, 2}, {1, 3}},
                                      m.length,
                                      true);
            tria.set_all_manifold_ids(0);
            tria.set_manifold(0, SphericalManifold<2>(c));
            names[0] = {"inner"};
            names[1] = {"outer"};
            names[2] = {"x0"};
            names[3] = {"y0"};
          }
        else
          throw InputError("Body '" + body_name +
                           "': 'Mesh = quarter ring' is available in 2D only.");
      }
    else if (m.type == "ring")
      {
        if constexpr (dim == 2)
          GridGenerator::hyper_shell(tria, c, m.inner_radius, m.radius);
        else
          {
            GridGenerator::cylinder_shell(tria,
                                          m.length,
                                          m.inner_radius,
                                          m.radius);
            GridTools::shift(Tensor<1, dim>(c), tria);
          }
        label_round_boundary<dim>(
          tria, c, {{m.inner_radius, 0}, {m.radius, 1}}, {}, m.length, true);
        tria.set_all_manifold_ids(0);
        if constexpr (dim == 2)
          tria.set_manifold(0, SphericalManifold<2>(c));
        else
          {
            Tensor<1, 3> axis;
            axis[2] = 1.;
            tria.set_manifold(0, CylindricalManifold<3>(axis, c));
          }
        names[0] = {"inner"};
        names[1] = {"outer"};
        if (dim == 3)
          {
            names[10] = {"bottom"};
            names[11] = {"top"};
          }
      }
    else if (m.type == "sphere octant")
      {
        GridGenerator::quarter_hyper_ball(tria, c, m.radius);
        std::vector<std::pair<unsigned int, types::boundary_id>> planes;
        for (unsigned int d = 0; d < dim; ++d)
          planes.emplace_back(d, 1 + d);
        label_round_boundary<dim>(tria, c, {{m.radius, 0}}, planes, 0., false);
        set_curved_faces(tria, {0});
        tria.set_manifold(0, SphericalManifold<dim>(c));
        names[0] = {"curved"};
        names[1] = {"x0"};
        names[2] = {"y0"};
        if (dim == 3)
          names[3] = {"z0"};
      }
    else if (m.type == "file")
      {
        // glide's own readers (mesh_file.h): the scene reader has read and
        // checked the file already; unit tests may call this directly.
        try
          {
            const auto imported =
              m.imported ?
                m.imported :
                std::make_shared<const ImportedMesh>(
                  import_mesh_file(m.file, dim, m.element_set, m.part));
            create_triangulation<dim>(*imported, tria, names);
          }
        catch (const InputError &e)
          {
            throw InputError("Body '" + body_name + "': " + e.what());
          }
      }
    else
      throw InputError("Body '" + body_name + "': unknown mesh type '" +
                       m.type + "'.");
  }



  template <int dim>
  void
  Mesh<dim>::build(const Scene                               &scene,
                   parallel::distributed::Triangulation<dim> &tria)
  {
    for (const auto &ns : scene.node_sets)
      if (ns.body != numbers::invalid_unsigned_int)
        file_node_sets.push_back(ns.name);
    std::vector<Point<dim>>                                      vertices;
    std::vector<CellData<dim>>                                   cells;
    SubCellData                                                  subcell;
    types::boundary_id                                           next_id = 0;
    std::map<types::manifold_id, std::unique_ptr<Manifold<dim>>> manifolds;

    // Global refinements of each body's coarse mesh that are not the
    // scene's: a block of N subdivisions is built as a coarse mesh of
    // N / 2^k and refined k times (2^k the largest power of two dividing
    // every N), the same cells. The distributed triangulation keeps the
    // whole coarse mesh on every process and visits every coarse cell in
    // each refinement cycle: with a block of 70^3 coarse cells the mesh
    // took 45 s of a 290 s run on two processes, as long as on one.
    std::vector<unsigned int> coarse_levels(scene.bodies.size(), 0);
    for (unsigned int b = 0; b < scene.bodies.size(); ++b)
      {
        const auto        &body = scene.bodies[b];
        Triangulation<dim> body_tria;
        std::map<types::boundary_id, std::vector<std::string>> names;
        if (body.mesh.type == "block" && !body.mesh.imported)
          {
            MeshParameters coarse = body.mesh;
            while (std::all_of(coarse.subdivisions.begin(),
                               coarse.subdivisions.begin() + dim,
                               [](const unsigned int n) { return n % 2 == 0; }))
              {
                for (unsigned int d = 0; d < dim; ++d)
                  coarse.subdivisions[d] /= 2;
                ++coarse_levels[b];
              }
            build_body_mesh<dim>(coarse, body.name, body_tria, names);
          }
        else
          build_body_mesh<dim>(body.mesh, body.name, body_tria, names);

        std::map<types::boundary_id, types::boundary_id> new_id;
        for (const auto &[id, surfaces] : names)
          {
            new_id[id] = next_id;
            for (const auto &n : surfaces)
              surface_ids[body.name + "." + n].insert(next_id);
            ++next_id;
          }
        if (body.mesh.imported)
          for (const auto &[n, why] : body.mesh.imported->unavailable)
            unavailable[body.name + "." + n] = why;
        const types::manifold_id manifold_offset = 10 * b;
        for (const auto id : body_tria.get_manifold_ids())
          if (id != numbers::flat_manifold_id)
            manifolds[id + manifold_offset] =
              body_tria.get_manifold(id).clone();
        auto manifold = [&](const types::manifold_id id) {
          return id == numbers::flat_manifold_id ? id : id + manifold_offset;
        };

        const unsigned int offset = vertices.size();
        std::vector<int>   new_vertex(body_tria.n_vertices(), -1);
        for (unsigned int v = 0; v < body_tria.n_vertices(); ++v)
          if (body_tria.get_used_vertices()[v])
            {
              new_vertex[v] = vertices.size();
              vertices.push_back(body_tria.get_vertices()[v]);
            }
        (void)offset;
        for (const auto &cell : body_tria.active_cell_iterators())
          {
            CellData<dim> data(cell->n_vertices());
            for (unsigned int v = 0; v < cell->n_vertices(); ++v)
              data.vertices[v] = new_vertex[cell->vertex_index(v)];
            data.material_id = b;
            data.manifold_id = manifold(cell->manifold_id());
            cells.push_back(data);
            for (const auto &face : cell->face_iterators())
              {
                const bool boundary = face->at_boundary();
                if (!boundary &&
                    face->manifold_id() == numbers::flat_manifold_id)
                  continue;
                CellData<dim - 1> f(face->n_vertices());
                for (unsigned int v = 0; v < face->n_vertices(); ++v)
                  f.vertices[v] = new_vertex[face->vertex_index(v)];
                f.boundary_id = boundary ? new_id.at(face->boundary_id()) :
                                           numbers::internal_face_boundary_id;
                f.manifold_id = manifold(face->manifold_id());
                if constexpr (dim == 2)
                  subcell.boundary_lines.push_back(f);
                else
                  {
                    subcell.boundary_quads.push_back(f);
                    for (unsigned int l = 0; l < face->n_lines(); ++l)
                      if (face->line(l)->manifold_id() !=
                          numbers::flat_manifold_id)
                        {
                          CellData<1> line(2);
                          line.vertices[0] =
                            new_vertex[face->line(l)->vertex_index(0)];
                          line.vertices[1] =
                            new_vertex[face->line(l)->vertex_index(1)];
                          line.boundary_id = numbers::internal_face_boundary_id;
                          line.manifold_id =
                            manifold(face->line(l)->manifold_id());
                          subcell.boundary_lines.push_back(line);
                        }
                  }
              }
          }
      }

    try
      {
        tria.create_triangulation(vertices, cells, subcell);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream s;
        e.print_info(s);
        throw InputError(
          "Cannot build the mesh of the scene: " + s.str() +
          " (check mesh files for inverted or distorted cells).");
      }
    for (const auto &[id, m] : manifolds)
      tria.set_manifold(id, *m);

    // Bounding box over all processes.
    Point<dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = std::numeric_limits<double>::max();
        hi[d] = -lo[d];
      }
    for (const auto &v : vertices)
      for (unsigned int d = 0; d < dim; ++d)
        {
          lo[d] = std::min(lo[d], v[d]);
          hi[d] = std::max(hi[d], v[d]);
        }
    size = lo.distance(hi);
    // Lengths whose squares and cubes (cell areas, volumes, Jacobian
    // determinants) double precision holds: 1e-80 to 1e80. Beyond, a cell's
    // measure underflows to 0 or overflows to infinity and the first
    // residual is not a number (a block 2e-300 or 2e300 long ended in
    // "KINSOL stopped ... uscale has nonpositive elements").
    {
      std::ostringstream text;
      text << std::setprecision(3) << size;
      require(std::isfinite(size) && size >= 1e-80 && size <= 1e80,
              "The scene's meshes span " + text.str() +
                " (the diagonal of their bounding box), beyond the lengths "
                "of 1e-80 to 1e80 whose areas and volumes double precision "
                "holds. Write the scene in another unit of length (e.g. mm "
                "or m), with every parameter that carries it: the meshes' "
                "corners, centres and radii ('Block', 'Round shapes'), the "
                "coordinates of the mesh files, the moduli and the loads.");
    }

    // Each refinement cycle is checked before it runs: the cells it would
    // make must fit in the machine's memory (Scene::check_size bounds only
    // the global refinement of generated meshes, before the mesh exists; a
    // wide 'Refinement radius' with many 'Local refinements', or a large
    // mesh file refined globally, is caught here, before it allocates).
    const double rss_before_refinement = [] {
      Utilities::System::MemoryStats stats;
      Utilities::System::get_memory_stats(stats);
      return static_cast<double>(stats.VmRSS);
    }();
    const auto check_refinement_fits = [&](const std::string &parameter) {
      std::vector<double> flagged(scene.bodies.size(), 0.);
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->refine_flag_set())
          flagged[cell->material_id()] += 1.;
      std::vector<double> total(flagged.size());
      Utilities::MPI::sum(flagged, tria.get_communicator(), total);
      const auto   most = std::max_element(total.begin(), total.end());
      const double cells =
        static_cast<double>(tria.n_global_active_cells()) +
        ((1 << dim) - 1) * std::accumulate(total.begin(), total.end(), 0.);
      // The bytes per active cell the mesh has taken so far: what the
      // triangulation reports, or what the process has grown by since the
      // coarse mesh (p4est's forest and the refinement's own work arrays,
      // which the report leaves out: 430 against 245 bytes per cell in 2D).
      // The parent cells' share only grows with more levels, so this is a
      // lower bound for the refined mesh, and the refusal comes after a few
      // seconds of refinement instead of minutes.
      Utilities::System::MemoryStats stats;
      Utilities::System::get_memory_stats(stats);
      const double grown =
        1024. * (static_cast<double>(stats.VmRSS) - rss_before_refinement);
      const double bytes_per_cell =
        Utilities::MPI::sum(
          std::max(static_cast<double>(tria.memory_consumption()), grown),
          tria.get_communicator()) /
        static_cast<double>(tria.n_global_active_cells());
      scene.check_refinement_fits(cells,
                                  bytes_per_cell,
                                  scene.bodies[most - total.begin()].name,
                                  parameter);
    };

    // Per-body refinement: global, then towards a point.
    for (unsigned int level = 0;; ++level)
      {
        bool any = false;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const auto b = cell->material_id();
              if (level <
                  scene.bodies[b].mesh.global_refinements + coarse_levels[b])
                {
                  cell->set_refine_flag();
                  any = true;
                }
            }
        if (Utilities::MPI::max(any ? 1 : 0, tria.get_communicator()) == 0)
          break;
        check_refinement_fits("Global refinements");
        tria.execute_coarsening_and_refinement();
      }
    // Local refinement: towards a point per body, by a radius that halves
    // with each level down to 'Minimum refinement radius'.
    const auto refinement_point = [&](const MeshParameters &m) {
      Point<dim> point;
      if (!m.refinement_point.empty())
        point = to_point<dim>(m.refinement_point);
      else if (m.type == "hertz")
        {
          point = to_point<dim>(m.center);
          point[1] -= m.radius;
        }
      else if (m.type == "block")
        for (unsigned int d = 0; d < dim; ++d)
          point[d] = 0.5 * (m.lower_corner[d] + m.upper_corner[d]);
      else
        point = to_point<dim>(m.center);
      return point;
    };
    const auto refinement_radius = [&](const MeshParameters &m,
                                       const unsigned int    level) {
      const double r0 =
        m.refinement_radius > 0 ? m.refinement_radius : 0.25 * size;
      return std::max(r0 / std::pow(2., level), m.minimum_refinement_radius);
    };
    // The levels that refined a cell, per body: a level that refines none
    // (the point off the body, or beyond the radius of every cell) ends
    // the body's refinement, as every later level is narrower.
    const unsigned int        n_bodies = scene.bodies.size();
    std::vector<unsigned int> levels_done(n_bodies, 0);
    for (unsigned int level = 0;; ++level)
      {
        std::vector<double> flagged(n_bodies, 0.);
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const auto &m = scene.bodies[cell->material_id()].mesh;
              if (level >= m.local_refinements ||
                  levels_done[cell->material_id()] < level)
                continue;
              Point<dim> nearest = refinement_point(m);
              if (dim == 3 && m.type == "half cylinder")
                nearest[2] =
                  cell->center()[2]; // refine along the line of contact
              if (cell->center().distance(nearest) <
                  refinement_radius(m, level) + 0.5 * cell->diameter())
                {
                  cell->set_refine_flag();
                  flagged[cell->material_id()] = 1.;
                }
            }
        std::vector<double> flagged_anywhere(n_bodies);
        Utilities::MPI::max(flagged, tria.get_communicator(), flagged_anywhere);
        bool any = false;
        for (unsigned int b = 0; b < n_bodies; ++b)
          if (flagged_anywhere[b] > 0.)
            {
              ++levels_done[b];
              any = true;
            }
        if (!any)
          break;
        check_refinement_fits("Local refinements");
        tria.execute_coarsening_and_refinement();
      }
    refinement_notes.clear();
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const auto &m = scene.bodies[b].mesh;
        if (levels_done[b] >= m.local_refinements)
          continue;
        std::ostringstream text;
        text << "body '" << scene.bodies[b].name
             << "': 'Refinement/Local refinements' = " << m.local_refinements
             << ", but "
             << (levels_done[b] == 0 ?
                   std::string("no level") :
                   "only the first " + std::to_string(levels_done[b]) +
                     " level(s)")
             << " refined a cell: at level " << levels_done[b] + 1
             << " no cell centre of the body lies within "
             << refinement_radius(m, levels_done[b])
             << " (the level's radius) plus half the cell's diameter of "
             << (m.refinement_point.empty() ? "the default refinement point" :
                                              "'Refinement point'")
             << " (";
        for (unsigned int d = 0; d < dim; ++d)
          text << (d ? ", " : "") << refinement_point(m)[d];
        text << "). Put 'Refinement point' on the body where the mesh must "
                "be fine, or widen 'Refinement radius' or 'Minimum "
                "refinement radius'.";
        refinement_notes.push_back(text.str());
      }
  }



  template <int dim>
  const std::set<types::boundary_id> &
  Mesh<dim>::surface(const std::string &name,
                     const std::string &parameter) const
  {
    const auto it = surface_ids.find(name);
    if (it == surface_ids.end() && unavailable.count(name))
      throw InputError("Parameter '" + parameter + "' = '" + name +
                       "': " + unavailable.at(name) +
                       ". The scene's surfaces are: " + surface_list() + ".");
    require(it != surface_ids.end(),
            "Parameter '" + parameter + "' = '" + name +
              "': no such surface. The scene's surfaces are: " +
              surface_list() + ".");
    return it->second;
  }

  template <int dim>
  bool
  Mesh<dim>::has_surface(const std::string &name) const
  {
    return surface_ids.count(name) > 0;
  }

  template <int dim>
  std::string
  Mesh<dim>::surface_list() const
  {
    std::string list;
    for (const auto &[n, ids] : surface_ids)
      list += (list.empty() ? "" : ", ") + n;
    std::string sets;
    for (const auto &n : file_node_sets)
      sets += (sets.empty() ? "" : ", ") + n;
    if (!sets.empty())
      list += " (node sets from mesh files: " + sets + ")";
    // A name from a mesh file with a comma in it cannot be named: a
    // scene's lists split at commas.
    std::string with_comma;
    for (const auto &[n, ids] : surface_ids)
      if (n.find(',') != std::string::npos)
        with_comma += (with_comma.empty() ? "'" : ", '") + n + "'";
    for (const auto &n : file_node_sets)
      if (n.find(',') != std::string::npos)
        with_comma += (with_comma.empty() ? "'" : ", '") + n + "'";
    if (!with_comma.empty())
      list += ". Names with a comma (" + with_comma +
              ") cannot be given in a scene, whose lists split at commas: "
              "rename those groups in the mesh file (spaces, dots and "
              "underscores work)";
    return list;
  }

  template class Mesh<2>;
  template class Mesh<3>;
  template void
  build_body_mesh<2>(const MeshParameters &,
                     const std::string &,
                     Triangulation<2> &,
                     std::map<types::boundary_id, std::vector<std::string>> &);
  template void
  build_body_mesh<3>(const MeshParameters &,
                     const std::string &,
                     Triangulation<3> &,
                     std::map<types::boundary_id, std::vector<std::string>> &);
} // namespace glide
