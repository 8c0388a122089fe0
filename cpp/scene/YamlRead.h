// Typed reading of YAML scene sections. Every getter validates type and range and throws
// SceneError naming the file, line, dotted key, the value found and what is allowed, so
// the section readers stay declarative.
#pragma once
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <yaml-cpp/yaml.h>

namespace cellphase::scene::yaml
{

/// Where values come from: the scene file and the `--set` overrides applied to it.
struct Origin
{
  std::string source;
  /// Dotted key path (cells addressed as cells.0) -> the override text as given.
  std::map<std::string, std::string> overrides;
  /// The override that set `canon` or one of its parents, if any.
  const std::string* override_for(const std::string& canon) const;
};

/// Allowed interval of a number, with its description for messages.
struct Range
{
  double min = -INFINITY, max = INFINITY;
  bool min_open = false, max_open = false;
  bool contains(double v) const;
  std::string describe(bool integer) const; ///< e.g. "a number > 0", "an integer in [0, 20]"
};
Range any();
Range positive();      ///< > 0
Range non_negative();  ///< >= 0
Range closed(double lo, double hi);
Range open(double lo, double hi);

/// "1.5", "-2", "1e-06": shortest %g-like text for messages.
std::string fmt(double v);

/// One YAML node at a known place, for conversions and messages.
struct Value
{
  const Origin* origin;
  YAML::Node node;
  std::string path;  ///< as shown to the user: numerics.epsilon, cells[1] ("rbc").radius
  std::string canon; ///< as addressed by --set: numerics.epsilon, cells.1.radius

  [[noreturn]] void fail(const std::string& problem) const;
  std::string found() const; ///< "-0.1", "\"abc\"", "a list of 3 items", "no value"

  double number(const Range& r) const;
  int integer(const Range& r) const;
  bool boolean() const;
  std::string string() const;
  Value element(std::size_t i) const;
};

/// A YAML mapping (or an absent / empty section) at a known key path.
class Section
{
public:
  Section(const Origin& origin, YAML::Node node, std::string path, std::string canon);
  static Section root(const Origin& origin, YAML::Node node);

  const std::string& path() const { return path_; }
  const std::string& canon() const { return canon_; }
  const YAML::Node& node() const { return node_; }
  /// Same node shown under another name in messages (cells get their name attached).
  Section relabel(std::string path) const;

  [[noreturn]] void fail(const std::string& problem) const;
  /// Error about a key of this section, located at the key's value if present.
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

  bool has(const std::string& key) const;
  /// Rejects keys not in `allowed`, duplicate keys and non-scalar keys.
  void allow_only(const std::vector<std::string>& allowed) const;
  /// Keys present, in file order.
  std::vector<std::string> keys() const;

  Value value(const std::string& key) const; ///< the key must be present
  Section section(const std::string& key) const; ///< absent or empty -> empty section
  std::vector<Section> list_of_sections(const std::string& key) const;

  double number(const std::string& key, const Range& r) const; ///< required
  double number(const std::string& key, double fallback, const Range& r) const;
  std::optional<double> optional_number(const std::string& key, const Range& r) const;
  int integer(const std::string& key, int fallback, const Range& r) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// A list of numbers whose length is one of `lengths`; the key must be present.
  std::vector<double> numbers(const std::string& key, const std::vector<std::size_t>& lengths,
                              const Range& r) const;
  std::vector<int> integers(const std::string& key, std::size_t length, const Range& r) const;
  std::vector<std::string> strings(const std::string& key) const;

  /// One of the named values; unknown names list the allowed ones.
  template <typename E>
  E choice(const std::string& key, E fallback,
           const std::vector<std::pair<std::string, E>>& allowed) const
  {
    if (!has(key))
      return fallback;
    const std::string v = value(key).string();
    std::vector<std::string> names;
    for (const auto& [name, e] : allowed)
    {
      if (name == v)
        return e;
      names.push_back(name);
    }
    fail_choice(key, v, names);
  }

private:
  [[noreturn]] void fail_choice(const std::string& key, const std::string& found,
                                const std::vector<std::string>& names) const;
  std::string child_path(const std::string& key) const;
  std::string child_canon(const std::string& key) const;

  const Origin* origin_;
  YAML::Node node_;
  std::string path_, canon_;
};

/// "a, b, c".
std::string join(const std::vector<std::string>& items, const std::string& sep = ", ");

/// "file:line:col: " for a node, or "file: --set k=v: " if an override set it.
std::string location(const Origin& origin, const YAML::Node& node, const std::string& canon);

} // namespace cellphase::scene::yaml
