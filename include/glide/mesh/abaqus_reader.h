#pragma once

#include <glide/mesh/mesh_file.h>

#include <string>

namespace glide
{
  /**
   * Read an Abaqus input file (doc/mesh-import.md): *NODE, *ELEMENT,
   * *NSET, *ELSET, *SURFACE (element- and node-based), *PART, *ASSEMBLY,
   * *INSTANCE (with its translation and rotation) and *INCLUDE; every other
   * keyword (materials, steps, ...) is skipped with its data lines, and the
   * keywords that generate nodes or elements (*NGEN, *ELGEN, ...) are
   * refused. Element and node ids may be any positive numbers. Elements
   * glide cannot mesh faithfully (triangles, tetrahedra, wedges, shells,
   * curved second-order elements, ...) are kept with the reason, and
   * import_body() refuses them if they belong to the body.
   *
   * @p part names the *PART or *INSTANCE to read from a file that has
   * parts; empty: the file's only instance (or the whole file if it has no
   * parts). Throws InputError naming the file and line.
   */
  MeshFileContent
  read_abaqus(const std::string &file,
              const unsigned int dim,
              const std::string &part);
} // namespace glide
