#include <glide/base/collective_failure.h>

#include <deal.II/base/mpi.h>

namespace glide
{
  std::string
  first_failure_on_any_process(const std::string &failure, MPI_Comm comm)
  {
    using namespace dealii::Utilities::MPI;
    if (max(failure.empty() ? 0 : 1, comm) == 0)
      return {};
    std::string message;
    for (const auto &m : gather(comm, failure, 0))
      if (message.empty() && !m.empty())
        message = m;
    return broadcast(comm, message, 0);
  }
} // namespace glide
