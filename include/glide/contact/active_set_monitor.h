#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <array>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace glide
{
  /// A slave node to hold (index as in Contact::status()): on master piece
  /// `piece`, or, where the formulation can, at the vertex that piece
  /// shares with `partner` (-1: none).
  struct Hold
  {
    unsigned int node    = 0;
    int          piece   = -1;
    int          partner = -1;
  };

  /**
   * The driver's record of the contact state at each Newton iteration of one
   * nonlinear solve (R16.1): how often each slave node switched between
   * open and closed, and how often its projection went back to the master
   * piece it had left (A, B, A). It lives in the load stepper, not in the
   * contact part, because the residual must not read it: the residual is a
   * function of the iterate alone, and what this records is the history of
   * one solve. Its two verdicts are used between solves only:
   * - cycling(): nodes that switched more than maximum_switches times, so
   *   that the solve is stopped early (and the step retried or cut back)
   *   instead of running into the iteration limit;
   * - holds(): nodes whose projection kept returning to a piece (a faceted
   *   master's corner, where the force direction jumps between the facets'
   *   normals), which the next attempt of the same step holds on that piece
   *   (Contact::hold()).
   */
  template <int dim>
  class ActiveSetMonitor
  {
  public:
    /// One slave node at one iterate (Contact::status()).
    struct Status
    {
      bool               closed   = false;
      int                piece    = -1;    ///< master piece, -1 where none
      bool               holdable = false; ///< a faceted master's node
      dealii::Point<dim> X;                ///< reference position, for messages
      /// The master ends inside the node's slave facets (mortar,
      /// Constraint::coverage below 1).
      bool at_master_end = false;
    };

    /// Switches between open and closed per node and solve before the
    /// solve is declared cycling (the active set of a semismooth Newton
    /// iteration settles after a few iterations; a node that changes its
    /// mind five times is going round in a circle).
    static constexpr unsigned int maximum_switches = 4;
    /// Returns to the piece before (A, B, A) after which a node is held.
    static constexpr unsigned int maximum_returns = 2;

    /// Iterates recorded since the last reset().
    unsigned int
    n_recorded() const
    {
      return recorded;
    }

    /// Forget everything: a new solve begins.
    void
    reset()
    {
      recorded = 0;
      last.clear();
      switches.clear();
      at_end.clear();
      pieces.clear();
      returns.clear();
    }

    /// Record the state of every locally owned slave node at one Newton
    /// iteration. Returns whether any of them is open where it was closed
    /// at the last iteration or the other way round (true at the first).
    bool
    record(const std::vector<Status> &status)
    {
      bool changed = false;
      ++recorded;
      if (last.size() != status.size())
        {
          last = status;
          switches.assign(status.size(), 0);
          at_end.assign(status.size(), false);
          for (unsigned int k = 0; k < status.size(); ++k)
            at_end[k] = status[k].at_master_end;
          returns.assign(status.size(), 0);
          pieces.assign(status.size(), {{-1, -1}});
          for (unsigned int k = 0; k < status.size(); ++k)
            pieces[k][1] = status[k].closed ? status[k].piece : -1;
          return true;
        }
      for (unsigned int k = 0; k < status.size(); ++k)
        {
          const auto &s = status[k];
          at_end[k]     = at_end[k] || s.at_master_end;
          if (s.closed != last[k].closed)
            {
              ++switches[k];
              changed = true;
            }
          if (s.holdable && s.closed && s.piece >= 0 && s.piece != pieces[k][1])
            {
              if (s.piece == pieces[k][0])
                ++returns[k];
              pieces[k] = {{pieces[k][1], s.piece}};
            }
          last[k] = s;
        }
      return changed;
    }

    /// The reference positions of the nodes (of every process) that
    /// switched more than maximum_switches times, as text; empty if none.
    std::string
    cycling(const MPI_Comm comm) const
    {
      std::ostringstream local;
      unsigned int       n = 0;
      for (unsigned int k = 0; k < switches.size(); ++k)
        if (switches[k] > maximum_switches && n++ < 10)
          local << (n > 1 ? ", " : "") << "(" << last[k].X << ")";
      const auto  all = dealii::Utilities::MPI::all_gather(comm, local.str());
      std::string nodes;
      for (const auto &a : all)
        if (!a.empty())
          nodes += (nodes.empty() ? "" : ", ") + a;
      return nodes;
    }

    /// Whether a node that cycling() lists had the master end inside its
    /// slave facets at any iterate (collective).
    bool
    cycling_at_master_end(const MPI_Comm comm) const
    {
      bool any = false;
      for (unsigned int k = 0; k < switches.size(); ++k)
        any = any || (switches[k] > maximum_switches && at_end[k]);
      return dealii::Utilities::MPI::max(any ? 1 : 0, comm) > 0;
    }

    /// Nodes whose projection went back to the piece it had left at least
    /// maximum_returns times, with the piece they were on last and the one
    /// they alternated with.
    std::vector<Hold>
    holds() const
    {
      std::vector<Hold> h;
      for (unsigned int k = 0; k < returns.size(); ++k)
        if (returns[k] >= maximum_returns && pieces[k][1] >= 0)
          h.push_back({k, pieces[k][1], pieces[k][0]});
      return h;
    }

  private:
    std::vector<Status>             last;
    std::vector<unsigned int>       switches;
    std::vector<bool>               at_end;
    std::vector<std::array<int, 2>> pieces;
    std::vector<unsigned int>       returns;
    unsigned int                    recorded = 0;
  };
} // namespace glide
