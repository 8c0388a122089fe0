#include "scene/YamlRead.h"
#include "scene/SceneLoader.h"
#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <sstream>

namespace cellphase::scene::yaml
{
namespace
{

/// YAML 1.2 core-schema floats plus anything std::from_chars reads completely.
std::optional<double> parse_double(std::string t)
{
  if (t == ".nan" || t == ".NaN" || t == ".NAN")
    return NAN;
  std::string body = (!t.empty() && (t[0] == '+' || t[0] == '-')) ? t.substr(1) : t;
  const double sign = (!t.empty() && t[0] == '-') ? -1.0 : 1.0;
  if (body == ".inf" || body == ".Inf" || body == ".INF")
    return sign * INFINITY;
  if (body.empty() || body[0] == '+' || body[0] == '-')
    return std::nullopt;
  double v;
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), v);
  if (ec != std::errc() || end != body.data() + body.size())
    return std::nullopt;
  return sign * v;
}

std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1,
                         prev[j - 1] + (std::tolower(a[i - 1]) != std::tolower(b[j - 1]))});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string suggestion(const std::string& word, const std::vector<std::string>& names)
{
  std::string best;
  std::size_t best_d = 3; // only close misspellings
  for (const std::string& n : names)
  {
    const std::size_t d = edit_distance(word, n);
    if (d < best_d)
    {
      best = n;
      best_d = d;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

std::string lengths_text(const std::vector<std::size_t>& lengths)
{
  std::vector<std::string> s;
  for (std::size_t n : lengths)
    s.push_back(std::to_string(n));
  return join(s, " or ");
}

} // namespace

std::string join(const std::vector<std::string>& items, const std::string& sep)
{
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i ? sep : "") + items[i];
  return out;
}

std::string fmt(double v)
{
  if (std::isnan(v))
    return "nan"; // not "-nan"
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

const std::string* Origin::override_for(const std::string& canon) const
{
  // canon itself or a parent (prefix ending at a dot) may have been set.
  for (const auto& [key, text] : overrides)
    if (canon == key || (canon.size() > key.size() && canon.compare(0, key.size(), key) == 0
                         && canon[key.size()] == '.'))
      return &text;
  return nullptr;
}

std::string location(const Origin& origin, const YAML::Node& node, const std::string& canon)
{
  if (const std::string* o = origin.override_for(canon))
    return origin.source + ": --set " + *o + ": ";
  if (!node.IsDefined() || node.Mark().is_null())
    return origin.source + ": ";
  return origin.source + ":" + std::to_string(node.Mark().line + 1) + ":"
         + std::to_string(node.Mark().column + 1) + ": ";
}

// ---- Range ----

bool Range::contains(double v) const
{
  const bool lo_ok = min_open ? v > min : v >= min;
  const bool hi_ok = max_open ? v < max : v <= max;
  return lo_ok && hi_ok;
}

std::string Range::describe(bool integer) const
{
  const std::string what = integer ? "an integer" : "a number";
  const bool has_lo = std::isfinite(min), has_hi = std::isfinite(max);
  if (has_lo && has_hi)
    return what + " in " + (min_open ? "(" : "[") + fmt(min) + ", " + fmt(max)
           + (max_open ? ")" : "]");
  if (has_lo)
    return what + (min_open ? " > " : " >= ") + fmt(min);
  if (has_hi)
    return what + (max_open ? " < " : " <= ") + fmt(max);
  return what;
}

Range any() { return {}; }
Range positive() { return {0, INFINITY, true, false}; }
Range non_negative() { return {0, INFINITY, false, false}; }
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
Range open(double lo, double hi) { return {lo, hi, true, true}; }

// ---- Value ----

void Value::fail(const std::string& problem) const
{
  throw SceneError(location(*origin, node, canon) + path + ": " + problem);
}

std::string Value::found() const
{
  if (!node.IsDefined() || node.IsNull())
    return "no value";
  if (node.IsSequence())
    return "a list of " + std::to_string(node.size()) + " item" + (node.size() == 1 ? "" : "s");
  if (node.IsMap())
    return "a mapping";
  const std::string& t = node.Scalar();
  if (node.Tag() != "!" && parse_double(t))
    return t;
  return "\"" + t + "\"";
}

double Value::number(const Range& r) const
{
  if (!node.IsDefined() || node.IsNull())
    fail("no value given; expected " + r.describe(false));
  std::optional<double> v;
  if (node.IsScalar())
    v = parse_double(node.Scalar());
  if (!v)
    fail("found " + found() + ", expected " + r.describe(false));
  if (!std::isfinite(*v))
    fail("found " + node.Scalar() + ", which is not a finite number; expected "
         + r.describe(false));
  if (!r.contains(*v))
    fail("found " + fmt(*v) + ", expected " + r.describe(false));
  return *v;
}

int Value::integer(const Range& r) const
{
  if (!node.IsDefined() || node.IsNull())
    fail("no value given; expected " + r.describe(true));
  std::optional<double> v;
  if (node.IsScalar())
    v = parse_double(node.Scalar());
  if (!v || !std::isfinite(*v) || *v != std::floor(*v))
    fail("found " + found() + ", expected " + r.describe(true));
  if (!r.contains(*v) || std::abs(*v) > INT_MAX)
    fail("found " + fmt(*v) + ", expected " + r.describe(true));
  return static_cast<int>(*v);
}

bool Value::boolean() const
{
  bool b = false;
  if (!node.IsScalar() || node.Tag() == "!" || !YAML::convert<bool>::decode(node, b))
    fail("found " + found() + ", expected true or false");
  return b;
}

std::string Value::string() const
{
  if (!node.IsScalar())
    fail("found " + found() + ", expected a text value");
  return node.Scalar();
}

Value Value::element(std::size_t i) const
{
  const YAML::Node& n = node;
  return {origin, n[i], path + "[" + std::to_string(i) + "]", canon + "." + std::to_string(i)};
}

// ---- Section ----

Section::Section(const Origin& origin, YAML::Node node, std::string path, std::string canon)
    : origin_(&origin), node_(std::move(node)), path_(std::move(path)), canon_(std::move(canon))
{
}

Section Section::root(const Origin& origin, YAML::Node node)
{
  return Section(origin, std::move(node), "", "");
}

Section Section::relabel(std::string path) const
{
  Section s = *this;
  s.path_ = std::move(path);
  return s;
}

std::string Section::child_path(const std::string& key) const
{
  return path_.empty() ? key : path_ + "." + key;
}

std::string Section::child_canon(const std::string& key) const
{
  return canon_.empty() ? key : canon_ + "." + key;
}

void Section::fail(const std::string& problem) const
{
  const std::string loc = path_.empty() ? origin_->source + ": "
                                        : location(*origin_, node_, canon_);
  throw SceneError(loc + (path_.empty() ? "" : path_ + ": ") + problem);
}

void Section::fail(const std::string& key, const std::string& problem) const
{
  if (has(key))
    value(key).fail(problem);
  // Absent key: point at the section (or nowhere for the top level).
  const std::string loc = path_.empty() ? origin_->source + ": "
                                        : location(*origin_, node_, child_canon(key));
  throw SceneError(loc + child_path(key) + ": " + problem);
}

bool Section::has(const std::string& key) const
{
  return node_.IsMap() && node_[key].IsDefined();
}

std::vector<std::string> Section::keys() const
{
  std::vector<std::string> out;
  if (node_.IsMap())
    for (const auto& kv : node_)
      out.push_back(kv.first.IsScalar() ? kv.first.Scalar() : "");
  return out;
}

void Section::allow_only(const std::vector<std::string>& allowed) const
{
  if (!node_.IsMap())
    return;
  std::vector<std::string> seen;
  for (const auto& kv : node_)
  {
    if (!kv.first.IsScalar())
      Value{origin_, kv.first, path_.empty() ? "top level" : path_, canon_}.fail(
          "found a key that is " + Value{origin_, kv.first, "", ""}.found()
          + "; keys must be plain names");
    const std::string name = kv.first.Scalar();
    const Value key{origin_, kv.first, child_path(name), child_canon(name)};
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      key.fail("duplicate key; each key may appear once");
    seen.push_back(name);
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      key.fail("unknown key; allowed keys "
               + (path_.empty() ? std::string("at the top level") : "in " + path_) + ": "
               + join(allowed) + suggestion(name, allowed));
  }
}

Value Section::value(const std::string& key) const
{
  const YAML::Node& n = node_;
  return {origin_, node_.IsMap() ? n[key] : YAML::Node(), child_path(key), child_canon(key)};
}

Section Section::section(const std::string& key) const
{
  if (!has(key))
    return Section(*origin_, YAML::Node(), child_path(key), child_canon(key));
  const Value v = value(key);
  if (!v.node.IsNull() && !v.node.IsMap())
    v.fail("found " + v.found() + ", expected a section of keys (a mapping)");
  return Section(*origin_, v.node, v.path, v.canon);
}

std::vector<Section> Section::list_of_sections(const std::string& key) const
{
  const Value v = value(key);
  if (!v.node.IsSequence())
    v.fail("found " + v.found() + ", expected a list");
  std::vector<Section> out;
  for (std::size_t i = 0; i < v.node.size(); ++i)
  {
    const Value e = v.element(i);
    if (!e.node.IsMap())
      e.fail("found " + e.found() + ", expected a mapping of keys");
    out.emplace_back(*origin_, e.node, e.path, e.canon);
  }
  return out;
}

double Section::number(const std::string& key, const Range& r) const
{
  if (!has(key))
    fail(key, "missing; this key is required (" + r.describe(false) + ")");
  return value(key).number(r);
}

double Section::number(const std::string& key, double fallback, const Range& r) const
{
  return has(key) ? value(key).number(r) : fallback;
}

std::optional<double> Section::optional_number(const std::string& key, const Range& r) const
{
  if (!has(key))
    return std::nullopt;
  return value(key).number(r);
}

int Section::integer(const std::string& key, int fallback, const Range& r) const
{
  return has(key) ? value(key).integer(r) : fallback;
}

bool Section::boolean(const std::string& key, bool fallback) const
{
  return has(key) ? value(key).boolean() : fallback;
}

std::string Section::string(const std::string& key, const std::string& fallback) const
{
  return has(key) ? value(key).string() : fallback;
}

std::vector<double> Section::numbers(const std::string& key,
                                     const std::vector<std::size_t>& lengths,
                                     const Range& r) const
{
  const Value v = value(key);
  const std::string expected = "a list of " + lengths_text(lengths) + " numbers"
                               + (r.describe(false) == "a number" ? "" : ", each "
                                                                             + r.describe(false));
  if (!v.node.IsSequence()
      || std::find(lengths.begin(), lengths.end(), v.node.size()) == lengths.end())
    v.fail("found " + v.found() + ", expected " + expected);
  std::vector<double> out;
  for (std::size_t i = 0; i < v.node.size(); ++i)
    out.push_back(v.element(i).number(r));
  return out;
}

std::vector<int> Section::integers(const std::string& key, std::size_t length,
                                   const Range& r) const
{
  const Value v = value(key);
  if (!v.node.IsSequence() || v.node.size() != length)
    v.fail("found " + v.found() + ", expected a list of " + std::to_string(length)
           + " integers, each " + r.describe(true));
  std::vector<int> out;
  for (std::size_t i = 0; i < length; ++i)
    out.push_back(v.element(i).integer(r));
  return out;
}

std::vector<std::string> Section::strings(const std::string& key) const
{
  const Value v = value(key);
  if (!v.node.IsSequence())
    v.fail("found " + v.found() + ", expected a list of names");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.node.size(); ++i)
    out.push_back(v.element(i).string());
  return out;
}

void Section::fail_choice(const std::string& key, const std::string& found,
                          const std::vector<std::string>& names) const
{
  value(key).fail("unknown value \"" + found + "\"; allowed: " + join(names)
                  + suggestion(found, names));
}

} // namespace cellphase::scene::yaml
