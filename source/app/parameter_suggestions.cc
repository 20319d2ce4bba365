#include <coulomb_adapt/app/parameter_suggestions.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <vector>

namespace coulomb_adapt
{
  namespace
  {
    std::string
    trimmed(const std::string &s)
    {
      const auto begin = s.find_first_not_of(" \t\r");
      if (begin == std::string::npos)
        return "";
      const auto end = s.find_last_not_of(" \t\r");
      return s.substr(begin, end - begin + 1);
    }

    std::string
    joined(const std::vector<std::string> &path)
    {
      std::string s;
      for (const auto &p : path)
        s += (s.empty() ? "" : "/") + p;
      return s;
    }

    // The subsection and end lines of parameter file text, with the line
    // numbers they stand on; blanks and comments removed.
    template <typename Visitor>
    void
    visit_lines(const std::string &text, Visitor &&visit)
    {
      std::istringstream input(text);
      std::string        line;
      unsigned int       number = 0;
      while (std::getline(input, line))
        {
          ++number;
          const std::string content = trimmed(line.substr(0, line.find('#')));
          if (!visit(number, content))
            return;
        }
    }

    // Edit distance between the lower-case forms of @p a and @p b.
    std::size_t
    distance(const std::string &a, const std::string &b)
    {
      std::vector<std::size_t> row(b.size() + 1);
      for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
      for (std::size_t i = 1; i <= a.size(); ++i)
        {
          std::size_t diagonal = row[0];
          row[0]               = i;
          for (std::size_t j = 1; j <= b.size(); ++j)
            {
              const std::size_t above = row[j];
              const bool        same =
                std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
              row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + !same});
              diagonal = above;
            }
        }
      return row[b.size()];
    }

    // The nearest of @p candidates, if a user could have meant it: at
    // most a third of its letters (and at least 2) differ.
    std::string
    nearest(const std::set<std::string> &candidates, const std::string &name)
    {
      std::string best;
      std::size_t best_distance = std::string::npos;
      for (const auto &c : candidates)
        if (const std::size_t d = distance(c, name); d < best_distance)
          {
            best          = c;
            best_distance = d;
          }
      if (best.empty() ||
          best_distance > std::max<std::size_t>(2, best.size() / 3))
        return "";
      return " Did you mean '" + best + "'?";
    }
  } // namespace



  // From deal.II's PRM output: "subsection NAME", "set NAME = ..." and
  // "end" lines, each entry after the comment lines of its documentation.
  DeclaredParameters::DeclaredParameters(const dealii::ParameterHandler &prm)
  {
    std::ostringstream out;
    prm.print_parameters(out, dealii::ParameterHandler::PRM);
    std::vector<std::string> path;
    std::string              comment;
    levels[""];
    std::istringstream input(out.str());
    for (std::string line; std::getline(input, line);)
      {
        const std::string text = trimmed(line);
        if (text.rfind("#", 0) == 0)
          {
            // Documentation; the listing's underline is none.
            const std::string words = trimmed(text.substr(1));
            if (words.find_first_not_of('-') != std::string::npos)
              comment += (comment.empty() ? "" : " ") + words;
            continue;
          }
        if (text.rfind("subsection ", 0) == 0)
          {
            const std::string name = trimmed(text.substr(11));
            levels[joined(path)].subsections.insert(name);
            path.push_back(name);
            levels[joined(path)];
          }
        else if (text == "end" && !path.empty())
          path.pop_back();
        else if (text.rfind("set ", 0) == 0)
          {
            const std::string name =
              trimmed(text.substr(4, text.find('=') - 4));
            levels[joined(path)].entries.insert(name);
            levels[joined(path)].documentation[name] = comment;
          }
        comment.clear();
      }
  }



  std::string
  DeclaredParameters::suggest_entry(const std::string &path,
                                    const std::string &name) const
  {
    const auto level = levels.find(path);
    return level == levels.end() ? "" : nearest(level->second.entries, name);
  }



  std::string
  DeclaredParameters::suggest_subsection(const std::string &path,
                                         const std::string &name) const
  {
    const auto level = levels.find(path);
    return level == levels.end() ? "" :
                                   nearest(level->second.subsections, name);
  }



  std::string
  DeclaredParameters::describe_entry(const std::string &path,
                                     const std::string &entry) const
  {
    const auto level = levels.find(path);
    if (level == levels.end())
      return "";
    const auto doc = level->second.documentation.find(entry);
    if (doc == level->second.documentation.end() || doc->second.empty())
      return "";
    return " '" + (path.empty() ? "" : path + "/") + entry +
           "': " + doc->second;
  }



  std::string
  subsection_path_at_line(const std::string &text, const unsigned int line)
  {
    std::vector<std::string> path;
    visit_lines(text,
                [&](const unsigned int number, const std::string &content) {
                  if (number >= line)
                    return false;
                  if (content.rfind("subsection ", 0) == 0)
                    path.push_back(trimmed(content.substr(11)));
                  else if (content == "end" && !path.empty())
                    path.pop_back();
                  return true;
                });
    return joined(path);
  }
} // namespace coulomb_adapt
