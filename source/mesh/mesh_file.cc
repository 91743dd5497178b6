#include <glide/mesh/abaqus_reader.h>
#include <glide/mesh/gmsh_reader.h>
#include <glide/mesh/mesh_file.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    std::string
    lower(std::string s)
    {
      for (auto &c : s)
        c = std::tolower(static_cast<unsigned char>(c));
      return s;
    }

    /// Corner positions (deal.II's lexicographic order) of each face of a
    /// quadrilateral or hexahedron, as GeometryInfo<dim> numbers them.
    const std::vector<std::vector<unsigned int>> &
    cell_faces(const unsigned int dim)
    {
      static const std::vector<std::vector<unsigned int>> quad{{0, 2},
                                                               {1, 3},
                                                               {0, 1},
                                                               {2, 3}};
      static const std::vector<std::vector<unsigned int>> hex{{0, 2, 4, 6},
                                                              {1, 3, 5, 7},
                                                              {0, 1, 4, 5},
                                                              {2, 3, 6, 7},
                                                              {0, 1, 2, 3},
                                                              {4, 5, 6, 7}};
      return dim == 2 ? quad : hex;
    }

    /// A cell whose corner Jacobian (relative to the product of its edge
    /// lengths there) is below this is degenerate: a zero angle, a zero
    /// edge, or corners on one line (zero area) or in one plane (zero
    /// volume). Far below any usable element (a 1e-6 rad angle) and far
    /// above round-off.
    constexpr double degenerate_corner = 1e-8;

    /// The signed corner Jacobians of a cell (vertices in deal.II's order),
    /// each divided by the lengths of its edges: +1 for a right angle.
    std::vector<double>
    corner_jacobians(const std::vector<std::array<double, 3>> &x,
                     const unsigned int                        dim)
    {
      std::vector<double> j;
      for (unsigned int v = 0; v < (1u << dim); ++v)
        {
          // Edges from corner v along each coordinate direction of the
          // reference cell, pointing into the cell.
          std::array<std::array<double, 3>, 3> e{};
          double                               lengths = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int w    = v ^ (1u << d);
              const double       sign = (v & (1u << d)) ? -1. : 1.;
              double             l    = 0;
              for (unsigned int c = 0; c < 3; ++c)
                {
                  e[d][c] = sign * (x[w][c] - x[v][c]);
                  l += e[d][c] * e[d][c];
                }
              lengths *= std::sqrt(l);
            }
          double det = 0;
          if (dim == 2)
            det = e[0][0] * e[1][1] - e[0][1] * e[1][0];
          else
            det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                  e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                  e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          j.push_back(lengths > 0 ? det / lengths : 0.);
        }
      return j;
    }

    /// Whether @p p lies on the face with corners @p x (deal.II's
    /// lexicographic order: a segment in 2D, a quadrilateral in 3D) without
    /// being one of its corners: within 1e-3 of the face's size of it, and
    /// farther than that from every corner. A flat face is split into two
    /// triangles; a warped one is taken as those triangles.
    bool
    inside_face(const std::array<double, 3>              &p,
                const std::vector<std::array<double, 3>> &x)
    {
      const auto minus = [](const std::array<double, 3> &a,
                            const std::array<double, 3> &b) {
        return std::array<double, 3>{{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
      };
      const auto dot = [](const std::array<double, 3> &a,
                          const std::array<double, 3> &b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      };
      double size = 0;
      for (const auto &a : x)
        for (const auto &b : x)
          size = std::max(size, std::sqrt(dot(minus(a, b), minus(a, b))));
      const double tolerance = 1e-3 * size;
      for (const auto &a : x)
        if (std::sqrt(dot(minus(p, a), minus(p, a))) <= tolerance)
          return false;
      if (x.size() == 2)
        {
          const auto   e = minus(x[1], x[0]), d = minus(p, x[0]);
          const double t = dot(d, e) / dot(e, e);
          const double normal =
            std::sqrt(std::max(0., dot(d, d) - t * t * dot(e, e)));
          return t > 0 && t < 1 && normal <= tolerance;
        }
      // Triangles (0, 1, 3) and (0, 3, 2) of the lexicographic corners.
      for (const auto &[i, j, k] : {std::array<unsigned int, 3>{{0, 1, 3}},
                                    std::array<unsigned int, 3>{{0, 3, 2}}})
        {
          const auto e1 = minus(x[j], x[i]), e2 = minus(x[k], x[i]),
                     d     = minus(p, x[i]);
          const double a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2),
                       b1 = dot(d, e1), b2 = dot(d, e2);
          const double det = a11 * a22 - a12 * a12;
          if (det <= 0)
            continue;
          const double s     = (b1 * a22 - b2 * a12) / det,
                       t     = (a11 * b2 - a12 * b1) / det;
          const double slack = tolerance / size;
          if (s < -slack || t < -slack || s + t > 1 + slack)
            continue;
          std::array<double, 3> r = d;
          for (unsigned int c = 0; c < 3; ++c)
            r[c] -= s * e1[c] + t * e2[c];
          if (std::sqrt(dot(r, r)) <= tolerance)
            return true;
        }
      return false;
    }

    /// Find @p name among @p sets: exactly, or ignoring case (Abaqus names
    /// are case-insensitive).
    template <typename Map>
    typename Map::const_iterator
    find_name(const Map &sets, const std::string &name)
    {
      auto it = sets.find(name);
      if (it != sets.end())
        return it;
      for (it = sets.begin(); it != sets.end(); ++it)
        if (lower(it->first) == lower(name))
          return it;
      return sets.end();
    }
  } // namespace



  std::string
  file_line(const std::string &file, const unsigned int line)
  {
    return "Mesh file '" + file + "', line " + std::to_string(line);
  }



  ImportedMesh
  import_body(const MeshFileContent &content,
              const unsigned int     dim,
              const std::string     &element_set)
  {
    ImportedMesh mesh;
    mesh.file              = content.file;
    const std::string file = "Mesh file '" + content.file + "'";

    // The body's cells.
    std::map<long, std::size_t> cell_index;
    for (std::size_t c = 0; c < content.cells.size(); ++c)
      cell_index[content.cells[c].id] = c;
    std::vector<std::size_t> selected;
    if (element_set.empty())
      for (std::size_t c = 0; c < content.cells.size(); ++c)
        selected.push_back(c);
    else
      {
        const auto it = find_name(content.cell_sets, element_set);
        if (it == content.cell_sets.end())
          {
            std::string list;
            for (const auto &[n, ids] : content.cell_sets)
              list += (list.empty() ? "" : ", ") + n;
            throw InputError(file + " has no " + content.set_word + " '" +
                             element_set + "' of " + std::to_string(dim) +
                             "D cells; its " + content.set_word +
                             "s are: " + (list.empty() ? "none" : list) + ".");
          }
        for (const auto id : it->second)
          {
            const auto c = cell_index.find(id);
            require(c != cell_index.end(),
                    file + ": the " + content.set_word + " '" + it->first +
                      "' names element " + std::to_string(id) +
                      ", which the file does not define as a cell.");
            selected.push_back(c->second);
          }
      }
    require(!selected.empty(),
            file + " has no " + std::to_string(dim) + "D cells" +
              (element_set.empty() ? "" : " in '" + element_set + "'") +
              "; glide reads quadrilaterals (2D) and hexahedra (3D).");

    // Every cell must be one glide can read faithfully.
    for (const auto c : selected)
      {
        if (!content.cells[c].problem.empty())
          throw InputError(content.cells[c].problem);
        mesh.element_types.insert(content.cells[c].type);
      }

    // Vertices: the corner nodes of the body's cells.
    std::map<long, unsigned int> vertex_of;
    std::map<long, std::size_t>  in_body; // cell id -> index in the body
    for (const auto c : selected)
      {
        in_body.emplace(content.cells[c].id, mesh.cells.size());
        std::vector<unsigned int> cell;
        for (const auto n : content.cells[c].nodes)
          {
            auto [it, inserted] = vertex_of.emplace(n, mesh.vertices.size());
            if (inserted)
              {
                mesh.vertices.push_back(content.nodes.at(n).x);
              }
            cell.push_back(it->second);
          }
        mesh.cells.push_back(cell);
      }
    // A 2D mesh lies in the plane z = 0, up to the round-off of a mesh
    // generator that wrote its coordinates in 3D (1e-14 was refused as
    // 'z = 0.000000' until 2026-12-06): 1e-10 of the mesh's extent.
    if (dim == 2)
      {
        double extent = 0.;
        for (unsigned int d = 0; d < 2; ++d)
          {
            const auto [low, high] =
              std::minmax_element(mesh.vertices.begin(),
                                  mesh.vertices.end(),
                                  [d](const auto &a, const auto &b) {
                                    return a[d] < b[d];
                                  });
            // Round-off scales with the coordinates too (a small part far
            // from the origin).
            extent = std::max({extent,
                               (*high)[d] - (*low)[d],
                               std::abs((*high)[d]),
                               std::abs((*low)[d])});
          }
        for (const auto &[n, v] : vertex_of)
          {
            auto              &x = mesh.vertices[v];
            std::ostringstream z;
            z << std::setprecision(6) << x[2];
            require(std::abs(x[2]) <= 1e-10 * extent,
                    file_line(content.file, content.nodes.at(n).line) +
                      ": node " + std::to_string(n) + " has z = " + z.str() +
                      ", but the scene is 2D (x, y); a 2D mesh lies in the "
                      "plane z = 0 (to 1e-10 of its coordinates).");
            x[2] = 0.;
          }
      }

    // Cells must not be degenerate or inverted.
    mesh.smallest_edge = std::numeric_limits<double>::max();
    for (std::size_t k = 0; k < selected.size(); ++k)
      {
        const auto                        &cell = content.cells[selected[k]];
        std::vector<std::array<double, 3>> x;
        for (const auto v : mesh.cells[k])
          x.push_back(mesh.vertices[v]);
        for (const auto &face : cell_faces(dim))
          for (unsigned int i = 0; i < face.size(); ++i)
            {
              double l = 0;
              for (unsigned int c = 0; c < 3; ++c)
                l += std::pow(x[face[i]][c] - x[face[(i + 1) % face.size()]][c],
                              2);
              mesh.smallest_edge = std::min(mesh.smallest_edge, std::sqrt(l));
            }
        const auto        j        = corner_jacobians(x, dim);
        const double      smallest = *std::min_element(j.begin(), j.end());
        const double      largest  = *std::max_element(j.begin(), j.end());
        const std::string label    = file_line(content.file, cell.line) +
                                  ": element " + std::to_string(cell.id) +
                                  " (" + cell.type + ")";
        const std::string area = dim == 2 ? "area" : "volume";
        if (std::max(std::abs(smallest), std::abs(largest)) <=
              degenerate_corner ||
            (std::abs(smallest) <= degenerate_corner && largest > 0) ||
            (std::abs(largest) <= degenerate_corner && smallest < 0))
          throw InputError(label + " has zero " + area +
                           " at a corner (two of its nodes coincide, or its "
                           "corners lie on one " +
                           (dim == 2 ? "line" : "plane") +
                           "); check its node list and the nodes' "
                           "coordinates.");
        if (smallest < 0 && largest > 0)
          throw InputError(
            label +
            " is distorted or inverted: it folds over at a corner "
            "(a bow-tie or non-convex " +
            std::string(dim == 2 ? "quadrilateral" : "hexahedron") +
            ", or its nodes in the wrong order); check its node list.");
        if (largest < 0 && content.clockwise_is_inverted)
          throw InputError(
            label + " has a negative " + area + " (it is inside out): " +
            (dim == 2 ?
               "its nodes go clockwise; Abaqus numbers the corners of a "
               "quadrilateral counterclockwise" :
               "its first face goes clockwise seen from its second; Abaqus "
               "numbers nodes 1-4 counterclockwise seen from nodes 5-8") +
            ". Reverse the order of its nodes.");
      }

    // Faces: each face of a cell, by its sorted vertices; a boundary face
    // belongs to one cell.
    struct FaceUse
    {
      std::size_t  cell = 0;
      unsigned int face = 0;
      unsigned int uses = 0;
    };
    std::map<std::vector<unsigned int>, FaceUse> faces;
    auto key = [](std::vector<unsigned int> v) {
      std::sort(v.begin(), v.end());
      return v;
    };
    for (std::size_t k = 0; k < mesh.cells.size(); ++k)
      for (unsigned int f = 0; f < 2 * dim; ++f)
        {
          std::vector<unsigned int> v;
          for (const auto i : cell_faces(dim)[f])
            v.push_back(mesh.cells[k][i]);
          auto &use = faces[key(v)];
          if (use.uses == 0)
            {
              use.cell = k;
              use.face = f;
            }
          ++use.uses;
          require(use.uses <= 2,
                  file + ": elements " +
                    std::to_string(content.cells[selected[use.cell]].id) +
                    " and " + std::to_string(content.cells[selected[k]].id) +
                    " and a third element share a face; elements must not "
                    "overlap (is an element defined twice under two ids?).");
        }

    // A conforming mesh: no corner of a boundary face lies on another
    // boundary face that shares a corner with it. Such a node hangs on the
    // face of a larger neighbour (meshed apart, or refined on one side), and
    // the body would be cut open between the two. Touching faces of
    // separate parts (a mesh file may hold several) share no corner and are
    // left alone.
    {
      std::vector<long> node_of(mesh.vertices.size());
      for (const auto &[n, v] : vertex_of)
        node_of[v] = n;
      const auto not_conforming = [&](const unsigned int v,
                                      const FaceUse     &use) {
        const auto &cell = content.cells[selected[use.cell]];
        throw InputError(
          file_line(content.file, cell.line) + ": node " +
          std::to_string(node_of[v]) + " lies on a " +
          (dim == 2 ? "side" : "face") + " of element " +
          std::to_string(cell.id) +
          " but is not one of its nodes: the mesh is not conforming there (a "
          "hanging node), and the body would be cut open along that " +
          (dim == 2 ? "side" : "face") +
          ". Mesh the body so that neighbouring elements share whole " +
          (dim == 2 ? "sides" : "faces") +
          " (in Gmsh: one mesh of the whole body, its regions sharing their "
          "boundary curves and surfaces), or put the two sides in separate "
          "element sets as two bodies in contact.");
      };
      std::map<unsigned int, std::vector<const std::vector<unsigned int> *>>
        boundary_at;
      for (const auto &[k, use] : faces)
        if (use.uses == 1)
          for (const auto v : k)
            boundary_at[v].push_back(&k);
      for (const auto &[k, use] : faces)
        if (use.uses == 1)
          {
            std::vector<std::array<double, 3>> x;
            for (const auto i : cell_faces(dim)[use.face])
              x.push_back(mesh.vertices[mesh.cells[use.cell][i]]);
            for (const auto a : k)
              for (const auto *other : boundary_at[a])
                for (const auto v : *other)
                  if (!std::binary_search(k.begin(), k.end(), v) &&
                      inside_face(mesh.vertices[v], x))
                    not_conforming(v, use);
          }

      // 2D, where the neighbours' sides are not straight continuations of
      // each other (a curved interface): the boundary sides, each directed
      // with its cell on the left, run round the body counterclockwise and
      // round a hole clockwise. From a side's end, at most 8 sides lead
      // back to its start round a hole of (almost) no area: a sliver
      // between a coarse side and the finer sides of the neighbour that
      // hangs on it. A real hole of that few sides has an area of at least
      // 2 % of its perimeter squared (a slot ten times as long as wide).
      if (dim == 2)
        {
          std::map<unsigned int, std::vector<unsigned int>> next;
          std::vector<std::pair<std::array<unsigned int, 2>, const FaceUse *>>
            sides;
          for (const auto &[k, use] : faces)
            if (use.uses == 1)
              {
                std::array<unsigned int, 2> e{
                  {mesh.cells[use.cell][cell_faces(2)[use.face][0]],
                   mesh.cells[use.cell][cell_faces(2)[use.face][1]]}};
                std::array<double, 2> c{{0., 0.}};
                for (const auto v : mesh.cells[use.cell])
                  for (unsigned int d = 0; d < 2; ++d)
                    c[d] += 0.25 * mesh.vertices[v][d];
                const auto &p = mesh.vertices[e[0]], &q = mesh.vertices[e[1]];
                if ((q[0] - p[0]) * (c[1] - p[1]) -
                      (q[1] - p[1]) * (c[0] - p[0]) <
                    0)
                  std::swap(e[0], e[1]);
                next[e[0]].push_back(e[1]);
                sides.emplace_back(e, &use);
              }
          // Every way from the side's end back to its start in at most 8
          // sides (a vertex where the boundary touches itself, such as a
          // corner of the sliver on the body's outside, has several).
          for (const auto &[e, use] : sides)
            {
              std::vector<unsigned int>   loop{e[0], e[1]};
              const std::function<void()> search = [&]() {
                const unsigned int v = loop.back();
                if (v == e[0])
                  {
                    if (loop.size() < 4)
                      return;
                    double area = 0, perimeter = 0;
                    for (std::size_t i = 0; i + 1 < loop.size(); ++i)
                      {
                        const auto &p = mesh.vertices[loop[i]],
                                   &q = mesh.vertices[loop[i + 1]];
                        area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
                        perimeter += std::hypot(q[0] - p[0], q[1] - p[1]);
                      }
                    if (std::abs(area) < 0.02 * perimeter * perimeter &&
                        (area < 0 ||
                         std::abs(area) < 1e-10 * perimeter * perimeter))
                      not_conforming(loop[2], *use);
                    return;
                  }
                const auto it = next.find(v);
                if (loop.size() > 9 || it == next.end())
                  return;
                for (const auto w : it->second)
                  {
                    loop.push_back(w);
                    search();
                    loop.pop_back();
                  }
              };
              search();
            }
        }
    }

    // Duplicate nodes: two nodes of the body at one place. The cells on
    // either side are not connected there (regions meshed apart, without
    // merging their nodes); the parts meet only through a contact pair.
    // Legitimate for a crack or two parts in contact, so a warning.
    {
      std::array<double, 3> lower = mesh.vertices.front(), upper = lower;
      for (const auto &x : mesh.vertices)
        for (unsigned int d = 0; d < 3; ++d)
          {
            lower[d] = std::min(lower[d], x[d]);
            upper[d] = std::max(upper[d], x[d]);
          }
      double size = 0;
      for (unsigned int d = 0; d < 3; ++d)
        size = std::max(size, upper[d] - lower[d]);
      // Positions rounded to 1e-10 of the body's size (a pair that
      // straddles a rounding boundary is missed; duplicates written by a
      // mesher are bitwise equal).
      const double      grid = 1e-10 * size;
      std::vector<long> node_of(mesh.vertices.size());
      for (const auto &[n, v] : vertex_of)
        node_of[v] = n;
      std::map<std::array<long long, 3>, unsigned int> at;
      unsigned int                                     count = 0;
      std::string                                      example;
      for (unsigned int v = 0; v < mesh.vertices.size(); ++v)
        {
          std::array<long long, 3> key;
          for (unsigned int d = 0; d < 3; ++d)
            key[d] = std::llround((mesh.vertices[v][d] - lower[d]) / grid);
          const auto [it, added] = at.emplace(key, v);
          if (added)
            continue;
          if (count++ == 0)
            {
              const auto        &x = mesh.vertices[v];
              std::ostringstream s;
              s << "nodes " << std::min(node_of[it->second], node_of[v])
                << " and " << std::max(node_of[it->second], node_of[v])
                << " at (" << x[0] << ", " << x[1];
              if (dim == 3)
                s << ", " << x[2];
              s << ")";
              example = s.str();
            }
        }
      if (count > 0)
        mesh.notes.push_back(
          std::to_string(count) + " pair(s) of nodes of the mesh file '" +
          content.file + "' lie at the same place (" + example +
          "): the elements on either side are not connected there "
          "(duplicate nodes, e.g. regions meshed apart) and meet only "
          "through a contact pair. If the body is one piece, merge the "
          "nodes (Gmsh: 'Coherence Mesh'; Abaqus/CAE: merge nodes).");
    }

    // Surfaces: faces of the body's boundary.
    std::map<std::vector<unsigned int>, std::set<std::string>> labels;
    std::set<std::string>                                      surface_names;
    for (const auto &[name, surface_faces] : content.surfaces)
      {
        unsigned int n = 0;
        // A face inside the body makes the surface unavailable, an error
        // only where the scene names it: a file written for another solver
        // may have such surfaces the scene does not use (until 2026-12-07
        // one stopped the whole file from being read).
        std::string inside;
        auto        add = [&](const std::vector<unsigned int> &k,
                       const MeshFileContent::Face     &f) {
          const auto it = faces.find(k);
          require(it != faces.end(),
                  file_line(content.file, f.line) + ": " + f.what +
                    " of surface '" + name +
                    "' is not a face of any cell of the body.");
          if (it->second.uses != 1)
            {
              if (inside.empty())
                inside = file_line(content.file, f.line) + ": " + f.what +
                         " of surface '" + name +
                         "' lies inside the body, between two elements; "
                                "glide's surfaces lie on the boundary of a body "
                                "(split the body into two element sets, or remove "
                                "the face)";
              return;
            }
          labels[k].insert(name);
          ++n;
        };
        for (const auto &f : surface_faces)
          {
            if (f.cell != 0 && !in_body.count(f.cell))
              continue; // a face of another body
            if (f.nodes.empty())
              {
                // All free faces of a cell.
                const std::size_t k = in_body.at(f.cell);
                for (const auto &face : cell_faces(dim))
                  {
                    std::vector<unsigned int> v;
                    for (const auto i : face)
                      v.push_back(mesh.cells[k][i]);
                    if (faces.at(key(v)).uses == 1)
                      {
                        labels[key(v)].insert(name);
                        ++n;
                      }
                  }
                continue;
              }
            std::vector<unsigned int> v;
            bool                      all = true;
            for (const auto node : f.nodes)
              {
                const auto it = vertex_of.find(node);
                if (it == vertex_of.end())
                  all = false;
                else
                  v.push_back(it->second);
              }
            if (!all)
              continue; // a face of another body (Gmsh)
            add(key(v), f);
          }
        if (!inside.empty())
          {
            for (auto l = labels.begin(); l != labels.end();)
              {
                l->second.erase(name);
                l = l->second.empty() ? labels.erase(l) : std::next(l);
              }
            mesh.unavailable[name] = inside;
            continue;
          }
        if (n > 0)
          surface_names.insert(name);
        else if (!element_set.empty())
          mesh.unavailable[name] = "the surface '" + name + "' of " + file +
                                   " has no face on the cells of this body "
                                   "(element set '" +
                                   element_set + "')";
        else
          require(!element_set.empty(),
                  file + ": the surface '" + name +
                    "' has no face on the boundary of the mesh's cells.");
      }

    // Boundary ids: one per combination of surfaces; 0 for faces in none.
    std::map<std::set<std::string>, types::boundary_id> combination;
    bool                                                unlabelled = false;
    for (const auto &[k, use] : faces)
      if (use.uses == 1)
        {
          const auto it = labels.find(k);
          if (it == labels.end())
            {
              unlabelled = true;
              continue;
            }
          auto [c, inserted] =
            combination.emplace(it->second, combination.size() + 1);
          if (inserted)
            mesh.surfaces[c->second] =
              std::vector<std::string>(it->second.begin(), it->second.end());
          mesh.faces.emplace_back(k, c->second);
        }
    if (unlabelled)
      mesh.surfaces[0] = {"unnamed"};

    // Node sets: their nodes that are vertices of the body. Mid-side nodes
    // of second-order elements are not nodes of glide's mesh.
    std::set<long> midside;
    for (const auto &cell : content.cells)
      if (cell.id != 0 && in_body.count(cell.id))
        midside.insert(cell.midside.begin(), cell.midside.end());
    for (const auto &[name, nodes] : content.node_sets)
      {
        std::vector<std::array<double, 3>> points;
        unsigned int                       other = 0, on_edges = 0;
        for (const auto n : nodes)
          if (const auto it = vertex_of.find(n); it != vertex_of.end())
            points.push_back(mesh.vertices[it->second]);
          else
            {
              ++other;
              on_edges += midside.count(n);
            }
        // '<name>.nodes' where the file has a surface of that name, also
        // one unavailable here (a face inside the body, or none on this
        // body's cells): the scene's '<body>.<name>' must reach the surface
        // and its error.
        const std::string set_name =
          content.surfaces.count(name) ? name + ".nodes" : name;
        // Mid-side nodes of the body's second-order elements are not in
        // glide's mesh: a force on the set acts on its corner nodes only,
        // which Abaqus' *CLOAD would not (until 2026-12-07 in silence: a
        // set of one corner and two mid-side nodes took a third of the
        // load).
        // Named in the log where the scene uses the set (mesh_notes() in
        // problem.cc). Not for the node sets made of an element set's nodes
        // (those are the whole elements', mid-side nodes included), nor for a
        // set that a surface of the same name is made of (a scene loads the
        // surface; its node set is '<name>.nodes').
        if (!points.empty() && on_edges > 0 &&
            !content.element_set_nodes.count(name) &&
            !surface_names.count(name))
          mesh.node_set_notes[set_name] =
            "the node set '" + name + "' of " + file + " has " +
            std::to_string(on_edges) +
            " mid-side node(s) of second-order elements, which glide does "
            "not have (it reads the elements with their corner nodes): a "
            "force or condition on it acts on its " +
            std::to_string(points.size()) +
            " corner node(s) only. Give the set corner nodes only, or load "
            "a surface with a traction instead.";
        if (!points.empty())
          mesh.node_sets[set_name] = points;
        else
          mesh.unavailable[set_name] =
            "the node set '" + name + "' of " + file +
            " has no corner node of a cell of this body (its " +
            std::to_string(other) +
            " nodes are mid-side nodes, nodes of no element or of another "
            "body)";
      }
    return mesh;
  }



  ImportedMesh
  import_mesh_file(const std::string &file,
                   const unsigned int dim,
                   const std::string &element_set,
                   const std::string &part)
  {
    std::string extension = std::filesystem::path(file).extension().string();
    extension             = lower(extension);
    if (extension == ".msh")
      {
        require(part.empty(),
                "Mesh file '" + file +
                  "': 'Part' names a part of an Abaqus file; in a Gmsh file "
                  "pick the body by its physical group with 'Element set'.");
        return import_body(read_gmsh(file, dim), dim, element_set);
      }
    require(extension == ".inp",
            "Mesh file '" + file +
              "': glide reads Gmsh '.msh' and Abaqus '.inp' files.");
    return import_body(read_abaqus(file, dim, part), dim, element_set);
  }



  template <int dim>
  void
  create_triangulation(
    const ImportedMesh                                     &mesh,
    Triangulation<dim>                                     &tria,
    std::map<types::boundary_id, std::vector<std::string>> &names)
  {
    std::vector<Point<dim>> vertices;
    for (const auto &x : mesh.vertices)
      {
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = x[d];
        vertices.push_back(p);
      }
    std::vector<CellData<dim>> cells;
    for (const auto &c : mesh.cells)
      {
        CellData<dim> data(c.size());
        for (unsigned int v = 0; v < c.size(); ++v)
          data.vertices[v] = c[v];
        cells.push_back(data);
      }
    SubCellData subcell;
    for (const auto &[v, id] : mesh.faces)
      {
        CellData<dim - 1> face(v.size());
        for (unsigned int i = 0; i < v.size(); ++i)
          face.vertices[i] = v[i];
        face.boundary_id = id;
        if constexpr (dim == 2)
          subcell.boundary_lines.push_back(face);
        else
          subcell.boundary_quads.push_back(face);
      }
    try
      {
        // Gmsh cells numbered clockwise are renumbered (Abaqus ones were
        // refused in import_body()); then the orientation of shared faces
        // is made consistent, as deal.II's GridIn does.
        // All cells one way or all the other: a cell numbered against
        // the others cannot be told from one folded over its neighbours.
        // The message names how many go each way and the centre of the
        // first cell of the smaller group (it named no cell, and its
        // advice was for 2D only, until 2026-12-07).
        std::array<std::vector<unsigned int>, 2> way; // positive, negative
        for (unsigned int c = 0; c < cells.size(); ++c)
          {
            std::vector<CellData<dim>> one{cells[c]};
            GridTools::invert_all_negative_measure_cells(vertices, one);
            way[one.front().vertices == cells[c].vertices ? 0 : 1].push_back(c);
          }
        if (!way[0].empty() && !way[1].empty())
          {
            const auto &fewer = way[0].size() < way[1].size() ? way[0] : way[1];
            Point<dim>  centre;
            for (const auto v : cells[fewer.front()].vertices)
              centre += vertices[v] / static_cast<double>(
                                        cells[fewer.front()].vertices.size());
            std::ostringstream text;
            text << "Mesh file '" << mesh.file << "': " << way[0].size()
                 << " of its cells are numbered one way round and "
                 << way[1].size()
                 << " the other (or are folded over their neighbours), e.g. "
                    "the cell with centre ("
                 << centre
                 << "); glide reads a mesh whose cells all go one way round. "
                    "In Gmsh, give all "
                 << (dim == 2 ? "surfaces" : "volumes")
                 << " of the body the same orientation (e.g. 'ReverseMesh "
                 << (dim == 2 ? "Surface" : "Volume")
                 << "{...};' in the .geo file for the others, or build them "
                    "from consistently oriented geometry) and mesh again.";
            throw InputError(text.str());
          }
        GridTools::invert_all_negative_measure_cells(vertices, cells);
        GridTools::consistently_order_cells(cells);
        tria.create_triangulation(vertices, cells, subcell);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream s;
        e.print_info(s);
        throw InputError(
          "Mesh file '" + mesh.file +
          "': deal.II cannot build a mesh of its cells: " + s.str());
      }
    names = mesh.surfaces;
  }

  template void
  create_triangulation<2>(
    const ImportedMesh &,
    Triangulation<2> &,
    std::map<types::boundary_id, std::vector<std::string>> &);
  template void
  create_triangulation<3>(
    const ImportedMesh &,
    Triangulation<3> &,
    std::map<types::boundary_id, std::vector<std::string>> &);
} // namespace glide
