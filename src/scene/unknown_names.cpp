// Messages for names the scene schema does not know: the allowed names and a suggestion (the
// closest spelling, or the section that has a key of that name).
#include "unknown_names.hpp"

#include "checker.hpp"
#include "message_text.hpp"
#include "narrows/scene/schema.hpp"

namespace narrows::scene::detail {

namespace {

// "; did you mean 'other.key' (in [other])?" for the first section other than `section` that
// has a key called `key`, else "".
std::string key_elsewhere(const std::string &section, const std::string &key) {
  for (const SectionSpec *other : all_sections())
    if (other->name != section && find_key(other->keys, key) != nullptr)
      return "; did you mean '" + std::string(other->name) + "." + key + "' (in [" +
             std::string(other->name) + "])?";
  return {};
}

} // namespace

std::vector<std::string> section_names() {
  std::vector<std::string> names;
  for (const SectionSpec *sec : all_sections())
    names.emplace_back(sec->name);
  return names;
}

std::string unknown_key_message(const std::string &section, const std::string &key) {
  const std::vector<std::string> allowed = names_of(find_section(section)->keys);
  std::string msg = "unknown key '" + section + "." + key + "'; allowed keys in [" + section +
                    "]: " + join(allowed);
  const std::string hint = closest(key, allowed);
  if (!hint.empty())
    return msg + "; did you mean '" + section + "." + hint + "'?";
  return msg + key_elsewhere(section, key);
}

std::string unknown_section_message(const std::string &name, const toml::value &v) {
  std::string msg = v.is_table() ? "unknown section [" + name + "]"
                                 : "unknown key '" + name + "' at the top level";
  msg += "; allowed sections: " + join(section_names());
  const std::string hint = closest(name, section_names());
  if (!hint.empty())
    return msg + "; did you mean [" + hint + "]?";
  return msg + key_elsewhere("", name);
}

} // namespace narrows::scene::detail
