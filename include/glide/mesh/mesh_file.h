#pragma once

#include <deal.II/base/types.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace glide
{
  /**
   * What a mesh file holds, after glide's own reader has checked it
   * (doc/mesh-import.md): nodes by their ids in the file, the cells of the
   * scene's dimension with their corner nodes, named element sets, named
   * surfaces (as faces) and named node sets. The same structure for Gmsh
   * and Abaqus files, so that one function (import_body()) picks a body out
   * of it. Every item remembers its line in the file, for messages.
   */
  struct MeshFileContent
  {
    /// The file, as given (for messages).
    std::string file;
    /// "element set" (Abaqus *ELSET) or "physical group" (Gmsh): the word
    /// for a named group of cells in messages.
    std::string set_word = "element set";
    /// Abaqus numbers the corners of a quadrilateral counterclockwise (and
    /// a hexahedron's first face counterclockwise seen from its second) and
    /// refuses elements numbered the other way round ("inside out"), so
    /// glide does too. Gmsh numbers them along the orientation of the
    /// geometry, which may be either way: glide renumbers those.
    bool clockwise_is_inverted = true;

    /// A node: coordinates (z = 0 in 2D) and the line that defines it.
    struct Node
    {
      std::array<double, 3> x{{0., 0., 0.}};
      unsigned int          line = 0;
    };
    std::map<long, Node> nodes;

    /// A cell of the scene's dimension: its corner nodes in deal.II's
    /// (lexicographic) order.
    struct Cell
    {
      long              id = 0;
      std::string       type; ///< as the file names it, for messages
      std::vector<long> nodes;
      /// The mid-side nodes of a second-order element, which glide's mesh
      /// does not have (for the node sets that hold some).
      std::vector<long> midside;
      unsigned int      line = 0;
      /// Why glide cannot read this element faithfully (its type, a curved
      /// edge, an undefined node, ...); empty if it can. import_body()
      /// refuses such an element if it belongs to the body.
      std::string problem;
    };
    std::vector<Cell> cells;

    /// Named groups of cells (Abaqus *ELSET, Gmsh physical groups of cells).
    std::map<std::string, std::set<long>> cell_sets;

    /**
     * One face of a surface: either given by its corner nodes (a boundary
     * element of a Gmsh file, a face S1..S6 of an Abaqus element), or all
     * free faces of a cell (an Abaqus element-based surface line without a
     * face identifier).
     */
    struct Face
    {
      std::vector<long> nodes;    ///< corner nodes; empty: all free faces
      long              cell = 0; ///< the cell it belongs to, 0: unknown
      std::string       what;     ///< e.g. "face S3 of element 12"
      unsigned int      line = 0;
    };
    std::map<std::string, std::vector<Face>> surfaces;

    /// Named node sets (Abaqus *NSET, node-based *SURFACE, the nodes of an
    /// *ELSET; Gmsh physical groups of points, and of lines in 3D).
    std::map<std::string, std::set<long>> node_sets;
    /// The node sets above that are the nodes of an element set (whole
    /// elements, mid-side nodes included).
    std::set<std::string> element_set_nodes;
  };

  /**
   * One body taken out of a mesh file: its vertices, cells, labelled
   * boundary faces and node sets, ready to become a deal.II Triangulation.
   * Built when the scene is read, so that every mistake in the file is
   * reported before anything is computed or written.
   */
  struct ImportedMesh
  {
    std::string                        file;
    std::vector<std::array<double, 3>> vertices;
    /// Cells as vertex indices in deal.II's order.
    std::vector<std::vector<unsigned int>> cells;
    /// Boundary faces that belong to at least one surface, as vertex
    /// indices, with their boundary id.
    std::vector<
      std::pair<std::vector<unsigned int>, dealii::types::boundary_id>>
      faces;
    /// Boundary id -> the names of the surfaces its faces belong to. A face
    /// in several surfaces gets the id of that combination; id 0 is the
    /// rest of the boundary (surface "unnamed").
    std::map<dealii::types::boundary_id, std::vector<std::string>> surfaces;
    /// Node set name -> coordinates of its nodes in this body.
    std::map<std::string, std::vector<std::array<double, 3>>> node_sets;
    /// Node sets of the file that are not node sets of this body, with the
    /// reason (for the message when the scene names one).
    std::map<std::string, std::string> unavailable;
    /// The smallest edge length (for tolerances).
    double smallest_edge = 0.;
    /// The element types of the body's cells as the file names them
    /// (Abaqus: CPE4R, CAX4, ...; Gmsh: "4-node quadrilateral").
    std::set<std::string> element_types;
    /// Warnings about the body's mesh for the log (duplicate nodes).
    std::vector<std::string> notes;
    /// Warnings about node sets (mid-side nodes), by set name: for the log
    /// where the scene uses the set.
    std::map<std::string, std::string> node_set_notes;
  };

  /**
   * Read @p file (Gmsh .msh or Abaqus .inp) for a @p dim -dimensional scene
   * and take out one body: the cells of the element set (Abaqus *ELSET, Gmsh
   * physical group) @p element_set, or all cells if it is empty; in an
   * Abaqus file with *PART and *INSTANCE, the part or instance @p part. Throws
   * InputError naming the file and line (or element) for anything glide
   * cannot read faithfully.
   */
  ImportedMesh
  import_mesh_file(const std::string &file,
                   const unsigned int dim,
                   const std::string &element_set,
                   const std::string &part);

  /// Take one body (see import_mesh_file()) out of the content of a file.
  ImportedMesh
  import_body(const MeshFileContent &content,
              const unsigned int     dim,
              const std::string     &element_set);

  /**
   * Build @p tria from @p mesh, with the surfaces of @p mesh as boundary ids
   * (their names in @p names).
   */
  template <int dim>
  void
  create_triangulation(
    const ImportedMesh                                             &mesh,
    dealii::Triangulation<dim>                                     &tria,
    std::map<dealii::types::boundary_id, std::vector<std::string>> &names);

  /// Quote a number of a file for messages ("element 641").
  std::string
  file_line(const std::string &file, const unsigned int line);
} // namespace glide
