#include <glide/base/collective_failure.h>
#include <glide/contact/facet_basis.h>
#include <glide/contact/master_surface.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_system.h>

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    using Fad = Sacado::Fad::DFad<double>;

    double
    plain(const double x)
    {
      return x;
    }
    double
    plain(const Fad &x)
    {
      return x.val();
    }

    template <typename T, std::size_t n>
    T
    dot(const std::array<T, n> &a, const std::array<T, n> &b)
    {
      T s = a[0] * b[0];
      for (std::size_t i = 1; i < n; ++i)
        s += a[i] * b[i];
      return s;
    }

    template <typename T, std::size_t n>
    void
    normalize(std::array<T, n> &a)
    {
      using std::sqrt;
      const T length = sqrt(dot(a, a));
      for (auto &x : a)
        x /= length;
    }

    /// Cubic Hermite basis h00, h10, h01, h11 and derivatives.
    template <typename T>
    void
    hermite(const T &t, T *h, T *dh)
    {
      const T t2 = t * t, t3 = t2 * t;
      h[0]  = 2. * t3 - 3. * t2 + 1.;
      h[1]  = t3 - 2. * t2 + t;
      h[2]  = -2. * t3 + 3. * t2;
      h[3]  = t3 - t2;
      dh[0] = 6. * t2 - 6. * t;
      dh[1] = 3. * t2 - 4. * t + 1.;
      dh[2] = -6. * t2 + 6. * t;
      dh[3] = 3. * t2 - 2. * t;
    }

    /// Blending weights (towards xi = 0, interior, towards xi = 1) of the
    /// 3D normal smoothing: a C1 step over the band of width f.
    template <typename T>
    std::array<T, 3>
    blend(const T &xi, const double f)
    {
      std::array<T, 3> w{{T(0.), T(1.), T(0.)}};
      if (f <= 0.)
        return w;
      auto step = [](const T &s) -> T { return s * s * (3. - 2. * s); };
      if (plain(xi) < f)
        {
          const T s = plain(xi) <= 0. ? T(0.) : T(xi / f);
          w[1]      = step(s);
          w[0]      = 1. - w[1];
        }
      else if (plain(xi) > 1. - f)
        {
          const T s = plain(xi) >= 1. ? T(0.) : T((1. - xi) / f);
          w[1]      = step(s);
          w[2]      = 1. - w[1];
        }
      return w;
    }

    template <int dim>
    std::string
    where(const Point<dim> &p)
    {
      std::ostringstream s;
      s << "(" << p << ")";
      return s.str();
    }

    /// Solve the (dim-1)x(dim-1) system J d = -R on the coordinates marked
    /// free; returns false if singular.
    template <std::size_t n>
    bool
    newton_step(const std::array<std::array<double, n>, n> &J,
                const std::array<double, n>                &R,
                const std::array<bool, n>                  &fixed,
                std::array<double, n>                      &d)
    {
      d.fill(0.);
      if constexpr (n == 1)
        {
          if (fixed[0])
            return true;
          if (std::abs(J[0][0]) < 1e-300)
            return false;
          d[0] = -R[0] / J[0][0];
          return true;
        }
      else
        {
          if (fixed[0] && fixed[1])
            return true;
          for (unsigned int a = 0; a < 2; ++a)
            if (fixed[a])
              {
                const unsigned int b = 1 - a;
                if (std::abs(J[b][b]) < 1e-300)
                  return false;
                d[b] = -R[b] / J[b][b];
                return true;
              }
          const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
          if (std::abs(det) < 1e-300)
            return false;
          d[0] = -(J[1][1] * R[0] - J[0][1] * R[1]) / det;
          d[1] = -(-J[1][0] * R[0] + J[0][0] * R[1]) / det;
          return true;
        }
    }

    /// The step of the closest-point iteration on the free coordinates.
    /// Newton on R = 0 finds any stationary point of the distance, its
    /// maxima too: where the piece curves more tightly than the distance
    /// to the point (the point beyond its centre of curvature, as a
    /// smoothed master's transition curves are seen from inside the
    /// master), J = dR/dxi is not negative definite, the Newton steps went
    /// uphill, and the iteration went back and forth between the piece's
    /// ends until it gave up: near a smoothed circle, a fifth of the points
    /// had such a candidate piece (unit.MasterSurface.
    /// ClosestPointIterationConvergesOnEveryPiece). There the distance
    /// falls along R (in 2D R = -d(|x_s - y|^2 / 2)/dxi exactly, in 3D up to
    /// the blended normal), which leads to the piece's side: the step goes
    /// that way, by at most the damping's half range per iteration.
    template <std::size_t n>
    void
    direction(const std::array<std::array<double, n>, n> &J,
              const std::array<double, n>                &R,
              const std::array<bool, n>                  &fixed,
              std::array<double, n>                      &d)
    {
      bool descent = false;
      if constexpr (n == 1)
        descent = !fixed[0] && !(J[0][0] < 0.);
      else
        {
          if (!fixed[0] && !fixed[1])
            {
              const double off = 0.5 * (J[0][1] + J[1][0]);
              descent = !(J[0][0] < 0. && J[0][0] * J[1][1] - off * off > 0.);
            }
          else
            for (unsigned int b = 0; b < 2; ++b)
              if (!fixed[b])
                descent = !(J[b][b] < 0.);
        }
      if (!descent && newton_step(J, R, fixed, d))
        return;
      double norm = 0.;
      for (std::size_t b = 0; b < n; ++b)
        if (!fixed[b])
          norm += R[b] * R[b];
      norm = std::sqrt(norm);
      for (std::size_t b = 0; b < n; ++b)
        d[b] = (fixed[b] || norm == 0.) ? 0. : R[b] / norm;
    }

    /// The parts of a Linearization that linearize() and
    /// linearize_at_vertex() share: the DoFs (slave node, then the master
    /// nodes @p local), gap, normal and gap gradient from the automatic
    /// derivatives, force and dforce sized and zero.
    template <int dim, typename Node>
    void
    fill_gap(const std::vector<unsigned int>                        &local,
             const std::vector<Node>                                &nodes,
             const std::array<dealii::types::global_dof_index, dim> &slave,
             const Fad                                              &g,
             const std::array<Fad, dim>                             &nrm,
             typename MasterSurface<dim>::Linearization             &l)
    {
      const unsigned int n = dim * (1 + local.size());
      l.dofs.resize(n);
      for (unsigned int d = 0; d < dim; ++d)
        l.dofs[d] = slave[d];
      for (unsigned int i = 0; i < local.size(); ++i)
        for (unsigned int d = 0; d < dim; ++d)
          l.dofs[dim * (1 + i) + d] = nodes[local[i]].dofs[d];
      l.gap = g.val();
      for (unsigned int d = 0; d < dim; ++d)
        l.normal[d] = nrm[d].val();
      l.dgap.reinit(n);
      l.force.reinit(n);
      l.dforce.reinit(n, n);
      for (unsigned int i = 0; i < n; ++i)
        l.dgap(i) = g.dx(i);
    }
  } // namespace

  template <int dim>
  std::map<unsigned int, std::array<unsigned int, dim>>
  face_node_indices(const FiniteElement<dim>                             &fe,
                    const typename DoFHandler<dim>::active_cell_iterator &cell,
                    const unsigned int                                    f)
  {
    std::map<unsigned int, std::array<unsigned int, dim>> nodes;
    for (unsigned int i = 0; i < fe.n_dofs_per_face(f); ++i)
      {
        const unsigned int k       = fe.face_to_cell_index(i,
                                                     f,
                                                     cell->face_orientation(f),
                                                     cell->face_flip(f),
                                                     cell->face_rotation(f));
        const auto         ci      = fe.system_to_component_index(k);
        nodes[ci.second][ci.first] = k;
      }
    return nodes;
  }

  template std::map<unsigned int, std::array<unsigned int, 2>>
  face_node_indices<2>(const FiniteElement<2> &,
                       const DoFHandler<2>::active_cell_iterator &,
                       const unsigned int);
  template std::map<unsigned int, std::array<unsigned int, 3>>
  face_node_indices<3>(const FiniteElement<3> &,
                       const DoFHandler<3>::active_cell_iterator &,
                       const unsigned int);

  template <int dim>
  MasterSurface<dim>::MasterSurface(const Elasticity<dim> &elasticity,
                                    const std::set<types::boundary_id> &ids,
                                    const double       fraction,
                                    const std::string &path,
                                    const bool         distributed)
    : fraction(fraction)
    , path(path)
  {
    const auto &dof_handler = elasticity.get_dof_handler();
    const auto &fe          = dof_handler.get_fe();
    const auto &mapping     = elasticity.get_mapping();
    const auto &unit_points = fe.get_unit_support_points();
    polynomial_degree       = fe.degree;
    const unsigned int p    = polynomial_degree;
    axisymmetric =
      elasticity.get_scene().analysis == AnalysisType::axisymmetric;
    comm = dof_handler.get_communicator();

    std::array<std::set<types::global_dof_index>, dim> symmetric;
    std::map<types::global_dof_index, unsigned int>    node_index;
    std::vector<double>                                diameters;
    std::vector<FacetId>                               ids_of_facets;
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    // Master facets of this process's cells; symmetry faces of its ghost
    // cells too, since a node of an owned facet may lie on a symmetry face
    // of a neighbouring process's cell (every cell at the node is owned or
    // ghost).
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        for (const auto f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const auto id = cell->face(f)->boundary_id();
            const bool is_master =
              ids.count(id) > 0 && cell->is_locally_owned();
            int symmetry = -1;
            for (unsigned int c = 0; c < dim; ++c)
              for (const auto s : elasticity.symmetry_boundary_ids(c))
                if (s == id)
                  symmetry = c;
            if (!is_master && symmetry < 0)
              continue;
            cell->get_dof_indices(cell_dofs);
            // The face's nodes: base index -> cell DoFs per component.
            const auto        face_nodes = face_node_indices<dim>(fe, cell, f);
            std::vector<Node> found;
            for (const auto &[base, k] : face_nodes)
              {
                Node node;
                for (unsigned int c = 0; c < dim; ++c)
                  node.dofs[c] = cell_dofs[k[c]];
                node.X =
                  mapping.transform_unit_to_real_cell(cell, unit_points[k[0]]);
                found.push_back(node);
                if (symmetry >= 0)
                  symmetric[symmetry].insert(node.dofs[symmetry]);
              }
            if (!is_master)
              continue;

            // Lexicographic order: match the nodes to the points at
            // parameters (i/p, j/p) of the face's (bi)linear vertex map.
            const auto         face = cell->face(f);
            Facet              facet;
            const unsigned int n_j = dim == 2 ? 1 : p + 1;
            for (unsigned int j = 0; j < n_j; ++j)
              for (unsigned int i = 0; i <= p; ++i)
                {
                  const double s = double(i) / p, t = double(j) / p;
                  Point<dim>   target;
                  if (dim == 2)
                    target =
                      face->vertex(0) + s * (face->vertex(1) - face->vertex(0));
                  else
                    target = (1 - s) * (1 - t) * face->vertex(0) +
                             s * (1 - t) * face->vertex(1) +
                             (1 - s) * t * face->vertex(2) +
                             s * t * face->vertex(3);
                  unsigned int best = 0;
                  for (unsigned int k = 1; k < found.size(); ++k)
                    if (found[k].X.distance(target) <
                        found[best].X.distance(target))
                      best = k;
                  const auto [it, inserted] =
                    node_index.emplace(found[best].dofs[0], nodes.size());
                  if (inserted)
                    nodes.push_back(found[best]);
                  facet.nodes.push_back(it->second);
                }
            facet.neighbours.fill(-1);
            facets.push_back(facet);
            diameters.push_back(face->diameter());
            {
              FacetId id;
              for (const auto k : facets.back().nodes)
                for (unsigned int d = 0; d < dim; ++d)
                  id.centre[d] += nodes[k].X[d] / facets.back().nodes.size();
              const auto binary = cell->id().template to_binary<dim>();
              std::copy(binary.begin(), binary.end(), id.cell.begin());
              id.cell.back() = f;
              ids_of_facets.push_back(id);
            }

            // Outward orientation: the facet's normal must point away from
            // its cell.
            x.resize(nodes.size());
            for (const auto k : facets.back().nodes)
              x[k] = nodes[k].X;
            pieces.assign(1, Piece());
            pieces[0].facet = facets.size() - 1;
            for (const auto k : facets.back().nodes)
              pieces[0].vnodes.emplace_back(k, false);
            pieces[0].upper.fill(1.);
            Xi middle;
            middle.fill(0.5);
            const auto center = evaluate(0, middle);
            if (center.second * (face->center() - cell->center()) < 0)
              {
                auto &v = facets.back().nodes;
                if (dim == 2)
                  std::reverse(v.begin(), v.end());
                else
                  {
                    const auto old = v;
                    for (unsigned int j = 0; j <= p; ++j)
                      for (unsigned int i = 0; i <= p; ++i)
                        v[i + (p + 1) * j] = old[j + (p + 1) * i];
                  }
              }
          }
      }
    sort_canonically(ids_of_facets, diameters);
    on_symmetry_plane.resize(nodes.size());
    for (unsigned int k = 0; k < nodes.size(); ++k)
      for (unsigned int c = 0; c < dim; ++c)
        on_symmetry_plane[k][c] = symmetric[c].count(nodes[k].dofs[c]) > 0;
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
      {
        for (unsigned int i = 0; i < facets.size(); ++i)
          {
            facets[i].key = i;
            max_size      = std::max(max_size, diameters[i]);
          }
        total_facets = facets.size();
        build();
      }
    else if (!distributed)
      gather(diameters, global_keys(ids_of_facets));
    else
      {
        // R15.2: this process's facets stay aside, numbered as in the
        // whole surface; gather_near() brings each process those within
        // its reach.
        const std::uint64_t n_own = facets.size();
        pack(diameters, global_keys(ids_of_facets), own_reals, own_integers);
        for (const auto &node : nodes)
          own_node_dofs.insert(own_node_dofs.end(),
                               node.dofs.begin(),
                               node.dofs.end());
        own_gathered_at.assign(own_node_dofs.size(), 0.);
        for (const double d : diameters)
          max_size = std::max(max_size, d);
        max_size     = Utilities::MPI::max(max_size, comm);
        owners       = Utilities::MPI::sum(n_own > 0 ? 1u : 0u, comm);
        total_facets = Utilities::MPI::sum(n_own, comm);
        nodes.clear();
        facets.clear();
        on_symmetry_plane.clear();
        build();
      }
  }

  template <int dim>
  void
  MasterSurface<dim>::sort_canonically(std::vector<FacetId> &ids,
                                       std::vector<double>  &diameters)
  {
    // The facets in the order of their centres (lexicographic; facets
    // that coincide in the order of their cells' ids and face numbers),
    // the nodes in the order the facets first name them: one order on one
    // process and on several, whatever the partition, the order of the
    // bodies and the numbering of a mesh file. The order in which a
    // process visits its cells is none of these: locally refined cells
    // come level by level, a partition splits them differently, and the
    // bodies' cells come in the order of the scene's list.
    std::vector<unsigned int> order(facets.size());
    for (unsigned int i = 0; i < order.size(); ++i)
      order[i] = i;
    std::sort(order.begin(), order.end(), [&](const auto a, const auto b) {
      return ids[a] < ids[b];
    });
    std::vector<Facet>   sorted_facets;
    std::vector<double>  sorted_diameters;
    std::vector<FacetId> sorted_ids;
    std::vector<Node>    sorted_nodes;
    std::vector<int>     new_index(nodes.size(), -1);
    for (const auto i : order)
      {
        Facet facet = facets[i];
        for (auto &k : facet.nodes)
          {
            if (new_index[k] < 0)
              {
                new_index[k] = sorted_nodes.size();
                sorted_nodes.push_back(nodes[k]);
              }
            k = new_index[k];
          }
        sorted_facets.push_back(facet);
        sorted_diameters.push_back(diameters[i]);
        sorted_ids.push_back(ids[i]);
      }
    facets    = std::move(sorted_facets);
    nodes     = std::move(sorted_nodes);
    diameters = std::move(sorted_diameters);
    ids       = std::move(sorted_ids);
  }

  template <int dim>
  std::vector<std::uint64_t>
  MasterSurface<dim>::global_keys(const std::vector<FacetId> &ids) const
  {
    // Every facet's position in the order of sort_canonically() over all
    // processes: what one process numbers it. The ids of the whole surface
    // pass through every process once, at set-up (dim + 5 numbers per
    // facet).
    std::vector<double>       centres;
    std::vector<unsigned int> cells;
    for (const auto &id : ids)
      {
        centres.insert(centres.end(), id.centre.begin(), id.centre.end());
        cells.insert(cells.end(), id.cell.begin(), id.cell.end());
      }
    const auto all_centres = Utilities::MPI::all_gather(comm, centres);
    const auto all_cells   = Utilities::MPI::all_gather(comm, cells);
    std::vector<FacetId> every;
    for (unsigned int r = 0; r < all_centres.size(); ++r)
      for (std::size_t a = 0, b = 0; a < all_centres[r].size();
           a += dim, b += std::tuple_size<decltype(FacetId::cell)>::value)
        {
          FacetId id;
          std::copy(all_centres[r].begin() + a,
                    all_centres[r].begin() + a + dim,
                    id.centre.begin());
          std::copy(all_cells[r].begin() + b,
                    all_cells[r].begin() + b + id.cell.size(),
                    id.cell.begin());
          every.push_back(id);
        }
    std::sort(every.begin(), every.end());
    std::vector<std::uint64_t> keys;
    for (const auto &id : ids)
      keys.push_back(std::lower_bound(every.begin(), every.end(), id) -
                     every.begin());
    return keys;
  }

  template <int dim>
  void
  MasterSurface<dim>::pack(const std::vector<double>            &diameters,
                           const std::vector<std::uint64_t>     &keys,
                           std::vector<double>                  &reals,
                           std::vector<types::global_dof_index> &integers) const
  {
    reals.clear();
    integers.clear();
    for (unsigned int i = 0; i < facets.size(); ++i)
      {
        reals.push_back(diameters[i]);
        integers.push_back(keys[i]);
        for (const auto k : facets[i].nodes)
          {
            for (unsigned int d = 0; d < dim; ++d)
              reals.push_back(nodes[k].X[d]);
            for (unsigned int d = 0; d < dim; ++d)
              integers.push_back(nodes[k].dofs[d]);
            for (unsigned int d = 0; d < dim; ++d)
              integers.push_back(on_symmetry_plane[k][d] ? 1 : 0);
          }
      }
  }

  template <int dim>
  void
  MasterSurface<dim>::unpack(
    const std::vector<std::pair<std::vector<double>,
                                std::vector<types::global_dof_index>>> &parts)
  {
    const unsigned int n_nodes =
      Utilities::fixed_power<dim - 1>(polynomial_degree + 1);
    // Per facet: key, and where its numbers start.
    std::vector<std::tuple<std::uint64_t,
                           const double *,
                           const types::global_dof_index *>>
      records;
    for (const auto &[R, I] : parts)
      for (std::size_t a = 0, b = 0; a < R.size();
           a += 1 + n_nodes * dim, b += 1 + 2 * n_nodes * dim)
        records.emplace_back(I[b], &R[a], &I[b]);
    std::sort(records.begin(), records.end(), [](const auto &u, const auto &v) {
      return std::get<0>(u) < std::get<0>(v);
    });
    nodes.clear();
    facets.clear();
    on_symmetry_plane.clear();
    std::map<types::global_dof_index, unsigned int> node_index;
    for (const auto &[key, R, I] : records)
      {
        max_size = std::max(max_size, R[0]);
        Facet facet;
        facet.neighbours.fill(-1);
        facet.key = key;
        for (unsigned int j = 0; j < n_nodes; ++j)
          {
            Node                           node;
            const double                  *r = R + 1 + j * dim;
            const types::global_dof_index *i = I + 1 + 2 * j * dim;
            std::array<bool, dim>          flags;
            for (unsigned int d = 0; d < dim; ++d)
              {
                node.X[d]    = r[d];
                node.dofs[d] = i[d];
                flags[d]     = i[dim + d] != 0;
              }
            const auto [it, inserted] =
              node_index.emplace(node.dofs[0], nodes.size());
            if (inserted)
              {
                nodes.push_back(node);
                on_symmetry_plane.push_back(flags);
              }
            else
              for (unsigned int d = 0; d < dim; ++d)
                on_symmetry_plane[it->second][d] =
                  on_symmetry_plane[it->second][d] || flags[d];
            facet.nodes.push_back(it->second);
          }
        facets.push_back(facet);
      }
    build();
  }

  template <int dim>
  void
  MasterSurface<dim>::build()
  {
    x.resize(nodes.size());
    for (unsigned int k = 0; k < nodes.size(); ++k)
      x[k] = nodes[k].X;
    pieces.clear();
    corners.clear();
    node_normal.clear();
    piece_of_key.clear();
    searchable = false;
    ++positions_version;
    if (facets.empty())
      return;
    if (dim == 2)
      build_pieces_2d(axisymmetric, path);
    else
      build_neighbours_3d();
    for (unsigned int i = 0; i < pieces.size(); ++i)
      piece_of_key[piece_key(i)] = i;
    set_displacement(VectorType());
  }

  template <int dim>
  int
  MasterSurface<dim>::find_piece(const std::uint64_t key) const
  {
    const auto it = piece_of_key.find(key);
    return it == piece_of_key.end() ? -1 : static_cast<int>(it->second);
  }

  template <int dim>
  std::vector<BoundingBox<dim>>
  covering_boxes(const std::vector<Point<dim>> &points, const double reach)
  {
    if (points.empty())
      return {};
    // The points binned into cubic cells, 16 along the longest side of
    // their box (at least twice the reach): one box per occupied cell, the
    // box of its points. An R-tree's nodes (extract_rtree_level()) balance
    // the number of points, not the geometry: a node may join the end of
    // one cluster to the start of another and span the gap between them.
    Point<dim> lo = points[0], hi = points[0];
    for (const auto &x : points)
      for (unsigned int d = 0; d < dim; ++d)
        {
          lo[d] = std::min(lo[d], x[d]);
          hi[d] = std::max(hi[d], x[d]);
        }
    double extent = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      extent = std::max(extent, hi[d] - lo[d]);
    const double cell = std::max({2. * reach, extent / 16., 1e-300});
    std::map<std::array<long, dim>, BoundingBox<dim>> cells;
    for (const auto &x : points)
      {
        std::array<long, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = static_cast<long>(std::floor((x[d] - lo[d]) / cell));
        const auto it = cells.find(key);
        if (it == cells.end())
          cells.emplace(key, BoundingBox<dim>(std::make_pair(x, x)));
        else
          it->second.merge_with(BoundingBox<dim>(std::make_pair(x, x)));
      }
    std::vector<BoundingBox<dim>> boxes;
    for (auto &[key, box] : cells)
      {
        box.extend(reach);
        boxes.push_back(box);
      }
    return boxes;
  }

  template <int dim>
  void
  MasterSurface<dim>::gather_near(const VectorType                    &U,
                                  const std::vector<BoundingBox<dim>> &mine)
  {
    // Every process's regions: lower corner, upper corner, per box.
    std::vector<double> flat;
    for (const auto &box : mine)
      {
        for (unsigned int d = 0; d < dim; ++d)
          flat.push_back(box.get_boundary_points().first[d]);
        for (unsigned int d = 0; d < dim; ++d)
          flat.push_back(box.get_boundary_points().second[d]);
      }
    const auto regions = Utilities::MPI::all_gather(comm, flat);

    // Send each own facet whose current bounding box meets a region there.
    const unsigned int n_nodes =
      Utilities::fixed_power<dim - 1>(polynomial_degree + 1);
    const std::size_t n_reals    = 1 + n_nodes * dim,
                      n_integers = 1 + 2 * n_nodes * dim;
    std::map<unsigned int, std::vector<double>>                  reals;
    std::map<unsigned int, std::vector<types::global_dof_index>> integers;
    for (std::size_t a = 0, b = 0; a < own_reals.size();
         a += n_reals, b += n_integers)
      {
        Point<dim> lo, hi;
        for (unsigned int j = 0; j < n_nodes; ++j)
          for (unsigned int d = 0; d < dim; ++d)
            {
              const auto   dof = own_integers[b + 1 + 2 * j * dim + d];
              const double y =
                own_reals[a + 1 + j * dim + d] + (U.size() > 0 ? U[dof] : 0.);
              lo[d] = j == 0 ? y : std::min(lo[d], y);
              hi[d] = j == 0 ? y : std::max(hi[d], y);
            }
        for (unsigned int r = 0; r < regions.size(); ++r)
          {
            const auto &g    = regions[r];
            bool        meet = false;
            for (std::size_t k = 0; k + 2 * dim <= g.size() && !meet;
                 k += 2 * dim)
              {
                meet = true;
                for (unsigned int d = 0; d < dim && meet; ++d)
                  meet = lo[d] <= g[k + dim + d] && g[k + d] <= hi[d];
              }
            if (!meet)
              continue;
            reals[r].insert(reals[r].end(),
                            own_reals.begin() + a,
                            own_reals.begin() + a + n_reals);
            integers[r].insert(integers[r].end(),
                               own_integers.begin() + b,
                               own_integers.begin() + b + n_integers);
          }
      }
    const auto got_reals    = Utilities::MPI::some_to_some(comm, reals);
    const auto got_integers = Utilities::MPI::some_to_some(comm, integers);
    std::vector<
      std::pair<std::vector<double>, std::vector<types::global_dof_index>>>
      parts;
    for (const auto &[rank, R] : got_reals)
      parts.emplace_back(R, got_integers.at(rank));
    // The smoothing's checks (a branching 2D chain, an edge of three
    // facets) may fail on the part one process holds only: every process
    // throws the same error.
    std::string failure;
    try
      {
        unpack(parts);
      }
    catch (const std::exception &e)
      {
        failure = e.what();
      }
    throw_first_failure<InputError>(failure, comm);
    for (unsigned int i = 0; i < own_node_dofs.size(); ++i)
      own_gathered_at[i] = U.size() > 0 ? U[own_node_dofs[i]] : 0.;
  }

  template <int dim>
  double
  MasterSurface<dim>::own_motion(const VectorType &U) const
  {
    double motion = 0.;
    if (U.size() > 0)
      for (unsigned int i = 0; i < own_node_dofs.size(); ++i)
        motion =
          std::max(motion, std::abs(U[own_node_dofs[i]] - own_gathered_at[i]));
    return motion;
  }

  template <int dim>
  void
  MasterSurface<dim>::gather(const std::vector<double>        &diameters,
                             const std::vector<std::uint64_t> &keys)
  {
    // Every process holds the facets of all processes, numbered by their
    // keys as on one process.
    const std::uint64_t n_own = facets.size();
    owners                    = Utilities::MPI::sum(n_own > 0 ? 1u : 0u, comm);
    total_facets              = Utilities::MPI::sum(n_own, comm);
    std::vector<double>                  reals;
    std::vector<types::global_dof_index> integers;
    pack(diameters, keys, reals, integers);
    const auto all_reals    = Utilities::MPI::all_gather(comm, reals);
    const auto all_integers = Utilities::MPI::all_gather(comm, integers);
    std::vector<
      std::pair<std::vector<double>, std::vector<types::global_dof_index>>>
      parts;
    for (unsigned int r = 0; r < all_reals.size(); ++r)
      parts.emplace_back(all_reals[r], all_integers[r]);
    unpack(parts);
  }

  template <int dim>
  void
  MasterSurface<dim>::build_pieces_2d(const bool         axisymmetric,
                                      const std::string &path)
  {
    const unsigned int p = polynomial_degree;
    const double       f = fraction;
    // Chains: each node starts at most one facet and ends at most one.
    std::vector<int> starts(nodes.size(), -1), ends(nodes.size(), -1);
    for (unsigned int i = 0; i < facets.size(); ++i)
      {
        const auto s = facets[i].nodes.front(), e = facets[i].nodes.back();
        require(starts[s] < 0 && ends[e] < 0,
                path +
                  ": the master surface is not a simple chain of "
                  "consistently oriented facets at node " +
                  where(nodes[starts[s] >= 0 ? s : e].X) +
                  " (it branches, or joins faces of bodies on opposite "
                  "sides); split it into several surfaces.");
        starts[s] = i;
        ends[e]   = i;
      }
    for (auto &facet : facets)
      {
        facet.neighbours[0] = ends[facet.nodes.front()];
        facet.neighbours[1] = starts[facet.nodes.back()];
      }

    // The symmetry plane at a chain end node: axis, or -1.
    auto mirror_axis = [&](const unsigned int node) {
      const double tolerance = 1e-10 * std::max(1., max_size);
      if (axisymmetric && std::abs(nodes[node].X[0]) < tolerance)
        return 0;
      for (unsigned int c = 0; c < dim; ++c)
        if (on_symmetry_plane[node][c])
          return int(c);
      return -1;
    };

    std::array<double, 3> N1, dN1, N2, dN2;
    lagrange(p, 1. - f, N1.data(), dN1.data());
    lagrange(p, f, N2.data(), dN2.data());

    // R1.2 for quadratic facets: the fraction of the transition at the
    // node between facet i and the next one. A Hermite transition on two
    // quadratic facets that meet without a kink (a straight run, or an arc)
    // is the same curve, but it passes load to the facets' corner and
    // mid-side nodes in other proportions than the facets do (at its
    // middle, the vertex, 0.70 / 0.20 / -0.05 instead of 1 / 0 / 0): with
    // f = 0.2 a uniform pressure loads the corners of a flat quadratic
    // master with 0.28 pL instead of pL / 3 (the error grows as 4 f^2), the
    // master ripples, and the nodal pressures alternated by +21 % / -10 %
    // between slave corners and mid-sides without converging. So where the
    // facets' reference tangents turn at the node by no more than 5 % of
    // the larger turn within either facet (not a polygon vertex, but the
    // O(h^3) kink of a curve interpolated by quadratics), the transition
    // spans only quadratic_fraction of each facet: the load is then passed
    // within 4 f^2 = 0.2 % of the facets' proportions, and the surface stays
    // C1 where the deforming master kinks there (without any transition
    // the force direction jumps at the node, and Newton alternates between
    // the two facets). Linear facets use f at every node: their transition
    // passes load like the facets do.
    const auto tangent = [&](const Facet &facet, const double t) {
      std::array<double, 3> N, dN;
      lagrange(p, t, N.data(), dN.data());
      Tensor<1, dim> d;
      for (unsigned int k = 0; k < facet.nodes.size(); ++k)
        d += dN[k] * nodes[facet.nodes[k]].X;
      return d;
    };
    const auto angle = [](const Tensor<1, dim> &a, const Tensor<1, dim> &b) {
      const double cross = a[0] * b[dim - 1] - a[dim - 1] * b[0];
      return std::abs(std::atan2(cross, a * b));
    };
    const auto junction_fraction = [&](const unsigned int i,
                                       const unsigned int next) {
      if (p == 1)
        return f;
      const double kink =
        angle(tangent(facets[i], 1.), tangent(facets[next], 0.));
      const double turn =
        std::max(angle(tangent(facets[i], 0.), tangent(facets[i], 1.)),
                 angle(tangent(facets[next], 0.), tangent(facets[next], 1.)));
      return kink > std::max(1e-8, 0.05 * turn) ?
               f :
               std::min(f, quadratic_fraction);
    };
    // A transition curve of facet i (mirrored about the plane x_a through
    // node `plane` if a >= 0), and one of its two ends: the Hermite data
    // (position at parameter s, tangent 2 f x'(s) times `sign`) of the
    // facet `nodes` at its start (t = 0) or its end (t = 1).
    auto transition = [&](const unsigned int i, const int plane, const int a) {
      Piece t;
      t.kind        = PieceKind::hermite;
      t.facet       = i;
      t.mirror_node = a >= 0 ? plane : -1;
      t.mirror_axis = a >= 0 ? a : 0;
      t.upper.fill(1.);
      return t;
    };
    auto add_end = [&](Piece                           &t,
                       const std::vector<unsigned int> &facet_nodes,
                       const bool                       mirrored,
                       const bool                       at_start,
                       const std::array<double, 3>     &N,
                       const std::array<double, 3>     &dN,
                       const double                     sign,
                       const double                     fraction = -1.) {
      const double ft = fraction >= 0. ? fraction : f;
      for (unsigned int k = 0; k <= p; ++k)
        {
          t.vnodes.emplace_back(facet_nodes[k], mirrored);
          const double m = sign * 2. * ft * dN[k];
          t.coefficients.push_back(at_start ?
                                     std::array<double, 4>{{N[k], m, 0., 0.}} :
                                     std::array<double, 4>{{0., 0., N[k], m}});
        }
    };
    for (unsigned int i = 0; i < facets.size(); ++i)
      {
        const auto &facet = facets[i];
        Piece       piece;
        piece.kind  = PieceKind::lagrange;
        piece.facet = i;
        piece.upper.fill(1.);
        for (const auto k : facet.nodes)
          piece.vnodes.emplace_back(k, false);

        // Start of the facet.
        const unsigned int start = facet.nodes.front();
        if (facet.neighbours[0] >= 0)
          piece.begin = junction_fraction(facet.neighbours[0], i);
        else if (const int a = mirror_axis(start); a >= 0)
          {
            // Mirror image of this facet across the plane x_a = const
            // precedes it (R2.1, R2.2).
            if (f > 0)
              {
                piece.begin = f;
                Piece t     = transition(i, start, a);
                t.role      = 1;
                add_end(t, facet.nodes, true, true, N2, dN2, -1.);
                add_end(t, facet.nodes, false, false, N2, dN2, 1.);
                pieces.push_back(t);
              }
          }
        else
          piece.begin = -0.05;

        // End of the facet, and the transition to the next facet.
        const unsigned int end = facet.nodes.back();
        if (facet.neighbours[1] >= 0)
          {
            const unsigned int next = facet.neighbours[1];
            const double       fj   = junction_fraction(i, next);
            if (fj > 0)
              {
                std::array<double, 3> M1, dM1, M2, dM2;
                lagrange(p, 1. - fj, M1.data(), dM1.data());
                lagrange(p, fj, M2.data(), dM2.data());
                piece.end = 1. - fj;
                Piece t   = transition(i, 0, -1);
                t.role    = 2;
                add_end(t, facet.nodes, false, true, M1, dM1, 1., fj);
                add_end(t, facets[next].nodes, false, false, M2, dM2, 1., fj);
                pieces.push_back(t);
              }
          }
        else if (const int a = mirror_axis(end); a >= 0)
          {
            if (f > 0)
              {
                piece.end = 1. - f;
                Piece t   = transition(i, end, a);
                t.role    = 3;
                add_end(t, facet.nodes, false, true, N1, dN1, 1.);
                add_end(t, facet.nodes, true, false, N1, dN1, -1.);
                pieces.push_back(t);
              }
          }
        else
          piece.end = 1.05;
        pieces.push_back(piece);
      }
  }

  template <int dim>
  void
  MasterSurface<dim>::build_neighbours_3d()
  {
    const unsigned int p = polynomial_degree;
    corners.resize(facets.size());
    // Corner nodes in lexicographic order, and the edges' corners.
    auto corner = [&](const unsigned int facet, const unsigned int v) {
      const unsigned int i = (v % 2) * p, j = (v / 2) * p;
      return facets[facet].nodes[i + (p + 1) * j];
    };
    const unsigned int edge_corners[4][2] = {{0, 2}, {1, 3}, {0, 1}, {2, 3}};
    std::map<unsigned int, std::vector<std::pair<unsigned int, unsigned int>>>
      at_node;
    std::map<std::pair<unsigned int, unsigned int>,
             std::vector<std::pair<unsigned int, unsigned int>>>
      at_edge;
    for (unsigned int i = 0; i < facets.size(); ++i)
      {
        for (unsigned int v = 0; v < 4; ++v)
          at_node[corner(i, v)].emplace_back(i, v);
        for (unsigned int e = 0; e < 4; ++e)
          {
            auto a = corner(i, edge_corners[e][0]),
                 b = corner(i, edge_corners[e][1]);
            at_edge[{std::min(a, b), std::max(a, b)}].emplace_back(i, e);
          }
      }
    for (const auto &[edge, list] : at_edge)
      {
        require(list.size() <= 2,
                "A master surface has an edge shared by more than two facets "
                "at " +
                  where(nodes[edge.first].X) +
                  "; split it into several surfaces.");
        if (list.size() == 2)
          {
            facets[list[0].first].neighbours[list[0].second] = list[1].first;
            facets[list[1].first].neighbours[list[1].second] = list[0].first;
          }
      }
    for (unsigned int i = 0; i < facets.size(); ++i)
      {
        for (unsigned int v = 0; v < 4; ++v)
          corners[i][v] = at_node[corner(i, v)];
        Piece piece;
        piece.facet = i;
        for (const auto k : facets[i].nodes)
          piece.vnodes.emplace_back(k, false);
        for (unsigned int a = 0; a < 2; ++a)
          {
            piece.lower[a] = facets[i].neighbours[2 * a] < 0 ? -0.05 : 0.;
            piece.upper[a] = facets[i].neighbours[2 * a + 1] < 0 ? 1.05 : 1.;
          }
        pieces.push_back(piece);
      }
  }

  template <int dim>
  void
  MasterSurface<dim>::set_displacement(const VectorType &U, const bool search)
  {
    bool moved = false;
    for (unsigned int k = 0; k < nodes.size(); ++k)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double v =
            nodes[k].X[d] + (U.size() > 0 ? U[nodes[k].dofs[d]] : 0.);
          moved   = moved || v != x[k][d];
          x[k][d] = v;
        }
    if (moved)
      {
        ++positions_version;
        searchable = false;
      }
    if (fraction == 0. && (moved || node_normal.size() != nodes.size()))
      update_node_normals();
    if (!search || searchable)
      return;
    searchable = true;
    std::vector<Leaf> boxes;
    boxes.reserve(pieces.size());
    for (unsigned int i = 0; i < pieces.size(); ++i)
      {
        const auto &piece = pieces[i];
        Point<dim>  lo = x[piece.vnodes[0].first], hi = lo;
        auto        include = [&](const Point<dim> &y) {
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], y[d]);
              hi[d] = std::max(hi[d], y[d]);
            }
        };
        for (const auto &[k, mirrored] : piece.vnodes)
          {
            Point<dim> y = x[k];
            if (mirrored)
              y[piece.mirror_axis] =
                2. * x[piece.mirror_node][piece.mirror_axis] -
                y[piece.mirror_axis];
            include(y);
          }
        const double margin = 0.1 * lo.distance(hi) + 1e-12 * max_size;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] -= margin;
            hi[d] += margin;
          }
        boxes.emplace_back(BoundingBox<dim>(std::make_pair(lo, hi)), i);
      }
    tree = pack_rtree(boxes);
  }

  template <int dim>
  void
  MasterSurface<dim>::update_node_normals()
  {
    node_normal.assign(nodes.size(), Tensor<1, dim>());
    const unsigned int p   = polynomial_degree;
    auto               pos = [&](const unsigned int k) {
      std::array<double, dim> y;
      for (unsigned int d = 0; d < dim; ++d)
        y[d] = x[k][d];
      return y;
    };
    for (unsigned int f = 0; f < facets.size(); ++f)
      for (unsigned int j = 0; j <= (dim == 3 ? p : 0); ++j)
        for (unsigned int i = 0; i <= p; ++i)
          {
            std::array<double, dim> n;
            if constexpr (dim == 2)
              {
                std::array<double, 3> N, dN;
                lagrange(p, double(i) / p, N.data(), dN.data());
                std::array<double, 2> a = {{0., 0.}};
                for (unsigned int m = 0; m <= p; ++m)
                  for (unsigned int d = 0; d < 2; ++d)
                    a[d] += dN[m] * x[facets[f].nodes[m]][d];
                n = {{a[1], -a[0]}};
                normalize(n);
              }
            else
              n =
                facet_normal<double>(f, {{double(i) / p, double(j) / p}}, pos);
            const unsigned int k = facets[f].nodes[i + (p + 1) * j];
            for (unsigned int d = 0; d < dim; ++d)
              node_normal[k][d] += n[d];
          }
    for (unsigned int k = 0; k < nodes.size(); ++k)
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (on_symmetry_plane[k][d])
            node_normal[k][d] = 0.;
        const double length = node_normal[k].norm();
        if (length > 0.)
          node_normal[k] /= length;
      }
  }

  template <int dim>
  template <typename T, typename Positions>
  std::array<T, dim>
  MasterSurface<dim>::facet_normal(const unsigned int            facet,
                                   const std::array<T, dim - 1> &xi,
                                   const Positions              &pos) const
  {
    const unsigned int p = polynomial_degree;
    std::array<T, 3>   Ns, dNs, Nt, dNt;
    lagrange(p, xi[0], Ns.data(), dNs.data());
    lagrange(p, xi[dim - 2], Nt.data(), dNt.data());
    std::array<std::array<T, dim>, 2> a;
    for (auto &v : a)
      v.fill(T(0.));
    for (unsigned int j = 0; j <= p; ++j)
      for (unsigned int i = 0; i <= p; ++i)
        {
          const auto y = pos(facets[facet].nodes[i + (p + 1) * j]);
          for (unsigned int d = 0; d < dim; ++d)
            {
              a[0][d] += dNs[i] * Nt[j] * y[d];
              a[1][d] += Ns[i] * dNt[j] * y[d];
            }
        }
    std::array<T, dim> n;
    n[0]       = a[0][1] * a[1][dim - 1] - a[0][dim - 1] * a[1][1];
    n[1]       = a[0][dim - 1] * a[1][0] - a[0][0] * a[1][dim - 1];
    n[dim - 1] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    normalize(n);
    return n;
  }

  template <int dim>
  template <typename T, typename Positions>
  void
  MasterSurface<dim>::geometry(const Piece                             &piece,
                               const std::array<T, dim - 1>            &xi,
                               const Positions                         &pos,
                               std::array<T, dim>                      &point,
                               std::array<std::array<T, dim>, dim - 1> &a,
                               std::array<T, dim>                      &n,
                               std::vector<T> *weights) const
  {
    const unsigned int                  p  = polynomial_degree;
    const unsigned int                  nv = piece.vnodes.size();
    std::vector<T>                      w(nv);
    std::vector<std::array<T, dim - 1>> dw(nv);
    if (piece.kind == PieceKind::hermite)
      {
        std::array<T, 4> h, dh;
        hermite(xi[0], h.data(), dh.data());
        for (unsigned int j = 0; j < nv; ++j)
          {
            const auto &c = piece.coefficients[j];
            w[j] = c[0] * h[0] + c[1] * h[1] + c[2] * h[2] + c[3] * h[3];
            dw[j][0] =
              c[0] * dh[0] + c[1] * dh[1] + c[2] * dh[2] + c[3] * dh[3];
          }
      }
    else if (dim == 2)
      {
        const double     length = piece.end - piece.begin;
        const T          s      = piece.begin + length * xi[0];
        std::array<T, 3> N, dN;
        lagrange(p, s, N.data(), dN.data());
        for (unsigned int j = 0; j < nv; ++j)
          {
            w[j]     = N[j];
            dw[j][0] = length * dN[j];
          }
      }
    else
      {
        std::array<T, 3> Ns, dNs, Nt, dNt;
        lagrange(p, xi[0], Ns.data(), dNs.data());
        lagrange(p, xi[dim - 2], Nt.data(), dNt.data());
        for (unsigned int j = 0; j <= p; ++j)
          for (unsigned int i = 0; i <= p; ++i)
            {
              const unsigned int k = i + (p + 1) * j;
              w[k]                 = Ns[i] * Nt[j];
              dw[k][0]             = dNs[i] * Nt[j];
              dw[k][dim - 2]       = Ns[i] * dNt[j];
            }
      }

    point.fill(T(0.));
    for (auto &v : a)
      v.fill(T(0.));
    for (unsigned int j = 0; j < nv; ++j)
      {
        auto y = pos(piece.vnodes[j].first);
        if (piece.vnodes[j].second)
          {
            const unsigned int m = piece.mirror_axis;
            y[m]                 = 2. * pos(piece.mirror_node)[m] - y[m];
          }
        for (unsigned int d = 0; d < dim; ++d)
          {
            point[d] += w[j] * y[d];
            for (unsigned int b = 0; b < dim - 1; ++b)
              a[b][d] += dw[j][b] * y[d];
          }
      }
    if (weights)
      *weights = w;

    if constexpr (dim == 2)
      {
        n[0] = a[0][1];
        n[1] = -a[0][0];
        normalize(n);
      }
    else
      blended_normal(piece, xi, pos, a, n);
  }

  template <int dim>
  template <typename T, typename Positions>
  void
  MasterSurface<dim>::blended_normal(
    const Piece                                   &piece,
    const std::array<T, dim - 1>                  &xi,
    const Positions                               &pos,
    const std::array<std::array<T, dim>, dim - 1> &a,
    std::array<T, dim>                            &n) const
  {
    // 3D: the facet's own normal, blended towards the edges and corners.
    n[0]       = a[0][1] * a[dim - 2][dim - 1] - a[0][dim - 1] * a[dim - 2][1];
    n[1]       = a[0][dim - 1] * a[dim - 2][0] - a[0][0] * a[dim - 2][dim - 1];
    n[dim - 1] = a[0][0] * a[dim - 2][1] - a[0][1] * a[dim - 2][0];
    normalize(n);
    if (fraction <= 0.)
      return;
    const auto bs = blend(xi[0], fraction), bt = blend(xi[dim - 2], fraction);
    if (plain(bs[1]) == 1. && plain(bt[1]) == 1.)
      return;
    const unsigned int facet       = piece.facet;
    auto               edge_normal = [&](const unsigned int e) {
      const std::array<double, 2> mid[4] = {{{0., 0.5}},
                                            {{1., 0.5}},
                                            {{0.5, 0.}},
                                            {{0.5, 1.}}};
      std::array<T, dim - 1>      m;
      for (unsigned int b = 0; b < dim - 1; ++b)
        m[b] = mid[e][b];
      auto      ne = facet_normal<T>(facet, m, pos);
      const int g  = facets[facet].neighbours[e];
      if (g < 0)
        {
          // An edge on a symmetry plane: the normal of the mirrored
          // continuation, i.e. the facet's normal projected into the plane.
          const unsigned int q                = polynomial_degree;
          const unsigned int corners_of[4][2] = {{0, 2},
                                                 {1, 3},
                                                 {0, 1},
                                                 {2, 3}};
          auto               node_at = [&](const unsigned int v) {
            return facets[facet].nodes[(v % 2) * q + (q + 1) * (v / 2) * q];
          };
          bool changed = false;
          for (unsigned int a = 0; a < dim; ++a)
            if (on_symmetry_plane[node_at(corners_of[e][0])][a] &&
                on_symmetry_plane[node_at(corners_of[e][1])][a])
              {
                ne[a]   = T(0.);
                changed = true;
              }
          if (changed)
            normalize(ne);
          return ne;
        }
      // The neighbour's normal at the midpoint of its edge towards us.
      for (unsigned int e2 = 0; e2 < 4; ++e2)
        if (facets[g].neighbours[e2] == int(facet))
          {
            std::array<T, dim - 1> m2;
            for (unsigned int b = 0; b < dim - 1; ++b)
              m2[b] = mid[e2][b];
            const auto ng = facet_normal<T>(g, m2, pos);
            for (unsigned int d = 0; d < dim; ++d)
              ne[d] += ng[d];
            normalize(ne);
            break;
          }
      return ne;
    };
    auto corner_normal = [&](const unsigned int v) {
      std::array<T, dim> nc;
      nc.fill(T(0.));
      for (const auto &[g, w] : corners[facet][v])
        {
          std::array<T, dim - 1> c;
          c[0]          = double(w % 2);
          c[dim - 2]    = double(w / 2);
          const auto ng = facet_normal<T>(g, c, pos);
          for (unsigned int d = 0; d < dim; ++d)
            nc[d] += ng[d];
        }
      // A node on a symmetry plane: the normal lies in the plane.
      const unsigned int q = polynomial_degree;
      const unsigned int node =
        facets[facet].nodes[(v % 2) * q + (q + 1) * (v / 2) * q];
      for (unsigned int a = 0; a < dim; ++a)
        if (on_symmetry_plane[node][a])
          nc[a] = T(0.);
      normalize(nc);
      return nc;
    };
    std::array<T, dim> blended;
    blended.fill(T(0.));
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          const double weight = plain(bs[i]) * plain(bt[j]);
          if (weight == 0. && !(i == 1 && j == 1))
            continue;
          std::array<T, dim> c;
          if (i == 1 && j == 1)
            c = n;
          else if (j == 1)
            c = edge_normal(i == 0 ? 0 : 1);
          else if (i == 1)
            c = edge_normal(j == 0 ? 2 : 3);
          else
            c = corner_normal((i == 0 ? 0 : 1) + (j == 0 ? 0 : 2));
          const T wij = bs[i] * bt[j];
          for (unsigned int d = 0; d < dim; ++d)
            blended[d] += wij * c[d];
        }
    normalize(blended);
    n = blended;
  }

  template <int dim>
  template <typename T, typename Positions>
  void
  MasterSurface<dim>::residual(const Piece                  &piece,
                               const std::array<T, dim - 1> &xi,
                               const std::array<T, dim>     &xs,
                               const Positions              &pos,
                               std::array<T, dim - 1>       &R) const
  {
    std::array<T, dim>                      y, n;
    std::array<std::array<T, dim>, dim - 1> a;
    geometry<T>(piece, xi, pos, y, a, n, nullptr);
    std::array<T, dim> r;
    for (unsigned int d = 0; d < dim; ++d)
      r[d] = xs[d] - y[d];
    const T rn = dot(r, n);
    for (unsigned int d = 0; d < dim; ++d)
      r[d] -= rn * n[d];
    for (unsigned int b = 0; b < dim - 1; ++b)
      R[b] = dot(r, a[b]);
  }

  template <int dim>
  std::pair<Point<dim>, Tensor<1, dim>>
  MasterSurface<dim>::evaluate(const unsigned int piece, const Xi &xi) const
  {
    auto pos = [&](const unsigned int k) {
      std::array<double, dim> y;
      for (unsigned int d = 0; d < dim; ++d)
        y[d] = x[k][d];
      return y;
    };
    std::array<double, dim>                      y, n;
    std::array<std::array<double, dim>, dim - 1> a;
    geometry<double>(pieces[piece], xi, pos, y, a, n, nullptr);
    Point<dim>     point;
    Tensor<1, dim> normal;
    for (unsigned int d = 0; d < dim; ++d)
      {
        point[d]  = y[d];
        normal[d] = n[d];
      }
    return {point, normal};
  }

  template <int dim>
  std::array<std::vector<std::pair<types::global_dof_index, double>>, dim>
  MasterSurface<dim>::point_weights(const unsigned int piece,
                                    const Xi          &xi) const
  {
    auto pos = [&](const unsigned int k) {
      std::array<double, dim> y;
      for (unsigned int d = 0; d < dim; ++d)
        y[d] = x[k][d];
      return y;
    };
    std::array<double, dim>                      y, n;
    std::array<std::array<double, dim>, dim - 1> a;
    std::vector<double>                          w;
    const Piece                                 &p = pieces[piece];
    geometry<double>(p, xi, pos, y, a, n, &w);
    std::array<std::vector<std::pair<types::global_dof_index, double>>, dim>
      result;
    for (unsigned int j = 0; j < p.vnodes.size(); ++j)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const auto &dofs = nodes[p.vnodes[j].first].dofs;
          if (p.vnodes[j].second && d == p.mirror_axis)
            {
              // Mirrored: 2 x_mirror - x_j in the axis' component.
              result[d].emplace_back(nodes[p.mirror_node].dofs[d], 2. * w[j]);
              result[d].emplace_back(dofs[d], -w[j]);
            }
          else
            result[d].emplace_back(dofs[d], w[j]);
        }
    return result;
  }

  template <int dim>
  typename MasterSurface<dim>::Projection
  MasterSurface<dim>::project_on(const unsigned int i,
                                 const Point<dim>  &xs) const
  {
    const Piece &piece = pieces[i];
    Projection   result;
    result.piece = i;
    auto pos     = [&](const unsigned int k) {
      std::array<Fad, dim> y;
      for (unsigned int d = 0; d < dim; ++d)
        y[d] = x[k][d];
      return y;
    };
    std::array<Fad, dim> s;
    for (unsigned int d = 0; d < dim; ++d)
      s[d] = xs[d];
    Xi xi;
    for (unsigned int b = 0; b < dim - 1; ++b)
      xi[b] = 0.5 * (piece.lower[b] + piece.upper[b]);
    std::array<bool, dim - 1> fixed{};
    bool                      converged = false;
    // Damping: at most half the parameter range per iteration, halved for
    // a coordinate each time its step turns back. Newton went back and
    // forth between two points for ever where the residual is steeper
    // between them than at either (a 3D piece at the edge of a sphere's
    // octant, seen from a block corner outside it: steps of +-0.42).
    std::array<double, dim - 1> limit, previous{};
    limit.fill(0.5);
    // The coordinates' magnitude, for the round-off floor below.
    double scale = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      scale = std::max(scale, std::abs(xs[d]));
    for (const auto &v : piece.vnodes)
      for (unsigned int d = 0; d < dim; ++d)
        scale = std::max(scale, std::abs(x[v.first][d]));
    for (unsigned int it = 0; it < 50 && !converged; ++it)
      {
        std::array<Fad, dim - 1> xf, R;
        for (unsigned int b = 0; b < dim - 1; ++b)
          xf[b] = Fad(dim - 1, b, xi[b]);
        residual<Fad>(piece, xf, s, pos, R);
        std::array<std::array<double, dim - 1>, dim - 1> J;
        std::array<double, dim - 1>                      r, step;
        for (unsigned int b = 0; b < dim - 1; ++b)
          {
            r[b] = R[b].val();
            for (unsigned int c = 0; c < dim - 1; ++c)
              J[b][c] = R[b].dx(c);
          }
        // Projected Newton: a coordinate at its bound whose step points out
        // stays there.
        fixed.fill(false);
        direction(J, r, fixed, step);
        for (unsigned int pass = 0; pass < dim - 1; ++pass)
          {
            bool more = false;
            for (unsigned int b = 0; b < dim - 1; ++b)
              if (!fixed[b] && ((xi[b] <= piece.lower[b] && step[b] < 0) ||
                                (xi[b] >= piece.upper[b] && step[b] > 0)))
                fixed[b] = more = true;
            if (!more)
              break;
            direction(J, r, fixed, step);
          }
        double change = 0;
        for (unsigned int b = 0; b < dim - 1; ++b)
          {
            if (step[b] * previous[b] < 0.)
              limit[b] *= 0.5;
            const double d = std::max(-limit[b], std::min(limit[b], step[b]));
            previous[b]    = d;
            const double v =
              std::max(piece.lower[b], std::min(piece.upper[b], xi[b] + d));
            change = std::max(change, std::abs(v - xi[b]));
            xi[b]  = v;
          }
        // The parameters live in [0, 1]: 1e-10 is far below any geometric
        // tolerance, and Newton converges quadratically past it. Unless the
        // coordinates are large against the piece: r carries the rounding
        // of xs - y(xi), about eps |x| |a| (a = dy/dxi, J ~ |a|^2), so xi
        // is resolved to about eps |x| / |a| and no better. In a scene 1e4
        // from the origin with pieces 6e-3 long, that is above 1e-10:
        // Newton never met it, the projections failed, slave nodes took
        // clamped points of neighbouring pieces, and the Hertz scene cut
        // back to the limit (scene.far_from_the_origin).
        double floor = 0.;
        for (unsigned int b = 0; b < dim - 1; ++b)
          if (J[b][b] != 0.)
            floor = std::max(floor,
                             64. * std::numeric_limits<double>::epsilon() *
                               scale / std::sqrt(std::abs(J[b][b])));
        converged = change < std::max(1e-10, floor);
      }
    if (!converged)
      {
        result.failed = true;
        return result;
      }
    result.found      = true;
    result.xi         = xi;
    result.clamped    = fixed;
    const auto [y, n] = evaluate(i, xi);
    result.point      = y;
    result.normal     = n;
    result.gap        = (xs - y) * n;
    // Clamped at an edge or node (and not on it): the gap is measured to
    // the piece's tangent plane there, along the piece's own normal (the
    // "extended facet"). project_within picks among the pieces meeting at
    // that point.
    for (const bool c : fixed)
      result.vertex = result.vertex || c;
    result.vertex = result.vertex && (xs - y).norm() > 1e-10 * max_size;
    return result;
  }

  template <int dim>
  bool
  MasterSurface<dim>::beyond_end(const Projection &p) const
  {
    // Clamped at a side beyond which there is no master: not in contact
    // through this piece.
    const Piece &piece  = pieces[p.piece];
    bool         beyond = false;
    for (unsigned int b = 0; b < dim - 1; ++b)
      if (p.clamped[b])
        {
          if (dim == 2 && piece.kind == PieceKind::lagrange)
            beyond = beyond || (p.xi[b] <= 0. && piece.begin < 0.) ||
                     (p.xi[b] >= 1. && piece.end > 1.);
          if (dim == 3)
            beyond = beyond || p.xi[b] < 0. || p.xi[b] > 1.;
        }
    return beyond;
  }

  template <int dim>
  typename MasterSurface<dim>::Projection
  MasterSurface<dim>::project_onto(const unsigned int piece,
                                   const Point<dim>  &xs) const
  {
    Projection p = project_on(piece, xs);
    if (p.found && p.vertex && beyond_end(p))
      p.found = false;
    return p;
  }

  template <int dim>
  typename MasterSurface<dim>::Projection
  MasterSurface<dim>::project_at_vertex(const unsigned int piece,
                                        const unsigned int partner,
                                        const Point<dim>  &xs) const
  {
    Projection p;
    p.failed = true;
    if (dim != 2 || fraction > 0. || piece >= pieces.size() ||
        partner >= pieces.size() || piece == partner)
      return p;
    const unsigned int deg   = polynomial_degree;
    const auto         whole = [&](const Piece &q) {
      return q.kind == PieceKind::lagrange && q.mirror_node < 0 &&
             facets[q.facet].nodes.size() == deg + 1;
    };
    const Piece &a = pieces[piece];
    const Piece &b = pieces[partner];
    if (!whole(a) || !whole(b))
      return p;
    const auto &na = facets[a.facet].nodes;
    const auto &nb = facets[b.facet].nodes;
    // The shared node: the end of one facet is the start of the other
    // (the chain's orientation), so that the normals agree in sense.
    int          v  = -1;
    unsigned int at = 0;
    if (na[deg] == nb[0])
      {
        v  = na[deg];
        at = 1;
      }
    else if (na[0] == nb[deg])
      {
        v  = na[0];
        at = 0;
      }
    if (v < 0)
      return p;
    // Each facet's normal at the shared node, from its tangent there (a
    // quadratic facet's end tangent; a straight facet's only one).
    Tensor<1, dim> m;
    for (const auto &[f, end] :
         {std::make_pair(&na, at), std::make_pair(&nb, 1 - at)})
      {
        std::array<double, 3> N, dN;
        lagrange(deg, static_cast<double>(end), N.data(), dN.data());
        Tensor<1, dim> t;
        for (unsigned int i = 0; i <= deg; ++i)
          t += dN[i] * x[(*f)[i]];
        Tensor<1, dim> n;
        n[0] = t[1];
        n[1] = -t[0];
        m += n / t.norm();
      }
    // Facets folded back onto each other have no mean normal.
    if (m.norm() < 1e-6)
      return p;
    p.found      = true;
    p.failed     = false;
    p.vertex     = true;
    p.piece      = piece;
    p.partner    = partner;
    p.xi[0]      = at;
    p.clamped[0] = true;
    p.point      = x[v];
    p.normal     = m / m.norm();
    p.gap        = (xs - p.point) * p.normal;
    return p;
  }

  template <int dim>
  typename MasterSurface<dim>::Projection
  MasterSurface<dim>::project(const Point<dim> &xs,
                              const double      search_radius) const
  {
    // The wider search only where the usual one finds nothing: deeper
    // candidates must not compete with the pieces next to the point.
    double     radius = 1.5 * max_size;
    Projection p      = project_within(xs, radius);
    if (!p.found && search_radius > radius)
      {
        radius = search_radius;
        p      = project_within(xs, radius);
      }
    // A point found farther away than the search reached: the pieces whose
    // boxes lie outside the search box were not tried, and one of them may
    // hold a closer point. A slave point 1.7 facet lengths beyond the end
    // of a smoothed master took the clamped end of the transition curve
    // before the end facet (whose box reached it) as its meeting point,
    // while the end facet's box, and with it the end of the master, was
    // out of reach: contact with nothing, exit 0
    // (scene.beyond_the_masters_end). Search again out to that distance: every
    // piece with a point closer than it is then tried. The candidates only
    // grow, so this ends; a few passes suffice (an inside projection is
    // preferred to a closer clamped one, so the distance may grow once more).
    for (unsigned int pass = 0; pass < 4 && p.found; ++pass)
      {
        const double distance = (xs - p.point).norm();
        if (distance <= radius)
          break;
        radius = distance * (1. + 1e-8) + 1e-12 * max_size;
        p      = project_within(xs, radius);
      }
    return p;
  }

  template <int dim>
  typename MasterSurface<dim>::Projection
  MasterSurface<dim>::project_within(const Point<dim> &xs,
                                     const double      radius) const
  {
    namespace bgi = boost::geometry::index;
    Projection best, best_vertex;
    if (pieces.empty())
      return best;
    Point<dim> lo = xs, hi = xs;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] -= radius;
        hi[d] += radius;
      }
    std::vector<Leaf> candidates;
    tree.query(bgi::intersects(BoundingBox<dim>(std::make_pair(lo, hi))),
               std::back_inserter(candidates));
    // Nearest boxes first: a projection inside a piece lies at distance
    // |g| from the slave point (r = g n), so once one is found, pieces
    // whose boxes are farther than |g| can neither beat it nor matter (a
    // clamped point counts only where no piece contains the projection).
    // Same result as trying every candidate, with ties still going to the
    // lowest piece number.
    std::vector<std::pair<double, unsigned int>> order;
    order.reserve(candidates.size());
    for (const auto &[box, i] : candidates)
      {
        double d2 = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double e =
              std::max({box.get_boundary_points().first[d] - xs[d],
                        0.,
                        xs[d] - box.get_boundary_points().second[d]});
            d2 += e * e;
          }
        order.emplace_back(std::sqrt(d2), i);
      }
    std::sort(order.begin(), order.end());
    // Clamped points: the closest one decides where the slave point meets
    // the master; the pieces that meet there compete by their extended
    // gaps, and the largest |g| wins (outside a convex corner the point is
    // outside if it is outside any of the facets' planes; inside a concave
    // corner it is inside if it is inside any of them). The force direction
    // is that piece's normal: bounded derivatives, where the direction to
    // the corner, r / |r|, turns as 1 / |r| and made Newton diverge for
    // slave nodes that almost touch a faceted corner.
    std::vector<std::pair<Projection, bool>> clamped;
    double best_distance = std::numeric_limits<double>::max();
    bool   any_failed    = false;
    for (const auto &[box_distance, i] : order)
      {
        if (best.found && box_distance > std::abs(best.gap))
          break;
        const Projection p = project_on(i, xs);
        any_failed         = any_failed || p.failed;
        if (!p.found)
          continue;
        if (!p.vertex)
          {
            if (!best.found || std::abs(p.gap) < std::abs(best.gap) ||
                (std::abs(p.gap) == std::abs(best.gap) && p.piece < best.piece))
              best = p;
            continue;
          }
        best_distance = std::min(best_distance, (xs - p.point).norm());
        clamped.emplace_back(p, beyond_end(p));
      }
    if (best.found)
      {
        best.incomplete = any_failed;
        return best;
      }
    // The closest point, and of the pieces there the largest |g| (with
    // more than two pieces at a 3D node: the largest positive gap if there
    // is one, the point is outside; else the most negative); if the point
    // lies beyond the end of the master, not in contact.
    const double tolerance = 1e-8 * max_size;
    Point<dim>   meeting;
    for (const auto &[p, beyond] : clamped)
      if ((xs - p.point).norm() <= best_distance + tolerance)
        {
          meeting = p.point;
          break;
        }
    bool beyond_end = false;
    for (const auto &[p, beyond] : clamped)
      if ((p.point - meeting).norm() <= tolerance)
        {
          const bool outside = p.gap > 0., best_outside = best_vertex.gap > 0.;
          if (!best_vertex.found || (outside && !best_outside) ||
              (outside == best_outside &&
               (std::abs(p.gap) > std::abs(best_vertex.gap) ||
                (std::abs(p.gap) == std::abs(best_vertex.gap) &&
                 p.piece < best_vertex.piece))))
            best_vertex = p;
          beyond_end = beyond_end || beyond;
        }
    if (beyond_end)
      best_vertex.found = false;
    best_vertex.failed     = !best_vertex.found && any_failed;
    best_vertex.incomplete = best_vertex.found && any_failed;
    return best_vertex;
  }

  template <int dim>
  std::vector<unsigned int>
  MasterSurface<dim>::patch(const unsigned int facet) const
  {
    std::vector<unsigned int> result;
    for (const auto &list : corners[facet])
      for (const auto &fv : list)
        for (const auto k : facets[fv.first].nodes)
          result.push_back(k);
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
  }

  template <int dim>
  std::vector<unsigned int>
  MasterSurface<dim>::nodes_of(const Projection &p) const
  {
    const Piece              &piece = pieces[p.piece];
    std::vector<unsigned int> result;
    for (const auto &v : piece.vnodes)
      result.push_back(v.first);
    if (p.partner >= 0)
      for (const auto &v : pieces[p.partner].vnodes)
        result.push_back(v.first);
    if (piece.mirror_node >= 0)
      result.push_back(piece.mirror_node);
    if (dim == 3 && fraction > 0.)
      {
        bool band = false;
        for (unsigned int b = 0; b < dim - 1; ++b)
          // (with a margin: the chord steps of linearize() move xi by
          // round-off, and the band decides which nodes enter)
          band =
            band || p.xi[b] < fraction + 1e-8 || p.xi[b] > 1. - fraction - 1e-8;
        if (band)
          for (const auto k : patch(piece.facet))
            result.push_back(k);
      }
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
  }

  template <int dim>
  std::vector<unsigned int>
  MasterSurface<dim>::nodes_near(const Point<dim> &xs,
                                 const double      radius) const
  {
    namespace bgi = boost::geometry::index;
    Point<dim> lo = xs, hi = xs;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] -= radius;
        hi[d] += radius;
      }
    std::vector<Leaf> candidates;
    tree.query(bgi::intersects(BoundingBox<dim>(std::make_pair(lo, hi))),
               std::back_inserter(candidates));
    std::vector<unsigned int> result;
    for (const auto &candidate : candidates)
      {
        const Piece &piece = pieces[candidate.second];
        for (const auto &v : piece.vnodes)
          result.push_back(v.first);
        if (piece.mirror_node >= 0)
          result.push_back(piece.mirror_node);
        if (dim == 3 && fraction > 0.)
          for (const auto k : patch(piece.facet))
            result.push_back(k);
      }
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
  }

  template <int dim>
  void
  MasterSurface<dim>::linearize(
    const Projection                               &p,
    const Point<dim>                               &xs,
    const std::array<types::global_dof_index, dim> &slave_dofs,
    Linearization                                  &l) const
  {
    if (p.partner >= 0)
      {
        linearize_at_vertex(p, xs, slave_dofs, l);
        return;
      }
    const Piece                         &piece = pieces[p.piece];
    const auto                           local = nodes_of(p);
    const unsigned int                   n     = dim * (1 + local.size());
    std::map<unsigned int, unsigned int> slot;
    std::vector<std::array<Fad, dim>>    xl(local.size());
    for (unsigned int i = 0; i < local.size(); ++i)
      {
        slot[local[i]] = i;
        for (unsigned int d = 0; d < dim; ++d)
          xl[i][d] = Fad(n, dim * (1 + i) + d, x[local[i]][d]);
      }
    auto pos = [&](const unsigned int k) { return xl[slot.at(k)]; };
    std::array<Fad, dim> s;
    for (unsigned int d = 0; d < dim; ++d)
      s[d] = Fad(n, d, xs[d]);

    // dR/dxi at the solution, in plain numbers, for the chord steps.
    std::array<std::array<double, dim - 1>, dim - 1> J;
    {
      auto plain_pos = [&](const unsigned int k) {
        std::array<Fad, dim> y;
        for (unsigned int d = 0; d < dim; ++d)
          y[d] = x[k][d];
        return y;
      };
      std::array<Fad, dim> sp;
      for (unsigned int d = 0; d < dim; ++d)
        sp[d] = xs[d];
      std::array<Fad, dim - 1> xf, R;
      for (unsigned int b = 0; b < dim - 1; ++b)
        xf[b] = Fad(dim - 1, b, p.xi[b]);
      residual<Fad>(piece, xf, sp, plain_pos, R);
      for (unsigned int b = 0; b < dim - 1; ++b)
        for (unsigned int c = 0; c < dim - 1; ++c)
          J[b][c] = R[b].dx(c);
    }
    // Two chord steps xi <- xi - J^{-1} R(xi, u): exact first derivatives
    // of the projection point with respect to u (a clamped coordinate
    // stays on its edge).
    std::array<Fad, dim - 1> xi;
    for (unsigned int b = 0; b < dim - 1; ++b)
      xi[b] = p.xi[b];
    for (unsigned int step = 0; step < 2; ++step)
      {
        std::array<Fad, dim - 1> R;
        residual<Fad>(piece, xi, s, pos, R);
        std::array<Fad, dim - 1> d;
        if constexpr (dim == 2)
          {
            if (!p.clamped[0])
              d[0] = -R[0] / J[0][0];
            else
              d[0] = 0.;
          }
        else
          {
            if (p.clamped[0] && p.clamped[1])
              {
                d[0] = 0.;
                d[1] = 0.;
              }
            else if (p.clamped[0] || p.clamped[1])
              {
                const unsigned int b = p.clamped[0] ? 1 : 0;
                d[b]                 = -R[b] / J[b][b];
                d[1 - b]             = 0.;
              }
            else
              {
                const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
                d[0]             = -(J[1][1] * R[0] - J[0][1] * R[1]) / det;
                d[1]             = -(-J[1][0] * R[0] + J[0][0] * R[1]) / det;
              }
          }
        for (unsigned int b = 0; b < dim - 1; ++b)
          xi[b] += d[b];
      }

    std::array<Fad, dim>                      y, nrm;
    std::array<std::array<Fad, dim>, dim - 1> a;
    std::vector<Fad>                          w;
    geometry<Fad>(piece, xi, pos, y, a, nrm, &w);
    std::array<Fad, dim> r;
    for (unsigned int d = 0; d < dim; ++d)
      r[d] = s[d] - y[d];
    const Fad g = dot(r, nrm);

    // Force direction: the slave node gets n, virtual node j gets -w_j n
    // (mirrored: -w_j M n, and -2 w_j n_a on the plane node's a-component).
    std::vector<Fad> G(n, Fad(0.));
    for (unsigned int d = 0; d < dim; ++d)
      G[d] = nrm[d];
    for (unsigned int j = 0; j < piece.vnodes.size(); ++j)
      {
        const auto [k, mirrored] = piece.vnodes[j];
        const unsigned int base  = dim * (1 + slot.at(k));
        for (unsigned int d = 0; d < dim; ++d)
          G[base + d] -= (mirrored && d == piece.mirror_axis) ?
                           Fad(-w[j] * nrm[d]) :
                           Fad(w[j] * nrm[d]);
        if (mirrored)
          G[dim * (1 + slot.at(piece.mirror_node)) + piece.mirror_axis] -=
            2. * w[j] * nrm[piece.mirror_axis];
      }

    // A direction continuous along a faceted master for the Jacobian
    // stabilization (Linearization::spring): nu = sum_j w_j nu_j,
    // distributed as G.
    l.spring.reinit(0);
    if (fraction == 0. && node_normal.size() == nodes.size())
      {
        Tensor<1, dim> nu;
        for (unsigned int j = 0; j < piece.vnodes.size(); ++j)
          {
            const auto [k, mirrored] = piece.vnodes[j];
            Tensor<1, dim> v         = node_normal[k];
            if (mirrored)
              v[piece.mirror_axis] = -v[piece.mirror_axis];
            nu += w[j].val() * v;
          }
        if (nu.norm() > 0.)
          {
            nu /= nu.norm();
            l.spring.reinit(n);
            for (unsigned int d = 0; d < dim; ++d)
              l.spring(d) = nu[d];
            for (unsigned int j = 0; j < piece.vnodes.size(); ++j)
              {
                const auto [k, mirrored] = piece.vnodes[j];
                const unsigned int base  = dim * (1 + slot.at(k));
                for (unsigned int d = 0; d < dim; ++d)
                  l.spring(base + d) -= (mirrored && d == piece.mirror_axis) ?
                                          -w[j].val() * nu[d] :
                                          w[j].val() * nu[d];
                if (mirrored)
                  l.spring(dim * (1 + slot.at(piece.mirror_node)) +
                           piece.mirror_axis) -=
                    2. * w[j].val() * nu[piece.mirror_axis];
              }
          }
      }

    fill_gap<dim>(local, nodes, slave_dofs, g, nrm, l);
    for (unsigned int i = 0; i < n; ++i)
      {
        l.force(i) = G[i].val();
        for (unsigned int j = 0; j < n; ++j)
          l.dforce(i, j) = G[i].dx(j);
      }
  }

  template <int dim>
  void
  MasterSurface<dim>::linearize_at_vertex(
    const Projection                               &p,
    const Point<dim>                               &xs,
    const std::array<types::global_dof_index, dim> &slave_dofs,
    Linearization                                  &l) const
  {
    // g = (x_s - x_v) . n_v, n_v = (n_a + n_b) / |n_a + n_b| over the three
    // nodes of the two facets: dgap is its exact gradient; the force acts
    // along n_v on the slave node and the shared node (equal and opposite,
    // as at a held facet's end), and dforce is its derivative.
    const auto                           local = nodes_of(p);
    const unsigned int                   n     = dim * (1 + local.size());
    std::map<unsigned int, unsigned int> slot;
    std::vector<std::array<Fad, dim>>    xl(local.size());
    for (unsigned int i = 0; i < local.size(); ++i)
      {
        slot[local[i]] = i;
        for (unsigned int d = 0; d < dim; ++d)
          xl[i][d] = Fad(n, dim * (1 + i) + d, x[local[i]][d]);
      }
    std::array<Fad, dim> s;
    for (unsigned int d = 0; d < dim; ++d)
      s[d] = Fad(n, d, xs[d]);
    // Each facet's normal at the shared node (project_at_vertex()): piece
    // p.piece ends there at s = p.xi[0], its partner at the other end.
    const unsigned int   deg = polynomial_degree;
    const unsigned int   at  = static_cast<unsigned int>(p.xi[0]);
    std::array<Fad, dim> m   = {};
    for (const int q : {static_cast<int>(p.piece), p.partner})
      {
        const auto  &f   = facets[pieces[q].facet].nodes;
        const double end = q == static_cast<int>(p.piece) ? at : 1. - at;
        std::array<double, 3> N, dN;
        lagrange(deg, end, N.data(), dN.data());
        Fad tx = 0., ty = 0.;
        for (unsigned int i = 0; i <= deg; ++i)
          {
            const auto &xi = xl[slot.at(f[i])];
            tx += dN[i] * xi[0];
            ty += dN[i] * xi[1];
          }
        const Fad len = sqrt(tx * tx + ty * ty);
        m[0] += ty / len;
        m[1] -= tx / len;
      }
    const Fad            mn  = sqrt(m[0] * m[0] + m[1] * m[1]);
    std::array<Fad, dim> nrm = {{m[0] / mn, m[1] / mn}};
    const unsigned int   v   = facets[pieces[p.piece].facet].nodes[at * deg];
    const auto          &xv  = xl[slot.at(v)];
    Fad                  g   = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      g += (s[d] - xv[d]) * nrm[d];

    l.spring.reinit(0);
    fill_gap<dim>(local, nodes, slave_dofs, g, nrm, l);
    const unsigned int base = dim * (1 + slot.at(v));
    for (unsigned int d = 0; d < dim; ++d)
      {
        l.force(d)        = nrm[d].val();
        l.force(base + d) = -nrm[d].val();
        for (unsigned int j = 0; j < n; ++j)
          {
            l.dforce(d, j)        = nrm[d].dx(j);
            l.dforce(base + d, j) = -nrm[d].dx(j);
          }
      }
  }

  template class MasterSurface<2>;
  template class MasterSurface<3>;
  template std::vector<BoundingBox<2>>
  covering_boxes(const std::vector<Point<2>> &, const double);
  template std::vector<BoundingBox<3>>
  covering_boxes(const std::vector<Point<3>> &, const double);
} // namespace glide
