#include <glide/output/output_parameters.h>
#include <glide/scene/input_error.h>

#include <cstdlib>
#include <string>

namespace glide
{
  using namespace dealii;

  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Directory",
                      "output",
                      Patterns::DirectoryName(),
                      "Results go to <Directory>/<Scene name>/: "
                      "<name>-NNNN.vtu per output step, <name>.pvd, "
                      "statistics.csv. Relative to the current directory; "
                      "a leading '~' is the home directory ($HOME), as in a "
                      "shell. "
                      "glide lists the files it writes there in "
                      ".glide-output and never deletes or overwrites any "
                      "other file.");
    prm.declare_entry("Write VTU",
                      "true",
                      Patterns::Bool(),
                      "false: write no VTU or PVD files, only the tables "
                      "(statistics.csv, timings.csv and the contact "
                      "pairs' CSV files; studies).");
    prm.declare_entry("Every n steps",
                      "1",
                      Patterns::Integer(1),
                      "Write the bodies' and the contact pairs' VTU files "
                      "every n-th converged load step (the last step is "
                      "always written; a run that fails writes the bodies' "
                      "VTU of its last converged step); the statistics and "
                      "the contact CSV files get every step.");
    prm.leave_subsection();
  }

  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory = prm.get("Directory");
    // '~' as a shell expands it: until 2026-12-06 '~/results' made a
    // directory named '~' in the current directory.
    if (directory == "~" || directory.rfind("~/", 0) == 0)
      {
        const char *home = std::getenv("HOME");
        require(home != nullptr && *home != '\0',
                "Parameter 'Output/Directory' = '" + directory +
                  "' starts with '~', but HOME is not set; give the path "
                  "without '~'.");
        directory = std::string(home) + directory.substr(1);
      }
    write_vtu = prm.get_bool("Write VTU");
    every     = prm.get_integer("Every n steps");
    prm.leave_subsection();
  }
} // namespace glide
