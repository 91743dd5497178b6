#include <glide/output/statistics.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <sstream>

namespace glide
{
  Statistics::Statistics(const std::string &filename, MPI_Comm comm)
    : filename(filename)
    , writer(dealii::Utilities::MPI::this_mpi_process(comm) == 0)
  {}

  void
  Statistics::add_row(
    const std::vector<std::pair<std::string, std::string>> &row)
  {
    if (!writer)
      return;
    if (header.empty())
      {
        out.open(filename);
        if (!out)
          throw std::runtime_error("cannot write the statistics table '" +
                                   filename + "'");
        for (const auto &[name, value] : row)
          header.push_back(name);
        for (unsigned int i = 0; i < header.size(); ++i)
          out << (i ? "," : "") << header[i];
        out << '\n';
      }
    AssertThrow(row.size() == header.size(), dealii::ExcInternalError());
    for (unsigned int i = 0; i < row.size(); ++i)
      out << (i ? "," : "") << row[i].second;
    out << '\n';
    out.flush();
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
