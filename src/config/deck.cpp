#include "config/deck.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace mp {

int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  // A truncated key ("dens" for "density") is the likeliest slip: among candidates that begin
  // with the word's first three letters, take the closest; otherwise the closest of all.
  std::string best;
  int best_d = 1 << 30;
  for (int pass = 0; pass < 2 && best.empty(); ++pass)
    for (const auto& c : candidates) {
      if (pass == 0 && (word.size() < 3 || c.compare(0, 3, word, 0, 3) != 0)) continue;
      const int d = edit_distance(word, c);
      if (d < best_d) {
        best_d = d;
        best = c;
      }
    }
  return best;
}

namespace {
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}
template <class T>
std::string fmt(T v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

KeyCatalogue*& KeyCatalogue::active() {
  static KeyCatalogue* catalogue = nullptr;
  return catalogue;
}

namespace {
// "materials.0.burn.detonators.1.type" -> "materials[].burn.detonators[].type"
std::string catalogue_path(const std::string& path) {
  std::string out, part;
  std::stringstream ss(path);
  while (std::getline(ss, part, '.')) {
    if (!part.empty() && std::all_of(part.begin(), part.end(), ::isdigit)) {
      out += "[]";
    } else {
      out += (out.empty() ? "" : ".") + part;
    }
  }
  return out;
}
std::string range_text(double lo, double hi) {
  const bool lo_any = lo <= -1e300, hi_any = hi >= 1e300;
  if (lo_any && hi_any) return "any";
  if (hi_any) return ">= " + fmt(lo);
  if (lo_any) return "<= " + fmt(hi);
  return "[" + fmt(lo) + ", " + fmt(hi) + "]";
}
std::string range_text(long lo, long hi) {
  return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}
template <class T>
std::string triple(const std::array<T, 3>& v) {
  return "[" + fmt(v[0]) + ", " + fmt(v[1]) + ", " + fmt(v[2]) + "]";
}
}  // namespace

void DeckNode::note(const std::string& key, const char* type, const std::string& range,
                    const std::string* fallback) const {
  KeyCatalogue* c = KeyCatalogue::active();
  if (!c) return;
  KeyInfo& k = c->keys[catalogue_path(path_.empty() ? key : path_ + "." + key)];
  k.type = type;
  k.range = range;
  if (fallback) k.defaults.insert(*fallback);
}

std::string DeckNode::choice_list(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? " | " : "") + names[i];
  return s;
}

std::string DeckNode::where() const {
  // A value given on the command line is reported as such, not by a line of the file.
  for (std::string p = path_;; p = p.substr(0, p.rfind('.'))) {
    const auto it = overrides_->find(p);
    if (it != overrides_->end()) return "--set " + it->second;
    if (p.find('.') == std::string::npos) break;
  }
  const YAML::Mark m = node_.Mark();
  // A node with no place in the file was made by an override deeper than its own path.
  if (m.line < 0)
    for (const auto& kv : *overrides_)
      if (kv.first.compare(0, path_.size() + 1, path_ + ".") == 0) return "--set " + kv.second;
  std::ostringstream os;
  os << *file_;
  if (m.line >= 0) os << ":" << m.line + 1 << ":" << m.column + 1;
  return os.str();
}

void DeckNode::fail(const std::string& message) const {
  std::ostringstream os;
  os << where() << ": key '" << (path_.empty() ? "<top>" : path_) << "': " << message;
  throw InputError(os.str());
}

DeckNode DeckNode::sub(const YAML::Node& n, const std::string& key) const {
  return DeckNode(n, path_.empty() ? key : path_ + "." + key, file_, overrides_);
}

void DeckNode::expect_keys(const std::vector<std::string>& allowed) const {
  if (KeyCatalogue* c = KeyCatalogue::active())
    for (const auto& key : allowed)
      c->keys[catalogue_path(path_.empty() ? key : path_ + "." + key)];
  if (!node_.IsMap()) fail("expected a map with keys from: " + join(allowed));
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    DeckNode bad(it->first, path_.empty() ? key : path_ + "." + key, file_, overrides_);
    bad.fail("unknown key '" + key + "'; did you mean '" + nearest(key, allowed) +
             "'? (allowed: " + join(allowed) + ")");
  }
}

bool DeckNode::present(const std::string& key) const {
  return node_.IsMap() && node_[key] && !node_[key].IsNull();
}

bool DeckNode::has(const std::string& key) const {
  if (KeyCatalogue* c = KeyCatalogue::active())
    c->keys[catalogue_path(path_.empty() ? key : path_ + "." + key)].probed = true;
  return present(key);
}

DeckNode DeckNode::child(const std::string& key) const {
  if (!node_.IsMap()) fail("expected a map holding '" + key + "'");
  // Reported at the enclosing map, under the missing key's own full path.
  if (!present(key)) sub(node_, key).fail("missing required key '" + key + "'");
  return sub(node_[key], key);
}

DeckNode DeckNode::operator[](std::size_t index) const {
  if (!node_.IsSequence()) fail("expected a list");
  if (index >= node_.size()) fail("list has no element " + std::to_string(index));
  return sub(node_[index], std::to_string(index));
}

std::vector<DeckNode> DeckNode::items() const {
  if (!node_.IsSequence()) fail("expected a list");
  std::vector<DeckNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) out.push_back((*this)[i]);
  return out;
}

double DeckNode::as_real(double lo, double hi) const {
  if (!node_.IsScalar()) fail("expected a number");
  double v = 0;
  try {
    v = node_.as<double>();
  } catch (const YAML::Exception&) {
    fail("expected a number, got '" + node_.Scalar() + "'");
  }
  if (!std::isfinite(v)) fail("expected a finite number, got '" + node_.Scalar() + "'");
  if (v < lo || v > hi)
    fail("value " + node_.Scalar() + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
  return v;
}

long DeckNode::as_int(long lo, long hi) const {
  if (!node_.IsScalar()) fail("expected an integer");
  long v = 0;
  try {
    v = node_.as<long>();
  } catch (const YAML::Exception&) {
    fail("expected an integer, got '" + node_.Scalar() + "'");
  }
  if (v < lo || v > hi)
    fail("value " + node_.Scalar() + " is out of range [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return v;
}

std::string DeckNode::as_string() const {
  if (!node_.IsScalar()) fail("expected a string");
  return node_.Scalar();
}

double DeckNode::get_real(const std::string& key, double lo, double hi) const {
  note(key, "real", range_text(lo, hi), nullptr);
  return child(key).as_real(lo, hi);
}
double DeckNode::get_real(const std::string& key, double lo, double hi, double fallback) const {
  const std::string d = fmt(fallback);
  note(key, "real", range_text(lo, hi), &d);
  return present(key) ? child(key).as_real(lo, hi) : fallback;
}
long DeckNode::get_int(const std::string& key, long lo, long hi) const {
  note(key, "integer", range_text(lo, hi), nullptr);
  return child(key).as_int(lo, hi);
}
long DeckNode::get_int(const std::string& key, long lo, long hi, long fallback) const {
  const std::string d = std::to_string(fallback);
  note(key, "integer", range_text(lo, hi), &d);
  return present(key) ? child(key).as_int(lo, hi) : fallback;
}
bool DeckNode::get_bool(const std::string& key, bool fallback) const {
  const std::string d = fallback ? "true" : "false";
  note(key, "bool", "true | false", &d);
  if (!present(key)) return fallback;
  const DeckNode n = child(key);
  if (!n.node_.IsScalar()) n.fail("expected true or false");
  try {
    return n.node_.as<bool>();
  } catch (const YAML::Exception&) {
    n.fail("expected true or false, got '" + n.node_.Scalar() + "'");
  }
}
std::string DeckNode::get_string(const std::string& key) const {
  note(key, "string", "", nullptr);
  return child(key).as_string();
}
std::string DeckNode::get_string(const std::string& key, const std::string& fallback) const {
  note(key, "string", "", &fallback);
  return present(key) ? child(key).as_string() : fallback;
}
std::string DeckNode::get_enum(const std::string& key,
                               const std::vector<std::string>& allowed) const {
  note(key, "choice", choice_list(allowed), nullptr);
  const DeckNode n = child(key);
  const std::string v = n.as_string();
  if (std::find(allowed.begin(), allowed.end(), v) == allowed.end())
    n.fail("'" + v + "' is not one of: " + join(allowed) + " (did you mean '" +
           nearest(v, allowed) + "'?)");
  return v;
}
std::string DeckNode::get_enum(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) const {
  note(key, "choice", choice_list(allowed), &fallback);
  return present(key) ? get_enum(key, allowed) : fallback;
}
std::array<double, 3> DeckNode::get_real3(const std::string& key, double lo, double hi) const {
  note(key, "real[3]", range_text(lo, hi), nullptr);
  const DeckNode n = child(key);
  if (!n.is_sequence() || n.size() != 3) n.fail("expected a list of 3 numbers [x, y, z]");
  return {n[0].as_real(lo, hi), n[1].as_real(lo, hi), n[2].as_real(lo, hi)};
}
std::array<double, 3> DeckNode::get_real3(const std::string& key, double lo, double hi,
                                          std::array<double, 3> fallback) const {
  const std::string d = triple(fallback);
  note(key, "real[3]", range_text(lo, hi), &d);
  return present(key) ? get_real3(key, lo, hi) : fallback;
}
std::array<int, 3> DeckNode::get_int3(const std::string& key, long lo, long hi) const {
  note(key, "integer[3]", range_text(lo, hi), nullptr);
  const DeckNode n = child(key);
  if (!n.is_sequence() || n.size() != 3) n.fail("expected a list of 3 integers [x, y, z]");
  return {static_cast<int>(n[0].as_int(lo, hi)), static_cast<int>(n[1].as_int(lo, hi)),
          static_cast<int>(n[2].as_int(lo, hi))};
}
std::array<int, 3> DeckNode::get_int3(const std::string& key, long lo, long hi,
                                      std::array<int, 3> fallback) const {
  const std::string d = triple(fallback);
  note(key, "integer[3]", range_text(lo, hi), &d);
  return present(key) ? get_int3(key, lo, hi) : fallback;
}

namespace {
void set_path(YAML::Node node, const std::vector<std::string>& keys, std::size_t i,
              const YAML::Node& value, const std::string& what) {
  const std::string& key = keys[i];
  const bool index = !key.empty() && std::all_of(key.begin(), key.end(), ::isdigit);
  if (node.IsSequence() && index) {
    const std::size_t n = std::stoul(key);
    if (n >= node.size()) throw InputError("--set " + what + ": list has no element " + key);
    if (i + 1 == keys.size()) {
      node[n] = value;
      return;
    }
    set_path(node[n], keys, i + 1, value, what);
    return;
  }
  if (!node.IsMap() && !node.IsNull())
    throw InputError("--set " + what + ": '" + key + "' is not inside a map");
  if (i + 1 == keys.size()) {
    node[key] = value;
    return;
  }
  if (!node[key] || node[key].IsNull() || node[key].IsScalar())
    node[key] = YAML::Node(YAML::NodeType::Map);
  set_path(node[key], keys, i + 1, value, what);
}
}  // namespace

namespace {
// A message quoting the deck's bytes, with anything unprintable (binary garbage) as \xNN.
std::string printable(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

// yaml-cpp keeps both entries of a key written twice (and lookups see the first): reject
// duplicates naming both lines, and keys that are not plain scalars.
void check_keys(const YAML::Node& n, const std::string& path, const std::string& file) {
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      check_keys(n[i], path + (path.empty() ? "" : ".") + std::to_string(i), file);
    return;
  }
  if (!n.IsMap()) return;
  std::map<std::string, int> seen;  // key -> line (1-based)
  for (auto it = n.begin(); it != n.end(); ++it) {
    const YAML::Mark m = it->first.Mark();
    const std::string where =
        file + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1) + ": ";
    if (!it->first.IsScalar())
      throw InputError(where + "key under '" + (path.empty() ? "<top>" : path) +
                       "': a key must be a plain name, not a list or map");
    const std::string key = it->first.Scalar();
    const std::string full = path.empty() ? key : path + "." + key;
    const auto [at, fresh] = seen.emplace(key, m.line + 1);
    if (!fresh)
      throw InputError(where + "key '" + full + "': given twice, at lines " +
                       std::to_string(at->second) + " and " + std::to_string(m.line + 1) +
                       "; keep one");
    check_keys(it->second, full, file);
  }
}
}  // namespace

Deck Deck::parse(const std::string& text, const std::string& name,
                 const std::vector<std::string>& overrides) {
  Deck d;
  d.file_ = std::make_shared<const std::string>(name);
  try {
    d.root_ = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    std::ostringstream os;
    os << name << ":" << e.mark.line + 1 << ":" << e.mark.column + 1
       << ": YAML syntax error: " << printable(e.msg);
    throw InputError(os.str());
  }
  if (!d.root_.IsMap()) throw InputError(name + ": a scene deck must be a YAML map");
  check_keys(d.root_, "", name);
  auto ov = std::make_shared<std::map<std::string, std::string>>();
  for (const auto& o : overrides) {
    const auto eq = o.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + o + ": expected key=value (for example mesh.cells=[64,64,64])");
    const std::string key = o.substr(0, eq);
    YAML::Node value;
    try {
      value = YAML::Load(o.substr(eq + 1));
    } catch (const YAML::ParserException& e) {
      throw InputError("--set " + o + ": YAML syntax error in the value: " + e.msg);
    }
    std::vector<std::string> keys;
    std::stringstream ss(key);
    for (std::string part; std::getline(ss, part, '.');) {
      if (part.empty()) throw InputError("--set " + o + ": empty key component");
      keys.push_back(part);
    }
    set_path(d.root_, keys, 0, value, o);
    (*ov)[key] = o;
  }
  d.overrides_ = ov;
  return d;
}

Deck Deck::load(const std::string& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open the scene deck");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), file, overrides);
}

namespace {
void flatten(const YAML::Node& n, const std::string& path,
             std::map<std::string, std::string>& out) {
  if (n.IsMap()) {
    for (auto it = n.begin(); it != n.end(); ++it)
      flatten(it->second, path.empty() ? it->first.Scalar() : path + "." + it->first.Scalar(), out);
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) flatten(n[i], path + "." + std::to_string(i), out);
  } else if (n.IsScalar()) {
    out[path] = n.Scalar();
  }
}
}  // namespace

std::map<std::string, std::string> Deck::values() const {
  std::map<std::string, std::string> out;
  flatten(root_, "", out);
  return out;
}

DeckNode Deck::root() const {
  return DeckNode(root_, "", file_, overrides_);
}

}  // namespace mp
