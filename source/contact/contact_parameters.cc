#include <glide/contact/contact_parameters.h>
#include <glide/mechanics/rotation.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>

#include <cmath>

namespace glide
{
  using namespace dealii;

  namespace
  {
    std::vector<double>
    read_point(ParameterHandler  &prm,
               const std::string &entry,
               const unsigned int dim,
               const std::string &path)
    {
      auto v = read_numbers(prm.get(entry), path + "/" + entry);
      if (dim == 3 && v.size() == 2 && prm.get(entry) == "0, 0")
        v.push_back(0.);
      if (dim == 3 && v.size() == 2 && prm.get(entry) == "0, 1")
        v.push_back(0.);
      require(v.size() == dim,
              "Parameter '" + path + "/" + entry + "' needs " +
                std::to_string(dim) + " comma-separated components in a " +
                std::to_string(dim) + "D scene.");
      return v;
    }
  } // namespace

  void
  ContactPairParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Slave",
      "",
      Patterns::Anything(),
      "Slave surface <body>.<surface> (usually the finer or softer "
      "side), or the name of a node set for a node-based slave surface "
      "(each node with contact area 1, so that its CPRESS is its contact "
      "force, as in Abaqus).");
    prm.declare_entry(
      "Master",
      "rigid plane",
      Patterns::Anything(),
      "A surface <body>.<surface> of a deformable body, or an "
      "analytical rigid master: 'rigid plane' (a line in 2D), "
      "'rigid circle' (a circle in 2D, a cylinder along z in 3D), "
      "'rigid sphere' (3D; a circle in 2D, e.g. axisymmetric).");
    prm.declare_entry(
      "Formulation",
      "node to surface",
      Patterns::Selection("node to surface|surface to surface|mortar"),
      "Contact discretization: node to surface (one constraint per "
      "slave node). surface to surface (small sliding only): one "
      "constraint per slave node that averages over the "
      "slave nodes around it, anchored where that region, projected along "
      "the slave normal, lands on the master (R9); falls back to node to "
      "surface per constraint where that is not possible, and the log "
      "counts those. mortar (finite sliding, master surface of a body; 2D "
      "of degree 1 and 2, 3D of degree 1): the gap is enforced in a "
      "weighted-integral sense over the slave surface with dual "
      "multipliers (R14, doc/theory/mortar.md); "
      "passes the contact patch test; integrates over the master facets as "
      "meshed, so 'Smoothing fraction' does not apply.");
    prm.declare_entry(
      "Sliding",
      "finite",
      Patterns::Selection("finite|small"),
      "finite: the projection onto the master is updated every iteration "
      "(also in geometrically linear scenes, R4.1). small: each slave node "
      "is tied once, before the first step, to a tangent plane of the master "
      "through its anchor point and loads a fixed list of master nodes "
      "(R6-R12); in a geometrically linear scene this is infinitesimal "
      "sliding (plane and weights never change). Cheaper, but only right "
      "while every slave node stays within about one master facet of its "
      "anchor (the log warns when one does not).");
    prm.declare_entry(
      "Master normals",
      "",
      Patterns::Anything(),
      "Small sliding: nodal normals of the master prescribed by the user "
      "(R8.1), replacing the averaged ones at the nodes of a node set (or "
      "surface): '<node set>: nx, ny[, nz]', several separated by ';', "
      "e.g. 'edge: 0, 1'. Empty: none.");
    prm.declare_entry(
      "Smoothing fraction",
      "0.2",
      Patterns::Double(),
      "Fraction f of the facet length over which kinks of a faceted "
      "master are smoothed (R1): 0 <= f < 0.5, 0 turns smoothing "
      "off. Analytical rigid masters are smooth already.");
    prm.declare_entry(
      "Enforcement",
      "hard",
      Patterns::Selection("hard|penalty"),
      "hard: one Lagrange multiplier (contact force) per slave node, "
      "complementarity solved by semismooth Newton in KINSOL; no "
      "penetration. penalty: pressure = stiffness x penetration.");
    prm.declare_entry(
      "Penalty stiffness",
      "0",
      Patterns::Double(0.),
      "Penalty stiffness (stress per length). 0: automatic, 1000 "
      "E_pair / h per slave node, with h the mean size of the slave facets "
      "at the node (so the penetration scales with the local mesh size; "
      "give a value for a uniform stiffness, e.g. in the penalty patch "
      "test) and E_pair the smaller "
      "Young's modulus of the slave's and the master's body. Values above "
      "1e12 or below 1e-12 times E / L (L the scene's size) are refused: "
      "double precision cannot resolve the bodies next to the first, and "
      "the bodies pass through each other with the second.");
    prm.declare_entry(
      "Linearization",
      "unsymmetric",
      Patterns::Selection("unsymmetric|symmetrized"),
      "unsymmetric: the full consistent Jacobian (R5.1, default). "
      "symmetrized: its symmetric part, as a symmetric solver would "
      "use (R5.2), to measure what that costs.");
    prm.enter_subsection("Rigid master");
    prm.declare_entry(
      "Point",
      "0, 0",
      Patterns::List(Patterns::Double(), 2, 3),
      "A point of the rigid plane, or the center of the rigid "
      "circle/cylinder/sphere, in the reference configuration.");
    prm.declare_entry(
      "Normal",
      "0, 1",
      Patterns::List(Patterns::Double(), 2, 3),
      "Normal of the rigid plane, pointing towards the slave side.");
    prm.declare_entry("Radius",
                      "1",
                      Patterns::Double(0.),
                      "Radius of the rigid circle, cylinder or sphere (> 0).");
    prm.declare_entry(
      "Slave inside",
      "false",
      Patterns::Bool(),
      "true: the slave lies inside the circle/cylinder/sphere (a "
      "rigid hole); false: outside (a rigid punch or roller).");
    prm.declare_entry(
      "Translation",
      "",
      Patterns::Anything(),
      "Prescribed rigid translation as ';'-separated functions of "
      "the load factor t, e.g. '0; -0.1*t'. Empty: none.");
    prm.declare_entry(
      "Rotation",
      "0",
      Patterns::Anything(),
      "Prescribed rotation angle (radians, right-hand rule about "
      "'Rotation axis') as a function of t, about 'Rotation center'.");
    prm.declare_entry(
      "Rotation center",
      "0, 0",
      Patterns::List(Patterns::Double(), 2, 3),
      "Center of the prescribed rotation (reference configuration).");
    prm.declare_entry(
      "Rotation axis",
      "0, 0, 1",
      Patterns::Anything(),
      "Axis of the prescribed rotation, three components (normalized); "
      "3D only, in 2D rotations are about z. The axis of a 'rigid "
      "circle' (a cylinder in 3D, along z) turns with it.");
    prm.leave_subsection();
  }

  void
  ContactPairParameters::parse_parameters(ParameterHandler  &prm,
                                          const std::string &pair_name,
                                          const unsigned int dim)
  {
    name                   = pair_name;
    const std::string path = "Contact pair " + name;
    slave                  = prm.get("Slave");
    master                 = prm.get("Master");
    formulation            = prm.get("Formulation");
    sliding                = prm.get("Sliding");
    smoothing              = prm.get_double("Smoothing fraction");
    enforcement       = prm.get("Enforcement") == "hard" ? Enforcement::hard :
                                                           Enforcement::penalty;
    penalty_stiffness = prm.get_double("Penalty stiffness");
    symmetrized       = prm.get("Linearization") == "symmetrized";
    master_normals.clear();
    for (const auto &entry :
         Utilities::split_string_list(prm.get("Master normals"), ';'))
      {
        const auto colon = entry.find(':');
        require(colon != std::string::npos,
                "Parameter '" + path + "/Master normals' = '" +
                  prm.get("Master normals") + "': the entry '" + entry +
                  "' is not of the form '<node set>: nx, ny" +
                  (dim == 3 ? ", nz" : "") + "'.");
        const std::string         set = Utilities::trim(entry.substr(0, colon));
        const std::vector<double> n =
          read_numbers(Utilities::trim(entry.substr(colon + 1)),
                       path + "/Master normals");
        double length = 0.;
        for (const double x : n)
          length += x * x;
        require(n.size() == dim && length > 0.,
                "Parameter '" + path + "/Master normals': the normal of '" +
                  set + "' needs " + std::to_string(dim) +
                  " comma-separated numbers, not all zero.");
        for (const auto &[other, normal] : master_normals)
          require(other != set,
                  "Parameter '" + path +
                    "/Master normals' names the node "
                    "set '" +
                    set + "' twice; give each node set one normal.");
        master_normals.emplace_back(set, n);
      }
    require(master_normals.empty() || sliding == "small",
            "Parameter '" + path +
              "/Master normals' applies to small sliding only; set "
              "'Sliding = small' or remove it.");
    require(!slave.empty(),
            "Parameter '" + path +
              "/Slave' is empty; name the slave surface as <body>.<surface>.");
    require(
      smoothing >= 0. && smoothing < 0.5,
      "Parameter '" + path + "/Smoothing fraction' = " +
        prm.get("Smoothing fraction") + " of contact pair '" + name +
        "' is out of range: it must satisfy 0 <= f < 0.5 (0 turns smoothing off).");
    if (master == "rigid plane")
      master_type = MasterType::rigid_plane;
    else if (master == "rigid circle")
      master_type = MasterType::rigid_circle;
    else if (master == "rigid sphere")
      master_type = MasterType::rigid_sphere;
    else
      {
        master_type = MasterType::surface;
        require(
          master.find('.') != std::string::npos,
          "Parameter '" + path + "/Master' = '" + master +
            "' is neither a surface <body>.<surface> nor one of 'rigid plane', "
            "'rigid circle', 'rigid sphere'.");
        require(
          master != slave,
          "Contact pair '" + name + "': the surface '" + master +
            "' is both slave and master; a surface cannot contact itself.");
      }

    require(master_normals.empty() || master_type == MasterType::surface,
            "Parameter '" + path +
              "/Master normals' applies to the master surface of a body; "
              "an analytical rigid master has exact normals.");
    require(formulation != "surface to surface" || sliding == "small",
            "Contact pair '" + name +
              "': 'Formulation = surface to surface' is available with "
              "'Sliding = small' only so far; use node to surface for "
              "finite sliding.");
    require(formulation != "mortar" || sliding == "finite",
            "Contact pair '" + name +
              "': 'Formulation = mortar' is a finite-sliding formulation; "
              "set 'Sliding = finite' (or use small-sliding node to surface "
              "or surface to surface).");
    require(formulation != "mortar" || master_type == MasterType::surface,
            "Contact pair '" + name +
              "': 'Formulation = mortar' needs a "
              "master surface of a body (deformable or meshed rigid), not "
              "the analytical '" +
              master + "'; use 'Formulation = node to surface' with it.");
    prm.enter_subsection("Rigid master");
    point        = read_point(prm, "Point", dim, path + "/Rigid master");
    normal       = read_point(prm, "Normal", dim, path + "/Rigid master");
    radius       = prm.get_double("Radius");
    slave_inside = prm.get_bool("Slave inside");
    translation  = prm.get("Translation");
    rotation     = prm.get("Rotation");
    rotation_center =
      read_point(prm, "Rotation center", dim, path + "/Rigid master");
    {
      const auto a  = parse_rotation_axis(prm.get("Rotation axis"),
                                         dim,
                                         path + "/Rigid master/Rotation axis");
      rotation_axis = {{a[0], a[1], a[2]}};
    }
    prm.leave_subsection();

    double n2 = 0;
    for (const double x : normal)
      n2 += x * x;
    require(n2 > 0.,
            "Parameter '" + path + "/Rigid master/Normal' must not be zero.");
    require(radius > 0.,
            "Parameter '" + path + "/Rigid master/Radius' must be > 0.");
    if (!translation.empty())
      require(Utilities::split_string_list(translation, ';').size() == dim,
              "Parameter '" + path + "/Rigid master/Translation' needs " +
                std::to_string(dim) + " ';'-separated functions of t.");
  }
} // namespace glide
