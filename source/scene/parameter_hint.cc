#include <glide/scene/parameter_hint.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /// The names one subsection declares.
    struct Names
    {
      std::vector<std::string> entries;
      std::vector<std::string> subsections;
    };

    /// Subsection paths (names joined by '/', "" for the top level) and
    /// what each declares, read from deal.II's own short listing.
    std::map<std::string, Names>
    declared_names(const ParameterHandler &declared)
    {
      std::ostringstream listing;
      declared.print_parameters(listing, ParameterHandler::ShortPRM);
      std::map<std::string, Names> names;
      std::vector<std::string>     path;
      const auto joined = [](const std::vector<std::string> &p) {
        std::string s;
        for (const auto &n : p)
          s += (s.empty() ? "" : "/") + n;
        return s;
      };
      names[""];
      std::istringstream in(listing.str());
      for (std::string line; std::getline(in, line);)
        {
          line = Utilities::trim(line);
          if (line.rfind("subsection ", 0) == 0)
            {
              const std::string name = Utilities::trim(line.substr(11));
              names[joined(path)].subsections.push_back(name);
              path.push_back(name);
              names[joined(path)];
            }
          else if (line == "end" && !path.empty())
            path.pop_back();
          else if (line.rfind("set ", 0) == 0)
            {
              const auto equal = line.find('=');
              if (equal != std::string::npos)
                names[joined(path)].entries.push_back(
                  Utilities::trim(line.substr(4, equal - 4)));
            }
        }
      return names;
    }

    /// The optimal string alignment distance of @p a and @p b, letters
    /// compared without case.
    unsigned int
    distance(const std::string &a, const std::string &b)
    {
      const auto lower = [](const char c) {
        return std::tolower(static_cast<unsigned char>(c));
      };
      const std::size_t                      n = a.size(), m = b.size();
      std::vector<std::vector<unsigned int>> d(n + 1,
                                               std::vector<unsigned int>(m + 1,
                                                                         0));
      for (std::size_t i = 0; i <= n; ++i)
        d[i][0] = i;
      for (std::size_t j = 0; j <= m; ++j)
        d[0][j] = j;
      for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j)
          {
            const unsigned int cost =
              lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            d[i][j] = std::min(
              {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                lower(a[i - 2]) == lower(b[j - 1]))
              d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
          }
      return d[n][m];
    }

    /// The candidate closest to @p name if it is close enough to be a
    /// typing mistake, else "".
    std::string
    closest(const std::string &name, const std::vector<std::string> &candidates)
    {
      // One mistake in names of up to 5 letters, two in longer ones: a
      // short name two mistakes away is as likely a different word.
      const unsigned int allowed = name.size() <= 5 ? 1 : 2;
      std::string        best;
      unsigned int       best_distance = allowed + 1;
      for (const auto &c : candidates)
        if (const auto d = distance(name, c); d < best_distance)
          {
            best          = c;
            best_distance = d;
          }
      return best;
    }
  } // namespace

  std::string
  parameter_hint(const ParameterHandler         &declared,
                 const std::vector<std::string> &path,
                 const std::string              &name,
                 const bool                      subsection)
  {
    const auto  names = declared_names(declared);
    std::string here;
    for (const auto &n : path)
      here += (here.empty() ? "" : "/") + n;
    const auto at = names.find(here);
    if (at == names.end())
      return "";
    const auto &own = subsection ? at->second.subsections : at->second.entries;
    if (const auto best = closest(name, own); !best.empty())
      return " Did you mean '" + best + "'?";
    if (subsection)
      {
        // 'Body <name>' for a name that 'Bodies' does not list: the ones
        // it does (as for conditions, node sets and contact pairs).
        const auto space = name.rfind(' ');
        if (space == std::string::npos)
          return "";
        const std::string prefix = name.substr(0, space + 1);
        std::string       listed;
        for (const auto &c : own)
          if (c.rfind(prefix, 0) == 0)
            listed += (listed.empty() ? "'" : ", '") + c + "'";
        const std::map<std::string, std::string> lists{
          {"Body ", "Bodies"},
          {"Boundary condition ", "Boundary conditions"},
          {"Node set ", "Node sets"},
          {"Contact pair ", "Contact pairs"}};
        const auto list = lists.find(prefix);
        return listed.empty() ?
                 "" :
                 " The scene's subsections '" + prefix + "...' are " + listed +
                   (list == lists.end() ?
                      std::string(".") :
                      " (one for each name in '" + list->second +
                        "'; add a name there for a new one).");
      }
    // An entry written in the wrong subsection: the subsections that
    // declare it, or else one close to it.
    std::vector<std::string> elsewhere;
    std::string              meant = name;
    for (const bool exact : {true, false})
      {
        for (const auto &[p, declared_here] : names)
          if (p != here)
            {
              const auto best = closest(name, declared_here.entries);
              if (!best.empty() && (!exact || distance(best, name) == 0) &&
                  (exact || elsewhere.empty() || best == meant))
                {
                  meant = best;
                  elsewhere.push_back(p.empty() ? "the top level" :
                                                  "'" + p + "'");
                }
            }
        if (!elsewhere.empty())
          break;
      }
    if (elsewhere.empty())
      return "";
    std::string list;
    for (unsigned int i = 0; i < elsewhere.size() && i < 3; ++i)
      list += (i ? ", " : "") + elsewhere[i];
    if (elsewhere.size() > 3)
      list += " and " + std::to_string(elsewhere.size() - 3) + " more";
    const std::string where =
      elsewhere.size() > 1 ? "one of those subsections." : "that subsection.";
    if (meant == name)
      return " '" + name + "' is an entry of " + list + "; write it inside " +
             where;
    return " Did you mean '" + meant + "' (an entry of " + list +
           ")? Write it inside " + where;
  }

  std::vector<std::string>
  subsection_path_at(const std::string &text, const unsigned int line)
  {
    std::vector<std::string> path;
    std::istringstream       in(text);
    unsigned int             n = 0;
    for (std::string l; n + 1 < line && std::getline(in, l); ++n)
      {
        if (const auto hash = l.find('#'); hash != std::string::npos)
          l.erase(hash);
        l = Utilities::trim(l);
        if (l.rfind("subsection ", 0) == 0 || l.rfind("subsection\t", 0) == 0)
          path.push_back(Utilities::trim(l.substr(11)));
        else if (l == "end" && !path.empty())
          path.pop_back();
      }
    return path;
  }

  bool
  is_declared_subsection(const ParameterHandler         &declared,
                         const std::vector<std::string> &path,
                         unsigned int                   &found)
  {
    const auto  names = declared_names(declared);
    std::string here;
    found = 0;
    for (const auto &n : path)
      {
        const auto &subsections = names.at(here).subsections;
        if (std::find(subsections.begin(), subsections.end(), n) ==
            subsections.end())
          return false;
        here += (here.empty() ? "" : "/") + n;
        ++found;
      }
    return true;
  }
} // namespace glide
