#include <glide/mechanics/rotation.h>
#include <glide/scene/input_error.h>
#include <glide/scene/parameter_hint.h>
#include <glide/scene/scene.h>
#include <glide/scene/text.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /// Where each line of an expanded .prm scene came from: the file as
    /// written and its line number (expand_includes()).
    using LineOrigins = std::vector<std::pair<std::string, unsigned int>>;

    /**
     * Entries that the expanded text @p text of a .prm scene sets more than
     * once to different values, with the lines they come from (@p
     * origins): deal.II keeps the last in silence (a second 'subsection
     * Boundary condition load' turned a traction into a pressure of 0;
     * until 2026-12-06 without a word). A note per entry, for the log.
     */
    std::vector<std::string>
    entries_set_twice(const std::string &text, const LineOrigins &origins)
    {
      const auto collapse = [](const std::string &s) {
        std::string        out;
        std::istringstream in(s);
        for (std::string w; in >> w;)
          out += (out.empty() ? "" : " ") + w;
        return out;
      };
      const auto keyword = [](const std::string &line, const std::string &k) {
        if (line.size() < k.size())
          return false;
        for (std::size_t i = 0; i < k.size(); ++i)
          if (std::tolower(static_cast<unsigned char>(line[i])) != k[i])
            return false;
        return line.size() == k.size() ||
               std::isspace(static_cast<unsigned char>(line[k.size()]));
      };
      const auto where = [&](const unsigned int line) {
        if (line >= origins.size())
          return std::string("a line of the scene");
        return "line " + std::to_string(origins[line].second) + " of '" +
               origins[line].first + "'";
      };
      // path -> (value, line of the text)
      std::map<std::string, std::pair<std::string, unsigned int>> seen;
      std::map<std::string, std::string>                          twice;
      std::vector<std::string>                                    order;
      std::vector<std::string>                                    stack;
      std::istringstream                                          in(text);
      std::string                                                 line;
      for (unsigned int n = 0; std::getline(in, line); ++n)
        {
          const unsigned int first = n;
          // A line continued with a backslash (deal.II trims each line,
          // then joins it to the next).
          line = Utilities::trim(line);
          while (!line.empty() && line.back() == '\\')
            {
              std::string next;
              if (!std::getline(in, next))
                break;
              line.pop_back();
              line += Utilities::trim(next);
              ++n;
            }
          std::replace(line.begin(), line.end(), '\t', ' ');
          if (const auto hash = line.find('#'); hash != std::string::npos)
            line.erase(hash);
          line = Utilities::trim(line);
          if (keyword(line, "subsection"))
            stack.push_back(collapse(line.substr(10)));
          else if (keyword(line, "end"))
            {
              if (!stack.empty())
                stack.pop_back();
            }
          else if (keyword(line, "set"))
            {
              const auto eq = line.find('=');
              if (eq == std::string::npos)
                continue;
              std::string path;
              for (const auto &sub : stack)
                path += sub + "/";
              path += collapse(line.substr(3, eq - 3));
              const std::string value = Utilities::trim(line.substr(eq + 1));
              const auto [it, inserted] =
                seen.emplace(path, std::make_pair(value, first));
              if (inserted)
                continue;
              if (without_white_space(it->second.first) !=
                  without_white_space(value))
                {
                  if (!twice.count(path))
                    order.push_back(path);
                  twice[path] = "'" + path + "' = '" + it->second.first +
                                "' (" + where(it->second.second) +
                                ") is not used: it is set again, to '" + value +
                                "', on " + where(first) +
                                ", and the last value holds. Set each "
                                "entry once.";
                }
              it->second = {value, first};
            }
        }
      std::vector<std::string> notes;
      for (const auto &path : order)
        notes.push_back(twice[path]);
      return notes;
    }

    /// While a scene's expanded text is parsed: the origins of its lines
    /// and the name deal.II's messages give it, so that explain() names
    /// the file and line a mistake is on.
    const LineOrigins *parsed_origins = nullptr;
    std::string        parsed_name;

    /// Turn a deal.II exception from ParameterHandler into a message for
    /// people: only its explanation, not the source location in deal.II.
    std::string
    explain(const ExceptionBase &e)
    {
      std::ostringstream s;
      e.print_info(s);
      // deal.II formats its messages over several indented lines; make
      // them one line.
      std::string        text, word;
      std::istringstream in(s.str());
      while (in >> word)
        text += (text.empty() ? "" : " ") + word;
      // The line of an expanded scene (expand_includes()) as the line of
      // the file it came from.
      const std::string marker = "Line <";
      if (const auto at = text.find(marker);
          parsed_origins != nullptr && at != std::string::npos)
        {
          // The name as the message has it, its whitespace collapsed.
          std::string        name;
          std::istringstream words(parsed_name);
          for (std::string w; words >> w;)
            name += (name.empty() ? "" : " ") + w;
          // deal.II's "no such subsection" message lacks the '>' after
          // the file name: "of file <name: There is no such ...".
          auto        close = text.find("> of file <" + name + ">", at);
          std::string end   = ">";
          if (close == std::string::npos)
            {
              close = text.find("> of file <" + name + ":", at);
              end   = ">:";
            }
          const auto    from = at + marker.size();
          unsigned long line = 0;
          try
            {
              line = std::stoul(text.substr(from, close - from));
            }
          catch (const std::exception &)
            {}
          if (close != std::string::npos && line >= 1 &&
              line <= parsed_origins->size())
            {
              const auto &[file, n] = (*parsed_origins)[line - 1];
              text.replace(at,
                           close + 12 + name.size() - at,
                           "Line <" + std::to_string(n) + "> of file <" + file +
                             end);
            }
        }
      // Whatever file it names: "of file <name: There is" as
      // "of file <name>: There is", and a full stop after the subsection.
      if (const auto at = text.find(": There is no such subsection");
          at != std::string::npos)
        {
          if (const auto open = text.rfind("of file <", at);
              open != std::string::npos && text.find('>', open) > at)
            text.insert(at, ">");
          if (!text.empty() && text.back() != '.')
            text += '.';
        }
      if (text.find("Can't convert the parameter value") != std::string::npos &&
          text.find("to a double") != std::string::npos)
        {
          if (!text.empty() && text.back() == '.')
            text.pop_back();
          text += " (not a number, or beyond double precision: its "
                  "magnitude must lie between about 2.3e-308 and 1.7e308, "
                  "or be 0).";
        }
      return text;
    }

    /// The hint of parameter_hint() for a name deal.II's parser did not
    /// know, read from the line of the expanded .prm @p text that its
    /// message names; "" for other mistakes and for JSON and XML scenes.
    std::string
    hint_at_line(const std::function<void(ParameterHandler &)> &declare,
                 const ExceptionBase                           &e,
                 const std::string                             &text)
    {
      std::ostringstream s;
      e.print_info(s);
      const std::string message = s.str();
      const auto        at      = message.find("Line <");
      if (text.empty() || at == std::string::npos)
        return "";
      unsigned long number = 0;
      try
        {
          number = std::stoul(message.substr(at + 6));
        }
      catch (const std::exception &)
        {
          return "";
        }
      std::istringstream in(text);
      std::string        line;
      unsigned long      read = 0;
      while (read < number && std::getline(in, line))
        ++read;
      if (number == 0 || read < number)
        return "";
      if (const auto hash = line.find('#'); hash != std::string::npos)
        line.erase(hash);
      line                  = Utilities::trim(line);
      const auto       path = subsection_path_at(text, number);
      ParameterHandler prm;
      declare(prm);
      if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
        return parameter_hint(prm,
                              path,
                              Utilities::trim(
                                line.substr(4, line.find('=') - 4)),
                              false);
      if (line.rfind("subsection ", 0) == 0)
        return parameter_hint(prm,
                              path,
                              Utilities::trim(line.substr(11)),
                              true);
      return "";
    }

    /// The format of a scene file as deal.II's ParameterHandler decides it:
    /// by its extension, in any case ("prm", "xml", "json"; empty for
    /// another, which deal.II refuses).
    std::string
    scene_format(const std::string &file)
    {
      const std::string extension =
        std::filesystem::path(file).extension().string();
      std::string lower;
      for (const char c : extension)
        lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (lower == ".prm" || lower == ".xml" || lower == ".json")
        return lower.substr(1);
      return "";
    }

    /// deal.II's message for a value of an XML or JSON scene that does not
    /// match its pattern names the value, not the entry (a .prm file's
    /// names both): add the entries of @p file that hold that value.
    std::string
    name_the_entry(const std::string &file, const std::string &message)
    {
      const std::string head = "The string <", tail = "> does not match";
      const auto        a      = message.find(head);
      const auto        b      = message.find(tail);
      const std::string format = scene_format(file);
      if (a == std::string::npos || b == std::string::npos || b < a ||
          (format != "xml" && format != "json"))
        return message;
      const std::string value =
        message.substr(a + head.size(), b - a - head.size());
      // deal.II writes the names of an XML file with characters other than
      // letters and digits as _XX (hex); JSON names are plain.
      const auto demangle = [&](const std::string &name) {
        if (format != "xml")
          return name;
        std::string out;
        for (std::size_t i = 0; i < name.size(); ++i)
          if (name[i] == '_' && i + 2 < name.size() &&
              std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
              std::isxdigit(static_cast<unsigned char>(name[i + 2])))
            {
              out += static_cast<char>(
                std::stoi(name.substr(i + 1, 2), nullptr, 16));
              i += 2;
            }
          else
            out += name[i];
        return out;
      };
      std::vector<std::string> found;
      try
        {
          boost::property_tree::ptree tree;
          if (format == "xml")
            boost::property_tree::read_xml(file, tree);
          else
            boost::property_tree::read_json(file, tree);
          const std::function<void(const boost::property_tree::ptree &,
                                   const std::string &)>
            walk = [&](const boost::property_tree::ptree &t,
                       const std::string                 &path) {
              for (const auto &[key, child] : t)
                {
                  if (key == "<xmlattr>" || key == "<xmlcomment>" ||
                      key == "documentation" || key == "pattern" ||
                      key == "pattern_description" || key == "default_value")
                    continue;
                  const std::string name =
                    key == "value" || key == "ParameterHandler" ?
                      path :
                      (path.empty() ? "" : path + "/") + demangle(key);
                  if (child.empty())
                    {
                      if (Utilities::trim(child.data()) == value &&
                          !name.empty())
                        found.push_back("'" + name + "'");
                    }
                  else
                    walk(child, name);
                }
            };
          walk(tree, "");
        }
      catch (...)
        {
          return message;
        }
      if (found.empty())
        return message;
      std::string list;
      for (const auto &f : found)
        list += (list.empty() ? "" : " or ") + f;
      return message + " The value is that of " + list + ".";
    }

    /// The UTF-8 byte-order mark some Windows editors write at the start
    /// of a text file.
    constexpr const char *byte_order_mark = "\xEF\xBB\xBF";

    /// The path an 'include' statement of @p including names: relative
    /// to the directory of the including file, as the mesh files of a scene
    /// are; if nothing is there, relative to the current directory (the
    /// rule of deal.II's ParameterHandler, which glide followed until
    /// 2026-12-06).
    std::string
    include_path(const std::string &including, const std::string &name)
    {
      namespace fs = std::filesystem;
      const fs::path written(name);
      if (written.is_absolute())
        return name;
      std::error_code ec;
      const fs::path  beside = fs::path(including).parent_path() / written;
      // As the operating system resolves it ('..' after a symbolic link
      // is not the link's parent); normalized in messages only.
      if (fs::exists(beside, ec))
        return beside.string();
      if (fs::exists(written, ec))
        return name;
      throw InputError(
        "The scene file '" + including + "' includes '" + name +
        "', which was found neither next to it ('" +
        beside.lexically_normal().string() +
        "') nor in the current directory (" + fs::current_path(ec).string() +
        "). Check the path; a relative path is taken from the directory "
        "of the file that includes it.");
    }

    /**
     * The text of the .prm scene file @p file with its 'include' statements
     * replaced by the files they name (include_path()), appended to
     * @p text, with the origin of each line in @p origins. deal.II's
     * ParameterHandler would open included files itself, relative to the
     * current directory. Refuses a file that includes itself, directly or
     * through others (deal.II's parser recursed until the stack
     * overflowed: a segmentation fault without a message) and an include
     * of a directory. A UTF-8 byte-order mark at the start of a file is
     * skipped (deal.II took it for part of the first line and refused a
     * line that looks right). @p chain holds the files that lead to
     * @p file, as written and as canonical paths.
     */
    void
    expand_includes(const std::string                                &file,
                    std::vector<std::pair<std::string, std::string>> &chain,
                    std::string                                      &text,
                    LineOrigins                                      &origins)
    {
      std::error_code   ec;
      const std::string canonical =
        std::filesystem::weakly_canonical(file, ec).string();
      const std::string top = chain.empty() ? file : chain.front().first;
      std::string       path;
      for (const auto &[written, c] : chain)
        path += "'" + written + "' -> ";
      path += "'" + file + "'";
      for (const auto &link : chain)
        require(link.second != canonical,
                "The scene file '" + top + "' includes itself: " + path +
                  ". Remove the 'include' that leads back to a file that "
                  "includes it.");
      require(chain.size() < 32,
              "The scene file '" + top +
                "' nests 'include' statements more than 32 deep: " + path +
                ".");
      if (!chain.empty())
        require(!std::filesystem::is_directory(file, ec),
                "The scene file '" + chain.back().first + "' includes '" +
                  file +
                  "', which is a directory; 'include' takes the path of a "
                  ".prm file.");
      require_regular_file(file,
                           chain.empty() ? std::string("The scene file") :
                                           "The file included by '" +
                                             chain.back().first + "',",
                           "give the path of a .prm file.");
      std::ifstream in(file);
      require(static_cast<bool>(in),
              "The scene file '" + file + "'" +
                (chain.empty() ?
                   std::string() :
                   " (included by '" + chain.back().first + "')") +
                " cannot be read. Check that it exists and can be read.");
      // The scene's own file is checked by deal.II, as a whole.
      const bool        included = !chain.empty();
      const std::string includer =
        included ? "' (included by '" + chain.back().first + "')" : "'";
      chain.emplace_back(file, canonical);
      std::string line;
      bool        continued = false;
      // deal.II read each included file on its own and refused one that
      // does not close the subsections it opens: an 'end' left out there
      // would otherwise put the rest of the including file into that
      // subsection, and the message would name an entry of the including
      // file. The lines of the subsections this file opened and has not
      // closed, from its statements (continued lines joined).
      std::vector<unsigned int> opened;
      const auto                check_balance = [&](const std::string &s,
                                     const unsigned int n) {
        if (s.rfind("subsection ", 0) == 0 || s.rfind("SUBSECTION ", 0) == 0)
          opened.push_back(n);
        else if (s == "end" || s == "END" || s.rfind("end ", 0) == 0 ||
                 s.rfind("END ", 0) == 0)
          {
            require(!opened.empty(),
                    "Line " + std::to_string(n) + " of the scene file '" +
                      file + includer +
                      ": this 'end' closes no subsection that this file "
                                     "opened. An included file must close exactly the "
                                     "subsections it opens (deal.II reads each file on its "
                                     "own); remove the 'end', or put it and its "
                                     "'subsection' into one file.");
            opened.pop_back();
          }
      };
      // The physical lines of the statement being read (deal.II joins a
      // line that ends in a backslash with the next before it removes
      // comments: a continued comment swallows the next line), with the
      // number of its first line.
      std::string  joined, pending;
      unsigned int first = 0, n_pending = 0;
      const auto   finish = [&]() {
        std::string statement = joined;
        if (const auto hash = statement.find('#'); hash != std::string::npos)
          statement.erase(hash);
        statement = Utilities::trim(statement);
        joined.clear();
        if (included)
          check_balance(statement, first);
        if (statement.rfind("include ", 0) == 0 ||
            statement.rfind("INCLUDE ", 0) == 0)
          {
            const std::string name = Utilities::trim(statement.substr(8));
            if (!name.empty())
              {
                expand_includes(include_path(file, name), chain, text, origins);
                pending.clear();
                n_pending = 0;
                return;
              }
          }
        text += pending;
        for (unsigned int k = 0; k < n_pending; ++k)
          origins.emplace_back(file, first + k);
        pending.clear();
        n_pending = 0;
      };
      for (unsigned int n = 1; std::getline(in, line); ++n)
        {
          if (n == 1 && line.rfind(byte_order_mark, 0) == 0)
            line.erase(0, 3);
          // As deal.II reads a line: tabs as spaces, without a CR.
          std::string statement = line;
          if (!statement.empty() && statement.back() == '\r')
            statement.pop_back();
          std::replace(statement.begin(), statement.end(), '\t', ' ');
          statement = Utilities::trim(statement);
          if (n_pending == 0)
            first = n;
          pending += line + "\n";
          ++n_pending;
          continued = !statement.empty() && statement.back() == '\\';
          joined +=
            continued ? statement.substr(0, statement.size() - 1) : statement;
          if (!continued)
            finish();
        }
      // deal.II read each included file on its own, so a join ends with
      // the file (an empty line ends it).
      if (continued)
        {
          pending += "\n";
          ++n_pending;
          finish();
        }
      require(opened.empty(),
              "The scene file '" + file + includer + " leaves " +
                std::to_string(opened.size()) +
                " subsection(s) open (the last opened on line " +
                (opened.empty() ? std::string() :
                                  std::to_string(opened.back())) +
                "). An included file must close every subsection it opens; "
                "add the missing 'end'.");
      chain.pop_back();
    }

    std::vector<std::string>
    split_names(const std::string &list)
    {
      std::vector<std::string> names;
      for (const auto &n : Utilities::split_string_list(list, ','))
        if (!n.empty())
          names.push_back(n);
      return names;
    }

    void
    check_names(const std::vector<std::string> &names,
                const std::string              &parameter)
    {
      std::set<std::string> seen;
      for (const auto &n : names)
        {
          require(std::all_of(n.begin(),
                              n.end(),
                              [](const char c) {
                                return std::isalnum(
                                         static_cast<unsigned char>(c)) ||
                                       c == '_' || c == '-';
                              }),
                  "Parameter '" + parameter + "': the name '" + n +
                    "' may contain only letters, digits, '_' and '-'.");
          require(seen.insert(n).second,
                  "Parameter '" + parameter + "': the name '" + n +
                    "' appears twice; names must be unique.");
        }
    }

    /**
     * The scene name becomes a directory under 'Output/Directory' and the
     * prefix of every file glide writes: it must stay inside that
     * directory and must not be a dot-name ('.' once made glide write into
     * the output directory itself, '../x' outside it).
     */
    void
    check_scene_name(const std::string &name,
                     const std::string &file,
                     const std::string &stem)
    {
      const std::string where = "In scene file '" + file + "': ";
      require(!name.empty(),
              where +
                "the scene name is empty: it defaults to the scene "
                "file's name without extension, which is empty for '" +
                file + "'. Set 'Scene name', e.g. 'set Scene name = run1'.");
      const bool        from_file = (name == stem);
      const std::string what =
        from_file ? "the scene name '" + name +
                      "' (the scene file's name without extension)" :
                    "parameter 'Scene name' = '" + name + "'";
      require(name.find('/') == std::string::npos &&
                name.find('\\') == std::string::npos,
              where + what +
                " contains a path separator; the results go to "
                "<Output/Directory>/<Scene name>/, so choose the directory "
                "with 'Output/Directory' and a plain name here, e.g. "
                "'hertz-fine'.");
      require(name[0] != '.',
              where + what +
                " starts with '.'; names such as '.', '..' or '.hidden' "
                "would put the results into the output directory itself, "
                "outside it, or hide them. Use a plain name, e.g. "
                "'hertz-fine'" +
                (from_file ? " (set 'Scene name')." : "."));
      for (const char c : name)
        require(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f,
                where + what +
                  " contains a control character; use letters, digits, "
                  "'-' and '_'.");
    }

    const std::vector<std::string> example_bodies{"body"};
    const std::vector<std::string> example_conditions{"example"};
    const std::vector<std::string> example_node_sets{"example"};
    const std::vector<std::string> example_pairs{"example"};
  } // namespace



  void
  Scene::declare_parameters(ParameterHandler               &prm,
                            const std::vector<std::string> &bodies,
                            const std::vector<std::string> &conditions,
                            const std::vector<std::string> &node_sets,
                            const std::vector<std::string> &contact_pairs)
  {
    prm.declare_entry("Scene name",
                      "",
                      Patterns::Anything(),
                      "Name of the scene; results go to "
                      "<Output/Directory>/<Scene name>/. Empty: the scene "
                      "file's name without extension. A plain name: no '/' "
                      "or '\\', not starting with '.'.");
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension: 2 for plane strain and "
                      "axisymmetric analysis, 3 for 3D.");
    prm.declare_entry("Analysis type",
                      "plane strain",
                      Patterns::Selection("plane strain|axisymmetric|3d"),
                      "plane strain (2D, per unit thickness), axisymmetric "
                      "(2D, x = radius r >= 0, y = axial z; forces and "
                      "reactions are totals over the full 360 degrees), or "
                      "3d.");

    prm.enter_subsection("Discretization");
    prm.declare_entry("Element degree",
                      "1",
                      Patterns::Integer(1, 2),
                      "Polynomial degree of the Lagrange elements (FE_Q): 1 "
                      "or 2.");
    prm.declare_entry("Geometric nonlinearity",
                      "false",
                      Patterns::Bool(),
                      "false: small strain, linear elastic bodies. true: "
                      "finite strain, compressible neo-Hookean bodies "
                      "(large displacements and rotations).");
    prm.leave_subsection();

    prm.declare_entry("Bodies",
                      "body",
                      Patterns::List(Patterns::Anything(), 1),
                      "Comma-separated names of the bodies; each name gets "
                      "a subsection 'Body <name>'. Surfaces are then named "
                      "<body>.<surface>.");
    prm.declare_entry("Boundary conditions",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Comma-separated names of boundary conditions; each "
                      "name gets a subsection 'Boundary condition <name>'.");
    prm.declare_entry("Node sets",
                      "",
                      Patterns::List(Patterns::Anything()),
                      "Comma-separated names of node sets defined by points; "
                      "each name gets a subsection 'Node set <name>'. Every "
                      "surface is also a node set under its own name.");

    prm.declare_entry(
      "Contact pairs",
      "",
      Patterns::List(Patterns::Anything()),
      "Comma-separated names of contact pairs; each name gets a "
      "subsection 'Contact pair <name>'. Empty: no contact, and "
      "no contact machinery is built.");

    for (const auto &b : bodies)
      {
        prm.enter_subsection("Body " + b);
        MeshParameters::declare_parameters(prm);
        MaterialParameters::declare_parameters(prm);
        prm.declare_entry("Body force",
                          "",
                          Patterns::Anything(),
                          "Body force per unit reference volume as "
                          "';'-separated components in x, y, (z,) t, e.g. "
                          "'0; -9.81*7850*t'. Empty: none.");
        prm.enter_subsection("Rigid body");
        prm.declare_entry(
          "Rigid",
          "false",
          Patterns::Bool(),
          "true: a meshed rigid body (as Abaqus' *RIGID BODY): every node "
          "follows the rigid motion below, the material does not matter "
          "(it does not count for E_max), and its surfaces can be contact "
          "masters (smoothed like deformable ones). No boundary condition "
          "may act on it.");
        prm.declare_entry("Translation",
                          "",
                          Patterns::Anything(),
                          "Translation of the rigid body as ';'-separated "
                          "components, functions of t. Empty: none.");
        prm.declare_entry("Rotation",
                          "0",
                          Patterns::Anything(),
                          "Rotation angle (radians, right-hand rule about "
                          "'Rotation axis') as a function of t, about "
                          "'Rotation center'.");
        prm.declare_entry("Rotation center",
                          "",
                          Patterns::List(Patterns::Double(), 0, 3),
                          "Center of the rotation (reference "
                          "configuration), comma-separated. Empty: origin.");
        prm.declare_entry("Rotation axis",
                          "0, 0, 1",
                          Patterns::Anything(),
                          "Axis of the rotation, three components "
                          "(normalized); 3D only, in 2D rotations are about "
                          "z.");
        prm.leave_subsection();
        prm.leave_subsection();
      }
    for (const auto &c : conditions)
      {
        prm.enter_subsection("Boundary condition " + c);
        BoundaryConditionParameters::declare_parameters(prm);
        prm.leave_subsection();
      }
    for (const auto &n : node_sets)
      {
        prm.enter_subsection("Node set " + n);
        NodeSetParameters::declare_parameters(prm);
        prm.leave_subsection();
      }

    for (const auto &c : contact_pairs)
      {
        prm.enter_subsection("Contact pair " + c);
        ContactPairParameters::declare_parameters(prm);
        prm.leave_subsection();
      }

    prm.enter_subsection("Verification");
    prm.declare_entry(
      "Manufactured solution",
      "none",
      Patterns::Selection("none|trigonometric"),
      "none, or a manufactured solution for convergence studies "
      "(geometrically linear scenes only): glide then sets the body force "
      "and the prescribed displacements of every 'displacement' boundary "
      "condition from the exact solution and writes L2 and H1 errors into "
      "the statistics table.");
    prm.leave_subsection();

    NonlinearSolverParameters::declare_parameters(prm);
    LinearSolverParameters::declare_parameters(prm);
    LoadSteppingParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm);
  }



  void
  Scene::parse_parameters(ParameterHandler &prm)
  {
    if (name.empty())
      name = prm.get("Scene name");
    dimension           = prm.get_integer("Dimension");
    const std::string a = prm.get("Analysis type");
    analysis            = (a == "plane strain" ? AnalysisType::plane_strain :
                           a == "axisymmetric" ? AnalysisType::axisymmetric :
                                                 AnalysisType::three_dimensional);
    require(!(analysis == AnalysisType::three_dimensional && dimension != 3),
            "Scene '" + file +
              "': 'Analysis type = 3d' needs 'Dimension = 3'.");
    require(!(analysis != AnalysisType::three_dimensional && dimension == 3),
            "Scene '" + file + "': 'Analysis type = " + a +
              "' is a 2D analysis and cannot be combined with 'Dimension = "
              "3'; use 'Analysis type = 3d' or 'Dimension = 2'.");

    prm.enter_subsection("Discretization");
    degree                 = prm.get_integer("Element degree");
    geometric_nonlinearity = prm.get_bool("Geometric nonlinearity");
    prm.leave_subsection();

    for (auto &body : bodies)
      {
        const std::string path = "Body " + body.name;
        prm.enter_subsection(path);
        try
          {
            body.mesh.parse_parameters(prm, path, directory, dimension);
          }
        catch (const InputError &e)
          {
            // Mistakes in the mesh file name the file and line; say which
            // body it is.
            const std::string what = e.what();
            if (what.rfind("Mesh file", 0) == 0 ||
                what.rfind("Abaqus file", 0) == 0 ||
                what.rfind("Gmsh file", 0) == 0)
              throw InputError("Body '" + body.name + "': " + what);
            throw;
          }
        body.mesh.axisymmetric = (analysis == AnalysisType::axisymmetric);
        body.material.parse_parameters(prm, path);
        body.body_force = prm.get("Body force");
        prm.enter_subsection("Rigid body");
        body.rigid             = prm.get_bool("Rigid");
        body.rigid_translation = prm.get("Translation");
        body.rigid_rotation    = prm.get("Rotation");
        {
          const auto a =
            parse_rotation_axis(prm.get("Rotation axis"),
                                dimension,
                                path + "/Rigid body/Rotation axis");
          body.rigid_axis = {{a[0], a[1], a[2]}};
        }
        body.rigid_center.assign(dimension, 0.);
        if (!prm.get("Rotation center").empty())
          {
            const auto c = read_numbers(prm.get("Rotation center"),
                                        path + "/Rigid body/Rotation center");
            require(c.size() == dimension,
                    "Parameter '" + path +
                      "/Rigid body/Rotation center' needs " +
                      std::to_string(dimension) +
                      " comma-separated coordinates.");
            for (unsigned int d = 0; d < dimension; ++d)
              body.rigid_center[d] = c[d];
          }
        prm.leave_subsection();
        prm.leave_subsection();
      }
    for (auto &bc : boundary_conditions)
      {
        prm.enter_subsection("Boundary condition " + bc.name);
        bc.parse_parameters(prm, bc.name, dimension);
        prm.leave_subsection();
      }
    for (auto &ns : node_sets)
      {
        prm.enter_subsection("Node set " + ns.name);
        ns.parse_parameters(prm, ns.name, dimension);
        prm.leave_subsection();
      }
    // Node sets of mesh files: <body>.<set>, on that body's vertices only.
    // The vertices of a body are copies of the file's nodes, so a tolerance
    // far below the smallest edge finds exactly them.
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].mesh.imported)
        for (const auto &[set, points] : bodies[b].mesh.imported->node_sets)
          {
            NodeSetParameters ns;
            ns.name      = bodies[b].name + "." + set;
            ns.body      = b;
            ns.tolerance = 1e-6 * bodies[b].mesh.imported->smallest_edge;
            for (const auto &x : points)
              ns.points.emplace_back(x.begin(), x.begin() + dimension);
            node_sets.push_back(ns);
          }

    for (auto &cp : contact_pairs)
      {
        prm.enter_subsection("Contact pair " + cp.name);
        cp.parse_parameters(prm, cp.name, dimension);
        prm.leave_subsection();
      }

    prm.enter_subsection("Verification");
    manufactured_solution = prm.get("Manufactured solution");
    prm.leave_subsection();

    nonlinear_solver.parse_parameters(prm);
    if (nonlinear_solver.strategy == "automatic")
      {
        nonlinear_solver.strategy =
          contact_pairs.empty() ? "line search" : "newton";
        nonlinear_solver.retry_with_line_search = !contact_pairs.empty();
      }
    linear_solver.parse_parameters(prm);
    load_stepping.parse_parameters(prm);
    output.parse_parameters(prm);
  }



  void
  Scene::check() const
  {
    std::set<std::string> body_names;
    for (const auto &b : bodies)
      body_names.insert(b.name);
    std::set<std::string> node_set_names;
    for (const auto &n : node_sets)
      node_set_names.insert(n.name);

    // Lists split at commas: a mesh file's group named 'top, loaded'
    // becomes 'part.top' and 'loaded'.
    const auto comma_hint = [](const std::string &list) -> std::string {
      if (list.find(',') == std::string::npos)
        return "";
      return " The list '" + list +
             "' was split at its commas; a surface or node set whose name "
             "has a comma (a group of a mesh file) cannot be named: rename "
             "it in the mesh file.";
    };
    for (const auto &bc : boundary_conditions)
      {
        const std::string path = "Boundary condition " + bc.name + "/Surface";
        require(!bc.surface.empty(),
                "Parameter '" + path +
                  "' is empty; name a surface as <body>.<surface>, e.g. "
                  "'block.bottom'.");
        // Forces and Dirichlet conditions may act on a node set.
        if ((bc.type == BoundaryConditionType::force || bc.is_dirichlet()) &&
            node_set_names.count(bc.surface) > 0)
          continue;
        for (const auto &surface :
             Utilities::split_string_list(bc.surface, ','))
          {
            // A list may mix surfaces and node sets (Elasticity::setup).
            if ((bc.type == BoundaryConditionType::force ||
                 bc.is_dirichlet()) &&
                node_set_names.count(surface) > 0)
              continue;
            const auto dot = surface.find('.');
            require(dot != std::string::npos,
                    "Parameter '" + path + "' = '" + surface +
                      "' is not of the form <body>.<surface> (or the name of "
                      "a node set, for forces and prescribed "
                      "displacements)." +
                      comma_hint(bc.surface));
            require(body_names.count(surface.substr(0, dot)) > 0,
                    "Parameter '" + path + "' = '" + surface +
                      "' names the body '" + surface.substr(0, dot) +
                      "', but the scene has no such body (see 'Bodies').");
          }
        require(!(bc.type == BoundaryConditionType::zsymm && dimension == 2),
                "Boundary condition '" + bc.name +
                  "': ZSYMM needs a 3D scene; in 2D use XSYMM or YSYMM.");
      }

    for (const auto &cp : contact_pairs)
      for (const auto &[set, normal] : cp.master_normals)
        {
          const auto dot = set.find('.');
          require(node_set_names.count(set) > 0 ||
                    (dot != std::string::npos &&
                     body_names.count(set.substr(0, dot)) > 0),
                  "Parameter 'Contact pair " + cp.name + "/Master normals': '" +
                    set +
                    "' is neither a node set of this scene (see 'Node sets') "
                    "nor a surface <body>.<surface>.");
        }
    for (const auto &cp : contact_pairs)
      {
        // A node-based slave surface: the name of a node set.
        if (node_set_names.count(cp.slave) > 0)
          continue;
        for (const auto &surface : Utilities::split_string_list(cp.slave, ','))
          {
            const std::string path = "Contact pair " + cp.name + "/Slave";
            const auto        dot  = surface.find('.');
            require(dot != std::string::npos &&
                      body_names.count(surface.substr(0, dot)) > 0,
                    "Parameter '" + path + "' = '" + surface +
                      "' is not a surface <body>.<surface> of a body of this "
                      "scene, nor the name of a node set." +
                      comma_hint(cp.slave));
          }
      }

    // Two pairs that constrain one slave surface against one master put
    // two constraints on each node (the direct solver failed on the
    // singular system after 6 cut-backs).
    for (std::size_t i = 0; i < contact_pairs.size(); ++i)
      for (std::size_t j = i + 1; j < contact_pairs.size(); ++j)
        {
          const auto &a = contact_pairs[i], &b = contact_pairs[j];
          if (a.master_type != MasterType::surface ||
              b.master_type != MasterType::surface)
            continue;
          const auto list = [](const std::string &text) {
            const auto            v = Utilities::split_string_list(text, ',');
            std::set<std::string> names(v.begin(), v.end());
            return names;
          };
          const auto slaves_a = list(a.slave), slaves_b = list(b.slave);
          const auto masters_a = list(a.master), masters_b = list(b.master);
          const auto shared = [](const std::set<std::string> &x,
                                 const std::set<std::string> &y) {
            for (const auto &n : x)
              if (y.count(n) > 0)
                return n;
            return std::string();
          };
          const std::string slave  = shared(slaves_a, slaves_b);
          const std::string master = shared(masters_a, masters_b);
          require(slave.empty() || master.empty(),
                  "Contact pairs '" + a.name + "' and '" + b.name +
                    "' both constrain the slave surface '" + slave +
                    "' against the master surface '" + master +
                    "': each of its nodes would carry two constraints. "
                    "Remove one of the pairs from 'Contact pairs'.");
        }

    require(!(manufactured_solution != "none" && geometric_nonlinearity),
            "Parameter 'Verification/Manufactured solution' needs a "
            "geometrically linear scene ('Discretization/Geometric "
            "nonlinearity = false').");
    // The manufactured body force and boundary values make the exact
    // solution that of the bodies alone; contact forces are not part of
    // it, so the error columns would measure nothing.
    require(!(manufactured_solution != "none" && !contact_pairs.empty()),
            "Parameter 'Verification/Manufactured solution' needs a scene "
            "without contact ('Contact pairs' empty): the manufactured "
            "solution knows no contact forces, so its error columns would "
            "be meaningless.");
    // Its boundary values are those of 'displacement' conditions on every
    // component; any other condition (fixed, symmetry, a traction, a
    // component left free) holds the body to other values, and the error
    // columns measured the mismatch (until 2026-12-06: 'fixed' instead of
    // 'displacement' tripled the L2 error).
    if (manufactured_solution != "none")
      for (const auto &bc : boundary_conditions)
        {
          bool all = true;
          for (unsigned int d = 0; d < dimension; ++d)
            all = all && bc.components[d];
          require(bc.type == BoundaryConditionType::displacement && all,
                  "Parameter 'Verification/Manufactured solution' takes the "
                  "boundary values from the manufactured solution on "
                  "'Type = displacement' conditions on all components only, "
                  "but 'Boundary condition " +
                    bc.name +
                    "' is another kind or leaves a component free, so the "
                    "error columns would measure the mismatch. Make it 'Type "
                    "= displacement' with every component (its 'Function' "
                    "is then not used), or remove it.");
        }

    // A displacement condition's expression for a component it leaves
    // free is not used: one that is not 0 is a mistake ('Components = z'
    // with '0; -0.02*t; 0' loaded nothing, exit 0).
    for (const auto &bc : boundary_conditions)
      {
        const std::string path = "Boundary condition " + bc.name;
        if (bc.type == BoundaryConditionType::displacement)
          {
            const auto parts = Utilities::split_string_list(bc.function, ';');
            for (unsigned int d = 0; d < dimension && d < parts.size(); ++d)
              {
                if (bc.components[d])
                  continue;
                double value = 1.;
                try
                  {
                    value = Utilities::string_to_double(parts[d]);
                  }
                catch (...)
                  {}
                const std::string name(1, "xyz"[d]);
                require(value == 0.,
                        "Parameter '" + path + "/Function' gives component " +
                          name + " the expression '" + parts[d] +
                          "', but 'Components' leaves " + name +
                          " free, so it is not used. Add " + name +
                          " to 'Components', or write 0 there.");
              }
          }
      }

    // Every result file's name fits the file systems' limit of 255 bytes
    // (NAME_MAX), with room for 6-digit step numbers and the '.tmp' of a
    // file being written: <scene name>-NNNNNN.vtu.tmp and
    // contact-<pair>-NNNNNN.csv.tmp. A longer name failed with an
    // input/output error after the first load step.
    constexpr std::size_t name_max     = 255;
    const std::size_t     scene_suffix = std::string("-000000.vtu.tmp").size();
    require(name.size() + scene_suffix <= name_max,
            "The scene name '" + name.substr(0, 40) + "...' has " +
              std::to_string(name.size()) +
              " characters: the result files are named <scene "
              "name>-NNNN.vtu, and file names may have at most " +
              std::to_string(name_max) +
              " bytes. Set 'Scene name' to at most " +
              std::to_string(name_max - scene_suffix) + " characters.");
    const std::size_t pair_affix =
      std::string("contact-").size() + std::string("-000000.csv.tmp").size();
    for (const auto &cp : contact_pairs)
      require(cp.name.size() + pair_affix <= name_max,
              "The contact pair name '" + cp.name.substr(0, 40) + "...' has " +
                std::to_string(cp.name.size()) +
                " characters: its result files are named contact-<pair>-"
                "NNNN.csv, and file names may have at most " +
                std::to_string(name_max) +
                " bytes. Give the pair a name of at most " +
                std::to_string(name_max - pair_affix) +
                " characters in 'Contact pairs'.");

    check_size();

    for (const auto &b : bodies)
      {
        b.mesh.check_sizes(dimension, "Body " + b.name);
        if (analysis == AnalysisType::axisymmetric && b.mesh.type != "file")
          {
            // The axisymmetric meridian plane is x = r >= 0.
            const bool centered_shape = (b.mesh.type != "block");
            if (centered_shape)
              require(b.mesh.center[0] - ((b.mesh.type == "sphere octant" ||
                                           b.mesh.type == "hertz") ?
                                            0. :
                                            b.mesh.radius) >=
                        -1e-12 * b.mesh.radius,
                      "Body '" + b.name +
                        "': in an axisymmetric scene the mesh must lie in "
                        "x = r >= 0; move 'Center' or use 'sphere octant' "
                        "for a solid of revolution touching the axis.");
            else
              require(b.mesh.lower_corner[0] >= 0.,
                      "Body '" + b.name +
                        "': in an axisymmetric scene the block must lie in "
                        "x = r >= 0; change 'Block/Lower corner'.");
          }
        if (analysis == AnalysisType::axisymmetric && b.mesh.imported)
          {
            // A mesh file's nodes too (until 2026-12-06 accepted: the part
            // at r < 0 counted with negative weight in every integral).
            // Round-off below 1e-6 of the mesh's extent is the axis (a
            // file written in single precision).
            const auto  &vertices = b.mesh.imported->vertices;
            double       extent = 0., lowest = 0.;
            unsigned int n = 0, deepest = 0;
            for (const auto &v : vertices)
              extent = std::max({extent, std::abs(v[0]), std::abs(v[1])});
            for (unsigned int k = 0; k < vertices.size(); ++k)
              if (vertices[k][0] < -1e-6 * extent)
                {
                  ++n;
                  if (vertices[k][0] < lowest)
                    {
                      lowest  = vertices[k][0];
                      deepest = k;
                    }
                }
            if (n > 0)
              {
                std::ostringstream text;
                text << "Body '" << b.name << "': in an axisymmetric scene the "
                     << "mesh must lie in x = r >= 0 (x is the radius), but "
                     << n << " node(s) of the mesh file '" << b.mesh.file
                     << "' lie at x < 0, the farthest at ("
                     << vertices[deepest][0] << ", " << vertices[deepest][1]
                     << "). Move the mesh to r >= 0, or model the part on one "
                        "side of the axis only.";
                throw InputError(text.str());
              }
          }
      }
  }



  namespace
  {
    /// The memory a process may use: the machine's physical memory, or
    /// less where the address space is limited (`ulimit -v`), times the
    /// number of processes (as if each had a machine of its own); and the
    /// end of a sentence that says which.
    std::pair<double, std::string>
    machine_memory()
    {
      const double page  = static_cast<double>(sysconf(_SC_PAGESIZE));
      double       bytes = page * static_cast<double>(sysconf(_SC_PHYS_PAGES));
      std::string  what  = "the machine has ";
      rlimit       limit;
      if (getrlimit(RLIMIT_AS, &limit) == 0 &&
          limit.rlim_cur != RLIM_INFINITY &&
          static_cast<double>(limit.rlim_cur) < bytes)
        {
          bytes = static_cast<double>(limit.rlim_cur);
          what  = "the process's address space is limited (ulimit -v) to ";
        }
      bytes *= dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      std::ostringstream text;
      text << std::setprecision(3) << what << bytes / (1 << 30) << " GiB";
      return {bytes, text.str()};
    }
  } // namespace



  double
  Scene::memory_lower_bound(const double cells,
                            const double bytes_per_cell) const
  {
    // DoFs of the Lagrange elements and the Jacobian's entries (12 bytes
    // each: value and column index; (2p+1)^dim vertex neighbours per row
    // and component) plus the cell data of deal.II and p4est (at least
    // 200 bytes per cell). The direct solver's factors, the VTU output and
    // the contact data come on top.
    const double dofs = cells * std::pow(degree, dimension) * dimension;
    const double entries_per_row =
      dimension * std::pow(2. * degree + 1., dimension);
    return std::max(200., bytes_per_cell) * cells +
           12. * entries_per_row * dofs;
  }



  void
  Scene::check_refinement_fits(const double       cells,
                               const double       bytes_per_cell,
                               const std::string &body,
                               const std::string &parameter) const
  {
    const double bytes             = memory_lower_bound(cells, bytes_per_cell);
    const auto [physical, machine] = machine_memory();
    std::ostringstream text;
    text << std::setprecision(3) << "refining the mesh by 'Body " << body
         << "/Refinement/" << parameter << "' would make about " << cells
         << " cells, at least " << bytes / (1 << 30) << " GiB of memory";
    require(bytes <= physical && cells < 4.e9,
            "The mesh is too large for this machine: " + text.str() + ", but " +
              machine +
              (cells < 4.e9 ? std::string() :
                              " (and deal.II numbers cells with 32-bit "
                              "integers here, at most about 4e9)") +
              ". Lower 'Body " + body + "/Refinement/" + parameter + "'" +
              (parameter == "Local refinements" ?
                 " or 'Body " + body +
                   "/Refinement/Refinement radius' (each local refinement "
                   "multiplies the cells inside the radius by " +
                   std::to_string(1 << dimension) + ")" :
                 std::string()) +
              ", or run on more machines with MPI.");
  }



  void
  Scene::check_size() const
  {
    // A lower bound of the memory the run needs, before the mesh is
    // built: cells after global refinement (local refinement only adds;
    // Mesh checks each refinement cycle with check_refinement_fits before
    // it runs). Refusing when this bound exceeds the memory of the
    // machine never refuses a scene that would fit.
    const auto [physical, machine] = machine_memory();
    double      cells = 0, dofs = 0;
    std::string largest;
    double      largest_cells = 0;
    for (const auto &b : bodies)
      {
        double coarse = 1; // round shapes: at least one coarse cell
        if (b.mesh.type == "block")
          for (const auto n : b.mesh.subdivisions)
            coarse *= n;
        // deal.II's rings have cells of about square shape: pi (R + r) /
        // (R - r) around (half of them for a half ring), and in 3D as
        // many along the axis as fit in 'Length' (an inner radius of
        // 0.99999 made 628 316 coarse cells, unchecked).
        const auto &m = b.mesh;
        if ((m.type == "ring" || m.type == "half ring") &&
            m.inner_radius < m.radius)
          {
            const double around =
              std::ceil(numbers::PI * (m.radius + m.inner_radius) /
                        (m.radius - m.inner_radius));
            coarse = m.type == "ring" ? around : std::ceil(around / 2);
            if (dimension == 3 && m.type == "ring")
              coarse *= std::ceil(m.length * around /
                                  (numbers::PI * (m.radius + m.inner_radius)));
          }
        const double n_cells =
          coarse * std::pow(2., dimension * b.mesh.global_refinements);
        cells += n_cells;
        dofs += n_cells * std::pow(degree, dimension) * dimension;
        if (n_cells > largest_cells)
          {
            largest_cells = n_cells;
            largest       = b.name;
          }
      }
    const double       bytes = memory_lower_bound(cells);
    std::ostringstream text;
    text << std::setprecision(3) << "about " << cells << " cells and " << dofs
         << " unknowns, at least " << bytes / (1 << 30) << " GiB of memory";
    const auto type_of_largest =
      std::find_if(bodies.begin(), bodies.end(), [&](const BodyParameters &b) {
        return b.name == largest;
      })->mesh.type;
    const std::string advice =
      " Lower " +
      (type_of_largest == "block" ?
         "'Body " + largest + "/Block/Subdivisions' or " :
       type_of_largest == "ring" || type_of_largest == "half ring" ?
         "the cells around the ring (about pi (R + r) / (R - r): "
         "make 'Body " +
           largest +
           "/Round shapes/Inner radius' smaller, a thicker ring) or " :
         std::string()) +
      "'Body " + largest +
      "/Refinement/Global refinements' (each global refinement multiplies "
      "the cells by " +
      std::to_string(1 << dimension) + "), or run on more machines with MPI.";
    require(bytes <= physical,
            "The mesh is too large for this machine: " + text.str() + ", but " +
              machine + "." + advice);
    // deal.II's DoF and cell indices here are 32-bit.
    require(dofs < 4.e9 && cells < 4.e9,
            "The mesh is too large: " + text.str() +
              "; this build of deal.II numbers cells and unknowns with "
              "32-bit integers (at most about 4e9)." +
              advice);
  }



  Scene
  Scene::read(const std::string              &filename,
              const std::vector<std::string> &overrides)
  {
    Scene scene;
    scene.file = filename;
    {
      std::error_code ec;
      require(!std::filesystem::is_directory(filename, ec),
              "The scene file '" + filename +
                "' is a directory; give the path of a .prm file in it.");
      require_regular_file(filename,
                           "The scene file",
                           "give the path of a .prm, .json or .xml file.");
      std::ifstream in(filename);
      require(static_cast<bool>(in),
              "Cannot open the scene file '" + filename +
                "': check the path (it is taken relative to the current "
                "directory).");
    }
    const auto slash = filename.rfind('/');
    scene.directory  = (slash == std::string::npos ? std::string(".") :
                                                     filename.substr(0, slash));
    std::string stem =
      (slash == std::string::npos ? filename : filename.substr(slash + 1));
    if (const auto d = stem.rfind('.'); d != std::string::npos)
      stem = stem.substr(0, d);

    // @p declare declares the parameters afresh for the hints of a
    // mistake (entering a subsection that does not exist creates it).
    auto apply_overrides =
      [&](ParameterHandler                              &prm,
          const bool                                     lenient,
          const std::function<void(ParameterHandler &)> &declare) {
        for (const auto &o : overrides)
          {
            const auto eq = o.find('=');
            require(eq != std::string::npos,
                    "Command-line option --set '" + o +
                      "' is not of the form \"Subsection/Entry=value\" (it "
                      "has no '='). Example: --set \"Body block/Material/"
                      "Young's modulus=210e3\".");
            // Every part of the path must name something: no empty entry,
            // no empty subsection ('a//b', '/a', 'a/').
            std::vector<std::string> path;
            {
              std::string rest = o.substr(0, eq) + "/";
              for (auto slash = rest.find('/'); slash != std::string::npos;
                   slash      = rest.find('/'))
                {
                       path.push_back(Utilities::trim(rest.substr(0, slash)));
                       rest = rest.substr(slash + 1);
                }
            }
            for (const auto &part : path)
              require(!part.empty(),
                      "Command-line option --set '" + o + "': the path '" +
                        o.substr(0, eq) +
                        "' has an empty part; write \"Subsection/Entry=value\" "
                        "with the names that 'glide --print-parameters' "
                        "shows.");
            const auto   value   = Utilities::trim(o.substr(eq + 1));
            unsigned int entered = 0;
            try
              {
                for (; entered + 1 < path.size(); ++entered)
                  prm.enter_subsection(path[entered]);
                prm.set(path.back(), value);
              }
            catch (const ExceptionBase &e)
              {
                for (; entered > 0; --entered)
                  prm.leave_subsection();
                // Names declared only in the second pass.
                if (lenient)
                  continue;
                const std::vector<std::string> subsections(path.begin(),
                                                           path.end() - 1);
                const auto joined = [](const std::vector<std::string> &p) {
                  std::string j;
                  for (const auto &n : p)
                    j += (j.empty() ? "" : "/") + n;
                  return j;
                };
                ParameterHandler declared;
                declare(declared);
                unsigned int found = 0;
                std::string  what;
                if (!is_declared_subsection(declared, subsections, found))
                  {
                    std::string known;
                    for (unsigned int i = 0; i <= found; ++i)
                      known += (i ? "/" : "") + path[i];
                    what = "the scene has no subsection '" + known + "'." +
                           parameter_hint(declared,
                                          {path.begin(), path.begin() + found},
                                          path[found],
                                          true);
                  }
                else if (explain(e).find("not yet declared") !=
                         std::string::npos)
                  what =
                    "there is no entry '" + path.back() + "' in " +
                    (subsections.empty() ?
                       std::string("the top level") :
                       "subsection '" + joined(subsections) + "'") +
                    "." +
                    parameter_hint(declared, subsections, path.back(), false);
                else
                  what = explain(e);
                throw InputError("Command-line option --set '" + o +
                                 "': " + what +
                                 " Run 'glide --print-parameters' to see "
                                 "every valid parameter.");
              }
            for (; entered > 0; --entered)
              prm.leave_subsection();
          }
      };

    // A .prm file is parsed from its text with its 'include' statements
    // expanded (expand_includes()) and without a UTF-8 byte-order mark at
    // its start (deal.II took the mark for part of the first line and
    // refused a line that looks right).
    const bool  prm_file = scene_format(filename) == "prm";
    std::string text;
    LineOrigins origins;
    if (prm_file)
      {
        std::vector<std::pair<std::string, std::string>> chain;
        expand_includes(filename, chain, text, origins);
      }
    // explain() names the file and line of a mistake from these, until
    // this function returns.
    struct ForgetOrigins
    {
      ~ForgetOrigins()
      {
        parsed_origins = nullptr;
      }
    } forget_origins;
    parsed_origins   = prm_file ? &origins : nullptr;
    parsed_name      = filename;
    const auto parse = [&](ParameterHandler &prm, const bool skip_undefined) {
      if (prm_file)
        {
          std::istringstream in(text);
          prm.parse_input(in, filename, "", skip_undefined);
        }
      else
        prm.parse_input(filename, "", skip_undefined);
    };

    // Pass 1: the lists of names only; everything else is skipped.
    std::vector<std::string> bodies, conditions, node_sets, pairs;
    try
      {
        ParameterHandler prm;
        declare_parameters(prm, {}, {}, {}, {});
        parse(prm, true);
        apply_overrides(prm, true, [](ParameterHandler &) {});
        bodies     = split_names(prm.get("Bodies"));
        conditions = split_names(prm.get("Boundary conditions"));
        node_sets  = split_names(prm.get("Node sets"));
        pairs      = split_names(prm.get("Contact pairs"));
      }
    catch (const ExceptionBase &e)
      {
        throw InputError("In scene file '" + filename +
                         "': " + name_the_entry(filename, explain(e)));
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const std::exception &e)
      {
        // The XML and JSON parsers' own errors (boost's property tree).
        throw InputError("In scene file '" + filename +
                         "': cannot be read: " + e.what() + ".");
      }
    check_names(bodies, "Bodies");
    check_names(conditions, "Boundary conditions");
    check_names(node_sets, "Node sets");
    check_names(pairs, "Contact pairs");
    require(!bodies.empty(),
            "Scene '" + filename + "': 'Bodies' must name at least one body.");

    // Pass 2: strict, with one subsection per name.
    const std::function<void(ParameterHandler &)> declare =
      [&](ParameterHandler &fresh) {
        declare_parameters(fresh, bodies, conditions, node_sets, pairs);
      };
    ParameterHandler prm;
    declare(prm);
    try
      {
        parse(prm, false);
      }
    catch (const ExceptionBase &e)
      {
        // A subsection of an object the scene's lists do not name.
        const std::string message = name_the_entry(filename, explain(e));
        const std::string marker =
          "There is no such subsection to be entered: ";
        if (const auto at = message.find(marker); at != std::string::npos)
          {
            std::string subsection =
              Utilities::trim(message.substr(at + marker.size()));
            if (!subsection.empty() && subsection.back() == '.')
              subsection.pop_back(); // explain() ends the sentence
            const std::vector<
              std::tuple<std::string, std::string, std::vector<std::string> *>>
              kinds{{"Body ", "Bodies", &bodies},
                    {"Boundary condition ", "Boundary conditions", &conditions},
                    {"Node set ", "Node sets", &node_sets},
                    {"Contact pair ", "Contact pairs", &pairs}};
            // Only a name at the object's own level (a nested
            // subsection's path has a '.', which glide's names cannot
            // contain) that the list does not hold.
            for (const auto &[prefix, list, names] : kinds)
              if (subsection.rfind(prefix, 0) == 0 &&
                  subsection.find('.') == std::string::npos &&
                  std::find(names->begin(),
                            names->end(),
                            subsection.substr(prefix.size())) == names->end())
                {
                  std::string listed;
                  for (const auto &n : *names)
                    listed += (listed.empty() ? "" : ", ") + n;
                  const std::string name = subsection.substr(prefix.size());
                  throw InputError(
                    "In scene file '" + filename +
                    "': " + message.substr(0, at) +
                    "the scene has 'subsection " + subsection + "', but '" +
                    list + "' does not name '" + name + "' (it names: " +
                    (listed.empty() ? std::string("nothing") : listed) +
                    "). Add '" + name + "' to '" + list +
                    "', or remove the subsection.");
                }
          }
        throw InputError("In scene file '" + filename + "': " + message +
                         hint_at_line(declare, e, text) +
                         " Run 'glide --print-parameters' to see every "
                         "valid parameter.");
      }
    apply_overrides(prm, false, declare);

    for (const auto &b : bodies)
      {
        BodyParameters body;
        body.name = b;
        scene.bodies.push_back(body);
      }
    for (const auto &c : conditions)
      {
        scene.boundary_conditions.emplace_back();
        scene.boundary_conditions.back().name = c;
      }
    for (const auto &n : node_sets)
      {
        scene.node_sets.emplace_back();
        scene.node_sets.back().name = n;
      }
    for (const auto &n : pairs)
      {
        scene.contact_pairs.emplace_back();
        scene.contact_pairs.back().name = n;
      }
    // Where a value that a message names came from: the last --set of
    // its path, else the scene file (until 2026-12-07 a range error of a
    // value given with --set named the scene file).
    const auto source_of = [&](const std::string &message) {
      for (auto o = overrides.rbegin(); o != overrides.rend(); ++o)
        if (const auto eq = o->find('='); eq != std::string::npos)
          {
            // Each part trimmed, as apply_overrides() reads the path.
            std::string path;
            for (const auto &part :
                 Utilities::split_string_list(o->substr(0, eq), '/'))
              path += (path.empty() ? "" : "/") + Utilities::trim(part);
            if (!path.empty() &&
                message.find("'" + path + "'") != std::string::npos)
              return "Command-line option --set '" + *o + "' (scene file '" +
                     filename + "'): ";
          }
      return "In scene file '" + filename + "': ";
    };
    try
      {
        scene.parse_parameters(prm);
      }
    catch (const ExceptionBase &e)
      {
        const std::string message = explain(e);
        throw InputError(source_of(message) + message);
      }
    catch (const InputError &e)
      {
        throw InputError(source_of(e.what()) + e.what());
      }
    if (scene.name.empty())
      scene.name = stem;
    check_scene_name(scene.name, filename, stem);
    require(!scene.output.directory.empty(),
            "In scene file '" + filename +
              "': parameter 'Output/Directory' is empty; use '.' for the "
              "current directory.");
    try
      {
        scene.check();
      }
    catch (const InputError &e)
      {
        throw InputError(source_of(e.what()) + e.what());
      }
    ParameterHandler defaults;
    declare_parameters(defaults, bodies, conditions, node_sets, pairs);
    scene.unused = scene.unused_entries(prm, defaults);
    if (prm_file)
      for (const auto &note : entries_set_twice(text, origins))
        scene.unused.push_back(note);
    return scene;
  }



  void
  Scene::print_parameters(std::ostream &out, const std::string &format)
  {
    ParameterHandler prm;
    declare_parameters(prm,
                       example_bodies,
                       example_conditions,
                       example_node_sets,
                       example_pairs);
    const auto style = (format == "json" ? ParameterHandler::JSON :
                        format == "xml"  ? ParameterHandler::XML :
                                           ParameterHandler::PRM);
    prm.print_parameters(out, style | ParameterHandler::KeepDeclarationOrder);
  }



  std::string
  Scene::analysis_name() const
  {
    switch (analysis)
      {
        case AnalysisType::plane_strain:
          return "plane strain";
        case AnalysisType::axisymmetric:
          return "axisymmetric";
        default:
          return "3d";
      }
  }
} // namespace glide
