#pragma once

#include <mpi.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace glide
{
  /**
   * The per-step statistics table (P5): one CSV row per converged load
   * step, written and flushed as soon as the step is done, so a run that is
   * stopped part-way leaves complete rows. Tests and studies read this
   * table, never the VTU files. Only rank 0 writes.
   */
  class Statistics
  {
  public:
    Statistics(const std::string &filename, MPI_Comm comm);

    /// Add one row; the columns of the first row fix the header.
    void
    add_row(const std::vector<std::pair<std::string, std::string>> &row);

  private:
    std::string              filename;
    bool                     writer;
    std::vector<std::string> header;
    std::ofstream            out;
  };

  /// Format a number for the table with full precision.
  std::string
  format_number(const double value);
} // namespace glide
