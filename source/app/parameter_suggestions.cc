#include <deal.II/base/utilities.h>

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
    joined(const std::vector<std::string> &path)
    {
      std::string s;
      for (const auto &p : path)
        s += (s.empty() ? "" : "/") + p;
      return s;
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
        const std::string text = dealii::Utilities::trim(line);
        if (text.rfind("#", 0) == 0)
          {
            // Documentation; the listing's underline is none.
            const std::string words = dealii::Utilities::trim(text.substr(1));
            if (words.find_first_not_of('-') != std::string::npos)
              comment += (comment.empty() ? "" : " ") + words;
            continue;
          }
        if (text.rfind("subsection ", 0) == 0)
          {
            const std::string name = dealii::Utilities::trim(text.substr(11));
            levels[joined(path)].subsections.insert(name);
            path.push_back(name);
            levels[joined(path)];
          }
        else if (text == "end" && !path.empty())
          path.pop_back();
        else if (text.rfind("set ", 0) == 0)
          {
            const std::string name =
              dealii::Utilities::trim(text.substr(4, text.find('=') - 4));
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



  std::vector<ParameterStatement>
  parameter_statements(const std::string &text)
  {
    std::vector<ParameterStatement> statements;
    std::vector<std::string>        path;
    std::istringstream              input(text);
    std::string                     line, joined_lines;
    unsigned int                    line_number = 0, start = 0;
    while (std::getline(input, line))
      {
        ++line_number;
        line = line.substr(0, line.find('#'));
        if (joined_lines.empty())
          start = line_number;
        if (!line.empty() && line.back() == '\\')
          {
            joined_lines += line.substr(0, line.size() - 1);
            continue;
          }
        joined_lines += line;
        const std::string statement = dealii::Utilities::trim(joined_lines);
        joined_lines.clear();
        if (statement.empty())
          continue;
        statements.push_back({start, joined(path), statement});
        if (statement.rfind("subsection ", 0) == 0)
          path.push_back(dealii::Utilities::trim(statement.substr(11)));
        else if (statement == "end" && !path.empty())
          path.pop_back();
      }
    return statements;
  }



  std::string
  subsection_path_at_line(const std::string &text, const unsigned int line)
  {
    std::string path;
    for (const ParameterStatement &statement : parameter_statements(text))
      if (statement.line <= line)
        path = statement.path;
    return path;
  }
} // namespace coulomb_adapt
