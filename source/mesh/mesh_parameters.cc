#include <glide/mesh/mesh_parameters.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    const std::map<std::string, std::string> default_of{
      {"Lower corner", "0, 0"},
      {"Upper corner", "1, 1"},
      {"Subdivisions", "1, 1"},
      {"Center", "0, 0"}};

    /// Read a point; a 2D default left untouched in a 3D scene gets its
    /// third component from @p fill, so 3D scenes need not repeat defaults
    /// of shapes they do not use.
    std::vector<double>
    get_point(ParameterHandler  &prm,
              const std::string &entry,
              const unsigned int dim,
              const double       fill,
              const std::string &path)
    {
      auto v = read_numbers(prm.get(entry), path + "/" + entry);
      if (dim == 3 && v.size() == 2 && prm.get(entry) == default_of.at(entry))
        v.push_back(fill);
      return v;
    }

    void
    require_size(const std::vector<double> &v,
                 const unsigned int         dim,
                 const std::string         &path)
    {
      require(v.size() == dim,
              "Parameter '" + path + "' needs " + std::to_string(dim) +
                " comma-separated components in a " + std::to_string(dim) +
                "D scene, but has " + std::to_string(v.size()) + ".");
    }
  } // namespace

  std::string
  MeshParameters::extension() const
  {
    std::string e = std::filesystem::path(file).extension().string();
    for (auto &c : e)
      c = std::tolower(static_cast<unsigned char>(c));
    return e;
  }

  bool
  MeshParameters::is_gmsh() const
  {
    return extension() == ".msh";
  }

  std::string
  MeshParameters::builder_names()
  {
    return "block|cylinder|half cylinder|hertz|ring|half ring|quarter ring|sphere octant|file";
  }

  void
  MeshParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Mesh",
      "block",
      Patterns::Selection(builder_names()),
      "How the body is meshed. block: box from 'Lower corner' to 'Upper "
      "corner' (surfaces left, right, bottom, top, and in 3D back, front). "
      "cylinder: disk (2D) or cylinder along z (3D) of 'Radius' around "
      "'Center' (surface: outer; 3D also bottom, top). half cylinder: the "
      "lower half of that disk/cylinder, flat side up (surfaces: curved, "
      "flat). hertz: the lower part of a round body, refined towards its "
      "lowest point ('Refinement'), for Hertz contact: in plane strain a half "
      "cylinder (surfaces curved, flat), in an axisymmetric scene the quarter "
      "disk r >= 0 below the center, i.e. a sphere (curved, flat, axis), in "
      "3D the sphere octant x >= cx, y <= cy, z >= cz (curved, flat, x0, z0). "
      "ring: annulus/tube between 'Inner "
      "radius' and 'Radius' (surfaces inner, outer). half ring (2D): the "
      "lower half of that annulus, flat ends up (surfaces inner, outer, "
      "ends), e.g. the die of the ironing problem. quarter ring (2D): the "
      "quarter x, y >= Center of that annulus, 3 cells around before "
      "refinement (surfaces inner, outer, x0, y0), e.g. a quarter model of "
      "concentric cylinders. sphere octant: quarter "
      "disk (2D; a sphere in an axisymmetric scene) or sphere octant (3D) "
      "with x, y (, z) >= Center (surfaces: curved, x0, y0 (, z0)). file: "
      "read 'Mesh file'.");
    prm.declare_entry(
      "Mesh file",
      "",
      Patterns::Anything(),
      "Gmsh .msh (ASCII 2.2 or 4.1: physical groups of boundary faces "
      "become surfaces <body>.<name>, named by $PhysicalNames or by "
      "number; physical groups of points are node sets) or Abaqus .inp "
      "(*SURFACE, element-based, become surfaces <body>.<NAME>; *NSET, "
      "node-based *SURFACE and the nodes of *ELSET become node sets "
      "<body>.<NAME>). Quadrilaterals (2D) and hexahedra (3D) only; "
      "second-order Abaqus elements are read with their corner nodes if "
      "their edges are straight. See doc/mesh-import.md. A relative path "
      "is taken relative to the scene file.");
    prm.declare_entry(
      "Element set",
      "",
      Patterns::Anything(),
      "The body's cells in a mesh file that holds several bodies: the name "
      "of an Abaqus *ELSET (case-insensitive) or of a Gmsh physical group "
      "of cells. Surfaces and node sets of the file then belong to this "
      "body where they lie on its cells. Empty: every cell of the file (or "
      "of the 'Part').");
    prm.declare_entry(
      "Part",
      "",
      Patterns::Anything(),
      "Abaqus files with *PART and *ASSEMBLY: the part (instanced once) or "
      "the *INSTANCE that is this body, placed as the instance says. Empty: "
      "the file's only instance.");

    prm.enter_subsection("Block");
    prm.declare_entry("Lower corner",
                      "0, 0",
                      Patterns::List(Patterns::Double(), 2, 3),
                      "Lower corner of the block (length units; 2 "
                      "components in 2D, 3 in 3D).");
    prm.declare_entry("Upper corner",
                      "1, 1",
                      Patterns::List(Patterns::Double(), 2, 3),
                      "Upper corner of the block.");
    prm.declare_entry("Subdivisions",
                      "1, 1",
                      Patterns::List(Patterns::Integer(1), 2, 3),
                      "Number of cells in each direction before refinement.");
    prm.leave_subsection();

    prm.enter_subsection("Round shapes");
    prm.declare_entry("Center",
                      "0, 0",
                      Patterns::List(Patterns::Double(), 2, 3),
                      "Center of the cylinder, half cylinder, ring or sphere "
                      "octant (in 3D the cylinder axis is parallel to z and "
                      "the center is on its lower end).");
    prm.declare_entry("Radius",
                      "1",
                      Patterns::Double(0.),
                      "Outer radius (length units, > 0).");
    prm.declare_entry("Inner radius",
                      "0.5",
                      Patterns::Double(0.),
                      "Inner radius of a ring (0 < inner < Radius).");
    prm.declare_entry("Length",
                      "1",
                      Patterns::Double(0.),
                      "Length along z of cylinders and rings in 3D.");
    prm.leave_subsection();

    prm.enter_subsection("Refinement");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 12),
                      "Times every cell of this body is split in 2^dim.");
    prm.declare_entry("Local refinements",
                      "0",
                      Patterns::Integer(0, 12),
                      "Extra refinements towards 'Refinement point': at "
                      "level k, cells within Refinement radius / 2^k of the "
                      "point are refined (grading towards a contact).");
    prm.declare_entry("Refinement point",
                      "",
                      Patterns::List(Patterns::Double(), 0, 3),
                      "Point to refine towards. Empty: for 'hertz' the "
                      "lowest point of the half cylinder, otherwise the "
                      "center of the body's bounding box.");
    prm.declare_entry("Refinement radius",
                      "0",
                      Patterns::Double(0.),
                      "Radius of the first local refinement level (length "
                      "units). 0: a quarter of the body's size.");
    prm.declare_entry(
      "Minimum refinement radius",
      "0",
      Patterns::Double(0.),
      "The radius of level k is max(Refinement radius / 2^k, this): "
      "set it to the size of the zone that must be resolved "
      "uniformly by the finest cells (e.g. twice a contact zone).");
    prm.leave_subsection();
  }

  void
  MeshParameters::parse_parameters(ParameterHandler  &prm,
                                   const std::string &path,
                                   const std::string &scene_directory,
                                   const unsigned int dim)
  {
    type        = prm.get("Mesh");
    file        = prm.get("Mesh file");
    element_set = Utilities::trim(prm.get("Element set"));
    part        = Utilities::trim(prm.get("Part"));
    imported.reset();
    require(type == "file" || (element_set.empty() && part.empty()),
            "Parameters '" + path +
              "/Element set' and 'Part' pick a body "
              "out of a mesh file; they need 'Mesh = file'.");
    // Forgetting 'Mesh = file' would mesh the default block in silence.
    require(type == "file" || Utilities::trim(file).empty(),
            "Parameter '" + path + "/Mesh file' = '" + file +
              "' is given, but 'Mesh = " + type +
              "' builds the body itself; set 'Mesh = file' to read the "
              "file, or remove 'Mesh file'.");
    if (type == "file")
      {
        require(!file.empty(),
                "Parameter '" + path +
                  "/Mesh file' is empty, but 'Mesh = file'; give the path "
                  "of a .msh or .inp file.");
        if (file[0] != '/')
          file = scene_directory + "/" + file;
        std::error_code ec;
        require(!std::filesystem::is_directory(file, ec),
                "Parameter '" + path + "/Mesh file': '" + file +
                  "' is a directory; give the path of a .msh or .inp file.");
        require_regular_file(file,
                             "Parameter '" + path + "/Mesh file':",
                             "give the path of a .msh or .inp file.");
        std::ifstream in(file);
        require(static_cast<bool>(in),
                "Parameter '" + path + "/Mesh file': cannot open '" + file +
                  "' (relative paths are taken relative to the scene "
                  "file).");
        const bool msh = is_gmsh();
        const bool inp = extension() == ".inp";
        require(msh || inp,
                "Parameter '" + path + "/Mesh file' = '" + file +
                  "': only Gmsh '.msh' and Abaqus '.inp' files are read.");
        // Read and check the file now, before anything is computed or
        // written; its node sets become node sets of the scene.
        imported = std::make_shared<const ImportedMesh>(
          import_mesh_file(file, dim, element_set, part));
      }

    prm.enter_subsection("Block");
    lower_corner = get_point(prm, "Lower corner", dim, 0., path + "/Block");
    upper_corner = get_point(prm, "Upper corner", dim, 1., path + "/Block");
    subdivisions.clear();
    for (const auto &s : Utilities::split_string_list(prm.get("Subdivisions")))
      subdivisions.push_back(Utilities::string_to_int(s));
    if (dim == 3 && subdivisions.size() == 2 &&
        prm.get("Subdivisions") == default_of.at("Subdivisions"))
      subdivisions.push_back(1);
    prm.leave_subsection();

    prm.enter_subsection("Round shapes");
    center       = get_point(prm, "Center", dim, 0., path + "/Round shapes");
    radius       = prm.get_double("Radius");
    inner_radius = prm.get_double("Inner radius");
    length       = prm.get_double("Length");
    prm.leave_subsection();

    prm.enter_subsection("Refinement");
    global_refinements = prm.get_integer("Global refinements");
    local_refinements  = prm.get_integer("Local refinements");
    refinement_point =
      get_point(prm, "Refinement point", dim, 0., path + "/Refinement");
    refinement_radius         = prm.get_double("Refinement radius");
    minimum_refinement_radius = prm.get_double("Minimum refinement radius");
    prm.leave_subsection();

    require(radius > 0.,
            "Parameter '" + path + "/Round shapes/Radius' must be > 0.");
    const bool ring =
      type == "ring" || type == "half ring" || type == "quarter ring";
    if (ring)
      require(inner_radius > 0. && inner_radius < radius,
              "Parameter '" + path +
                "/Round shapes/Inner radius' must satisfy 0 < Inner radius "
                "< Radius.");
    // A round shape's faces are told apart by their distance from the
    // centre, to 1e-6 of the radius: coordinates whose round-off exceeds
    // that (a centre 1e10 radii away), or a radius whose square
    // overflows, left a face on no surface (an internal error).
    if (type != "block" && type != "file")
      {
        double far = 0.;
        for (const double c : center)
          far = std::max(far, std::abs(c));
        const double smallest = ring ? inner_radius : radius;
        require(radius <= 1e100 && far <= 1e8 * smallest,
                "Parameters '" + path + "/Round shapes/Center' and 'Radius'" +
                  (ring ? std::string(" and 'Inner radius'") : "") +
                  ": a round shape needs a radius of at most 1e100 and "
                  "its centre within 1e8 radii of the origin (double "
                  "precision cannot tell its surfaces apart otherwise); "
                  "move the origin near the body or change the units.");
      }
  }

  void
  MeshParameters::check_sizes(const unsigned int dim,
                              const std::string &path) const
  {
    const MeshParameters &m = *this;
    require((m.type != "half ring" && m.type != "quarter ring") || dim == 2,
            "Parameter '" + path + "/Mesh' = '" + m.type +
              "' is available in 2D only.");
    require_size(m.lower_corner, dim, path + "/Block/Lower corner");
    require_size(m.upper_corner, dim, path + "/Block/Upper corner");
    require(m.subdivisions.size() == dim,
            "Parameter '" + path + "/Block/Subdivisions' needs " +
              std::to_string(dim) + " components.");
    for (unsigned int d = 0; d < dim; ++d)
      require(m.upper_corner[d] > m.lower_corner[d],
              "Parameters '" + path +
                "/Block/Lower corner' and 'Upper corner': every component "
                "of the upper corner must be larger than that of the lower "
                "corner.");
    // Cells of an aspect ratio beyond 1e8 make a stiffness matrix that
    // double precision cannot factor (2 x 1e-300: the direct solver failed
    // after 6 cut-backs, naming no parameter).
    if (m.type == "block")
      {
        double smallest = std::numeric_limits<double>::max(), largest = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double h =
              (m.upper_corner[d] - m.lower_corner[d]) / m.subdivisions[d];
            smallest = std::min(smallest, h);
            largest  = std::max(largest, h);
          }
        std::ostringstream ratio;
        ratio << std::setprecision(3) << largest / smallest;
        require(largest <= 1e8 * smallest,
                "Parameters '" + path +
                  "/Block/Lower corner', 'Upper corner' and 'Subdivisions' "
                  "make cells with an aspect ratio of " +
                  ratio.str() +
                  " (longest to shortest side); double precision cannot "
                  "solve for cells beyond 1e8. Change 'Subdivisions' so "
                  "that the cells are closer to square, or the corners.");
      }
    require_size(m.center, dim, path + "/Round shapes/Center");
    if (!m.refinement_point.empty())
      require_size(m.refinement_point,
                   dim,
                   path + "/Refinement/Refinement point");
  }
} // namespace glide
