// Unit tests of the elimination of hard-contact multipliers
// (MultiplierCondensation, issue 14): on small saddle-point systems with the
// structure of mortar and node-to-surface contact (each multiplier's force on
// its own slave node, shares of it on master nodes; closed multipliers with
// a constraint row c dg/du, open ones with a unit diagonal), the solution
// through the condensed displacement system must equal the solution of the
// whole system by Gauss elimination. Why that is right: the condensation is
// an exact block elimination plus an orthogonal change of variables, so
// both solutions agree to round-off for any right-hand side. The matrices
// are random (seeded), with a symmetric positive definite stiffness block.
#include <glide/solver/multiplier_condensation.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
  using namespace dealii;
  using glide::MultiplierCondensation;

  /// A saddle-point system of @p dim-dimensional nodes: nodes 0 .. n_s - 1
  /// are slave nodes with one multiplier each, the next three nodes are
  /// master nodes reached by every multiplier, the rest are other nodes.
  /// @p closed says which multipliers are closed; @p constrained_axis (if
  /// < dim) gives every slave force a zero component along that axis (a
  /// symmetry plane).
  struct System
  {
    unsigned int                               dim, n_u, n;
    FullMatrix<double>                         J;
    Vector<double>                             b;
    std::vector<MultiplierCondensation::Block> blocks;
  };

  System
  make_system(const unsigned int       dim,
              const std::vector<bool> &closed,
              const unsigned int       constrained_axis,
              const unsigned int       seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-1., 1.);
    const unsigned int n_s = closed.size(), n_nodes = n_s + 6;
    System             s;
    s.dim = dim;
    s.n_u = dim * n_nodes;
    s.n   = s.n_u + n_s;
    s.J.reinit(s.n, s.n);
    s.b.reinit(s.n);
    // A = R R^T + n I: symmetric positive definite.
    FullMatrix<double> R(s.n_u, s.n_u);
    for (unsigned int i = 0; i < s.n_u; ++i)
      for (unsigned int j = 0; j < s.n_u; ++j)
        R(i, j) = u(rng);
    for (unsigned int i = 0; i < s.n_u; ++i)
      for (unsigned int j = 0; j < s.n_u; ++j)
        {
          double v = (i == j) ? s.n_u : 0.;
          for (unsigned int k = 0; k < s.n_u; ++k)
            v += R(i, k) * R(j, k);
          s.J(i, j) = v;
        }
    for (unsigned int j = 0; j < n_s; ++j)
      {
        const unsigned int  m = s.n_u + j;
        std::vector<double> normal(dim);
        double              norm = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            normal[d] =
              (d == constrained_axis) ? 0. : u(rng) + (d == 1 ? 2. : 0.);
            norm += normal[d] * normal[d];
          }
        MultiplierCondensation::Block block{m, {}};
        for (unsigned int d = 0; d < dim; ++d)
          {
            normal[d] /= std::sqrt(norm);
            block.dofs.push_back(dim * j + d);
            s.J(dim * j + d, m) = normal[d];
          }
        s.blocks.push_back(block);
        // Shares of the force on the three master nodes.
        for (unsigned int a = 0; a < 3; ++a)
          {
            const double w = 0.2 + 0.3 * std::abs(u(rng));
            for (unsigned int d = 0; d < dim; ++d)
              s.J(dim * (n_s + a) + d, m) = -w * normal[d];
          }
        if (closed[j])
          {
            // c dg/du: about -c n on the node, c w n on the master nodes,
            // and small entries elsewhere (normal derivatives).
            const double c = 10. * s.n_u;
            for (unsigned int i = 0; i < s.n_u; ++i)
              s.J(m, i) = 0.05 * c * u(rng);
            for (unsigned int d = 0; d < dim; ++d)
              {
                s.J(m, dim * j + d) = -c * normal[d];
                for (unsigned int a = 0; a < 3; ++a)
                  s.J(m, dim * (n_s + a) + d) = c * 0.3 * normal[d];
              }
          }
        else
          s.J(m, m) = 1. + std::abs(u(rng));
      }
    for (unsigned int i = 0; i < s.n; ++i)
      s.b(i) = u(rng);
    return s;
  }

  /// Make slave node @p h of @p s a hanging node, u_h = (u_0 + u_1) / 2, as
  /// deal.II's AffineConstraints leave the Newton system of a refined slave
  /// surface: J = C^T J C and b = C^T b with C the constraint's map, so
  /// that the node's rows and columns are empty but for a diagonal entry,
  /// and its multiplier's force and constraint act on nodes 0 and 1.
  void
  make_hanging(System &s, const unsigned int h)
  {
    const unsigned int dim = s.dim;
    FullMatrix<double> C(s.n, s.n);
    for (unsigned int i = 0; i < s.n; ++i)
      C(i, i) = 1.;
    for (unsigned int d = 0; d < dim; ++d)
      {
        C(dim * h + d, dim * h + d) = 0.;
        C(dim * h + d, d)           = 0.5;
        C(dim * h + d, dim + d)     = 0.5;
      }
    FullMatrix<double> JC(s.n, s.n), CtJC(s.n, s.n);
    s.J.mmult(JC, C);
    C.Tmmult(CtJC, JC);
    for (unsigned int d = 0; d < dim; ++d)
      CtJC(dim * h + d, dim * h + d) = s.J(d, d);
    s.J = CtJC;
    Vector<double> b(s.n);
    C.Tvmult(b, s.b);
    s.b = b;
  }

  /// The Trilinos matrix of the dense @p A (entries that are zero left out).
  void
  to_trilinos(const FullMatrix<double> &A, TrilinosWrappers::SparseMatrix &T)
  {
    DynamicSparsityPattern dsp(A.m(), A.n());
    for (unsigned int i = 0; i < A.m(); ++i)
      for (unsigned int j = 0; j < A.n(); ++j)
        if (A(i, j) != 0. || i == j)
          dsp.add(i, j);
    T.reinit(complete_index_set(A.m()),
             complete_index_set(A.n()),
             dsp,
             MPI_COMM_WORLD);
    for (unsigned int i = 0; i < A.m(); ++i)
      for (unsigned int j = 0; j < A.n(); ++j)
        if (A(i, j) != 0. || i == j)
          T.set(i, j, A(i, j));
    T.compress(VectorOperation::insert);
  }

  /// Solve through the condensation and compare with Gauss elimination.
  void
  check(const System &s)
  {
    TrilinosWrappers::SparseMatrix J;
    to_trilinos(s.J, J);
    MultiplierCondensation condensation(s.blocks,
                                        s.n_u,
                                        complete_index_set(s.n),
                                        MPI_COMM_WORLD);
    condensation.condense(J);
    unsigned int n_closed = 0;
    for (const auto &block : s.blocks)
      n_closed += s.J(block.multiplier, block.multiplier) == 0. ? 1 : 0;
    EXPECT_EQ(condensation.n_closed(), n_closed);

    // The condensed matrix as a dense one.
    const Epetra_CrsMatrix &C = condensation.matrix();
    ASSERT_EQ(C.NumGlobalRows(), static_cast<int>(s.n_u));
    FullMatrix<double> Cd(s.n_u, s.n_u);
    for (int i = 0; i < C.NumMyRows(); ++i)
      {
        int     n      = 0;
        double *values = nullptr;
        int    *idx    = nullptr;
        C.ExtractMyRowView(i, n, values, idx);
        for (int e = 0; e < n; ++e)
          Cd(C.RowMap().GID(i), C.ColMap().GID(idx[e])) = values[e];
      }
    // The normal row of a closed node is its constraint, scaled so that
    // its diagonal is the node's normal stiffness n^T A_SS n (n = b_j /
    // |b_j|), whatever the constraint's own scale c.
    for (const auto &block : s.blocks)
      if (s.J(block.multiplier, block.multiplier) == 0.)
        {
          std::vector<double> normal;
          double              norm = 0.;
          for (const auto d : block.dofs)
            {
              normal.push_back(s.J(d, block.multiplier));
              norm += normal.back() * normal.back();
            }
          double stiffness = 0.;
          for (unsigned int l = 0; l < block.dofs.size(); ++l)
            for (unsigned int k = 0; k < block.dofs.size(); ++k)
              stiffness += normal[l] * s.J(block.dofs[l], block.dofs[k]) *
                           normal[k] / norm;
          ASSERT_GT(stiffness, 0.);
          EXPECT_NEAR(Cd(block.dofs[0], block.dofs[0]),
                      stiffness,
                      1e-12 * stiffness);
        }

    TrilinosWrappers::MPI::Vector b(complete_index_set(s.n), MPI_COMM_WORLD);
    for (unsigned int i = 0; i < s.n; ++i)
      b(i) = s.b(i);
    b.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector cb;
    condensation.condense_rhs(b, cb);
    Vector<double> cbd(s.n_u), cxd(s.n_u);
    for (unsigned int i = 0; i < s.n_u; ++i)
      cbd(i) = cb(i);
    FullMatrix<double> Cinv(s.n_u, s.n_u);
    Cinv.invert(Cd);
    Cinv.vmult(cxd, cbd);
    TrilinosWrappers::MPI::Vector cx(cb), x(b);
    for (unsigned int i = 0; i < s.n_u; ++i)
      cx(i) = cxd(i);
    cx.compress(VectorOperation::insert);
    condensation.expand(b, cx, x);

    FullMatrix<double> Jinv(s.n, s.n);
    Jinv.invert(s.J);
    Vector<double> reference(s.n);
    Jinv.vmult(reference, s.b);
    const double scale = reference.linfty_norm();
    for (unsigned int i = 0; i < s.n; ++i)
      EXPECT_NEAR(x(i), reference(i), 1e-10 * scale) << "unknown " << i;

    // The rigid-body modes are rotated like the unknowns: the rotated
    // reference solution solves the condensed system.
    TrilinosWrappers::MPI::Vector r(b);
    for (unsigned int i = 0; i < s.n; ++i)
      r(i) = reference(i);
    r.compress(VectorOperation::insert);
    const auto     rotated = condensation.rotated_modes({r});
    Vector<double> xr(s.n_u), residual(s.n_u);
    for (unsigned int i = 0; i < s.n_u; ++i)
      xr(i) = (*rotated)[0][i];
    Cd.vmult(residual, xr);
    residual -= cbd;
    EXPECT_LT(residual.linfty_norm(), 1e-10 * Cd.linfty_norm() * scale);
  }
} // namespace

TEST(MultiplierCondensation, MatchesTheWholeSystem2D)
{
  check(make_system(2, {true, false, true, true}, 2, 1));
}

TEST(MultiplierCondensation, MatchesTheWholeSystem3D)
{
  check(make_system(3, {true, true, false, true, false}, 3, 2));
}

TEST(MultiplierCondensation, ForcesWithAZeroComponent3D)
{
  // Slave forces with no x (z) component, as on a symmetry plane x = 0
  // whose DoF is constrained: the frame takes that axis as a tangent (its
  // own branch of the frame's construction).
  check(make_system(3, {true, true, true}, 0, 3));
  check(make_system(3, {true, false, true}, 2, 4));
}

TEST(MultiplierCondensation, AllOpen)
{
  check(make_system(2, {false, false}, 2, 5));
  check(make_system(3, {false, false, false}, 3, 6));
}

// A hanging slave node (a refined slave surface) passes its multiplier's
// force to its parents' rows, and its own rows are empty. Open, its
// multiplier is known and goes to the right-hand side of those rows, closed
// or open (without that, the solution differs from Gauss elimination).
// Closed, the node-by-node elimination does not apply: NotCondensable, so
// that the linear solver can take the direct solver for that Jacobian.
TEST(MultiplierCondensation, OpenHangingSlaveNode)
{
  for (const unsigned int dim : {2u, 3u})
    for (const bool parents_closed : {true, false})
      {
        System s = make_system(dim,
                               {parents_closed, parents_closed, false, true},
                               dim,
                               8 + dim);
        make_hanging(s, 2);
        check(s);
      }
}

TEST(MultiplierCondensation, ClosedHangingSlaveNodeIsNotCondensable)
{
  System s = make_system(3, {true, true, true, false}, 3, 12);
  make_hanging(s, 2);
  TrilinosWrappers::SparseMatrix J;
  to_trilinos(s.J, J);
  MultiplierCondensation condensation(s.blocks,
                                      s.n_u,
                                      complete_index_set(s.n),
                                      MPI_COMM_WORLD);
  EXPECT_THROW(condensation.condense(J),
               MultiplierCondensation::NotCondensable);
  // The same system with the node open again is condensed.
  s.J(s.blocks[2].multiplier, s.blocks[2].multiplier) = 1.;
  for (unsigned int i = 0; i < s.n_u; ++i)
    s.J(s.blocks[2].multiplier, i) = 0.;
  check(s);
}

// The caller's numbering is checked (on every process at once under MPI):
// multipliers out of the blocks' order, a DoF in two blocks.
TEST(MultiplierCondensation, RejectsInconsistentBlocks)
{
  const System s       = make_system(2, {true, false}, 2, 7);
  auto         swapped = s.blocks;
  std::swap(swapped[0].multiplier, swapped[1].multiplier);
  EXPECT_THROW(MultiplierCondensation(
                 swapped, s.n_u, complete_index_set(s.n), MPI_COMM_WORLD),
               std::logic_error);
  auto shared       = s.blocks;
  shared[1].dofs[0] = shared[0].dofs[0];
  EXPECT_THROW(MultiplierCondensation(
                 shared, s.n_u, complete_index_set(s.n), MPI_COMM_WORLD),
               std::logic_error);
  EXPECT_NO_THROW(MultiplierCondensation(
    s.blocks, s.n_u, complete_index_set(s.n), MPI_COMM_WORLD));
}

// Penalty contact is solved as a perturbed Lagrangian: a closed penalty
// multiplier's row holds c dg/du and the diagonal c / k, so it follows from
// the displacements, dl_j = (h_j - C_j du) / E_jj, whatever rows its force
// acts on (surface to surface spreads it over several nodes; Contact gives
// such blocks no node of their own). Mixed with closed and open hard
// multipliers, the solution through the condensed system must equal Gauss
// elimination of the whole system; without the compliant fill -B C / E it
// does not (the penalty stiffness would be missing).
TEST(MultiplierCondensation, CompliantPenaltyMultipliers)
{
  for (const unsigned int dim : {2u, 3u})
    {
      System s = make_system(dim, {true, false, true, false, true}, dim, 13);
      std::mt19937                           rng(dim);
      std::uniform_real_distribution<double> u(-1., 1.);
      const unsigned int                     n_s = 5;
      for (const unsigned int j : {1u, 3u})
        {
          const unsigned int m = s.n_u + j;
          const double       c = 10. * s.n_u;
          for (unsigned int i = 0; i < s.n_u; ++i)
            s.J(m, i) = 0.05 * c * u(rng);
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double normal = s.J(dim * j + d, m);
              s.J(m, dim * j + d) = -c * normal;
              for (unsigned int a = 0; a < 3; ++a)
                s.J(m, dim * (n_s + a) + d) = 0.3 * c * normal;
              // A share of the force on a node that is no slave node.
              s.J(dim * (n_s + 3 + j % 3) + d, m) = 0.4 * u(rng);
            }
          s.J(m, m) = 0.1; // c / k (the default k = 1000 c gives 1e-3)
          s.blocks[j].dofs.clear();
        }
      check(s);
    }
}
