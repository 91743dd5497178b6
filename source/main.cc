// glide: finite-element contact between elastic bodies. This is the
// program: it reads a scene (.prm), dispatches on its dimension once, and
// turns every error into one message and a non-zero exit status.

#include <glide/output/interruption.h>
#include <glide/output/output_error.h>
#include <glide/problem.h>
#include <glide/revision.h> // generated at build time (cmake/version.cmake)
#include <glide/scene/input_error.h>
#include <glide/scene/scene.h>

#include <deal.II/base/config.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <Trilinos_version.h>
#include <p4est_config.h>
#include <sundials/sundials_config.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <vector>

namespace
{
  const char *usage =
    "Usage: glide [options] SCENE.prm\n"
    "\n"
    "Runs the scene and writes VTU/PVD files and statistics.csv to\n"
    "<Output/Directory>/<Scene name>/ (default output/<scene file name>/).\n"
    "\n"
    "Options:\n"
    "  --help                     print this help and exit\n"
    "  --version                  print glide's source revision and the\n"
    "                             versions of the libraries it runs on\n"
    "  --print-parameters [FMT]   print every scene parameter with default,\n"
    "                             pattern and documentation; FMT is prm\n"
    "                             (default), json or xml\n"
    "  --check                    read the scene, build the mesh and the\n"
    "                             contact pairs and run the input checks\n"
    "                             (not those of the output directory),\n"
    "                             print the summary and the warnings, then\n"
    "                             stop (nothing is solved or written)\n"
    "  --set \"Path/Entry=value\"   override a scene parameter after reading\n"
    "                             the file, e.g. --set \"Body block/Refinement/\n"
    "                             Global refinements=3\" (repeatable)\n"
    "\n"
    "Exit status: 0 success, 1 input error, 2 a load step failed, 3 internal\n"
    "error, 4 input/output error (output directory, full disk, closed\n"
    "standard output, file size limit), 128+N stopped by signal N (SIGTERM:\n"
    "143, SIGINT: 130; also SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGXCPU and\n"
    "SIGALRM) after the last complete load step. Run in parallel with\n"
    "mpirun -np N glide SCENE.prm.\n";

  /// What a bug report needs: glide's revision (git describe of the tree
  /// it was built from; "-dirty" with uncommitted changes) and the
  /// libraries, as compiled against and, for MPI, as loaded.
  void
  print_version(std::ostream &out)
  {
    char library[MPI_MAX_LIBRARY_VERSION_STRING] = "";
    int  length                                  = 0;
    MPI_Get_library_version(library, &length);
    std::string mpi(library, library + length);
    mpi = mpi.substr(0, mpi.find_first_of(",\n"));
    out << "glide " << GLIDE_REVISION << "\n"
        << "  deal.II " << DEAL_II_PACKAGE_VERSION << ", Trilinos "
        << TRILINOS_VERSION_STRING << ", SUNDIALS " << SUNDIALS_VERSION
        << ", p4est " << P4EST_VERSION << ", " << mpi << "\n";
  }

  /// Standard output must have taken everything (a closed or full
  /// standard output is an input/output error, not a crash).
  void
  check_standard_output(const std::string &what)
  {
    std::cout.flush();
    if (!std::cout)
      throw glide::OutputError(
        "Cannot write " + what +
        " to standard output (it is closed or the disk is full); "
        "redirect it to a file you may write, e.g. 'glide "
        "--print-parameters > parameters.prm'.");
  }
} // namespace

#ifdef GLIDE_SANITIZE
// Open MPI keeps memory until the process exits; LeakSanitizer would report
// it as leaks and fail every run. Address and UB checks stay on.
extern "C" const char *
__asan_default_options()
{
  return "detect_leaks=0";
}
#endif

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                           comm = MPI_COMM_WORLD;
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;

  // The interrupt handlers (stop between load steps, keep the complete
  // ones) are installed by Problem::run() when the load steps begin: until
  // then SIGTERM and SIGINT end glide at once, also in the middle of
  // reading a mesh (a FIFO, a slow file system) or building a large one,
  // where a flag that nobody checks kept it running.
  // A file that reaches the file size limit (ulimit -f): a failed write
  // (EFBIG), which the output reports as an input/output error, instead of
  // SIGXFSZ, whose default action ended glide in the middle of a file.
  std::signal(SIGXFSZ, SIG_IGN);
  try
    {
      std::vector<std::string> args(argv + 1, argv + argc), overrides;
      std::string              scene_file;
      bool                     check_only = false;
      for (unsigned int i = 0; i < args.size(); ++i)
        {
          const std::string &a = args[i];
          if (a == "--help" || a == "-h")
            {
              if (root)
                {
                  std::cout << usage;
                  check_standard_output("the help");
                }
              return 0;
            }
          if (a == "--version")
            {
              if (root)
                {
                  print_version(std::cout);
                  check_standard_output("the version");
                }
              return 0;
            }
          if (a == "--print-parameters")
            {
              std::string format = "prm";
              if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0)
                format = args[++i];
              glide::require(
                format == "prm" || format == "json" || format == "xml",
                "--print-parameters takes prm, json or xml, not '" + format +
                  "'.");
              if (root)
                {
                  try
                    {
                      glide::Scene::print_parameters(std::cout, format);
                    }
                  catch (const std::exception &)
                    {
                      // ParameterHandler's ExcIO, boost's JSON or XML
                      // writer: the stream failed.
                      std::cout.setstate(std::ios::badbit);
                    }
                  check_standard_output("the parameters");
                }
              return 0;
            }
          if (a == "--check")
            {
              check_only = true;
              continue;
            }
          if (a == "--set")
            {
              glide::require(i + 1 < args.size(),
                             "--set needs an argument \"Path/Entry=value\".");
              overrides.push_back(args[++i]);
              continue;
            }
          glide::require(a.rfind("--", 0) != 0,
                         "Unknown option '" + a + "'; see 'glide --help'.");
          glide::require(scene_file.empty(),
                         "More than one scene file given ('" + scene_file +
                           "' and '" + a +
                           "'); glide runs one scene at a time.");
          scene_file = a;
        }
      glide::require(!scene_file.empty(),
                     std::string("No scene file given.\n") + usage);

      const glide::Scene scene = glide::Scene::read(scene_file, overrides);
      if (scene.dimension == 2)
        glide::run_scene<2>(scene, comm, check_only);
      else
        glide::run_scene<3>(scene, comm, check_only);
    }
  catch (const glide::InputError &e)
    {
      if (root)
        std::cerr << "glide: input error: " << e.what() << std::endl;
      return 1;
    }
  catch (const glide::OutputError &e)
    {
      if (root)
        std::cerr << "glide: input/output error: " << e.what() << std::endl;
      return 4;
    }
  catch (const std::filesystem::filesystem_error &e)
    {
      if (root)
        std::cerr << "glide: input/output error: " << e.what() << std::endl;
      return 4;
    }
  catch (const glide::Interrupted &e)
    {
      if (root)
        std::cerr << "glide: " << e.what()
                  << "; every load step in statistics.csv and the .pvd "
                     "files is complete."
                  << std::endl;
      return 128 + e.signal_number;
    }
  catch (const std::bad_alloc &)
    {
      if (root)
        std::cerr << "glide: input error: out of memory: the scene is too "
                     "large for this machine; lower 'Subdivisions', "
                     "'Global refinements' or 'Local refinements', or run "
                     "on more machines with MPI."
                  << std::endl;
      return 1;
    }
  catch (const dealii::ExceptionBase &e)
    {
      if (root)
        std::cerr << "glide: internal error: " << e.what() << std::endl;
      return 3;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "glide: error: " << e.what() << std::endl;
      return 2;
    }
  return 0;
}
