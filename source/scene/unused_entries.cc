#include <glide/scene/scene.h>
#include <glide/scene/text.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>

namespace glide
{
  using namespace dealii;

  std::vector<std::string>
  Scene::unused_entries(const ParameterHandler &prm,
                        const ParameterHandler &defaults) const
  {
    std::vector<std::string> notes;
    // An entry counts as given where its value is not its default: the
    // parameter file cannot tell a default written out from one left out,
    // and a default changes nothing.
    const auto note = [&](const std::vector<std::string> &path,
                          const std::vector<std::string> &entries,
                          const std::string              &why) {
      for (const auto &entry : entries)
        {
          const std::string value = prm.get(path, entry);
          if (without_white_space(value) ==
              without_white_space(defaults.get(path, entry)))
            continue;
          std::string name;
          for (const auto &s : path)
            name += s + "/";
          notes.push_back("'" + name + entry + "' = '" + value +
                          "' is not used: " + why);
        }
    };

    for (const auto &body : bodies)
      {
        const std::string b    = "Body " + body.name;
        const auto       &mesh = body.mesh;
        if (mesh.type != "block")
          note({b, "Block"},
               {"Lower corner", "Upper corner", "Subdivisions"},
               "'Mesh = " + mesh.type + "' is not a block.");
        if (mesh.type == "block" || mesh.type == "file")
          note({b, "Round shapes"},
               {"Center", "Radius", "Inner radius", "Length"},
               "'Mesh = " + mesh.type + "' has no round shape.");
        else
          {
            if (mesh.type.find("ring") == std::string::npos)
              note({b, "Round shapes"},
                   {"Inner radius"},
                   "'Mesh = " + mesh.type + "' is not a ring.");
            if (dimension == 2)
              note({b, "Round shapes"},
                   {"Length"},
                   "the scene is 2D; 'Length' is the extent along z of 3D "
                   "cylinders and rings.");
          }
        if (mesh.local_refinements == 0)
          note({b, "Refinement"},
               {"Refinement point",
                "Refinement radius",
                "Minimum refinement radius"},
               "'Local refinements' is 0; set it to the number of levels "
               "to refine towards the point.");
        if (manufactured_solution != "none" && !body.rigid)
          note({b},
               {"Body force"},
               "'Verification/Manufactured solution = " +
                 manufactured_solution +
                 "' sets the body force from the exact solution.");
        if (body.rigid)
          note({b},
               {"Body force"},
               "a meshed rigid body ('Rigid body/Rigid = true') follows "
               "its prescribed motion; loads do not act on it.");
        else
          note({b, "Rigid body"},
               {"Translation", "Rotation", "Rotation center", "Rotation axis"},
               "'Rigid body/Rigid' is false, so the body is deformable and "
               "moves as its boundary conditions say; set 'Rigid = true' "
               "for a meshed rigid body that follows this motion.");
      }

    for (const auto &bc : boundary_conditions)
      {
        const std::string c = "Boundary condition " + bc.name;
        const std::string t =
          bc.type == BoundaryConditionType::fixed ?
            "fixed" :
          bc.is_symmetry() ?
            std::string(1, "XYZ"[bc.symmetry_component()]) + "SYMM" :
          bc.type == BoundaryConditionType::displacement ? "displacement" :
          bc.type == BoundaryConditionType::traction     ? "traction" :
          bc.type == BoundaryConditionType::pressure     ? "pressure" :
                                                           "force";
        if (bc.type == BoundaryConditionType::fixed || bc.is_symmetry())
          note({c},
               {"Function"},
               "'Type = " + t + "' holds " +
                 (bc.is_symmetry() ?
                    "u_" + std::string(1, "xyz"[bc.symmetry_component()]) :
                    std::string("u")) +
                 " = 0; for a prescribed displacement set 'Type = "
                 "displacement'.");
        bool all_components = true;
        for (unsigned int d = 0; d < dimension; ++d)
          all_components = all_components && bc.components[d];
        if (bc.type != BoundaryConditionType::displacement && !all_components)
          note({c},
               {"Components"},
               "it selects the components of 'Type = displacement' only; "
               "'Type = " +
                 t + "' acts on " +
                 (bc.type == BoundaryConditionType::fixed ?
                    "every component. To hold some components only, set "
                    "'Type = displacement' with a 'Function' of zeros." :
                  bc.is_symmetry() ? "its own component." :
                                     "every component of its 'Function'."));
      }

    for (const auto &pair : contact_pairs)
      {
        const std::string p = "Contact pair " + pair.name;
        if (pair.enforcement == Enforcement::hard)
          note({p},
               {"Penalty stiffness"},
               "'Enforcement = hard' has no penalty; set 'Enforcement = "
               "penalty' to use it.");
        if (pair.master_type != MasterType::surface)
          note({p},
               {"Smoothing fraction"},
               "an analytical rigid master ('" + pair.master +
                 "') is smooth already.");
        else if (pair.formulation == "mortar")
          note({p},
               {"Smoothing fraction"},
               "mortar integrates over the master facets as meshed.");
        if (pair.master_type == MasterType::surface)
          note({p, "Rigid master"},
               {"Point",
                "Normal",
                "Radius",
                "Slave inside",
                "Translation",
                "Rotation",
                "Rotation center",
                "Rotation axis"},
               "the master is the surface '" + pair.master +
                 "' of a body, not an analytical rigid master; a meshed "
                 "rigid body moves as its 'Body <name>/Rigid body' "
                 "subsection says.");
        else if (pair.master_type == MasterType::rigid_plane)
          note({p, "Rigid master"},
               {"Radius", "Slave inside"},
               "a rigid plane has no radius and no inside.");
        else
          note({p, "Rigid master"},
               {"Normal"},
               "'" + pair.master +
                 "' is round; 'Normal' is the rigid "
                 "plane's.");
      }

    if (linear_solver.type == "direct")
      note({"Linear solver"},
           {"Relative tolerance",
            "Maximum iterations",
            "Automatic direct limit"},
           "'Type = direct' solves exactly, without iterations.");
    else if (linear_solver.type == "amg")
      note({"Linear solver"},
           {"Automatic direct limit"},
           "it applies to 'Type = automatic' only.");
    if (!output.write_vtu)
      note({"Output"},
           {"Every n steps"},
           "'Write VTU' is false; no VTU files are written.");
    return notes;
  }
} // namespace glide
