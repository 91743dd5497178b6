#include <glide/mesh/gmsh_reader.h>
#include <glide/scene/input_error.h>

#include <fstream>
#include <sstream>

namespace glide
{
  namespace
  {
    /// Gmsh's element types (gmsh.info, "MSH file format"): name,
    /// topological dimension, order. glide reads first-order quadrilaterals
    /// and hexahedra as cells and first-order lines and quadrilaterals as
    /// boundary faces.
    struct GmshType
    {
      const char  *name;
      unsigned int dim;
      unsigned int order;
    };

    GmshType
    gmsh_type(const int type)
    {
      switch (type)
        {
          case 1:
            return {"2-node line", 1, 1};
          case 2:
            return {"3-node triangle", 2, 1};
          case 3:
            return {"4-node quadrilateral", 2, 1};
          case 4:
            return {"4-node tetrahedron", 3, 1};
          case 5:
            return {"8-node hexahedron", 3, 1};
          case 6:
            return {"6-node prism", 3, 1};
          case 7:
            return {"5-node pyramid", 3, 1};
          case 8:
            return {"3-node second-order line", 1, 2};
          case 9:
            return {"6-node second-order triangle", 2, 2};
          case 10:
            return {"9-node second-order quadrilateral", 2, 2};
          case 11:
            return {"10-node second-order tetrahedron", 3, 2};
          case 12:
            return {"27-node second-order hexahedron", 3, 2};
          case 13:
            return {"18-node second-order prism", 3, 2};
          case 14:
            return {"14-node second-order pyramid", 3, 2};
          case 15:
            return {"1-node point", 0, 1};
          case 16:
            return {"8-node second-order quadrilateral", 2, 2};
          case 17:
            return {"20-node second-order hexahedron", 3, 2};
          case 18:
            return {"15-node second-order prism", 3, 2};
          case 19:
            return {"13-node second-order pyramid", 3, 2};
          default:
            return {"higher-order or special element", 9, 3};
        }
    }

    /// Number of nodes of the element types glide reads.
    std::size_t
    expected_nodes(const int type)
    {
      return type == 15 ? 1 : type == 1 ? 2 : type == 3 ? 4 : 8;
    }

    /// What to do about an element glide does not read.
    std::string
    advice(const GmshType &t, const unsigned int dim)
    {
      const std::string name(t.name);
      if (t.order > 1)
        return "glide reads first-order meshes only: mesh with "
               "'Mesh.ElementOrder = 1' (gmsh -order 1) and set "
               "'Discretization/Element degree = 2' in the scene for "
               "quadratic elements.";
      if (t.dim != 9 && t.dim > dim)
        return "the scene has 'Dimension = " + std::to_string(dim) +
               "'; write a " + std::to_string(dim) +
               "D mesh or set "
               "'Dimension = " +
               std::to_string(t.dim) + "'.";
      // A triangle in a 3D mesh is a face of a surface group: the faces
      // of hexahedra are quadrilaterals (the advice was for 2D bodies
      // until 2026-12-07).
      if (name.find("triangle") != std::string::npos && dim == 3)
        return "glide meshes 3D bodies with hexahedra, whose faces are "
               "quadrilaterals: mesh the surfaces of the volumes with "
               "quadrilaterals too (recombined, transfinite surfaces and "
               "volumes, or Mesh.SubdivisionAlgorithm = 2, which splits "
               "every cell into hexahedra).";
      if (name.find("triangle") != std::string::npos)
        return "glide meshes 2D bodies with quadrilaterals: recombine the "
               "triangles into quadrilaterals ('Recombine Surface{...};' in "
               "the .geo file, or Mesh.RecombineAll = 1 with "
               "Mesh.Algorithm = 8).";
      if (name.find("tetrahedron") != std::string::npos ||
          name.find("prism") != std::string::npos ||
          name.find("pyramid") != std::string::npos)
        return "glide meshes 3D bodies with hexahedra: use transfinite, "
               "recombined volumes (or Mesh.SubdivisionAlgorithm = 2, which "
               "splits every cell into hexahedra).";
      return "glide reads quadrilaterals (2D) and hexahedra (3D).";
    }

    class GmshReader
    {
    public:
      GmshReader(const std::string &file, const unsigned int dim)
        : file(file)
        , dim(dim)
      {
        std::ifstream in(file);
        require(static_cast<bool>(in),
                "Cannot open the Gmsh file '" + file + "'.");
        std::string l;
        while (std::getline(in, l))
          {
            if (!l.empty() && l.back() == '\r')
              l.pop_back();
            // A UTF-8 byte-order mark before '$MeshFormat' (some Windows
            // editors write one).
            if (lines.empty() && l.rfind("\xEF\xBB\xBF", 0) == 0)
              l.erase(0, 3);
            lines.push_back(l);
          }
        content.file                  = file;
        content.set_word              = "physical group";
        content.clockwise_is_inverted = false;
      }

      MeshFileContent
      read();

    private:
      const std::string        file;
      const unsigned int       dim;
      std::vector<std::string> lines;
      std::size_t              next = 0; // index of the next line
      MeshFileContent          content;
      std::map<std::pair<int, int>, std::string> physical_names;
      // 4.1: (entity dimension, tag) -> physical tags
      std::map<std::pair<int, int>, std::vector<int>> entity_physicals;

      std::string
      where(const std::size_t index) const
      {
        return file_line(file, index + 1);
      }

      /// The next non-empty line; its index in @p index.
      std::istringstream
      line(std::size_t       &index,
           const std::string &section,
           const bool         end_of_section = false)
      {
        while (next < lines.size() &&
               lines[next].find_first_not_of(" \t") == std::string::npos)
          ++next;
        require(next < lines.size(),
                "Gmsh file '" + file + "' ends inside the " + section +
                  " section; the file is cut off or not a Gmsh file.");
        index = next++;
        require(end_of_section || lines[index].rfind('$', 0) != 0,
                where(index) + ": the $" + section +
                  " section ends here, but its counts announce more "
                  "entries; the counts or the entries are wrong, or the "
                  "file is cut off.");
        return std::istringstream(lines[index]);
      }

      template <typename T>
      T
      number(std::istringstream &in,
             const std::size_t   index,
             const std::string  &what)
      {
        T x;
        require(static_cast<bool>(in >> x),
                where(index) + ": cannot read " + what + " in '" +
                  lines[index] + "'.");
        return x;
      }

      void
      expect_end(const std::string &section)
      {
        std::size_t index;
        auto        in = line(index, section, true);
        std::string word;
        in >> word;
        require(word == "$End" + section,
                where(index) + ": expected $End" + section + ", found '" +
                  lines[index] + "' (wrong count of entries above?).");
      }

      std::string
      group_name(const int group_dim, const int tag) const
      {
        const auto it = physical_names.find({group_dim, tag});
        return it == physical_names.end() ? std::to_string(tag) : it->second;
      }

      /// The rest of an element line: its node ids.
      std::vector<long>
      node_list(std::istringstream &in, const std::size_t index)
      {
        std::vector<long> nodes;
        std::string       token;
        while (in >> token)
          {
            std::size_t used = 0;
            long        id   = 0;
            try
              {
                id = std::stol(token, &used);
              }
            catch (...)
              {
                used = 0;
              }
            require(used == token.size() && id > 0,
                    where(index) + ": cannot read '" + token +
                      "' as a node id in '" + lines[index] + "'.");
            nodes.push_back(id);
          }
        return nodes;
      }

      void
      add_node(const long                   id,
               const std::array<double, 3> &x,
               const std::size_t            index);

      void
      add_element(const long               id,
                  const int                type,
                  const std::vector<int>  &physicals,
                  const std::vector<long> &nodes,
                  const std::size_t        index);

      std::map<long, std::size_t> element_lines;
      std::string                 face_problem;
    };



    void
    GmshReader::add_node(const long                   id,
                         const std::array<double, 3> &x,
                         const std::size_t            index)
    {
      const auto prev = content.nodes.find(id);
      require(prev == content.nodes.end(),
              where(index) + ": node " + std::to_string(id) +
                " is defined a second time (first at line " +
                std::to_string(
                  prev == content.nodes.end() ? 0 : prev->second.line) +
                "); every node id must be defined once.");
      MeshFileContent::Node n;
      n.x               = x;
      n.line            = index + 1;
      content.nodes[id] = n;
    }



    void
    GmshReader::add_element(const long               id,
                            const int                type,
                            const std::vector<int>  &physicals,
                            const std::vector<long> &nodes,
                            const std::size_t        index)
    {
      const auto prev = element_lines.find(id);
      require(prev == element_lines.end(),
              where(index) + ": element " + std::to_string(id) +
                " is defined a second time (first at line " +
                std::to_string(prev == element_lines.end() ? 0 :
                                                             prev->second + 1) +
                "); every element id must be defined once.");
      element_lines[id] = index;

      const GmshType    t     = gmsh_type(type);
      const std::string label = "element " + std::to_string(id) + " (" +
                                t.name + ", Gmsh type " + std::to_string(type) +
                                ")";
      const bool supported = t.order == 1 && t.dim <= dim &&
                             (t.dim != 2 || type == 3) &&
                             (t.dim != 3 || type == 5);
      auto undefined = [&]() -> std::string {
        for (const auto n : nodes)
          if (content.nodes.count(n) == 0)
            return where(index) + ": " + label + " references node " +
                   std::to_string(n) + ", which the file does not define.";
        return "";
      };

      if (t.dim == dim || t.dim == 9 || t.dim > dim)
        {
          // A cell (or something where a cell should be).
          MeshFileContent::Cell cell;
          cell.id   = id;
          cell.type = t.name;
          cell.line = index + 1;
          if (!supported)
            cell.problem = where(index) + ": " + label + ": " + advice(t, dim);
          else if (nodes.size() != expected_nodes(type))
            cell.problem = where(index) + ": " + label + " has " +
                           std::to_string(nodes.size()) + " nodes instead of " +
                           std::to_string(expected_nodes(type)) + ".";
          else
            cell.problem = undefined();
          if (cell.problem.empty())
            {
              // Gmsh numbers quadrilaterals and the faces of hexahedra
              // counterclockwise; deal.II wants lexicographic order.
              static const unsigned int to_dealii[] = {0, 1, 3, 2, 4, 5, 7, 6};
              for (unsigned int v = 0; v < nodes.size(); ++v)
                cell.nodes.push_back(nodes[to_dealii[v]]);
            }
          content.cells.push_back(cell);
          for (const auto p : physicals)
            content.cell_sets[group_name(dim, p)].insert(id);
          return;
        }
      if (physicals.empty())
        return; // a face, edge or point in no group: it names nothing
      if (!supported)
        {
          // Reported after all elements are read, unless a cell of an
          // unsupported type explains it better (the triangles on the
          // boundary of tetrahedra).
          if (face_problem.empty())
            face_problem =
              where(index) + ": " + label + " is in the physical group '" +
              group_name(t.dim, physicals[0]) + "': " + advice(t, dim);
          return;
        }
      require(nodes.size() == expected_nodes(type),
              where(index) + ": " + label + " has " +
                std::to_string(nodes.size()) + " nodes instead of " +
                std::to_string(expected_nodes(type)) + ".");
      const std::string u = undefined();
      require(u.empty(), u);
      if (t.dim + 1 == dim)
        for (const auto p : physicals)
          {
            MeshFileContent::Face f;
            f.nodes = nodes;
            f.what  = label;
            f.line  = index + 1;
            content.surfaces[group_name(t.dim, p)].push_back(f);
          }
      else
        for (const auto p : physicals)
          content.node_sets[group_name(t.dim, p)].insert(nodes.begin(),
                                                         nodes.end());
    }



    MeshFileContent
    GmshReader::read()
    {
      double version = 0;
      bool   nodes = false, elements = false, entities = false;
      while (next < lines.size())
        {
          const std::size_t index   = next++;
          std::string       section = lines[index];
          section.erase(section.find_last_not_of(" \t") + 1);
          if (section.empty())
            continue;
          require(section[0] == '$',
                  where(index) +
                    ": expected a section such as $Nodes, found '" + section +
                    "'; is this a Gmsh file?");
          const std::string name = section.substr(1);
          if (name == "MeshFormat")
            {
              std::size_t i;
              auto        in     = line(i, name);
              int         binary = 0, size = 0;
              version = number<double>(in, i, "the format version");
              binary  = number<int>(in, i, "the file type");
              size    = number<int>(in, i, "the data size");
              (void)size;
              require(binary == 0,
                      where(i) + ": a binary Gmsh file; glide reads ASCII "
                                 "files: save with 'Mesh.Binary = 0'.");
              require((version >= 2 && version < 3) ||
                        std::abs(version - 4.1) < 1e-6,
                      where(i) + ": Gmsh format " + lines[i] +
                        "; glide reads the ASCII formats 2.2 and 4.1 "
                        "(Mesh.MshFileVersion = 2.2 or 4.1).");
              expect_end(name);
            }
          else if (name == "PhysicalNames")
            {
              std::size_t i;
              auto        in = line(i, name);
              const int   n  = number<int>(in, i, "the number of names");
              for (int k = 0; k < n; ++k)
                {
                  auto        l   = line(i, name);
                  const int   d   = number<int>(l, i, "a dimension");
                  const int   tag = number<int>(l, i, "a physical tag");
                  std::string rest;
                  std::getline(l, rest);
                  const auto first = rest.find('"'), last = rest.rfind('"');
                  if (first != std::string::npos && last > first)
                    rest = rest.substr(first + 1, last - first - 1);
                  else
                    rest.erase(0, rest.find_first_not_of(" \t"));
                  for (const auto &[key, other] : physical_names)
                    require(key.first != d || other != rest,
                            where(i) + ": the physical groups " +
                              std::to_string(key.second) + " and " +
                              std::to_string(tag) + " of dimension " +
                              std::to_string(d) + " are both named '" + rest +
                              "'; glide would merge them into one surface "
                              "or set. Give them different names, or make "
                              "them one group.");
                  physical_names[{d, tag}] = rest;
                }
              expect_end(name);
            }
          else if (name == "Entities" && version > 4)
            {
              require(!elements,
                      where(index) +
                        ": the $Entities section comes after $Elements; "
                        "format 4.1 defines the entities (and their "
                        "physical groups) before the elements that use "
                        "them. Save the mesh again with Gmsh.");
              entities = true;
              std::size_t i;
              auto        in = line(i, name);
              int         count[4];
              for (auto &c : count)
                c = number<int>(in, i, "the number of entities");
              for (int d = 0; d < 4; ++d)
                for (int k = 0; k < count[d]; ++k)
                  {
                    auto      l   = line(i, name);
                    const int tag = number<int>(l, i, "an entity tag");
                    for (int c = 0; c < (d == 0 ? 3 : 6); ++c)
                      number<double>(l, i, "a coordinate");
                    const int n = number<int>(l, i, "a number of tags");
                    auto     &p = entity_physicals[{d, tag}];
                    for (int c = 0; c < n; ++c)
                      {
                        const int tag = number<int>(l, i, "a physical tag");
                        if (tag != 0)
                          p.push_back(std::abs(tag));
                      }
                  }
              expect_end(name);
            }
          else if (name == "Nodes" || name == "ParametricNodes")
            {
              require(version > 0,
                      where(index) + ": $Nodes before $MeshFormat; is this "
                                     "a Gmsh file?");
              nodes = true;
              std::size_t i;
              auto        in = line(i, name);
              if (version < 3)
                {
                  const long n = number<long>(in, i, "the number of nodes");
                  for (long k = 0; k < n; ++k)
                    {
                      auto       l  = line(i, name);
                      const long id = number<long>(l, i, "a node id");
                      std::array<double, 3> x;
                      for (auto &c : x)
                        c = number<double>(l, i, "a coordinate");
                      add_node(id, x, i);
                    }
                }
              else
                {
                  const long blocks =
                    number<long>(in, i, "the number of node blocks");
                  for (long b = 0; b < blocks; ++b)
                    {
                      auto l = line(i, name);
                      number<int>(l, i, "an entity dimension");
                      number<int>(l, i, "an entity tag");
                      const int  parametric = number<int>(l, i, "a flag");
                      const long n = number<long>(l, i, "a number of nodes");
                      (void)parametric;
                      std::vector<std::pair<long, std::size_t>> ids;
                      for (long k = 0; k < n; ++k)
                        {
                          auto t = line(i, name);
                          ids.emplace_back(number<long>(t, i, "a node id"), i);
                        }
                      for (long k = 0; k < n; ++k)
                        {
                          auto                  t = line(i, name);
                          std::array<double, 3> x;
                          for (auto &c : x)
                            c = number<double>(t, i, "a coordinate");
                          add_node(ids[k].first, x, ids[k].second);
                        }
                    }
                }
              expect_end("Nodes");
            }
          else if (name == "Elements")
            {
              require(nodes,
                      where(index) + ": $Elements before $Nodes; glide "
                                     "needs the nodes first.");
              elements = true;
              std::size_t i;
              auto        in = line(i, name);
              if (version < 3)
                {
                  const long n = number<long>(in, i, "the number of elements");
                  for (long k = 0; k < n; ++k)
                    {
                      auto       l    = line(i, name);
                      const long id   = number<long>(l, i, "an element id");
                      const int  type = number<int>(l, i, "an element type");
                      const int  ntag = number<int>(l, i, "a number of tags");
                      std::vector<int> physicals;
                      for (int t = 0; t < ntag; ++t)
                        {
                          const int tag = number<int>(l, i, "a tag");
                          if (t == 0 && tag != 0)
                            physicals.push_back(tag);
                        }
                      add_element(id, type, physicals, node_list(l, i), i);
                    }
                }
              else
                {
                  const long blocks =
                    number<long>(in, i, "the number of element blocks");
                  for (long b = 0; b < blocks; ++b)
                    {
                      auto       l   = line(i, name);
                      const int  d   = number<int>(l, i, "an entity dimension");
                      const int  tag = number<int>(l, i, "an entity tag");
                      const int  type = number<int>(l, i, "an element type");
                      const long n = number<long>(l, i, "a number of elements");
                      const auto it = entity_physicals.find({d, tag});
                      const std::vector<int> physicals =
                        it == entity_physicals.end() ? std::vector<int>() :
                                                       it->second;
                      for (long k = 0; k < n; ++k)
                        {
                          auto       e  = line(i, name);
                          const long id = number<long>(e, i, "an element id");
                          add_element(id, type, physicals, node_list(e, i), i);
                        }
                    }
                }
              expect_end(name);
            }
          else
            {
              // Any other section ($NodeData, $Periodic, ...): skip it.
              while (next < lines.size() &&
                     lines[next].rfind("$End" + name, 0) != 0)
                ++next;
              require(next < lines.size(),
                      where(index) + ": the section $" + name + " has no $End" +
                        name + ".");
              ++next;
            }
        }
      require(version > 0,
              "Gmsh file '" + file +
                "' has no $MeshFormat section; is it a Gmsh file?");
      require(nodes && elements,
              "Gmsh file '" + file + "' has no " +
                (nodes ? "$Elements" : "$Nodes") + " section.");
      // Format 4.1 puts elements into physical groups through their
      // entities; without $Entities every group would be empty.
      require(version < 4 || entities || physical_names.empty(),
              "Gmsh file '" + file +
                "' (format 4.1) names physical groups in $PhysicalNames "
                "but has no $Entities section, through which format 4.1 "
                "puts elements into them: none of its groups would have an "
                "element. Save the mesh again with Gmsh (format 4.1 with "
                "$Entities), or in format 2.2 ('Mesh.MshFileVersion = "
                "2.2'), where each element names its groups.");
      if (!face_problem.empty())
        {
          for (const auto &c : content.cells)
            if (!c.problem.empty())
              throw InputError(c.problem);
          throw InputError(face_problem);
        }
      return content;
    }
  } // namespace



  MeshFileContent
  read_gmsh(const std::string &file, const unsigned int dim)
  {
    return GmshReader(file, dim).read();
  }
} // namespace glide
