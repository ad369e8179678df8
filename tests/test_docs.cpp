// The documentation checked against the code (issue #56): docs/options.md is what the deck
// reader accepts (minipagosa --list-keys writes it from the reader), every shipped deck uses
// only keys the reader accepts, and every deck's header stays short (at most 15 comment lines
// before its first key; history and measurements live in docs/studies/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "config/catalogue.hpp"
#include "config/deck.hpp"
#include "paths.hpp"

namespace {

// the source tree (tests/paths.hpp: MINIPAGOSA_SOURCE_DIR, else the configured one)
std::string source_dir() {
  return mp::test::source_dir();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) out.push_back(line);
  return out;
}

// The rows of docs/options.md's tables: key -> the row's cells (type, range, default, meaning).
std::map<std::string, std::vector<std::string>> doc_rows(const std::string& text) {
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& line : lines_of(text)) {
    if (line.compare(0, 3, "| `") != 0) continue;
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
        cell += '|';
        ++i;
      } else if (line[i] == '|') {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    if (cells.size() < 5) continue;
    std::string key = cells[0];
    key.erase(std::remove(key.begin(), key.end(), '`'), key.end());
    key.erase(std::remove(key.begin(), key.end(), ' '), key.end());
    rows[key] = {cells[1], cells[2], cells[3], cells[4]};
  }
  return rows;
}

std::string trim(std::string s) {
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

TEST(OptionsDoc, IsWhatTheReaderPrints) {
  const std::string doc = read_file(source_dir() + "/docs/options.md");
  const std::string now = mp::options_markdown();
  const auto a = lines_of(doc), b = lines_of(now);
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  EXPECT_EQ(doc, now) << "docs/options.md differs from `minipagosa --list-keys` at line " << i + 1
                      << ":\n  doc:    " << (i < a.size() ? a[i] : "(end)")
                      << "\n  reader: " << (i < b.size() ? b[i] : "(end)")
                      << "\nregenerate: build/minipagosa --list-keys > docs/options.md";
}

// Every key the reader accepts is a row of docs/options.md with a type (or is a section), a
// default (or says required / none / optional) and a meaning; no row names a key the reader
// does not accept.
TEST(OptionsDoc, EveryAcceptedKeyHasARowAndNoRowIsUnknown) {
  const auto keys = mp::accepted_keys();
  const auto rows = doc_rows(read_file(source_dir() + "/docs/options.md"));
  std::printf("%zu keys accepted, %zu rows in docs/options.md\n", keys.size(), rows.size());
  EXPECT_GT(keys.size(), 100u);  // observed 145
  for (const auto& [key, info] : keys) {
    const auto it = rows.find(key);
    ASSERT_NE(it, rows.end()) << key << " is accepted by the reader but not in docs/options.md";
    EXPECT_FALSE(trim(it->second[0]).empty()) << key << ": no type";
    EXPECT_FALSE(trim(it->second[2]).empty()) << key << ": no default";
    EXPECT_FALSE(trim(it->second[3]).empty()) << key << ": no meaning";
    if (!info.defaults.empty() && trim(it->second[2]).rfind('`', 0) == 0) {
      EXPECT_NE(it->second[2].find(*info.defaults.begin()), std::string::npos)
          << key << ": the doc's default is not the reader's " << *info.defaults.begin();
    }
  }
  for (const auto& row : rows)
    EXPECT_TRUE(keys.count(row.first))
        << row.first << " is in docs/options.md, unknown to the reader";
}

// The catalogue decks take every branch: each key a map lists is read with a type somewhere
// (else its type, range and default would be missing), and the meanings name only real keys.
TEST(OptionsDoc, CatalogueReadsEveryListedKey) {
  const auto keys = mp::accepted_keys();
  for (const auto& [key, info] : keys) {
    if (!info.type.empty()) continue;
    bool section = false;
    for (const auto& other : keys)
      if (other.first.size() > key.size() && other.first.compare(0, key.size(), key) == 0 &&
          (other.first[key.size()] == '.' || other.first[key.size()] == '['))
        section = true;
    EXPECT_TRUE(section) << key << " is listed by the reader but no catalogue deck reads it "
                         << "(src/config/catalogue.cpp, kCatalogueDecks)";
  }
  for (const auto& note : mp::key_notes())
    EXPECT_TRUE(keys.count(note.first))
        << "key_notes() names " << note.first << ", which the reader does not accept";
}

// Every key of every shipped deck is one the catalogue knows (so docs/options.md lists it).
TEST(OptionsDoc, ShippedDecksUseOnlyListedKeys) {
  const auto keys = mp::accepted_keys();
  const auto decks = mp::test::shipped_decks();
  ASSERT_GE(decks.size(), 20u);
  for (const auto& file : decks) {
    for (const auto& kv : mp::Deck::load(file).values()) {
      // "materials.0.burn.detonators.1.at.2" -> "materials[].burn.detonators[].at"
      std::string path, part;
      std::stringstream ss(kv.first);
      while (std::getline(ss, part, '.'))
        path += std::all_of(part.begin(), part.end(), ::isdigit) ? "[]"
                                                                 : (path.empty() ? "" : ".") + part;
      while (path.size() > 2 && path.compare(path.size() - 2, 2, "[]") == 0 && !keys.count(path))
        path.resize(path.size() - 2);
      EXPECT_TRUE(keys.count(path))
          << file << ": " << kv.first << " (" << path << ") is not in docs/options.md";
    }
  }
}

// A deck's header (the comment lines before its first key) says what the scene is, its source,
// units, deviations and how to change the resolution, in at most 15 lines.
TEST(Decks, HeadersAtMostFifteenCommentLines) {
  const auto decks = mp::test::shipped_decks();
  ASSERT_GE(decks.size(), 20u);
  for (const auto& file : decks) {
    int comments = 0;
    bool key = false;
    for (const auto& line : lines_of(read_file(file))) {
      if (!line.empty() && line[0] != '#' && line[0] != ' ') {
        key = true;
        break;
      }
      if (!line.empty() && line[0] == '#') ++comments;
    }
    EXPECT_TRUE(key) << file << ": no key";
    std::printf("%-60s %2d header lines\n", file.c_str(), comments);
    EXPECT_LE(comments, 15) << file << ": " << comments
                            << " comment lines before the first key; move history and "
                               "measurements to docs/studies/";
    EXPECT_GE(comments, 1) << file << ": no header saying what the scene is";
  }
}
