#include <glide/mechanics/boundary_conditions.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>

namespace glide
{
  using namespace dealii;

  bool
  BoundaryConditionParameters::is_symmetry() const
  {
    return type == BoundaryConditionType::xsymm ||
           type == BoundaryConditionType::ysymm ||
           type == BoundaryConditionType::zsymm;
  }

  bool
  BoundaryConditionParameters::is_dirichlet() const
  {
    return type == BoundaryConditionType::fixed ||
           type == BoundaryConditionType::displacement || is_symmetry();
  }

  unsigned int
  BoundaryConditionParameters::symmetry_component() const
  {
    return type == BoundaryConditionType::xsymm ? 0 :
           type == BoundaryConditionType::ysymm ? 1 :
                                                  2;
  }

  void
  BoundaryConditionParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Surface",
      "",
      Patterns::Anything(),
      "Where the condition acts: one or more comma-separated "
      "surfaces <body>.<surface> (e.g. 'block.bottom, "
      "block.left') and, except for traction and pressure, node "
      "sets (scene 'Node set' sections or sets from mesh files, "
      "e.g. 'block.bottom, die.SYM'; a node set acts on its mesh "
      "vertices). Reactions are reported per boundary condition.");
    prm.declare_entry(
      "Type",
      "fixed",
      Patterns::Selection(
        "fixed|displacement|traction|pressure|force|XSYMM|YSYMM|ZSYMM"),
      "fixed: u = 0. displacement: the components in 'Components' follow "
      "'Function'. traction: force per unit reference area (vector "
      "'Function'). pressure: scalar 'Function' acting against the outward "
      "normal (positive pushes in). force: concentrated force (vector "
      "'Function') on every node of the node set. XSYMM/YSYMM/ZSYMM: "
      "symmetry about a plane x/y/z = const (u_x/u_y/u_z = 0), recorded for "
      "contact.");
    prm.declare_entry("Components",
                      "x, y, z",
                      Patterns::MultipleSelection("x|y|z"),
                      "For 'displacement': which components are prescribed "
                      "(the others stay free). z is ignored in 2D; in "
                      "axisymmetric scenes x is the radius r and y the "
                      "axis z.");
    prm.declare_entry("Function",
                      "",
                      Patterns::Anything(),
                      "';'-separated components in x, y, (z,) t, with t "
                      "the load factor (0 to 1 over the load steps), e.g. "
                      "'0; -0.01*t'. pressure takes one expression. "
                      "Constants: pi. Units: length for displacement, "
                      "stress for traction and pressure, force for force.");
  }

  void
  BoundaryConditionParameters::parse_parameters(ParameterHandler  &prm,
                                                const std::string &bc_name,
                                                const unsigned int dim)
  {
    name         = bc_name;
    surface      = prm.get("Surface");
    const auto t = prm.get("Type");
    type         = (t == "fixed"        ? BoundaryConditionType::fixed :
                    t == "displacement" ? BoundaryConditionType::displacement :
                    t == "traction"     ? BoundaryConditionType::traction :
                    t == "pressure"     ? BoundaryConditionType::pressure :
                    t == "force"        ? BoundaryConditionType::force :
                    t == "XSYMM"        ? BoundaryConditionType::xsymm :
                    t == "YSYMM"        ? BoundaryConditionType::ysymm :
                                          BoundaryConditionType::zsymm);
    const auto c = Utilities::split_string_list(prm.get("Components"));
    components   = {false, false, false};
    const std::string path = "Boundary condition " + name;
    for (const auto &s : c)
      {
        const unsigned int k = s == "x" ? 0 : s == "y" ? 1 : 2;
        // A component named twice is most likely a typo for another one
        // (until 2026-12-06 'x, x, y' was taken as 'x, y').
        require(!components[k],
                "Parameter '" + path + "/Components' = '" +
                  prm.get("Components") + "' names '" + s +
                  "' twice; name each component once (x, y or z).");
        components[k] = true;
      }
    function = prm.get("Function");

    const bool needs_function = type == BoundaryConditionType::displacement ||
                                type == BoundaryConditionType::traction ||
                                type == BoundaryConditionType::pressure ||
                                type == BoundaryConditionType::force;
    if (needs_function)
      {
        const auto         parts = Utilities::split_string_list(function, ';');
        const unsigned int expected =
          (type == BoundaryConditionType::pressure ? 1 : dim);
        require(!function.empty() && parts.size() == expected,
                "Parameter '" + path + "/Function' = '" + function +
                  "' must have " + std::to_string(expected) +
                  " ';'-separated expression(s) for Type = " + t + " in " +
                  std::to_string(dim) + "D.");
      }
    if (type == BoundaryConditionType::displacement)
      require(components[0] || components[1] || (dim == 3 && components[2]),
              "Parameter '" + path +
                "/Components' selects no component of this scene's "
                "dimension.");
  }

  void
  NodeSetParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Points",
                      "",
                      Patterns::Anything(),
                      "';'-separated points, each with comma-separated "
                      "coordinates, e.g. '0, 1; 0.5, 1'. Each selects the "
                      "mesh vertex at that point.");
    prm.declare_entry("Tolerance",
                      "1e-8",
                      Patterns::Double(0.),
                      "Largest distance (length units) between a point and "
                      "its vertex; no vertex that close is an error.");
  }

  void
  NodeSetParameters::parse_parameters(ParameterHandler  &prm,
                                      const std::string &set_name,
                                      const unsigned int dim)
  {
    name      = set_name;
    tolerance = prm.get_double("Tolerance");
    points.clear();
    const std::string path = "Node set " + name + "/Points";
    for (const auto &p : Utilities::split_string_list(prm.get("Points"), ';'))
      {
        const std::vector<double> x = read_numbers(p, path);
        require(x.size() == dim,
                "Parameter '" + path + "': the point '" + p + "' needs " +
                  std::to_string(dim) + " coordinates.");
        points.push_back(x);
      }
    require(!points.empty(),
            "Parameter '" + path + "' is empty; give at least one point.");
  }
} // namespace glide
