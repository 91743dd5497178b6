#pragma once

#include <array>
#include <vector>

namespace glide
{
  /// 1D Lagrange basis of degree @p p (1 or 2) on [0, 1] with equispaced
  /// nodes, and its derivatives, at @p s.
  template <typename T>
  void
  lagrange(const unsigned int p, const T &s, T *N, T *dN)
  {
    if (p == 1)
      {
        N[0]  = 1. - s;
        N[1]  = s;
        dN[0] = -1.;
        dN[1] = 1.;
      }
    else
      {
        N[0]  = (2. * s - 3.) * s + 1.;
        N[1]  = 4. * s * (1. - s);
        N[2]  = (2. * s - 1.) * s;
        dN[0] = 4. * s - 3.;
        dN[1] = 4. - 8. * s;
        dN[2] = 4. * s - 1.;
      }
  }

  /// Shape functions of a master facet of degree @p p (a line in 2D, a
  /// quadrilateral in 3D, nodes in lexicographic order i + (p + 1) j) and
  /// their derivatives with respect to the facet parameters at @p xi.
  template <int dim, typename T>
  void
  facet_basis(const unsigned int                   p,
              const std::array<T, dim - 1>        &xi,
              std::vector<T>                      &N,
              std::vector<std::array<T, dim - 1>> &dN)
  {
    std::array<T, 3> Ns, dNs, Nt, dNt;
    lagrange(p, xi[0], Ns.data(), dNs.data());
    const unsigned int n_j = dim == 2 ? 1 : p + 1;
    if (dim == 3)
      lagrange(p, xi[dim - 2], Nt.data(), dNt.data());
    N.resize((p + 1) * n_j);
    dN.resize((p + 1) * n_j);
    for (unsigned int j = 0; j < n_j; ++j)
      for (unsigned int i = 0; i <= p; ++i)
        {
          const unsigned int k = i + (p + 1) * j;
          if constexpr (dim == 2)
            {
              N[k]     = Ns[i];
              dN[k][0] = dNs[i];
            }
          else
            {
              N[k]     = Ns[i] * Nt[j];
              dN[k][0] = dNs[i] * Nt[j];
              dN[k][1] = Ns[i] * dNt[j];
            }
        }
  }
} // namespace glide
