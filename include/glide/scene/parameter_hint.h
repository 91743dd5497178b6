#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace glide
{
  /**
   * What a name the scene's parameters do not declare was probably meant
   * to be, for the input error that names it (P3: a misspelt parameter).
   * @p declared holds every parameter of the scene; @p path is the
   * subsection the name was written in (empty: the top level); @p name is
   * an entry's name or, if @p subsection, a subsection's.
   *
   * Returns " Did you mean '<name>'?" for the closest declared name of the
   * same kind in that subsection (names compared without case; at most
   * two letters added, removed, changed or swapped, fewer in short
   * names), else for an entry declared under that name in other
   * subsections " '<name>' is an entry of '<path>' ...", else "".
   */
  std::string
  parameter_hint(const dealii::ParameterHandler &declared,
                 const std::vector<std::string> &path,
                 const std::string              &name,
                 bool                            subsection);

  /**
   * The subsection path in force at line @p line (1-based) of a .prm
   * text: its 'subsection' and 'end' lines before @p line, comments left
   * out.
   */
  std::vector<std::string>
  subsection_path_at(const std::string &text, unsigned int line);

  /**
   * Whether @p path (subsection names from the top) is a subsection of
   * @p declared; @p found is set to the number of its leading names that
   * are.
   */
  bool
  is_declared_subsection(const dealii::ParameterHandler &declared,
                         const std::vector<std::string> &path,
                         unsigned int                   &found);
} // namespace glide
