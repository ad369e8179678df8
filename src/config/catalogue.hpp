// Every deck key the reader accepts, with its type, range or choices and default, found by
// reading a set of catalogue decks with the reader's recording on (deck.hpp, KeyCatalogue):
// the reader is the one source. `minipagosa --list-keys` prints options_markdown(), which is
// docs/options.md (the CTest test test_docs checks the two are equal).
#pragma once
#include <map>
#include <string>

#include "config/deck.hpp"

namespace mp {

// The catalogue: every key the reader listed or read while reading the catalogue decks.
std::map<std::string, KeyInfo> accepted_keys();

// docs/options.md: one table per section, a row per key (type, range/choices, default, meaning).
std::string options_markdown();

// The meaning column: one short line per key (checked against accepted_keys() by test_config).
const std::map<std::string, std::string>& key_notes();

}  // namespace mp
