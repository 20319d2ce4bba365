#ifndef coulomb_adapt_app_parameter_suggestions_h
#define coulomb_adapt_app_parameter_suggestions_h

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace coulomb_adapt
{
  /**
   * The entry and subsection names a ParameterHandler declares, by
   * subsection path ("" for the top level, "Scene/Blocks"), with the
   * entries' documentation, so that a message about a misspelled name can
   * say which declared name was probably meant, and one about a value
   * that does not match its pattern what the entry takes. deal.II's own
   * messages name the unknown name, or the pattern, only.
   */
  class DeclaredParameters
  {
  public:
    explicit DeclaredParameters(const dealii::ParameterHandler &prm);

    /** " Did you mean 'NAME'?" for the entry of subsection @p path
     * nearest to @p name, or "" if none is near. */
    std::string
    suggest_entry(const std::string &path, const std::string &name) const;

    /** The same for the subsections of @p path. */
    std::string
    suggest_subsection(const std::string &path, const std::string &name) const;

    /** " 'PATH/ENTRY': its documentation", or "" for no such entry. */
    std::string
    describe_entry(const std::string &path, const std::string &entry) const;

  private:
    struct Level
    {
      std::set<std::string>              entries;
      std::set<std::string>              subsections;
      std::map<std::string, std::string> documentation;
    };
    std::map<std::string, Level> levels;
  };

  /** One statement of parameter file text, as deal.II's parser reads it:
   * comments removed, lines ending in a backslash joined, blanks around
   * it trimmed. */
  struct ParameterStatement
  {
    /** Its first line (1-based). */
    unsigned int line;
    /** The subsection path it stands in ("A/B", "" at the top). */
    std::string path;
    std::string text;
  };

  /** The non-empty statements of @p text, in order. */
  std::vector<ParameterStatement>
  parameter_statements(const std::string &text);

  /** The subsection path ("A/B", "" at the top) of the statement at line
   * @p line (1-based) of the parameter file text @p text: where deal.II's
   * parser stood when it reported that line. */
  std::string
  subsection_path_at_line(const std::string &text, const unsigned int line);
} // namespace coulomb_adapt

#endif
