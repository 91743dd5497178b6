#pragma once

#include <glide/output/output_directory.h>

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

namespace glide
{
  /**
   * The per-step statistics table (P5): one CSV row per converged load
   * step. add_row() keeps the row; write() writes the whole table as an
   * index of OutputDirectory::commit_step() (under a temporary name, checked,
   * renamed together with the `.pvd` files), so the table under its final
   * name is always complete and lists the same steps as the `.pvd` files.
   * Tests and studies read this table, never the VTU files. Only process 0
   * writes.
   */
  class Statistics
  {
  public:
    Statistics(OutputDirectory &output, MPI_Comm comm);

    /// Add one row; the columns of the first row fix the header.
    void
    add_row(const std::vector<std::pair<std::string, std::string>> &row);

    /// Process 0, inside commit_step(): write the table as an index.
    void
    write();

    /// The table's file name.
    static const char *const file_name;

  private:
    OutputDirectory         &output;
    bool                     writer;
    std::vector<std::string> header;
    std::string              rows;
  };

  /// Format a number for the table with full precision.
  std::string
  format_number(const double value);
} // namespace glide
