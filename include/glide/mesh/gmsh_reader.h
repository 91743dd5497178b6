#pragma once

#include <glide/mesh/mesh_file.h>

#include <string>

namespace glide
{
  /**
   * Read a Gmsh file in ASCII format 2.2 or 4.1 (doc/mesh-import.md).
   * Quadrilaterals (2D) and hexahedra (3D) are the cells; boundary elements
   * (lines in 2D, quadrilaterals in 3D) in physical groups become surfaces
   * named by $PhysicalNames (or by the group's number); physical groups of
   * points (and, in 3D, of lines) become node sets; physical groups of cells
   * are element sets. Elements of other types (triangles, tetrahedra,
   * second-order elements, ...) are kept with the reason, and import_body()
   * refuses them. Throws InputError naming the file and line.
   */
  MeshFileContent
  read_gmsh(const std::string &file, const unsigned int dim);
} // namespace glide
