#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace glide
{
  /// The contact fields of one slave node at a converged step (R3.3,
  /// R12.1, R13.1).
  template <int dim>
  struct ContactNodeFields
  {
    dealii::Point<dim>                          X; ///< reference position
    dealii::Point<dim>                          x; ///< current position
    double                                      COPEN   = 0.;
    double                                      force   = 0.;
    double                                      CPRESS  = 0.;
    double                                      CSTATUS = 0.;
    double                                      CSLIP   = 0.;
    dealii::Tensor<1, dim>                      normal;
    std::array<dealii::Tensor<1, dim>, dim - 1> tangents;
    std::array<double, dim - 1>                 CSLIP_components{};
  };

  /// The slave nodes of one contact pair (on the first process: all
  /// processes' nodes; elsewhere empty).
  template <int dim>
  struct ContactPairFields
  {
    std::string                         pair;
    std::vector<ContactNodeFields<dim>> nodes;
  };

  /**
   * Writes the contact output of every pair, on the first process: per
   * step a CSV file `contact-<pair>-NNNN.csv` (one row per slave node) and,
   * if asked, a VTU point set `contact-<pair>-NNNN.vtu` with the same
   * fields, the contact normal, the tangents and the displacement, listed
   * in `contact-<pair>.pvd` for ParaView. Every file is written under a
   * temporary name and renamed when complete; Problem writes into the
   * output's staging directory, which OutputDirectory checks and moves
   * into place with the step's indexes (doc/output-and-faults.md).
   */
  template <int dim>
  class ContactWriter
  {
  public:
    explicit ContactWriter(const std::string &directory);

    /// Write step @p step at load factor @p time. Returns what failed
    /// (empty if nothing): the caller turns it into an OutputError on every
    /// process, so that no process waits for one that failed alone.
    std::string
    write(const std::vector<ContactPairFields<dim>> &pairs,
          const unsigned int                         step,
          const double                               time,
          const bool                                 vtu);

  private:
    std::string directory;
    /// Written steps per pair, for the .pvd files.
    std::map<std::string, std::vector<std::pair<double, std::string>>> records;
  };
} // namespace glide
