// Reading TOML text without letting toml11 fail badly: limits checked on the raw text before
// toml11 sees it (size, binary content, nesting, integers beyond 64 bits), long array lines
// broken (toml11 is quadratic in line length), and toml11's multi-line syntax errors condensed
// to the scene's one-line message with the line of the scene file.
#include "toml_errors.hpp"

#include "message_text.hpp"
#include "narrows/core/error.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace narrows::scene::detail {

using toml::value;

namespace {

// toml11's syntax_error what() is a multi-line annotated excerpt. Condense it to
//   file: line N: TOML syntax error: <what>; found '<source line>' (<note>)
std::string condense_syntax_error(const std::string &what, const std::string &file,
                                  std::size_t fallback_line,
                                  const std::vector<std::size_t> &line_map = {}) {
  std::istringstream in(what);
  std::string line, headline, src_text, note;
  std::size_t src_line = 0;
  bool first = true;
  while (std::getline(in, line)) {
    // strip ANSI colour sequences, in case toml11 was built to colourise
    std::string clean;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (line[i] == '\x1b') {
        while (i < line.size() && line[i] != 'm')
          ++i;
        continue;
      }
      clean += line[i];
    }
    if (first) {
      headline = clean;
      first = false;
      continue;
    }
    const auto bar = clean.find(" | ");
    const auto bar_end = clean.find(" |");
    if (bar_end == std::string::npos)
      continue;
    const std::string lhs = trim(clean.substr(0, bar_end));
    const std::string rhs = bar == std::string::npos ? "" : clean.substr(bar + 3);
    if (!lhs.empty() &&
        std::all_of(lhs.begin(), lhs.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      src_line = std::stoul(lhs);
      src_text = trim(rhs);
      note.clear();
    } else if (lhs.empty() && src_line != 0) {
      // the marker line under the source line: "^--- note" or "~~~~ note"
      const auto mark = rhs.find_first_not_of(" ^~-");
      if (mark != std::string::npos)
        note = trim(rhs.substr(mark));
    }
  }
  // "[error] toml::parse_array: missing ..." -> "missing ..."
  std::string msg = trim(headline);
  if (msg.rfind("[error]", 0) == 0)
    msg = trim(msg.substr(7));
  while (msg.rfind("toml::", 0) == 0) {
    const auto colon = msg.find(": ");
    if (colon == std::string::npos)
      break;
    msg = trim(msg.substr(colon + 2));
  }
  while (!msg.empty() && (msg.back() == '.' || msg.back() == ' '))
    msg.pop_back();
  if (msg.empty())
    msg = "invalid TOML";
  if (src_line == 0)
    src_line = fallback_line;
  if (src_line >= 1 && src_line <= line_map.size())
    src_line = line_map[src_line - 1]; // the line of the scene file, not of the parsed text
  std::string out = file + ": line " + std::to_string(src_line) + ": TOML syntax error: " + msg;
  if (!src_text.empty()) {
    if (src_text.size() > 60)
      src_text = src_text.substr(0, 57) + "...";
    out += "; found '" + src_text + "'";
    if (!note.empty() && note != "here")
      out += " (" + note + ")";
  }
  return one_line(out);
}

// The index of the last character of the TOML string that starts at text[i] (a quote): its
// closing quote, the newline that ends an unterminated one-line string, or the text's end.
// Basic strings ("...", """...""") have backslash escapes; literal ones ('...') do not.
std::size_t string_end(const std::string &text, std::size_t i) {
  const char quote = text[i];
  const std::string triple(3, quote);
  const bool multi = text.compare(i, 3, triple) == 0;
  const std::size_t n = text.size();
  for (i += multi ? 3 : 1; i < n; ++i) {
    if (quote == '"' && text[i] == '\\') {
      ++i;
      continue;
    }
    if (text[i] == quote && (!multi || text.compare(i, 3, triple) == 0))
      return multi ? i + 2 : i;
    if (!multi && text[i] == '\n')
      return i;
  }
  return n - 1;
}

// Limits checked on the raw text before toml11 sees it: toml11 recurses once per nesting level
// (bracket or dotted-key component), so a deep enough text overflows the stack.
constexpr std::size_t max_scene_bytes = std::size_t{16} << 20;
constexpr int max_scene_nesting = 64;

// toml11 scans a value's whole line for comments (region::comments) after parsing each value,
// so an array of n values on one line takes O(n^2). Long lines of arrays are broken after
// their commas: newlines are allowed between array elements, also of an array inside an inline
// table (TOML 1.0: "unless they are valid within a value"; the profile of
// continuum.initial.values is one), but not between the keys of an inline table. Returns the text
// toml11 reads; line_map[k] is the scene file's line of its line k + 1 (empty when nothing was
// broken).
std::string break_long_arrays(const std::string &text, std::vector<std::size_t> &line_map) {
  constexpr std::size_t long_line = 1024;
  bool any_long = false;
  for (std::size_t at = 0, nl; at < text.size(); at = nl + 1) {
    nl = text.find('\n', at);
    if (nl == std::string::npos)
      nl = text.size();
    any_long = any_long || nl - at > long_line;
  }
  if (!any_long)
    return text;
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  std::vector<char> open; // the brackets around the current position
  std::size_t line = 1, column = 0;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char ch = text[i];
    const auto newline = [&] {
      line_map.push_back(line);
      column = 0;
    };
    if (ch == '#') {
      while (i < n && text[i] != '\n')
        out += text[i++];
      --i;
    } else if (ch == '"' || ch == '\'') { // copy a string verbatim
      const std::size_t end = string_end(text, i);
      for (std::size_t k = i; k <= end; ++k)
        if (text[k] == '\n') {
          newline();
          ++line;
        }
      out.append(text, i, end - i + 1);
      column += 2;
      i = end;
      continue;
    } else if (ch == '[' || ch == '{') {
      open.push_back(ch);
    } else if ((ch == ']' || ch == '}') && !open.empty()) {
      open.pop_back();
    }
    if (ch == '#')
      continue;
    out += ch;
    ++column;
    if (ch == '\n') {
      newline();
      ++line;
    } else if (ch == ',' && column > 80 && !open.empty() && open.back() == '[') {
      out += '\n';
      newline();
    }
  }
  line_map.push_back(line);
  return out;
}

} // namespace

// Refuses a text toml11 must not parse: too long, binary (a NUL byte), or nested deeper than
// max_scene_nesting brackets or dotted-key components. Strings and comments are skipped.
void check_raw_text(const std::string &text, const std::string &file) {
  if (text.size() > max_scene_bytes)
    throw input_error(file + ": scene file of " + std::to_string(text.size()) +
                      " bytes; allowed: at most " + std::to_string(max_scene_bytes) + " bytes");
  if (const auto nul = text.find('\0'); nul != std::string::npos)
    throw input_error(file + ": byte " + std::to_string(nul) +
                      " is NUL (binary content); allowed: a TOML text file");
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw input_error(file + ": the scene file is empty; allowed: a TOML scene with at least "
                             "[run] (see docs/scenes.md)");
  int depth = 0, dots = 0, line = 1;
  const std::size_t n = text.size();
  const auto deep = [&](const char *what) {
    throw input_error(file + ": line " + std::to_string(line) + ": " + what +
                      " nested deeper than " + std::to_string(max_scene_nesting) +
                      " levels; allowed: at most " + std::to_string(max_scene_nesting));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const char ch = text[i];
    if (ch == '#') { // comment to the end of the line
      while (i + 1 < n && text[i + 1] != '\n')
        ++i;
    } else if (ch == '"' || ch == '\'') {
      const std::size_t end = string_end(text, i);
      line +=
          static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                      text.begin() + static_cast<std::ptrdiff_t>(end) + 1, '\n'));
      i = end;
    } else if ((std::isdigit(static_cast<unsigned char>(ch)) || ch == '+' || ch == '-') &&
               (i == 0 || std::strchr(" \t\r\n=,[{", text[i - 1]) != nullptr)) {
      // A number (or a bare key starting with a digit): toml11 clamps decimal integers beyond
      // 64 bits to the largest one, so they are refused here.
      std::size_t j = i;
      while (j < n && std::strchr(" \t\r\n,]}#=", text[j]) == nullptr)
        ++j;
      const std::string token = text.substr(i, j - i);
      if (std::count(token.begin(), token.end(), '.') > max_scene_nesting)
        deep("dotted keys");
      std::string digits;
      for (const char d : token.substr(token[0] == '+' || token[0] == '-' ? 1 : 0))
        if (d != '_')
          digits += d;
      if (!digits.empty() && digits.size() < 1000 &&
          std::all_of(digits.begin(), digits.end(), [](char d) { return d >= '0' && d <= '9'; })) {
        digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
        const std::string most = token[0] == '-' ? "9223372036854775808" : "9223372036854775807";
        if (digits.size() > most.size() || (digits.size() == most.size() && digits > most))
          throw input_error(file + ": line " + std::to_string(line) + ": integer " + token +
                            " is beyond 64 bits; allowed: -9223372036854775808 to "
                            "9223372036854775807");
      } else if (digits.size() >= 1000) {
        throw input_error(file + ": line " + std::to_string(line) + ": a number of " +
                          std::to_string(digits.size()) + " characters; allowed: a TOML number");
      }
      i = j - 1;
    } else if (ch == '[' || ch == '{') {
      if (++depth > max_scene_nesting)
        deep("brackets");
      dots = 0;
    } else if (ch == ']' || ch == '}') {
      depth = std::max(depth - 1, 0);
      dots = 0;
    } else if (ch == '.') {
      if (++dots > max_scene_nesting)
        deep("dotted keys");
    } else if (ch == '\n' || ch == '=' || ch == ',') {
      line += ch == '\n';
      dots = 0;
    }
  }
}

value parse_toml(const std::string &text, const std::string &file) {
  check_raw_text(text, file);
  std::vector<std::size_t> line_map;
  std::istringstream in(break_long_arrays(text, line_map));
  try {
    return toml::parse(in, file);
  } catch (const toml::syntax_error &e) {
    throw input_error(condense_syntax_error(e.what(), file, e.location().line(), line_map));
  } catch (const toml::exception &e) {
    throw input_error(condense_syntax_error(e.what(), file, e.location().line(), line_map));
  } catch (const std::exception &e) {
    throw input_error(one_line(file + ": TOML syntax error: " + e.what()));
  }
}

} // namespace narrows::scene::detail
