// Unit tests of the mesh builders and of putting bodies together (P1.3).
// Why the expected answers are right: areas and volumes of the refined
// round shapes must approach the exact ones (pi R^2, ...) because curved
// boundaries carry manifolds; each builder must name its surfaces as
// documented; two touching bodies must not share vertices; the Gmsh reader
// must take surface names from $PhysicalNames.
#include <glide/mesh/mesh.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/numbers.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>

#include "test_helpers.h"
#include <gtest/gtest.h>

using namespace dealii;
using namespace glide;

namespace
{
  template <int dim>
  double
  measure_after(const std::string                         &type,
                const unsigned int                         refinements,
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
  const double                              pi = numbers::PI;
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
  Triangulation<2>                          tria;
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

TEST(Mesh, GmshPhysicalNamesBecomeSurfaces)
{
  MeshParameters m;
  m.type = "file";
  m.file = std::string(GLIDE_TEST_DATA) + "/two_quads.msh";
  Triangulation<2>                          tria;
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
  Triangulation<2>                          tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  EXPECT_THROW(build_body_mesh<2>(m, "slab", tria, names), InputError);
}

TEST(Mesh, AbaqusSurfacesBecomeNumberedSurfaces)
{
  // deal.II's Abaqus reader numbers surfaces by the digits of their name
  // (SS2 -> 2); glide names them <body>.<number>.
  MeshParameters m;
  m.type = "file";
  m.file = std::string(GLIDE_TEST_DATA) + "/two_quads.inp";
  Triangulation<2>                          tria;
  std::map<types::boundary_id, std::vector<std::string>> names;
  build_body_mesh<2>(m, "part", tria, names);
  EXPECT_EQ(tria.n_active_cells(), 2u);
  EXPECT_EQ(values(names).count("2"), 1u);
  unsigned int top_faces = 0;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary() && face->boundary_id() == 2)
        {
          EXPECT_NEAR(face->center()[1], 1., 1e-12);
          ++top_faces;
        }
  EXPECT_EQ(top_faces, 2u);
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
