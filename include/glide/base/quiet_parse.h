#pragma once

#include <deal.II/base/exceptions.h>

#include <cctype>
#include <functional>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>

namespace glide
{
  /**
   * Runs @p parse, which initializes and first evaluates a
   * dealii::FunctionParser, with std::cerr captured. deal.II 9.4 prints
   * muparser's whole error report (Message, Formula, Token, Position,
   * Errc) to std::cerr before it throws, and its exception text calls the
   * error code a column ("Parsing Error at Column 25"). Returns "" if the
   * expression is valid, else muparser's own message and the expression it
   * concerns, e.g. "Unexpected end of expression at position 5 in 'sin('",
   * for glide's input error. Set-up only (std::cerr is process-wide).
   */
  inline std::string
  parse_quietly(const std::function<void()> &parse)
  {
    std::ostringstream captured;
    auto *const        original = std::cerr.rdbuf(captured.rdbuf());
    std::string        error;
    try
      {
        parse();
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::ostringstream s;
        e.print_info(s);
        error = s.str();
      }
    catch (const std::exception &e)
      {
        error = e.what();
      }
    std::cerr.rdbuf(original);
    if (error.empty())
      return error;
    std::smatch       m;
    const std::string report = captured.str();
    if (std::regex_search(report,
                          m,
                          std::regex(R"(Message:\s*<([^>]*)>\s*\n)"
                                     R"(Formula:\s*<\s*(.*?)\s*>)")))
      return m[1].str() + " in '" + m[2].str() + "'";
    // Not muparser's report: the exception's text, trimmed.
    const auto said = error.find("The parser said: ");
    if (said != std::string::npos)
      error = error.substr(said + 17);
    while (!error.empty() &&
           std::isspace(static_cast<unsigned char>(error.back())))
      error.pop_back();
    while (!error.empty() &&
           std::isspace(static_cast<unsigned char>(error.front())))
      error.erase(error.begin());
    return error;
  }
} // namespace glide
