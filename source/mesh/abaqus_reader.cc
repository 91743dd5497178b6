#include <glide/mesh/abaqus_reader.h>
#include <glide/scene/input_error.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace glide
{
  namespace
  {
    /// One line of the input, with where it came from (*INCLUDE files keep
    /// their own name and line numbers).
    struct Line
    {
      std::string  file;
      unsigned int number = 0;
      std::string  text;
    };

    std::string
    where(const Line &l)
    {
      return file_line(l.file, l.number);
    }

    /// "line 12", or the file and line if @p l is in another (included)
    /// file than @p here.
    std::string
    earlier(const Line &l, const Line &here)
    {
      return l.file == here.file ? "line " + std::to_string(l.number) :
                                   where(l);
    }

    std::string
    upper(std::string s)
    {
      for (auto &c : s)
        c = std::toupper(static_cast<unsigned char>(c));
      return s;
    }

    std::string
    trim(const std::string &s)
    {
      const auto b = s.find_first_not_of(" \t\r");
      if (b == std::string::npos)
        return "";
      const auto e = s.find_last_not_of(" \t\r");
      return s.substr(b, e - b + 1);
    }

    /// Comma-separated entries of a data line, trimmed; a trailing comma
    /// (which continues a line in Abaqus) gives no empty last entry.
    std::vector<std::string>
    split(const std::string &text)
    {
      std::vector<std::string> out;
      std::string              item;
      std::istringstream       in(text);
      while (std::getline(in, item, ','))
        out.push_back(trim(item));
      while (!out.empty() && out.back().empty())
        out.pop_back();
      return out;
    }

    /// Names are case-insensitive in Abaqus unless quoted; glide keeps them
    /// as written and looks them up in upper case.
    std::string
    unquote(const std::string &s)
    {
      if (s.size() >= 2 && s.front() == '"' && s.back() == '"')
        return s.substr(1, s.size() - 2);
      return s;
    }

    /// Read @p file into @p lines, expanding *INCLUDE, INPUT=<file>;
    /// @p chain holds the files being read, the outermost first (a file
    /// that includes one of them is a loop; until 2026-12-06 it ended at
    /// the depth limit with a message that did not say so).
    void
    load(const std::string        &file,
         std::vector<Line>        &lines,
         std::vector<std::string> &chain)
    {
      // The path as written where it cannot be made canonical (an empty
      // one would make unrelated files look alike).
      const auto canonical_of = [](const std::string &f) {
        std::error_code ec;
        const auto      c = std::filesystem::weakly_canonical(f, ec);
        return ec || c.empty() ? f : c.string();
      };
      chain.push_back(canonical_of(file));
      const int     depth = static_cast<int>(chain.size()) - 1;
      std::ifstream in(file);
      require(static_cast<bool>(in),
              "Cannot open the Abaqus file '" + file + "'.");
      std::string  text;
      unsigned int number = 0;
      while (std::getline(in, text))
        {
          ++number;
          if (!text.empty() && text.back() == '\r')
            text.pop_back();
          // A UTF-8 byte-order mark (some Windows editors write one): not
          // part of the first keyword (it was read as a data line).
          if (number == 1 && text.rfind("\xEF\xBB\xBF", 0) == 0)
            text.erase(0, 3);
          const std::string t = trim(text);
          if (upper(t).rfind("*INCLUDE", 0) == 0)
            {
              const auto eq = t.find('=');
              require(eq != std::string::npos,
                      file_line(file, number) +
                        ": *INCLUDE needs INPUT=<file>.");
              std::string name = unquote(trim(t.substr(eq + 1)));
              if (!name.empty() && name[0] != '/')
                name =
                  (std::filesystem::path(file).parent_path() / name).string();
              require(std::filesystem::exists(name),
                      file_line(file, number) +
                        ": cannot open the included "
                        "file '" +
                        name + "'.");
              require_regular_file(name,
                                   file_line(file, number) +
                                     ": the file included by *INCLUDE,",
                                   "give the path of an Abaqus .inp file.");
              const std::string canonical = canonical_of(name);
              if (std::find(chain.begin(), chain.end(), canonical) !=
                  chain.end())
                {
                  std::string loop;
                  for (const auto &c : chain)
                    loop += "'" + c + "' -> ";
                  throw InputError(file_line(file, number) + ": *INCLUDE of '" +
                                   name + "' makes a loop: " + loop + "'" +
                                   canonical +
                                   "'. Remove the *INCLUDE that leads back "
                                   "to a file that includes it.");
                }
              require(depth < 10,
                      file_line(file, number) +
                        ": *INCLUDE nests more than 10 levels of files.");
              load(name, lines, chain);
              continue;
            }
          lines.push_back({file, number, text});
        }
      chain.pop_back();
    }

    /// A keyword line: its name in upper case ("ELEMENT", "END PART") and
    /// its parameters (keys in upper case, values as written).
    struct Keyword
    {
      std::string                        name;
      std::map<std::string, std::string> parameters;

      bool
      has(const std::string &key) const
      {
        return parameters.count(key) > 0;
      }
      std::string
      get(const std::string &key) const
      {
        const auto it = parameters.find(key);
        return it == parameters.end() ? "" : it->second;
      }
    };

    Keyword
    parse_keyword(const std::string &text)
    {
      Keyword    k;
      const auto items = split(text.substr(1));
      if (items.empty())
        return k;
      // "*End  Part" -> "END PART"
      std::istringstream words(upper(items[0]));
      std::string        w;
      while (words >> w)
        k.name += (k.name.empty() ? "" : " ") + w;
      for (unsigned int i = 1; i < items.size(); ++i)
        {
          const auto eq = items[i].find('=');
          if (eq == std::string::npos)
            k.parameters[upper(items[i])] = "";
          else
            k.parameters[upper(trim(items[i].substr(0, eq)))] =
              unquote(trim(items[i].substr(eq + 1)));
        }
      return k;
    }

    bool
    is_integer(const std::string &s)
    {
      if (s.empty())
        return false;
      for (unsigned int i = (s[0] == '-' || s[0] == '+') ? 1 : 0; i < s.size();
           ++i)
        if (!std::isdigit(static_cast<unsigned char>(s[i])))
          return false;
      return true;
    }

    long
    to_id(const std::string &s, const Line &l, const std::string &what)
    {
      // Ids beyond the range of long (stol throws) are no ids either.
      long id = 0;
      if (is_integer(s))
        try
          {
            id = std::stol(s);
          }
        catch (const std::out_of_range &)
          {
            id = 0;
          }
      require(id > 0,
              where(l) + ": cannot read '" + s + "' as " + what +
                " (a positive integer of at most 18 digits).");
      return id;
    }

    double
    to_double(const std::string &s, const Line &l, const std::string &what)
    {
      std::size_t used = 0;
      double      x    = 0;
      try
        {
          x = std::stod(s, &used);
        }
      catch (...)
        {
          used = 0;
        }
      require(!s.empty() && used == s.size() && std::isfinite(x),
              where(l) + ": cannot read '" + s + "' as " + what + ".");
      return x;
    }

    /// The element types glide reads, by their number of nodes.
    struct ElementType
    {
      unsigned int dim     = 0; ///< 2: quadrilateral, 3: hexahedron
      unsigned int n_nodes = 0; ///< nodes on a data line
      std::string  refusal;     ///< why not, if glide cannot read it
    };

    ElementType
    classify(const std::string &type, const unsigned int dim)
    {
      static const std::regex quad(
        "^(CPE|CPS|CAX|CPEG|CGAX|DC2D|DCAX)(4|8)[A-Z]*$");
      static const std::regex hex("^(C3D|DC3D)(8|20)[A-Z]*$");
      static const std::regex tri("^(CPE|CPS|CAX|CPEG|CGAX|DC2D|DCAX)(3|6)"
                                  "[A-Z]*$");
      static const std::regex tet("^(C3D|DC3D)(4|10)[A-Z]*$");
      static const std::regex wedge("^(C3D|DC3D)(6|15|5|13)[A-Z]*$");
      std::smatch             m;
      ElementType             t;
      const std::string       what = "glide meshes bodies with quadrilaterals "
                                     "(CPE4, CPS4, CAX4, CPE8, ... and their R, "
                                     "H, I variants) in 2D and hexahedra (C3D8, "
                                     "C3D20, ...) in 3D";
      if (std::regex_match(type, m, quad))
        {
          t.dim     = 2;
          t.n_nodes = std::stoi(m[2]);
        }
      else if (std::regex_match(type, m, hex))
        {
          t.dim     = 3;
          t.n_nodes = std::stoi(m[2]);
        }
      else if (std::regex_match(type, m, tri))
        t.refusal = "a triangle; " + what +
                    ". Mesh the body with quadrilaterals (Abaqus/CAE: Mesh "
                    "Controls, Element Shape = Quad).";
      else if (std::regex_match(type, m, tet))
        t.refusal = "a tetrahedron; " + what +
                    ". Mesh the body with hexahedra (Abaqus/CAE: Mesh "
                    "Controls, Element Shape = Hex).";
      else if (std::regex_match(type, m, wedge))
        t.refusal = "a wedge or pyramid; " + what +
                    ". Mesh the body with "
                    "hexahedra only.";
      else
        t.refusal = "not a continuum element glide knows; " + what +
                    " (rigid surfaces are declared in the scene: "
                    "'Master = rigid plane', or a body with 'Rigid = true').";
      if (t.refusal.empty() && t.dim != dim)
        t.refusal =
          "a " + std::to_string(t.dim) +
          "D element, but the scene has 'Dimension = " + std::to_string(dim) +
          "'; " + what + ".";
      return t;
    }

    /// Corner positions (in the file's order) of the faces S1, S2, ...
    const std::vector<std::vector<unsigned int>> &
    faces_of(const unsigned int dim)
    {
      static const std::vector<std::vector<unsigned int>> quad{{0, 1},
                                                               {1, 2},
                                                               {2, 3},
                                                               {3, 0}};
      static const std::vector<std::vector<unsigned int>> hex{{0, 1, 2, 3},
                                                              {4, 7, 6, 5},
                                                              {0, 4, 5, 1},
                                                              {1, 5, 6, 2},
                                                              {2, 6, 7, 3},
                                                              {3, 7, 4, 0}};
      return dim == 2 ? quad : hex;
    }

    /// The corners between which each mid-side node of a CPE8 / C3D20
    /// element lies (positions in the file's order).
    const std::vector<std::pair<unsigned int, unsigned int>> &
    edges_of(const unsigned int dim)
    {
      static const std::vector<std::pair<unsigned int, unsigned int>> quad{
        {0, 1}, {1, 2}, {2, 3}, {3, 0}};
      static const std::vector<std::pair<unsigned int, unsigned int>> hex{
        {0, 1},
        {1, 2},
        {2, 3},
        {3, 0},
        {4, 5},
        {5, 6},
        {6, 7},
        {7, 4},
        {0, 4},
        {1, 5},
        {2, 6},
        {3, 7}};
      return dim == 2 ? quad : hex;
    }

    /// A mid-side node more than this fraction of its edge's length away
    /// from the middle of the edge makes the edge curved (or the element
    /// distorted). glide's cells have straight edges, so it refuses such an
    /// element rather than straightening it silently. Files carry 6 to 8
    /// significant digits: 1e-4 is far above their round-off and far below
    /// any curvature that matters for contact.
    constexpr double straight_edge_tolerance = 1e-4;

    struct RawElement
    {
      std::string       type;
      std::vector<long> nodes; ///< in the file's order
      Line              line;
    };

    /// A set: ids per instance ("" = the scope's own nodes or elements).
    struct RawSet
    {
      std::string                           name;
      std::map<std::string, std::set<long>> ids;
      Line                                  line;
      /// Abaqus/CAE's helper sets (INTERNAL) are no node sets of the scene.
      bool internal = false;
    };

    struct RawSurface
    {
      std::string name;
      bool        node_based = false;
      struct Entry
      {
        std::string instance;
        long        id   = 0;
        int         face = -1; ///< S1 = 0, ...; -1: all free faces
        Line        line;
      };
      std::vector<Entry> entries;
    };

    /// A part, or the whole model (or its assembly) in the scope "".
    struct Scope
    {
      std::map<long, MeshFileContent::Node> nodes;
      std::map<long, Line>                  node_lines;
      std::map<long, RawElement>            elements;
      std::map<std::string, RawSet>         nsets, elsets;
      std::map<std::string, RawSurface>     surfaces;
    };

    struct Instance
    {
      std::string           name;
      std::string           part; ///< upper case
      std::array<double, 3> translation{{0., 0., 0.}};
      std::vector<double>   rotation; ///< a, b (axis points), angle (deg)
    };

    class Reader
    {
    public:
      Reader(const std::string &file, const unsigned int dim)
        : file(file)
        , dim(dim)
      {
        std::vector<std::string> chain;
        load(file, lines, chain);
      }

      void
      read();

      MeshFileContent
      content(const std::string &part) const;

    private:
      const std::string                  file;
      const unsigned int                 dim;
      std::vector<Line>                  lines;
      std::map<std::string, Scope>       scopes;     // "" and parts
      std::map<std::string, std::string> part_names; // upper -> as written
      std::vector<Instance>              instances;
      std::string                        scope; // current
      bool                               in_assembly = false;

      /// Data lines of the keyword at line @p k: lines k+1 ... until the
      /// next keyword; returns the index of that keyword.
      std::size_t
      data_end(const std::size_t k) const
      {
        std::size_t i = k + 1;
        for (; i < lines.size(); ++i)
          {
            const std::string t = trim(lines[i].text);
            if (!t.empty() && t[0] == '*' && t.rfind("**", 0) != 0)
              break;
          }
        return i;
      }
      static bool
      skip(const Line &l)
      {
        const std::string t = trim(l.text);
        return t.empty() || t.rfind("**", 0) == 0;
      }

      /// Resolve one entry of a set's data line: an id, <instance>.<id>, a
      /// set name or <instance>.<set name>.
      void
      add_to_set(RawSet                              &set,
                 const std::string                   &token,
                 const std::string                   &instance,
                 const std::map<std::string, RawSet> &known,
                 const bool                           nodes,
                 const Line                          &l) const;

      const Instance *
      find_instance(const std::string &name) const
      {
        for (const auto &i : instances)
          if (upper(i.name) == upper(name))
            return &i;
        return nullptr;
      }

      void
      read_surface(const Keyword &k, std::size_t &i);
    };



    void
    Reader::add_to_set(RawSet                              &set,
                       const std::string                   &token,
                       const std::string                   &instance,
                       const std::map<std::string, RawSet> &known,
                       const bool                           nodes,
                       const Line                          &l) const
    {
      const std::string what = nodes ? "node" : "element";
      if (is_integer(token))
        {
          set.ids[instance].insert(to_id(token, l, "a " + what + " id"));
          return;
        }
      const auto dot = token.find('.');
      if (dot != std::string::npos && in_assembly)
        if (const Instance *inst = find_instance(token.substr(0, dot)))
          {
            const std::string rest = token.substr(dot + 1);
            const std::string I    = upper(inst->name);
            if (is_integer(rest))
              {
                set.ids[I].insert(to_id(rest, l, "a " + what + " id"));
                return;
              }
            const auto &part_sets = nodes ? scopes.at(inst->part).nsets :
                                            scopes.at(inst->part).elsets;
            const auto  it        = part_sets.find(upper(unquote(rest)));
            require(it != part_sets.end(),
                    where(l) + ": the " + what + " set '" + rest +
                      "' is not defined in the part of instance '" +
                      inst->name + "'.");
            for (const auto &[i, ids] : it->second.ids)
              if (i.empty())
                set.ids[I].insert(ids.begin(), ids.end());
            return;
          }
      const auto it = known.find(upper(unquote(token)));
      require(it != known.end(),
              where(l) + ": '" + token + "' is neither a " + what +
                " id nor the name of a " + (nodes ? "*NSET" : "*ELSET") +
                " defined above.");
      for (const auto &[i, ids] : it->second.ids)
        set.ids[i].insert(ids.begin(), ids.end());
    }



    void
    Reader::read_surface(const Keyword &k, std::size_t &i)
    {
      const Line       &head = lines[i];
      const std::string name = k.get("NAME");
      require(!name.empty(), where(head) + ": *SURFACE needs NAME=<name>.");
      const std::string type = upper(k.get("TYPE"));
      require(type.empty() || type == "ELEMENT" || type == "NODE",
              where(head) + ": *SURFACE, TYPE=" + k.get("TYPE") +
                " is not read by glide; glide reads element-based "
                "(TYPE=ELEMENT) and node-based (TYPE=NODE) surfaces. Rigid "
                "masters are declared in the scene ('Master = rigid plane' "
                "or a meshed body with 'Rigid = true').");
      Scope      &s       = scopes[scope];
      RawSurface &surface = s.surfaces[upper(name)];
      if (surface.name.empty())
        surface.name = name;
      surface.node_based    = (type == "NODE");
      const std::size_t end = data_end(i);
      for (++i; i < end; ++i)
        {
          const Line &l = lines[i];
          if (skip(l))
            continue;
          const auto items = split(l.text);
          require(!items.empty(), where(l) + ": empty surface line.");
          RawSet tmp;
          if (surface.node_based)
            {
              // <node set or node id>[, area]
              add_to_set(tmp, items[0], "", s.nsets, true, l);
              for (const auto &[inst, ids] : tmp.ids)
                for (const auto id : ids)
                  surface.entries.push_back({inst, id, -1, l});
              continue;
            }
          // <element set or element id>[, S<n>]
          int face = -1;
          if (items.size() > 1 && !items[1].empty())
            {
              const std::string  f       = upper(items[1]);
              const unsigned int n_faces = 2 * dim;
              require(f.size() >= 2 && f.size() <= 3 && f[0] == 'S' &&
                        is_integer(f.substr(1)) &&
                        std::stoi(f.substr(1)) >= 1 &&
                        std::stoi(f.substr(1)) <= static_cast<int>(n_faces),
                      where(l) + ": face identifier '" + items[1] +
                        "' of surface '" + name +
                        "': glide reads the faces S1 to S" +
                        std::to_string(n_faces) + " of " +
                        (dim == 2 ? "quadrilaterals" : "hexahedra") +
                        " (SPOS, SNEG and edge identifiers belong to shells "
                        "and beams).");
              face = std::stoi(f.substr(1)) - 1;
            }
          add_to_set(tmp, items[0], "", s.elsets, false, l);
          for (const auto &[inst, ids] : tmp.ids)
            for (const auto id : ids)
              surface.entries.push_back({inst, id, face, l});
        }
      require(!surface.entries.empty(),
              where(head) + ": the surface '" + name + "' has no faces.");
      --i;
    }



    void
    Reader::read()
    {
      for (std::size_t i = 0; i < lines.size(); ++i)
        {
          const Line &l = lines[i];
          if (skip(l))
            continue;
          std::string t = trim(l.text);
          require(t[0] == '*',
                  where(l) + ": a data line outside any keyword: '" + t +
                    "'. Every block of data starts with a keyword line "
                    "such as *NODE or *ELEMENT.");
          // A keyword line that ends with a comma continues.
          while (t.back() == ',' && i + 1 < lines.size() &&
                 trim(lines[i + 1].text).rfind("*", 0) != 0)
            t += trim(lines[++i].text);
          const Keyword     k    = parse_keyword(t);
          const std::size_t end  = data_end(i);
          const std::string name = k.name;
          // Data in another file: glide reads the keywords it uses from
          // this one only (until 2026-12-06 *ELEMENT, *NSET, *ELSET and
          // *SURFACE with INPUT= were read as empty, in silence).
          for (const char *used :
               {"NODE", "ELEMENT", "NSET", "ELSET", "SURFACE"})
            require(name != used || !k.has("INPUT"),
                    where(l) + ": *" + name +
                      ", INPUT=... is not read by glide; put the data lines "
                      "into the file, or *INCLUDE, INPUT=<file> a file that "
                      "holds the keyword line and its data.");

          if (name == "PART")
            {
              require(!k.get("NAME").empty(),
                      where(l) + ": *PART needs NAME=<name>.");
              scope             = upper(k.get("NAME"));
              part_names[scope] = k.get("NAME");
            }
          else if (name == "END PART")
            scope.clear();
          else if (name == "ASSEMBLY")
            in_assembly = true;
          else if (name == "END ASSEMBLY")
            in_assembly = false;
          else if (name == "INSTANCE")
            {
              Instance inst;
              inst.name = k.get("NAME");
              inst.part = upper(k.get("PART"));
              require(!inst.name.empty() && !inst.part.empty() &&
                        scopes.count(inst.part) && part_names.count(inst.part),
                      where(l) +
                        ": *INSTANCE needs NAME=<name> and PART=<a part "
                        "defined above>.");
              unsigned int n = 0;
              for (std::size_t j = i + 1; j < end; ++j)
                if (!skip(lines[j]))
                  {
                    const auto          items = split(lines[j].text);
                    std::vector<double> v;
                    for (const auto &x : items)
                      v.push_back(to_double(x, lines[j], "a coordinate"));
                    if (n == 0)
                      {
                        require(v.size() == 3 || (v.size() == 2 && dim == 2),
                                where(lines[j]) +
                                  ": the translation of an instance needs "
                                  "x, y, z.");
                        for (unsigned int d = 0; d < v.size(); ++d)
                          inst.translation[d] = v[d];
                      }
                    else
                      {
                        require(v.size() == 7,
                                where(lines[j]) +
                                  ": the rotation of an instance needs "
                                  "seven numbers: two points of the axis "
                                  "and the angle in degrees.");
                        // Two distinct points (until 2026-12-06 a zero
                        // axis made NaN coordinates, reported as an
                        // element of zero volume elsewhere).
                        double length = 0., size = 0.;
                        for (unsigned int d = 0; d < 3; ++d)
                          {
                            length += (v[3 + d] - v[d]) * (v[3 + d] - v[d]);
                            size = std::max(
                              {size, std::abs(v[d]), std::abs(v[3 + d])});
                          }
                        require(v[6] == 0. || std::sqrt(length) > 1e-12 * size,
                                where(lines[j]) +
                                  ": the rotation of an instance turns "
                                  "about the axis through its first two "
                                  "points, but they coincide; give two "
                                  "different points of the axis.");
                        inst.rotation = v;
                      }
                    ++n;
                  }
              instances.push_back(inst);
              i = end - 1;
              continue;
            }
          else if (name == "END INSTANCE")
            ;
          else if (name == "NODE")
            {
              require(upper(k.get("SYSTEM")).empty() ||
                        upper(k.get("SYSTEM")) == "R",
                      where(l) + ": *NODE, SYSTEM=" + k.get("SYSTEM") +
                        " is not read by glide; give rectangular "
                        "coordinates (SYSTEM=R, the default).");
              Scope  &s    = scopes[scope];
              RawSet *nset = k.get("NSET").empty() ?
                               nullptr :
                               &s.nsets[upper(k.get("NSET"))];
              if (nset && nset->name.empty())
                nset->name = k.get("NSET"), nset->line = l;
              for (std::size_t j = i + 1; j < end; ++j)
                {
                  const Line &d = lines[j];
                  if (skip(d))
                    continue;
                  const auto items = split(d.text);
                  require(is_integer(items[0]),
                          where(d) + ": '" + trim(d.text) +
                            "' is not a node line (id, x, y" +
                            (dim == 3 ? ", z" : "") +
                            "); a keyword line starts with '*'.");
                  // Coordinates left out at the end of the line, or left
                  // blank, are 0, as in Abaqus (until 2026-12-07 such lines
                  // were refused).
                  require(items.size() <= 4,
                          where(d) + ": a node line has its id and up to " +
                            "3 coordinates (id, x, y" +
                            (dim == 3 ? ", z" : "") +
                            "; coordinates left out are 0).");
                  const long            id = to_id(items[0], d, "a node id");
                  MeshFileContent::Node node;
                  for (unsigned int c = 1; c < items.size(); ++c)
                    if (!items[c].empty())
                      node.x[c - 1] = to_double(items[c], d, "a coordinate");
                  node.line       = d.number;
                  const auto prev = s.node_lines.find(id);
                  require(prev == s.node_lines.end(),
                          where(d) + ": node " + std::to_string(id) +
                            " is defined a second time (first at " +
                            earlier(prev == s.node_lines.end() ? d :
                                                                 prev->second,
                                    d) +
                            "); every node id must be defined once.");
                  s.nodes[id]      = node;
                  s.node_lines[id] = d;
                  if (nset)
                    nset->ids[""].insert(id);
                }
            }
          else if (name == "ELEMENT")
            {
              const std::string type = upper(k.get("TYPE"));
              require(!type.empty(),
                      where(l) + ": *ELEMENT needs TYPE=<element type>.");
              const ElementType et    = classify(type, dim);
              Scope            &s     = scopes[scope];
              RawSet           *elset = k.get("ELSET").empty() ?
                                          nullptr :
                                          &s.elsets[upper(k.get("ELSET"))];
              if (elset && elset->name.empty())
                elset->name = k.get("ELSET"), elset->line = l;
              for (std::size_t j = i + 1; j < end; ++j)
                {
                  if (skip(lines[j]))
                    continue;
                  const Line &d     = lines[j];
                  auto        items = split(d.text);
                  // Long elements continue on the next line(s): a line
                  // that ends with a comma, or that is full (16 entries).
                  auto continues = [&](const std::size_t j_last,
                                       const std::size_t n_items) {
                    const std::string last = trim(lines[j_last].text);
                    return j_last + 1 < end &&
                           (et.n_nodes == 0 || n_items < 1 + et.n_nodes) &&
                           ((!last.empty() && last.back() == ',') ||
                            (et.n_nodes > 0 && n_items == 16));
                  };
                  while (continues(j, items.size()))
                    {
                      const auto more = split(lines[++j].text);
                      items.insert(items.end(), more.begin(), more.end());
                    }
                  require(!items.empty(), where(d) + ": empty element line.");
                  const long id = to_id(items[0], d, "an element id");
                  require(et.n_nodes == 0 || items.size() == 1 + et.n_nodes,
                          where(d) + ": element " + std::to_string(id) +
                            " of type " + type + " has " +
                            std::to_string(items.size() - 1) + " nodes; " +
                            type + " has " + std::to_string(et.n_nodes) + ".");
                  RawElement e;
                  e.type = type;
                  e.line = d;
                  for (unsigned int c = 1; c < items.size(); ++c)
                    e.nodes.push_back(
                      items[c] == "0" ? 0 : to_id(items[c], d, "a node id"));
                  const auto prev = s.elements.find(id);
                  require(prev == s.elements.end(),
                          where(d) + ": element " + std::to_string(id) +
                            " is defined a second time (first at " +
                            earlier(prev == s.elements.end() ?
                                      d :
                                      prev->second.line,
                                    d) +
                            "); every element id must be defined once.");
                  s.elements[id] = e;
                  if (elset)
                    elset->ids[""].insert(id);
                }
            }
          else if (name == "NSET" || name == "ELSET")
            {
              const bool        nodes    = (name == "NSET");
              const std::string set_name = k.get(nodes ? "NSET" : "ELSET");
              require(!set_name.empty(),
                      where(l) + ": *" + name + " needs " + name + "=<name>.");
              Scope      &s     = scopes[scope];
              auto       &known = nodes ? s.nsets : s.elsets;
              std::string instance;
              if (k.has("INSTANCE"))
                {
                  const Instance *inst = find_instance(k.get("INSTANCE"));
                  require(in_assembly && inst,
                          where(l) + ": INSTANCE=" + k.get("INSTANCE") +
                            " names no *INSTANCE defined above.");
                  instance = upper(inst->name);
                }
              RawSet set = known[upper(set_name)];
              if (set.name.empty())
                set.name = set_name, set.line = l;
              set.internal = k.has("INTERNAL");
              for (std::size_t j = i + 1; j < end; ++j)
                {
                  const Line &d = lines[j];
                  if (skip(d))
                    continue;
                  const auto items = split(d.text);
                  if (k.has("GENERATE"))
                    {
                      require(items.size() == 2 || items.size() == 3,
                              where(d) + ": with GENERATE, a line needs "
                                         "first, last[, increment].");
                      const long a   = to_id(items[0], d, "an id");
                      const long b   = to_id(items[1], d, "an id");
                      const long inc = items.size() == 3 ?
                                         to_id(items[2], d, "an increment") :
                                         1;
                      require(b >= a,
                              where(d) + ": GENERATE needs first <= last.");
                      // Every id of the range must be defined on a line of
                      // the file, so a range of more ids than the file has
                      // lines is a mistake (a huge range filled the memory).
                      const long count = (b - a) / inc + 1;
                      require(count <= static_cast<long>(lines.size()),
                              where(d) + ": GENERATE from " +
                                std::to_string(a) + " to " + std::to_string(b) +
                                " in steps of " + std::to_string(inc) +
                                " names " + std::to_string(count) +
                                " ids, more than the file defines (it has " +
                                std::to_string(lines.size()) +
                                " lines); check the range.");
                      for (long n = 0; n < count; ++n)
                        set.ids[instance].insert(a + n * inc);
                    }
                  else if (nodes && k.has("ELSET"))
                    ; // handled below
                  else
                    for (const auto &token : items)
                      add_to_set(set, token, instance, known, nodes, d);
                }
              if (nodes && k.has("ELSET"))
                {
                  // *NSET, ELSET=e: the nodes of the elements of e.
                  RawSet elements;
                  add_to_set(
                    elements, k.get("ELSET"), instance, s.elsets, false, l);
                  for (const auto &[inst, ids] : elements.ids)
                    {
                      const Scope &owner =
                        inst.empty() ? s : scopes.at(find_instance(inst)->part);
                      for (const auto id : ids)
                        {
                          const auto e = owner.elements.find(id);
                          require(e != owner.elements.end(),
                                  where(l) + ": element " + std::to_string(id) +
                                    " of *ELSET '" + k.get("ELSET") +
                                    "' is not defined.");
                          for (const auto n : e->second.nodes)
                            if (n > 0)
                              set.ids[inst].insert(n);
                        }
                    }
                }
              known[upper(set_name)] = set;
              i                      = end - 1;
              continue;
            }
          else if (name == "SURFACE")
            {
              read_surface(k, i);
              continue;
            }
          else if (name == "NGEN" || name == "NFILL" || name == "NCOPY" ||
                   name == "NMAP" || name == "ELGEN" || name == "ELCOPY" ||
                   name == "SYSTEM" || name == "ELEMENT MATRIX" ||
                   name == "USER ELEMENT")
            throw InputError(where(l) + ": *" + name +
                             " is not read by glide; glide reads meshes given "
                             "node by node (*NODE) and element by element "
                             "(*ELEMENT). Write the input file with the "
                             "generated nodes and elements (Abaqus/CAE and "
                             "most preprocessors do).");
          // Every other keyword (materials, sections, steps, boundary
          // conditions, ...) says nothing about the mesh: skip its data.
          i = end - 1;
        }
    }



    /// Rotate @p x about the axis through a and b by angle degrees
    /// (Rodrigues' formula).
    std::array<double, 3>
    rotate(const std::array<double, 3> &x, const std::vector<double> &r)
    {
      std::array<double, 3> a{{r[0], r[1], r[2]}},
        k{{r[3] - r[0], r[4] - r[1], r[5] - r[2]}};
      const double norm = std::sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
      for (auto &c : k)
        c /= norm;
      const double                angle = r[6] * M_PI / 180.;
      std::array<double, 3>       v{{x[0] - a[0], x[1] - a[1], x[2] - a[2]}};
      const std::array<double, 3> kxv{{k[1] * v[2] - k[2] * v[1],
                                       k[2] * v[0] - k[0] * v[2],
                                       k[0] * v[1] - k[1] * v[0]}};
      const double                kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
      std::array<double, 3>       out;
      for (unsigned int d = 0; d < 3; ++d)
        out[d] = a[d] + v[d] * std::cos(angle) + kxv[d] * std::sin(angle) +
                 k[d] * kv * (1. - std::cos(angle));
      return out;
    }



    MeshFileContent
    Reader::content(const std::string &part) const
    {
      MeshFileContent c;
      c.file = file;

      // Which scope (part) and which instance of it.
      std::string     part_scope;
      const Instance *instance = nullptr;
      if (part_names.empty())
        require(part.empty(),
                "Abaqus file '" + file +
                  "' has no *PART, but the scene asks "
                  "for 'Part = " +
                  part +
                  "'; leave 'Part' empty (use 'Element "
                  "set' to pick a body out of a file without parts).");
      else
        {
          std::string list;
          for (const auto &i : instances)
            list += (list.empty() ? "" : ", ") + i.name + " (part " +
                    part_names.at(i.part) + ")";
          if (instances.empty())
            for (const auto &[u, n] : part_names)
              list += (list.empty() ? "" : ", ") + n;
          if (part.empty())
            {
              require(instances.size() == 1 ||
                        (instances.empty() && part_names.size() == 1),
                      "Abaqus file '" + file +
                        "' has several parts or instances: " + list +
                        ". Name the one this body is with 'Part'.");
              if (instances.size() == 1)
                instance = &instances[0];
              else
                part_scope = part_names.begin()->first;
            }
          else if ((instance = find_instance(part)) == nullptr)
            {
              const std::string P = upper(part);
              unsigned int      n = 0;
              for (const auto &i : instances)
                if (i.part == P)
                  {
                    instance = &i;
                    ++n;
                  }
              require((n == 1) || (instances.empty() && part_names.count(P)),
                      "Abaqus file '" + file + "': 'Part = " + part + "' " +
                        (n > 1 ? "is instanced " + std::to_string(n) +
                                   " times; name the instance" :
                                 "names no part or instance of the file") +
                        ". The file has: " + list + ".");
              if (n == 0)
                part_scope = P;
            }
          if (instance)
            part_scope = instance->part;
        }
      const std::string I = instance ? upper(instance->name) : "";
      const Scope       own =
        scopes.count(part_scope) ? scopes.at(part_scope) : Scope();
      // Assembly-level sets and surfaces of this instance (files with parts).
      const Scope *assembly =
        (!part_names.empty() && instance && scopes.count("")) ? &scopes.at("") :
                                                                nullptr;

      for (const auto &[id, node] : own.nodes)
        {
          auto n = node;
          if (instance)
            {
              // Abaqus translates an instance first, then rotates it.
              for (unsigned int d = 0; d < 3; ++d)
                n.x[d] += instance->translation[d];
              if (!instance->rotation.empty())
                n.x = rotate(n.x, instance->rotation);
            }
          c.nodes[id] = n;
        }

      for (const auto &[id, e] : own.elements)
        {
          MeshFileContent::Cell cell;
          cell.id              = id;
          cell.type            = e.type;
          cell.line            = e.line.number;
          const auto        et = classify(e.type, dim);
          const std::string label =
            "element " + std::to_string(id) + " (type " + e.type + ")";
          if (!et.refusal.empty())
            cell.problem = where(e.line) + ": element " + std::to_string(id) +
                           " has type " + e.type + ", " + et.refusal;
          const unsigned int n_corners = 1u << dim;
          for (unsigned int v = 0; v < e.nodes.size(); ++v)
            if (cell.problem.empty() && e.nodes[v] == 0 && v < n_corners)
              cell.problem = where(e.line) + ": " + label +
                             " has no corner node " + std::to_string(v + 1) +
                             ".";
            else if (cell.problem.empty() && e.nodes[v] != 0 &&
                     c.nodes.count(e.nodes[v]) == 0)
              cell.problem = where(e.line) + ": " + label +
                             " references node " + std::to_string(e.nodes[v]) +
                             ", which the file does not define.";
          if (cell.problem.empty())
            {
              // Second-order elements: their corner nodes, if every
              // mid-side node is at the middle of a straight edge.
              const auto &edges = edges_of(dim);
              for (unsigned int m = n_corners; m < e.nodes.size(); ++m)
                {
                  if (e.nodes[m] == 0 || !cell.problem.empty())
                    continue; // an omitted mid-side node: a straight edge
                  cell.midside.push_back(e.nodes[m]);
                  const auto [p, q] = edges[m - n_corners];
                  const auto &a     = c.nodes.at(e.nodes[p]).x;
                  const auto &b     = c.nodes.at(e.nodes[q]).x;
                  const auto &x     = c.nodes.at(e.nodes[m]).x;
                  double      off = 0, length = 0;
                  for (unsigned int d = 0; d < 3; ++d)
                    {
                      off += std::pow(x[d] - 0.5 * (a[d] + b[d]), 2);
                      length += std::pow(b[d] - a[d], 2);
                    }
                  off    = std::sqrt(off);
                  length = std::sqrt(length);
                  if (off > straight_edge_tolerance * length)
                    {
                      std::ostringstream s;
                      s << where(e.line) << ": " << label
                        << " has a curved or distorted edge: its mid-side "
                           "node "
                        << e.nodes[m] << " lies " << off
                        << " away from the middle of the edge between nodes "
                        << e.nodes[p] << " and " << e.nodes[q] << " (length "
                        << length
                        << "). glide reads second-order elements with their "
                           "corner nodes and straight edges only (a mid-side "
                           "node within "
                        << straight_edge_tolerance
                        << " of the edge length from its middle); use "
                           "first-order elements (e.g. CPE4, C3D8) on a mesh "
                           "fine enough for the curvature, with 'Element "
                           "degree = 2' for quadratic shape functions.";
                      cell.problem = s.str();
                    }
                }
              // Corner nodes in deal.II's lexicographic order.
              static const unsigned int to_dealii[] = {0, 1, 3, 2, 4, 5, 7, 6};
              for (unsigned int v = 0; v < n_corners; ++v)
                cell.nodes.push_back(e.nodes[to_dealii[v]]);
            }
          c.cells.push_back(cell);
        }

      // Sets: the part's own ("" instance) and the assembly's for this
      // instance.
      auto collect = [&](const std::map<std::string, RawSet>   &own_sets,
                         const std::map<std::string, RawSet>   *assembly_sets,
                         std::map<std::string, std::set<long>> &out) {
        std::map<std::string, std::string> spelled; // upper -> first name
        auto add = [&](const RawSet &s, const std::string &inst) {
          const auto it = s.ids.find(inst);
          if (it == s.ids.end() || (s.internal && &out == &c.node_sets))
            return;
          // A node set's ids must be nodes of the file (element sets are
          // checked where they are read).
          if (&out == &c.node_sets)
            for (const auto id : it->second)
              require(c.nodes.count(id) > 0,
                      where(s.line) + ": node " + std::to_string(id) +
                        " of *NSET '" + s.name + "'" +
                        (inst.empty() ? "" : " (instance '" + inst + "')") +
                        " is not defined in the file (*NODE).");
          const std::string u = upper(s.name);
          if (!spelled.count(u))
            spelled[u] = s.name;
          out[spelled[u]].insert(it->second.begin(), it->second.end());
        };
        for (const auto &[u, s] : own_sets)
          add(s, "");
        if (assembly_sets)
          for (const auto &[u, s] : *assembly_sets)
            add(s, I);
      };
      collect(own.nsets, assembly ? &assembly->nsets : nullptr, c.node_sets);
      collect(own.elsets, assembly ? &assembly->elsets : nullptr, c.cell_sets);

      // The nodes of an element set are a node set too, unless a *NSET
      // has that name.
      std::set<std::string> nset_names;
      for (const auto &[n, ids] : c.node_sets)
        nset_names.insert(upper(n));
      std::set<std::string> internal;
      for (const auto *sets :
           {&own.elsets, assembly ? &assembly->elsets : &own.elsets})
        for (const auto &[u, set] : *sets)
          if (set.internal)
            internal.insert(u);
      for (const auto &[n, ids] : c.cell_sets)
        if (!nset_names.count(upper(n)) && !internal.count(upper(n)))
          {
            auto &nodes = c.node_sets[n];
            c.element_set_nodes.insert(n);
            for (const auto id : ids)
              if (const auto e = own.elements.find(id); e != own.elements.end())
                for (const auto node : e->second.nodes)
                  if (node > 0)
                    nodes.insert(node);
          }

      auto add_surfaces = [&](const Scope &s, const std::string &inst) {
        for (const auto &[u, surface] : s.surfaces)
          for (const auto &entry : surface.entries)
            {
              if (entry.instance != inst)
                continue;
              if (surface.node_based)
                {
                  c.node_sets[surface.name].insert(entry.id);
                  continue;
                }
              MeshFileContent::Face f;
              f.cell       = entry.id;
              f.line       = entry.line.number;
              const auto e = own.elements.find(entry.id);
              require(e != own.elements.end(),
                      where(entry.line) + ": surface '" + surface.name +
                        "' names element " + std::to_string(entry.id) +
                        ", which the file does not define.");
              if (entry.face >= 0)
                {
                  f.what = "face S" + std::to_string(entry.face + 1) +
                           " of element " + std::to_string(entry.id);
                  if (classify(e->second.type, dim).refusal.empty())
                    for (const auto v : faces_of(dim)[entry.face])
                      f.nodes.push_back(e->second.nodes[v]);
                  else
                    f.what += " (type " + e->second.type + ")";
                }
              else
                f.what =
                  "the free faces of element " + std::to_string(entry.id);
              c.surfaces[surface.name].push_back(f);
            }
      };
      add_surfaces(own, "");
      if (assembly)
        add_surfaces(*assembly, I);
      return c;
    }
  } // namespace



  MeshFileContent
  read_abaqus(const std::string &file,
              const unsigned int dim,
              const std::string &part)
  {
    Reader reader(file, dim);
    reader.read();
    return reader.content(part);
  }
} // namespace glide
