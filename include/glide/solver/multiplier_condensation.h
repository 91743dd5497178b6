#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace glide
{
  /**
   * Elimination of the multipliers of hard contact from the Newton system
   * (issue 14, doc/theory/mortar.md, "Condensation"), so that GMRES with
   * algebraic multigrid can solve it. It applies where the contact force
   * of each multiplier acts on one slave node alone (the dual mortar basis
   * and node to surface): the node's rows S_j of the Jacobian
   *
   *   [ A  B ] [du]   [f]
   *   [ C  E ] [dl] = [h]
   *
   * hold the multiplier j and no other, with the column b_j = B(S_j, j)
   * (the force direction on the node). Then
   *  - an open multiplier (E_jj = 1, C_j = 0) is known: dl_j = h_j / E_jj;
   *  - a compliant one (E_jj != 0 and C_j != 0: penalty contact, solved as
   *    a perturbed Lagrangian) is dl_j = (h_j - C_j du) / E_jj; in every
   *    row i that holds it this adds -B_ij C_j / E_jj, the penalty
   *    stiffness;
   *  - a closed one (E_jj = 0) follows from the node's rows projected on
   *    b_j: dl_j = b_j^T (f_S - A_S du) / |b_j|^2. Put into every other
   *    row i that holds it (the master nodes the force reaches), this adds
   *    -B_ij b_j^T A_S / |b_j|^2; the node's own rows become its tangential
   *    rows t_k^T A_S and, in the normal direction, the constraint row C_j.
   * The closed node's displacements are written in its frame [n t_1 t_2]
   * (n = b_j / |b_j|), so that the constraint row has c dg/du_n, a
   * positive entry of the size of the stiffness, on its diagonal and the
   * tangential block stays t^T A t. The result is a displacement-only
   * matrix with the sparsity of the bulk plus the master-slave fill, which
   * ML's smoothed aggregation handles with the rigid-body modes rotated
   * into the same frames. After the solve, du is rotated back and dl
   * recovered from the rows above.
   *
   * Under MPI (issue 15) each process condenses its own rows. Every
   * process holds the list of all blocks and, at each condense(), the
   * state of every block (closed, b_j, frame, scale: O(slave nodes) per
   * process, like the gathered master surface); the fill of a master row
   * needs the rows of the slave nodes it is coupled to, which are imported
   * from their owners (Epetra_Import) when they are on another process.
   * A slave node's DoFs and its multiplier must be owned by one process.
   *
   * A hanging slave node (a refined slave surface: its DoFs are
   * constrained to its parents', and its rows of J are empty) passes its
   * force to its parents' rows. While it is open its multiplier is known,
   * and its entries in the parents' rows go to the right-hand side; once
   * it is closed the node-by-node elimination does not apply and
   * condense() throws NotCondensable (LinearSolver then takes the direct
   * solver for that Jacobian).
   */
  class MultiplierCondensation
  {
  public:
    /// The Jacobian given to condense() cannot be condensed (a closed
    /// slave node has no rows of its own: a hanging node, or a node whose
    /// displacements are all prescribed); thrown on every process.
    class NotCondensable : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    /// One multiplier and the DoFs of its slave node.
    struct Block
    {
      dealii::types::global_dof_index              multiplier;
      std::vector<dealii::types::global_dof_index> dofs;
    };

    /// @p blocks: this process's multipliers (numbered from
    /// @p n_displacements on, contiguously over the processes in rank
    /// order) with their slave nodes' DoFs, which no other block shares.
    /// Collective.
    MultiplierCondensation(
      std::vector<Block>                    blocks,
      const dealii::types::global_dof_index n_displacements,
      const dealii::IndexSet               &owned,
      MPI_Comm                              comm);

    ~MultiplierCondensation();

    /// Build the condensed matrix of the full Jacobian @p J (its closed
    /// multipliers are those with a zero diagonal entry), and keep what
    /// condense_rhs() and expand() need of J: J may be released after.
    /// Collective; an error on one process is thrown on every process.
    void
    condense(const dealii::TrilinosWrappers::SparseMatrix &J);

    /// The condensed matrix (displacement DoFs, closed nodes rotated).
    const Epetra_CrsMatrix &
    matrix() const
    {
      return *condensed;
    }

    /// The rigid-body modes @p modes (full vectors) on the condensed
    /// system, rotated like the unknowns.
    std::unique_ptr<Epetra_MultiVector>
    rotated_modes(
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &modes) const;

    /// The right-hand side of the condensed system for the full one @p b.
    void
    condense_rhs(const dealii::TrilinosWrappers::MPI::Vector &b,
                 dealii::TrilinosWrappers::MPI::Vector &condensed_b) const;

    /// The full solution @p x from the condensed one @p condensed_x and the
    /// full right-hand side @p b.
    void
    expand(const dealii::TrilinosWrappers::MPI::Vector &b,
           const dealii::TrilinosWrappers::MPI::Vector &condensed_x,
           dealii::TrilinosWrappers::MPI::Vector       &x) const;

    /// The owned displacement DoFs (the condensed system's rows).
    const dealii::IndexSet &
    displacements() const
    {
      return owned_displacements;
    }

    /// Closed multipliers at the last condense(), on all processes
    /// (collective).
    unsigned int
    n_closed() const;

  private:
    /// A block at the current Jacobian.
    struct State
    {
      bool closed = false;
      /// Not closed, with displacement entries C_j in its row (penalty, a
      /// perturbed Lagrangian: E_jj = c / k): dl_j = (h_j - C_j du) / E_jj.
      bool                compliant     = false;
      double              open_diagonal = 1.; ///< E_jj of an open multiplier
      std::vector<double> b;                  ///< B(S_j, j)
      double              b_norm2 = 0.;
      /// Frame: column 0 the normal n, then the tangents (frame[l][k]: row
      /// l = DoF of the node, column k = direction).
      std::vector<std::vector<double>> frame;
      /// Factor of the constraint row: its diagonal becomes the node's
      /// normal stiffness n^T A_SS n (see condense()).
      double scale = 1.;
      /// For each DoF l of the node, the multipliers of other slave nodes
      /// (hanging nodes constrained to this one) in its row, as (block,
      /// entry); shared with the other processes for closed blocks.
      std::vector<std::vector<std::pair<unsigned int, double>>> foreign;
    };

    /// The local view of row @p row of J, or of the rows imported from
    /// other processes: @p n entries, @p values, local column indices
    /// @p idx into @p columns.
    void
    row_view(const dealii::types::global_dof_index row,
             int                                  &n,
             double                              *&values,
             int                                 *&idx,
             const Epetra_BlockMap               *&columns) const;

    /// B_Sh dl_h in row @p l of (closed or own) block @p j: the force of the
    /// open hanging nodes constrained to its node, their multipliers known
    /// from the right-hand side @p b (ghosted at them under MPI).
    double
    foreign_force(const unsigned int                           j,
                  const unsigned int                           l,
                  const dealii::TrilinosWrappers::MPI::Vector &b) const;

    /// The state of block @p j (this process's) from the rows of J.
    void
    compute_state(const unsigned int j);

    /// Every process's states to every process.
    void
    share_states();

    /// The rows of other processes' closed slave nodes whose multipliers
    /// reach this process's rows, into @p remote.
    void
    import_rows();

    /// The entries of row @p row of J (global column indices).
    void
    row_of_j(const dealii::types::global_dof_index         row,
             int                                          &n,
             double                                      *&values,
             std::vector<dealii::types::global_dof_index> &columns) const;

    /// Call add(column, value) for the entries of condensed row @p row
    /// (unrotated columns: add() rotates them); repeated columns possible.
    template <typename Add>
    void
    condensed_row(const dealii::types::global_dof_index row, Add &&add) const;

    std::vector<Block>                    blocks;
    const dealii::types::global_dof_index n_u;
    const dealii::IndexSet                owned;
    dealii::IndexSet                      owned_displacements;
    MPI_Comm                              comm;
    const bool                            parallel;
    /// Every process's blocks; this process's are [first_own, end_own).
    unsigned int first_own = 0, end_own = 0;
    /// Under MPI, during condense(): rows of other processes' slave nodes.
    std::unique_ptr<Epetra_CrsMatrix> remote;
    /// Under MPI: the entries of other processes that condense_rhs() reads
    /// of the right-hand side and expand() of the condensed solution.
    dealii::IndexSet                              rhs_ghosts, solution_ghosts;
    const dealii::TrilinosWrappers::SparseMatrix *J = nullptr;
    std::vector<State>                            states;
    /// For each displacement DoF: its block (-1: none) and its component.
    std::vector<int>           block_of;
    std::vector<unsigned char> component_of;
    /// A multiplier entry of a row that is not a closed node's.
    struct Coupling
    {
      dealii::types::global_dof_index row;
      unsigned int                    block;
      double                          value;
    };
    std::vector<Coupling> couplings;
    /// Compliant blocks of this process: the displacement entries of the
    /// multiplier's row (C_j).
    std::vector<std::vector<std::pair<dealii::types::global_dof_index, double>>>
      compliant_rows;
    /// Closed blocks: the displacement entries of each of the node's rows.
    std::vector<std::vector<
      std::vector<std::pair<dealii::types::global_dof_index, double>>>>
                                      closed_rows;
    std::unique_ptr<Epetra_Map>       map;
    std::unique_ptr<Epetra_CrsMatrix> condensed;
  };
} // namespace glide
