// GoogleTest main for glide's unit tests: MPI (needed by Trilinos, p4est
// and KINSOL) is initialized once for all tests.
#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

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
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
