// Unit tests of scene reading (P4.1): a valid scene gives the values it
// states; each kind of input mistake gives an InputError whose message
// names the file and the parameter and says what to do. (The program-level
// tests in tests/scenes check the exit status and that nothing is written.)
#include <glide/scene/input_error.h>
#include <glide/scene/parameter_hint.h>
#include <glide/scene/scene.h>

#include "test_helpers.h"
#include <gtest/gtest.h>

#include <sstream>

using namespace glide;

namespace
{
  const std::string valid = R"(
set Dimension = 2
set Analysis type = axisymmetric
set Bodies = puck, base
set Boundary conditions = hold, push
subsection Discretization
  set Element degree = 2
end
subsection Body puck
  set Mesh = block
  subsection Block
    set Lower corner = 0, 1
    set Upper corner = 1, 2
  end
  subsection Material
    set Young's modulus = 200
    set Poisson's ratio = 0.25
  end
end
subsection Body base
  set Mesh = block
end
subsection Boundary condition hold
  set Surface = base.bottom
  set Type = YSYMM
end
subsection Boundary condition push
  set Surface = puck.top, puck.right
  set Type = pressure
  set Function = 3*t
end
)";

  /// Read @p text as a scene and return the InputError message ("" if
  /// none).
  std::string
  error_of(const std::string &text, const std::string &file = "scene_test.prm")
  {
    const std::string path = glide_test::write_file(file, text);
    try
      {
        Scene::read(path);
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }

  std::string
  replace(std::string text, const std::string &from, const std::string &to)
  {
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return text.replace(pos, from.size(), to);
  }
} // namespace

TEST(Scene, ReadsWhatTheFileSays)
{
  const Scene s = Scene::read(glide_test::write_file("scene_valid.prm", valid));
  EXPECT_EQ(s.name, "scene_valid");
  EXPECT_EQ(s.analysis, AnalysisType::axisymmetric);
  EXPECT_EQ(s.degree, 2u);
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].name, "puck");
  EXPECT_DOUBLE_EQ(s.bodies[0].material.youngs_modulus, 200.);
  EXPECT_DOUBLE_EQ(s.bodies[0].mesh.upper_corner[1], 2.);
  ASSERT_EQ(s.boundary_conditions.size(), 2u);
  EXPECT_EQ(s.boundary_conditions[0].type, BoundaryConditionType::ysymm);
  EXPECT_TRUE(s.boundary_conditions[0].is_symmetry());
  EXPECT_EQ(s.boundary_conditions[1].type, BoundaryConditionType::pressure);
}

TEST(Scene, CommandLineOverrides)
{
  const Scene s = Scene::read(glide_test::write_file("scene_valid.prm", valid),
                              {"Discretization/Element degree=1",
                               "Body puck/Material/Young's modulus=7"});
  EXPECT_EQ(s.degree, 1u);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.youngs_modulus, 7.);
}

TEST(Scene, MisspeltParameterNamesFileLineAndEntry)
{
  const auto m =
    error_of(replace(valid, "set Element degree", "set Element degre"));
  EXPECT_NE(m.find("scene_test.prm"), std::string::npos) << m;
  EXPECT_NE(m.find("Element degre"), std::string::npos) << m;
  EXPECT_NE(m.find("--print-parameters"), std::string::npos) << m;
}

TEST(Scene, ValueOutOfRange)
{
  const auto m = error_of(
    replace(valid, "set Poisson's ratio = 0.25", "set Poisson's ratio = 0.7"));
  EXPECT_NE(m.find("Poisson's ratio"), std::string::npos) << m;
  EXPECT_NE(m.find("0.7"), std::string::npos) << m;
  const auto d = error_of(
    replace(valid, "set Element degree = 2", "set Element degree = 3"));
  EXPECT_NE(d.find("Element degree"), std::string::npos) << d;
}

TEST(Scene, UnknownBodyInSurfaceName)
{
  const auto m = error_of(
    replace(valid, "set Surface = base.bottom", "set Surface = bse.bottom"));
  EXPECT_NE(m.find("Boundary condition hold/Surface"), std::string::npos) << m;
  EXPECT_NE(m.find("no such body"), std::string::npos) << m;
}

TEST(Scene, SurfaceNameWithoutBody)
{
  const auto m = error_of(
    replace(valid, "set Surface = base.bottom", "set Surface = bottom"));
  EXPECT_NE(m.find("<body>.<surface>"), std::string::npos) << m;
}

TEST(Scene, AxisymmetricIn3DIsRejected)
{
  const auto m =
    error_of(replace(valid, "set Dimension = 2", "set Dimension = 3"));
  EXPECT_NE(m.find("axisymmetric"), std::string::npos) << m;
  EXPECT_NE(m.find("Dimension = 3"), std::string::npos) << m;
}

TEST(Scene, AxisymmetricBodyMustLieAtPositiveRadius)
{
  const auto m = error_of(
    replace(valid, "set Lower corner = 0, 1", "set Lower corner = -1, 1"));
  EXPECT_NE(m.find("Body 'puck'"), std::string::npos) << m;
  EXPECT_NE(m.find("r >= 0"), std::string::npos) << m;
}

TEST(Scene, MissingMeshFile)
{
  const auto m = error_of(replace(
    valid,
    "subsection Body base\n  set Mesh = block",
    "subsection Body base\n  set Mesh = file\n  set Mesh file = nowhere.msh"));
  EXPECT_NE(m.find("Body base/Mesh file"), std::string::npos) << m;
  EXPECT_NE(m.find("nowhere.msh"), std::string::npos) << m;
}

TEST(Scene, MissingSceneFile)
{
  try
    {
      Scene::read("does-not-exist.prm");
      FAIL() << "no error";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("does-not-exist.prm"),
                std::string::npos);
    }
}

TEST(Scene, WrongNumberOfFunctionComponents)
{
  const auto m =
    error_of(replace(valid, "set Function = 3*t", "set Function = 3*t; 0"));
  EXPECT_NE(m.find("Boundary condition push/Function"), std::string::npos) << m;
}

TEST(Scene, ZsymmNeeds3D)
{
  const auto m =
    error_of(replace(valid, "set Type = YSYMM", "set Type = ZSYMM"));
  EXPECT_NE(m.find("ZSYMM"), std::string::npos) << m;
}

TEST(Scene, DuplicateBodyNames)
{
  const auto m = error_of(
    replace(valid, "set Bodies = puck, base", "set Bodies = puck, puck"));
  EXPECT_NE(m.find("twice"), std::string::npos) << m;
}

TEST(Scene, PrintParametersDocumentsEverything)
{
  std::ostringstream out;
  Scene::print_parameters(out, "prm");
  for (const char *entry : {"Analysis type",
                            "Element degree",
                            "Geometric nonlinearity",
                            "Young's modulus",
                            "Mesh file",
                            "Manufactured solution",
                            "Maximum cut-backs",
                            "Direct solver"})
    EXPECT_NE(out.str().find(entry), std::string::npos) << entry;
}

// P4.1: a name the scene does not declare gets the declared name it was
// probably meant to be, and none where no name is close.
TEST(ParameterHint, ClosestNameOrNone)
{
  dealii::ParameterHandler prm;
  prm.declare_entry("Dimension", "2");
  prm.enter_subsection("Body block");
  prm.declare_entry("Mesh", "block");
  prm.enter_subsection("Material");
  prm.declare_entry("Young's modulus", "1");
  prm.declare_entry("Poisson's ratio", "0.3");
  prm.leave_subsection();
  prm.leave_subsection();

  const std::vector<std::string> material{"Body block", "Material"};
  // Two mistakes in a long name, case ignored.
  EXPECT_EQ(parameter_hint(prm, material, "youngs modulus", false),
            " Did you mean 'Young's modulus'?");
  EXPECT_EQ(parameter_hint(prm, material, "Poissons ration", false),
            " Did you mean 'Poisson's ratio'?");
  // Three mistakes: no guess.
  EXPECT_EQ(parameter_hint(prm, material, "Yongs modulos", false), "");
  // Letters swapped count once; in a short name only one mistake.
  EXPECT_EQ(parameter_hint(prm, {"Body block"}, "Msh", false),
            " Did you mean 'Mesh'?");
  EXPECT_EQ(parameter_hint(prm, {"Body block"}, "Mxs", false), "");
  EXPECT_EQ(parameter_hint(prm, {"Body block"}, "Materail", true),
            " Did you mean 'Material'?");
  EXPECT_EQ(parameter_hint(prm, {}, "Body blok", true),
            " Did you mean 'Body block'?");
  // A body that 'Bodies' does not list: the ones it does.
  EXPECT_EQ(parameter_hint(prm, {}, "Body punch", true),
            " The scene's subsections 'Body ...' are 'Body block' (one for "
            "each name in 'Bodies'; add a name there for a new one).");
  EXPECT_EQ(parameter_hint(prm, {}, "Nowhere", true), "");
  // An entry of another subsection, exact and misspelt.
  EXPECT_EQ(parameter_hint(prm, {"Body block"}, "Young's modulus", false),
            " 'Young's modulus' is an entry of 'Body block/Material'; write "
            "it inside that subsection.");
  EXPECT_EQ(parameter_hint(prm, {}, "Youngs modulus", false),
            " Did you mean 'Young's modulus' (an entry of 'Body "
            "block/Material')? Write it inside that subsection.");
  // Nothing like it anywhere.
  EXPECT_EQ(parameter_hint(prm, material, "Density", false), "");
}

TEST(ParameterHint, SubsectionPathAtALine)
{
  const std::string text = "set A = 1\n"
                           "subsection Body block # comment\n"
                           "  subsection Material\n"
                           "    set Young's modulus = 1\n"
                           "  end\n"
                           "  # subsection Not one\n"
                           "  set Mesh = block\n"
                           "end\n";
  EXPECT_EQ(subsection_path_at(text, 1), std::vector<std::string>{});
  EXPECT_EQ(subsection_path_at(text, 4),
            (std::vector<std::string>{"Body block", "Material"}));
  EXPECT_EQ(subsection_path_at(text, 7),
            std::vector<std::string>{"Body block"});
}
