// Strict reading of YAML scene decks (STYLE.md practice 6). Every value is read through a
// DeckNode, which knows the file and line it came from; every map lists the keys it accepts,
// so a typo is an error naming file:line, the key path, and the nearest valid key.
#pragma once
#include <yaml-cpp/yaml.h>

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace mp {

// What the reader accepts, recorded while it reads (config/catalogue.hpp: minipagosa
// --list-keys writes docs/options.md from it). Keys are dotted paths with list indices as
// "[]" (materials[].burn.detonators[].type); a key appears once a map lists it in
// expect_keys, and gets its type, range and default when a get_* reads it.
struct KeyInfo {
  std::string type;                // real, integer, bool, string, choice, real[3], integer[3]
  std::string range;               // "[lo, hi]", ">= lo", "any", or the choices "a | b"
  std::set<std::string> defaults;  // the fallbacks seen (none: required or optional)
  bool probed = false;             // the reader asked whether it is there (optional)
};
struct KeyCatalogue {
  std::map<std::string, KeyInfo> keys;
  // The catalogue a DeckNode records into; nullptr (the default): nothing is recorded.
  static KeyCatalogue*& active();
};

class DeckNode {
 public:
  DeckNode(YAML::Node node, std::string path, std::shared_ptr<const std::string> file,
           std::shared_ptr<const std::map<std::string, std::string>> overrides)
      : node_(std::move(node)),
        path_(std::move(path)),
        file_(std::move(file)),
        overrides_(std::move(overrides)) {}

  const std::string& path() const { return path_; }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  std::size_t size() const { return node_.size(); }

  // Rejects keys not in `allowed` (with the nearest allowed key suggested); the node must be a map.
  void expect_keys(const std::vector<std::string>& allowed) const;
  bool has(const std::string& key) const;        // (for the catalogue: the key is optional)
  DeckNode child(const std::string& key) const;  // required
  DeckNode operator[](std::size_t index) const;  // sequence element
  std::vector<DeckNode> items() const;           // sequence elements (must be a sequence)

  // Scalars, checked for type and range.
  double get_real(const std::string& key, double lo, double hi) const;
  double get_real(const std::string& key, double lo, double hi, double fallback) const;
  long get_int(const std::string& key, long lo, long hi) const;
  long get_int(const std::string& key, long lo, long hi, long fallback) const;
  bool get_bool(const std::string& key, bool fallback) const;
  std::string get_string(const std::string& key) const;
  std::string get_string(const std::string& key, const std::string& fallback) const;
  // One of `allowed`; the error lists them all.
  std::string get_enum(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string get_enum(const std::string& key, const std::vector<std::string>& allowed,
                       const std::string& fallback) const;
  // One of the names in `choices`, as its value (an enum class); the error lists the names.
  template <class E>
  E get_choice(const std::string& key, const std::vector<std::pair<std::string, E>>& choices,
               E fallback) const {
    std::vector<std::string> names;
    std::string fallback_name;
    for (const auto& c : choices) {
      names.push_back(c.first);
      if (c.second == fallback) fallback_name = c.first;
    }
    note(key, "choice", choice_list(names), &fallback_name);
    if (!present(key)) return fallback;
    const std::string v = get_enum(key, names);
    for (const auto& c : choices)
      if (c.first == v) return c.second;
    return fallback;  // (get_enum refused any other name)
  }
  std::array<double, 3> get_real3(const std::string& key, double lo, double hi) const;
  std::array<double, 3> get_real3(const std::string& key, double lo, double hi,
                                  std::array<double, 3> fallback) const;
  std::array<int, 3> get_int3(const std::string& key, long lo, long hi) const;
  std::array<int, 3> get_int3(const std::string& key, long lo, long hi,
                              std::array<int, 3> fallback) const;

  // This node's own value (for sequence items and scalars).
  double as_real(double lo, double hi) const;
  long as_int(long lo, long hi) const;
  std::string as_string() const;

  // "file:line:col: key 'a.b.c': message" (or "--set a.b.c=...: message" for overrides).
  [[noreturn]] void fail(const std::string& message) const;
  std::string where() const;

 private:
  DeckNode sub(const YAML::Node& n, const std::string& key) const;
  bool present(const std::string& key) const;
  // Records `key` (under this node) in the active catalogue, if any; `fallback` null: no default.
  void note(const std::string& key, const char* type, const std::string& range,
            const std::string* fallback) const;
  static std::string choice_list(const std::vector<std::string>& names);
  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const std::string> file_;
  std::shared_ptr<const std::map<std::string, std::string>> overrides_;
};

// A whole deck: the parsed file with the command line's --set overrides applied.
class Deck {
 public:
  // Parses `file`; each override is "dotted.key=yaml-value". Throws InputError.
  static Deck load(const std::string& file, const std::vector<std::string>& overrides = {});
  static Deck parse(const std::string& text, const std::string& name,
                    const std::vector<std::string>& overrides = {});
  DeckNode root() const;
  const std::string& file() const { return *file_; }
  // Every scalar of the deck (overrides applied) as "dotted.path" -> text, for comparing the
  // deck of a checkpoint with the deck of a restart.
  std::map<std::string, std::string> values() const;

 private:
  YAML::Node root_;
  std::shared_ptr<const std::string> file_;
  std::shared_ptr<const std::map<std::string, std::string>> overrides_;
};

// Levenshtein distance, for "did you mean" suggestions.
int edit_distance(const std::string& a, const std::string& b);
std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace mp
