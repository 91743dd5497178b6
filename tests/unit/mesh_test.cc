// Unit tests of the mesh builders and of putting bodies together (P1.3).
// Why the expected answers are right: areas and volumes of the refined
// round shapes must approach the exact ones (pi R^2, ...) because curved
// boundaries carry manifolds; each builder must name its surfaces as
// documented; two touching bodies must not share vertices; the Gmsh reader
// must take surface names from $PhysicalNames; glide's own readers (issue
// 13) must keep Abaqus names, pick bodies by element set or part, import
// node sets, accept any numbering and read straight second-order elements
// with their corners.
#include <glide/mesh/mesh.h>
#include <glide/mesh/mesh_file.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/numbers.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>

#include "test_helpers.h"
#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace dealii;
using namespace glide;

namespace
{
  template <int dim>
  double
  measure_after(const std::string &type,
                const unsigned int refinements,
                std::map<types::boundary_id, std::vector<std::string>> &names)
  {
    MeshParameters m;
    m.type         = type;
    m.center       = {0., 0., 0.};
    m.radius       = 2.;
    m.inner_radius = 1.;
    m.length       = 3.;
    Triangulation<dim> tria;
    build_body_mesh<dim>(m, "b", tria, names);
    tria.refine_global(refinements);
    // A cubic mapping, so the error is that of the refined geometry, not of
    // a polygonal approximation of it.
    return GridTools::volume(tria, MappingQ<dim>(3));
  }

  std::set<std::string>
  values(const std::map<types::boundary_id, std::vector<std::string>> &m)
  {
    std::set<std::string> s;
    for (const auto &[k, v] : m)
      s.insert(v.begin(), v.end());
    return s;
  }
} // namespace

TEST(Mesh, RoundShapesFollowTheirManifolds)
{
  const double                                           pi = numbers::PI;
  std::map<types::boundary_id, std::vector<std::string>> names;
  EXPECT_NEAR(measure_after<2>("cylinder", 5, names), pi * 4., 2e-3);
  EXPECT_EQ(values(names), (std::set<std::string>{"outer"}));
  EXPECT_NEAR(measure_after<2>("half cylinder", 5, names), pi * 2., 2e-3);
  EXPECT_EQ(values(names), (std::set<std::string>{"curved", "flat"}));
  EXPECT_NEAR(measure_after<2>("ring", 5, names), pi * 3., 2e-3);
  EXPECT_EQ(values(names), (std::set<std::string>{"inner", "outer"}));
  EXPECT_NEAR(measure_after<2>("sphere octant", 5, names), pi, 2e-3);
  EXPECT_EQ(values(names), (std::set<std::string>{"curved", "x0", "y0"}));
  EXPECT_NEAR(measure_after<3>("cylinder", 3, names), pi * 4. * 3., 0.05);
  EXPECT_EQ(values(names), (std::set<std::string>{"outer", "bottom", "top"}));
  EXPECT_NEAR(measure_after<3>("sphere octant", 3, names),
              4. / 3. * pi * 8. / 8.,
              0.02);
  EXPECT_EQ(values(names), (std::set<std::string>{"curved", "x0", "y0", "z0"}));
}

TEST(Mesh, HalfCylinderIsTheLowerHalf)
{
  MeshParameters m;
  m.type   = "hertz";
  m.center = {0., 1.};
  m.radius = 1.;
  Triangulation<2>                                       tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  build_body_mesh<2>(m, "b", tria, names);
  tria.refine_global(2); // the lowest point is a vertex from one refinement on
  for (const auto &v : tria.get_vertices())
    EXPECT_LE(v[1], 1. + 1e-12);
  const auto box = GridTools::compute_bounding_box(tria);
  EXPECT_NEAR(box.get_boundary_points().first[1], 0., 1e-12);
}

TEST(Mesh, BlockSurfacesAndTwoBodiesStaySeparate)
{
  const std::string text = R"(
set Bodies = lower, upper
subsection Body lower
  subsection Block
    set Upper corner = 1, 1
    set Subdivisions = 2, 2
  end
end
subsection Body upper
  subsection Block
    set Lower corner = 0, 1
    set Upper corner = 1, 2
    set Subdivisions = 3, 3
  end
  subsection Refinement
    set Global refinements = 1
  end
end
)";
  const Scene       scene =
    Scene::read(glide_test::write_file("mesh_two_bodies.prm", text));
  parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  Mesh<2>                                 mesh;
  mesh.build(scene, tria);
  EXPECT_EQ(tria.n_global_active_cells(), 4u + 36u);
  EXPECT_TRUE(mesh.has_surface("lower.top"));
  EXPECT_TRUE(mesh.has_surface("upper.bottom"));
  EXPECT_NE(*mesh.surface("lower.top", "x").begin(),
            *mesh.surface("upper.bottom", "x").begin());
  // The interface y = 1 is a boundary of both bodies: no shared vertices.
  unsigned int boundary_faces_on_interface = 0;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary() && std::abs(face->center()[1] - 1.) < 1e-12)
        ++boundary_faces_on_interface;
  EXPECT_EQ(boundary_faces_on_interface, 2u + 6u);
  try
    {
      mesh.surface("upper.side", "Boundary condition x/Surface");
      FAIL();
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("upper.top"), std::string::npos)
        << "lists the known surfaces";
    }
}

// A block of N subdivisions is built as a coarse mesh of N / 2^k cells per
// direction refined k times (fewer coarse cells for p4est): the same cells
// (each a square of the uniform grid), the same surfaces, and the scene's
// own global refinements on top. 12 x 8 over [0, 3] x [0, 2] has 3 x 2
// coarse cells; with one global refinement 24 x 16 cells of size 1/8.
TEST(Mesh, BlockSubdivisionsGiveTheUniformGridOnAFewCoarseCells)
{
  for (const unsigned int global : {0u, 1u})
    {
      const std::string text =
        "set Bodies = slab\nsubsection Body slab\n  subsection Block\n"
        "    set Upper corner = 3, 2\n    set Subdivisions = 12, 8\n  end\n"
        "  subsection Refinement\n    set Global refinements = " +
        std::to_string(global) + "\n  end\nend\n";
      const Scene scene =
        Scene::read(glide_test::write_file("mesh_block_coarse.prm", text));
      parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
      Mesh<2>                                 mesh;
      mesh.build(scene, tria);
      const unsigned int n = 1u << global;
      EXPECT_EQ(tria.n_cells(0), 6u) << "coarse cells";
      EXPECT_EQ(tria.n_global_active_cells(), 96u * n * n);
      const double                        h = 0.25 / n;
      std::map<std::string, unsigned int> faces;
      for (const auto &cell : tria.active_cell_iterators())
        {
          // Every cell is one square of the uniform grid.
          const Point<2> lo = cell->vertex(0);
          EXPECT_NEAR(cell->vertex(3)[0] - lo[0], h, 1e-14);
          EXPECT_NEAR(cell->vertex(3)[1] - lo[1], h, 1e-14);
          EXPECT_NEAR(lo[0] / h, std::round(lo[0] / h), 1e-10);
          EXPECT_NEAR(lo[1] / h, std::round(lo[1] / h), 1e-10);
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              for (const auto &[name, ids] : mesh.surfaces())
                if (ids.count(face->boundary_id()) > 0)
                  ++faces[name];
        }
      EXPECT_EQ(faces["slab.top"], 12u * n);
      EXPECT_EQ(faces["slab.bottom"], 12u * n);
      EXPECT_EQ(faces["slab.left"], 8u * n);
      EXPECT_EQ(faces["slab.right"], 8u * n);
    }
}

TEST(Mesh, GmshPhysicalNamesBecomeSurfaces)
{
  MeshParameters m;
  m.type = "file";
  m.file = std::string(GLIDE_TEST_DATA) + "/two_quads.msh";
  Triangulation<2>                                       tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  build_body_mesh<2>(m, "slab", tria, names);
  EXPECT_EQ(tria.n_active_cells(), 2u);
  EXPECT_EQ(values(names).count("bottom"), 1u);
  EXPECT_EQ(values(names).count("top"), 1u);
}

TEST(Mesh, UnreadableMeshFileIsAnInputError)
{
  MeshParameters m;
  m.type = "file";
  m.file =
    glide_test::write_file("broken.msh", "$MeshFormat\nthis is not gmsh\n");
  Triangulation<2>                                       tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  EXPECT_THROW(build_body_mesh<2>(m, "slab", tria, names), InputError);
}

TEST(Mesh, AbaqusSurfacesKeepTheirNames)
{
  // Issue 13: deal.II's reader numbered surfaces by the digits of their
  // name (SS2 -> 2, and names without digits all became 0); glide's reader
  // keeps the name: the two top edges of two_quads.inp are surface SS2.
  MeshParameters m;
  m.type = "file";
  m.file = std::string(GLIDE_TEST_DATA) + "/two_quads.inp";
  Triangulation<2>                                       tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  build_body_mesh<2>(m, "part", tria, names);
  EXPECT_EQ(tria.n_active_cells(), 2u);
  EXPECT_EQ(values(names), (std::set<std::string>{"SS2", "unnamed"}));
  unsigned int top_faces = 0;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary() && names[face->boundary_id()][0] == "SS2")
        {
          EXPECT_NEAR(face->center()[1], 1., 1e-12);
          ++top_faces;
        }
  EXPECT_EQ(top_faces, 2u);
}

namespace
{
  std::string
  mesh_data(const std::string &name)
  {
    return std::string(GLIDE_TEST_DATA) + "/mesh/" + name;
  }

  /// Faces of @p mesh in the surface @p name: their centers.
  std::vector<std::array<double, 3>>
  surface_centers(const ImportedMesh &mesh, const std::string &name)
  {
    std::vector<std::array<double, 3>> centers;
    for (const auto &[v, id] : mesh.faces)
      {
        const auto &n = mesh.surfaces.at(id);
        if (std::find(n.begin(), n.end(), name) == n.end())
          continue;
        std::array<double, 3> c{{0., 0., 0.}};
        for (const auto i : v)
          for (unsigned int d = 0; d < 3; ++d)
            c[d] += mesh.vertices[i][d] / v.size();
        centers.push_back(c);
      }
    return centers;
  }
} // namespace

TEST(Mesh, AbaqusBodiesByElementSetWithAnyNumbering)
{
  // Issue 13: one file, two bodies (elements 1-8 and 641-648, nodes 1-15
  // and 1001-1015); each body is one *ELSET. Surfaces and node sets belong
  // to the body whose cells they lie on; the element set name is
  // case-insensitive (the file says "Body2").
  const auto lower =
    import_mesh_file(mesh_data("two_bodies.inp"), 2, "BODY1", "");
  const auto upper =
    import_mesh_file(mesh_data("two_bodies.inp"), 2, "body2", "");
  EXPECT_EQ(lower.cells.size(), 8u);
  EXPECT_EQ(lower.vertices.size(), 15u);
  EXPECT_EQ(upper.cells.size(), 8u);
  EXPECT_EQ(upper.vertices.size(), 15u);

  // MASTER: the 4 top faces of the lower block (y = 1), SLAVE: the 4
  // bottom faces of the upper block (y = 1); neither in the other body.
  const auto master = surface_centers(lower, "MASTER");
  ASSERT_EQ(master.size(), 4u);
  for (const auto &c : master)
    EXPECT_NEAR(c[1], 1., 1e-12);
  EXPECT_EQ(surface_centers(upper, "SLAVE").size(), 4u);
  EXPECT_TRUE(surface_centers(upper, "MASTER").empty());
  EXPECT_TRUE(surface_centers(lower, "SLAVE").empty());

  // Node sets: FIXED (5 nodes, y = 0) in the lower body; LOADED (y = 1.5)
  // and the node-based surface SLAVE_NODES (y = 1) in the upper one.
  ASSERT_EQ(lower.node_sets.count("FIXED"), 1u);
  EXPECT_EQ(lower.node_sets.at("FIXED").size(), 5u);
  for (const auto &x : lower.node_sets.at("FIXED"))
    EXPECT_EQ(x[1], 0.);
  EXPECT_EQ(upper.node_sets.at("LOADED").size(), 5u);
  for (const auto &x : upper.node_sets.at("SLAVE_NODES"))
    EXPECT_EQ(x[1], 1.);
  EXPECT_EQ(lower.node_sets.count("LOADED"), 0u);
  EXPECT_EQ(lower.unavailable.count("LOADED"), 1u);
  // The nodes of an element set are a node set too.
  EXPECT_EQ(lower.node_sets.at("MASTER_ROW").size(), 10u);
}

TEST(Mesh, FileNodeSetsBelongToTheirBody)
{
  // The upper block's node set SLAVE_NODES lies on y = 1, where the lower
  // block has vertices at the same places (x = 0.5, 1, 1.5): the node set
  // must select the upper body's 5 vertices only.
  const std::string dir  = std::string(GLIDE_TEST_DATA) + "/mesh";
  const std::string text = "set Bodies = lower, upper\n"
                           "subsection Body lower\n  set Mesh = file\n"
                           "  set Mesh file = " +
                           dir +
                           "/two_bodies.inp\n  set Element set = BODY1\n"
                           "end\nsubsection Body upper\n  set Mesh = file\n"
                           "  set Mesh file = " +
                           dir +
                           "/two_bodies.inp\n  set Element set = BODY2\n"
                           "end\n";
  const Scene scene =
    Scene::read(glide_test::write_file("mesh_file_node_sets.prm", text));
  const NodeSetParameters *set = nullptr;
  for (const auto &ns : scene.node_sets)
    if (ns.name == "upper.SLAVE_NODES")
      set = &ns;
  ASSERT_NE(set, nullptr);
  EXPECT_EQ(set->body, 1u);
  EXPECT_EQ(set->points.size(), 5u);
  EXPECT_GT(set->tolerance, 0.);
  EXPECT_LT(set->tolerance, 1e-3 * 0.25); // far below the smallest edge
  parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  Mesh<2>                                 mesh;
  mesh.build(scene, tria);
  EXPECT_TRUE(mesh.has_surface("upper.SLAVE"));
  EXPECT_TRUE(mesh.has_surface("lower.MASTER"));
  EXPECT_NE(mesh.surface_list().find("upper.LOADED"), std::string::npos);
  try
    {
      mesh.surface("lower.LOADED", "Boundary condition x/Surface");
      FAIL();
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("no corner node of a cell of this "
                                           "body"),
                std::string::npos)
        << e.what();
    }
}

TEST(Mesh, OverlappingSurfacesShareFaces)
{
  // A face in two surfaces (TOP and ALL, the latter all free faces of the
  // element) belongs to both: its boundary id is named for both.
  const std::string file = glide_test::write_file(
    "overlap.inp",
    "*NODE\n1, 0, 0\n2, 1, 0\n3, 1, 1\n4, 0, 1\n"
    "*ELEMENT, TYPE=CPE4\n7, 1, 2, 3, 4\n"
    "*SURFACE, NAME=TOP\n7, S3\n*SURFACE, NAME=ALL\n7\n");
  const auto mesh = import_mesh_file(file, 2, "", "");
  EXPECT_EQ(surface_centers(mesh, "ALL").size(), 4u);
  const auto top = surface_centers(mesh, "TOP");
  ASSERT_EQ(top.size(), 1u);
  EXPECT_NEAR(top[0][1], 1., 1e-12);
  EXPECT_EQ(mesh.surfaces.count(0), 0u) << "no face outside every surface";
}

TEST(Mesh, StraightSecondOrderElementsAreReadWithTheirCorners)
{
  // Two CPE8 elements with straight edges: 2 cells with 6 corner vertices;
  // the node set TOP (2 corners... and 2 mid-side nodes) keeps its 3
  // corner nodes, and is renamed TOP.nodes because the surface TOP exists.
  const auto mesh = import_mesh_file(mesh_data("straight_cpe8.inp"), 2, "", "");
  EXPECT_EQ(mesh.cells.size(), 2u);
  EXPECT_EQ(mesh.vertices.size(), 6u);
  EXPECT_EQ(mesh.node_sets.at("TOP.nodes").size(), 3u);
  EXPECT_EQ(surface_centers(mesh, "TOP").size(), 2u);
  // With a curved edge: refused, naming the element type and the node.
  try
    {
      import_mesh_file(mesh_data("bad_curved_cpe8.inp"), 2, "", "");
      FAIL();
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("CPE8"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("mid-side node 17"),
                std::string::npos);
    }
}

TEST(Mesh, AbaqusPartsAndInstances)
{
  // parts.inp (Abaqus/CAE style): instance Block-1 of part Block is
  // translated by (0.5, 1); its surfaces are Top (part level) and Bottom
  // (assembly level), its node sets Corner (part) and Pushed (assembly,
  // nodes 3 and 4 of the instance). Helper sets (INTERNAL) are no node
  // sets. Without 'Part' the file is ambiguous.
  const auto block = import_mesh_file(mesh_data("parts.inp"), 2, "", "Block-1");
  ASSERT_EQ(block.node_sets.at("Corner").size(), 1u);
  EXPECT_NEAR(block.node_sets.at("Corner")[0][0], 1.5, 1e-12);
  EXPECT_NEAR(block.node_sets.at("Corner")[0][1], 2., 1e-12);
  EXPECT_EQ(block.node_sets.at("Pushed").size(), 2u);
  EXPECT_EQ(block.node_sets.count("_Top_S3"), 0u);
  EXPECT_NEAR(surface_centers(block, "Top").at(0)[1], 2., 1e-12);
  EXPECT_NEAR(surface_centers(block, "Bottom").at(0)[1], 1., 1e-12);
  const auto base = import_mesh_file(mesh_data("parts.inp"), 2, "", "Base");
  EXPECT_EQ(base.node_sets.at("Held").size(), 2u);
  EXPECT_THROW(import_mesh_file(mesh_data("parts.inp"), 2, "", ""), InputError);

  // An instance translated by (1, 0) and then (as in Abaqus) turned by 90
  // degrees about the z axis through the origin: node (1, 1) -> (2, 1) ->
  // (-1, 2).
  const std::string rotated = glide_test::write_file(
    "rotated.inp",
    "*Part, name=P\n*Node\n1, 0., 0.\n2, 1., 0.\n3, 1., 1.\n4, 0., 1.\n"
    "*Element, type=CPE4\n1, 1, 2, 3, 4\n*Nset, nset=N3\n3\n*End Part\n"
    "*Assembly, name=A\n*Instance, name=I, part=P\n 1., 0., 0.\n"
    " 0., 0., 0., 0., 0., 1., 90.\n*End Instance\n*End Assembly\n");
  const auto turned = import_mesh_file(rotated, 2, "", "");
  ASSERT_EQ(turned.node_sets.at("N3").size(), 1u);
  EXPECT_NEAR(turned.node_sets.at("N3")[0][0], -1., 1e-12);
  EXPECT_NEAR(turned.node_sets.at("N3")[0][1], 2., 1e-12);
}

TEST(Mesh, GmshFormat41AndHexahedra)
{
  // Files written by Gmsh 4.x (format 4.1): the plate's physical curves are
  // surfaces, its physical point a node set; the 3D box has 2 hexahedra and
  // the physical surfaces bottom and top (2 faces each).
  const auto plate = import_mesh_file(mesh_data("plate41.msh"), 2, "", "");
  EXPECT_EQ(plate.cells.size(), 2u);
  EXPECT_EQ(surface_centers(plate, "bottom").size(), 2u);
  EXPECT_EQ(surface_centers(plate, "sides").size(), 2u);
  ASSERT_EQ(plate.node_sets.at("corner").size(), 1u);
  EXPECT_EQ(plate.node_sets.at("corner")[0][0], 2.);
  const auto by_group =
    import_mesh_file(mesh_data("plate41.msh"), 2, "plate", "");
  EXPECT_EQ(by_group.cells.size(), 2u);

  const auto box = import_mesh_file(mesh_data("box41.msh"), 3, "", "");
  EXPECT_EQ(box.cells.size(), 2u);
  EXPECT_EQ(surface_centers(box, "top").size(), 2u);
  for (const auto &c : surface_centers(box, "top"))
    EXPECT_NEAR(c[2], 1., 1e-12);
  Triangulation<3>                                       tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  create_triangulation<3>(box, tria, names);
  EXPECT_NEAR(GridTools::volume(tria), 2., 1e-12);
}

TEST(Mesh, NodeSetPointsSeparatedBySemicolons)
{
  // Issue 13: 'Points = 0, 10;0, 5' is two points, with or without blanks
  // around ';' and with a trailing ';'.
  for (const std::string points : {"0, 10;0, 5", "0,10 ; 0,5", "0, 10; 0, 5;"})
    {
      ParameterHandler prm;
      NodeSetParameters::declare_parameters(prm);
      prm.set("Points", points);
      NodeSetParameters ns;
      ns.parse_parameters(prm, "tip", 2);
      ASSERT_EQ(ns.points.size(), 2u) << points;
      EXPECT_EQ(ns.points[0], (std::vector<double>{0., 10.}));
      EXPECT_EQ(ns.points[1], (std::vector<double>{0., 5.}));
    }
}

TEST(Mesh, HertzBodiesAreTheLowerPartOfASphere)
{
  // Axisymmetric: the quarter disk r >= 0 below the center (area pi R^2/4);
  // 3D: the sphere octant below the center (volume pi R^3/6), with the flat
  // top a quarter disk (area pi R^2/4), and the lowest point exactly at
  // center - R e_y.
  std::map<types::boundary_id, std::vector<std::string>> names;
  for (const unsigned int dim : {2u, 3u})
    {
      MeshParameters m;
      m.type         = "hertz";
      m.axisymmetric = (dim == 2);
      m.center       = {0., 1., 0.};
      m.radius       = 1.;
      double volume = 0, flat = 0, lowest = 1;
      if (dim == 2)
        {
          Triangulation<2> tria;
          build_body_mesh<2>(m, "b", tria, names);
          tria.refine_global(4);
          volume = GridTools::volume(tria, MappingQ<2>(3));
          for (const auto &v : tria.get_vertices())
            lowest = std::min(lowest, v[1]);
          EXPECT_NEAR(volume, numbers::PI / 4, 1e-4);
          EXPECT_EQ(values(names),
                    (std::set<std::string>{"curved", "flat", "axis"}));
        }
      else
        {
          Triangulation<3> tria;
          build_body_mesh<3>(m, "b", tria, names);
          tria.refine_global(3);
          volume = GridTools::volume(tria, MappingQ<3>(3));
          const MappingQ<3> mapping(3);
          for (const auto &cell : tria.active_cell_iterators())
            for (const auto f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  names[cell->face(f)->boundary_id()][0] == "flat")
                {
                  flat += cell->face(f)->measure();
                  EXPECT_NEAR(cell->face(f)->center()[1], 1., 1e-12)
                    << cell->face(f)->center();
                }
          for (const auto &v : tria.get_vertices())
            lowest = std::min(lowest, v[1]);
          EXPECT_NEAR(volume, numbers::PI / 6, 2e-3);
          EXPECT_NEAR(flat, numbers::PI / 4, 2e-2);
          EXPECT_EQ(values(names),
                    (std::set<std::string>{"curved", "flat", "x0", "z0"}));
        }
      EXPECT_EQ(lowest, 0.);
    }
}
