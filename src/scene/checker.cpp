// The checker of scene values: refusals that name the source of a value, typed getters, look-ups
// in TOML tables.
#include "checker.hpp"

#include "narrows/core/error.hpp"
#include "unknown_names.hpp"

#include <algorithm>

namespace narrows::scene::detail {

const toml::value *find(const toml::value *table, const char *key) {
  if (table == nullptr)
    return nullptr;
  const auto &t = table->as_table();
  const auto it = t.find(key);
  return it == t.end() ? nullptr : &it->second;
}

std::map<std::string, const toml::value *> sorted(const toml::value &table) {
  std::map<std::string, const toml::value *> out;
  for (const auto &[k, v] : table.as_table())
    out.emplace(k, &v);
  return out;
}

std::vector<std::pair<std::string, const toml::value *>> in_file_order(const toml::value &table) {
  std::vector<std::pair<std::string, const toml::value *>> items;
  for (const auto &[k, v] : table.as_table())
    items.emplace_back(k, &v);
  std::sort(items.begin(), items.end(), [](const auto &a, const auto &b) {
    const auto la = a.second->location().line(), lb = b.second->location().line();
    return la != lb ? la < lb : a.first < b.first;
  });
  return items;
}

std::vector<std::string> names_of(const std::vector<KeySpec> &keys) {
  std::vector<std::string> out;
  for (const auto &k : keys)
    out.emplace_back(k.name);
  return out;
}

const std::vector<KeySpec> &sub_keys(std::string_view section, std::string_view key) {
  return find_key(find_section(section)->keys, key)->sub_keys;
}

void Checker::fail(const std::string &key, const std::string &message) const {
  // array entries ("domain.size[1]") come from where their array came from
  const auto it = set_.find(key.substr(0, key.find('[')));
  if (it != set_.end())
    throw input_error(
        one_line("--set '" + it->second + "': " + message + " (overriding " + file_ + ")"));
  throw input_error(one_line(file_ + ": " + message));
}

void Checker::fail_set(const std::string &text, const std::string &message) const {
  throw input_error(one_line("--set '" + text + "': " + message + " (overriding " + file_ + ")"));
}

std::string Checker::string(const toml::value &v, const std::string &key,
                            const std::string &allowed) const {
  if (!v.is_string())
    wrong_type(key, v, allowed);
  return v.as_string().str;
}

std::size_t Checker::choice(const toml::value &v, const std::string &key, const char *what,
                            const std::vector<std::string> &names) const {
  const std::string allowed = join(names);
  const std::string s = string(v, key, "one of " + allowed);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (s == names[i])
      return i;
  std::string msg = key + " = " + repr(v) + " is not " + what + "; allowed: " + allowed;
  const std::string hint = closest(s, names);
  if (!hint.empty())
    msg += "; did you mean \"" + hint + "\"?";
  fail(key, msg);
}

std::array<double, 3> Checker::vector(const toml::value &v, const std::string &key, int dims,
                                      const std::string &what) const {
  const std::string allowed =
      "an array of " + std::to_string(dims) + " finite numbers (" + what + ")";
  if (!v.is_array())
    wrong_type(key, v, allowed);
  const auto &a = v.as_array();
  if (static_cast<int>(a.size()) != dims)
    fail(key, key + " = " + repr(v) + " has " + std::to_string(a.size()) +
                  (a.size() == 1 ? " entry" : " entries") + "; allowed: " + std::to_string(dims) +
                  " entries (run.dimensions = " + std::to_string(dims) + ")");
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (int d = 0; d < dims; ++d)
    out[d] = number(a[d], key + "[" + std::to_string(d) + "]", "a finite number",
                    [](double) { return true; });
  return out;
}

const toml::value *Checker::section(const toml::value &root, const char *name) const {
  const toml::value *sec = find(&root, name);
  if (sec != nullptr && !sec->is_table())
    wrong_type(name, *sec, std::string("a table [") + name + "]");
  return sec;
}

void Checker::check_keys(const toml::value *sec, const char *name) const {
  if (sec == nullptr)
    return;
  const SectionSpec *spec = find_section(name);
  for (const auto &[k, v] : in_file_order(*sec)) {
    (void)v;
    if (find_key(spec->keys, k) == nullptr)
      fail(std::string(name) + "." + k, unknown_key_message(name, k));
  }
}

} // namespace narrows::scene::detail
