#include <glide/output/statistics.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <ostream>
#include <sstream>

namespace glide
{
  const char *const Statistics::file_name = "statistics.csv";

  Statistics::Statistics(OutputDirectory &output, MPI_Comm comm)
    : output(output)
    , writer(dealii::Utilities::MPI::this_mpi_process(comm) == 0)
  {}

  void
  Statistics::add_row(
    const std::vector<std::pair<std::string, std::string>> &row)
  {
    if (!writer)
      return;
    if (header.empty())
      for (const auto &[name, value] : row)
        header.push_back(name);
    AssertThrow(row.size() == header.size(), dealii::ExcInternalError());
    for (unsigned int i = 0; i < row.size(); ++i)
      rows += (i ? "," : "") + row[i].second;
    rows += '\n';
  }

  void
  Statistics::write()
  {
    if (!writer || header.empty())
      return;
    output.write_index(file_name, [&](std::ostream &out) {
      for (unsigned int i = 0; i < header.size(); ++i)
        out << (i ? "," : "") << header[i];
      out << '\n' << rows;
    });
  }

  std::string
  format_number(const double value)
  {
    std::ostringstream s;
    s.precision(12);
    s << value;
    return s.str();
  }
} // namespace glide
