// Where a test finds the minipagosa executable and the source tree (the decks in configs/).
// MINIPAGOSA_EXE and MINIPAGOSA_SOURCE_DIR, when set, name them. Otherwise the executable is
// the one beside the test binary: the path from the tests' build directory to the executable
// that CMake computed (MP_EXE_FROM_TESTS), taken from the test binary's own location
// (/proc/self/exe), so a test binary run by hand, or from a build directory carried to another
// directory or machine, still finds it. The source tree is the one CMake configured
// (configured_source_dir(), tests/paths.cpp) where it exists, else the working directory or its
// parent, whichever holds configs/. Both come back absolute (the command-line tests change
// directory before running).
#pragma once
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace mp::test {

// The source tree CMake configured (library mp_test_paths: tests/paths.cpp).
const char* configured_source_dir();

inline std::string minipagosa_exe() {
  namespace fs = std::filesystem;
  if (const char* e = std::getenv("MINIPAGOSA_EXE"); e && *e) return e;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path from = ec ? fs::current_path() : self.parent_path();
  return (from / MP_EXE_FROM_TESTS).lexically_normal().string();
}

inline std::string source_dir() {
  namespace fs = std::filesystem;
  if (const char* s = std::getenv("MINIPAGOSA_SOURCE_DIR"); s && *s) return s;
  const fs::path cwd = fs::current_path();
  for (const fs::path& dir : {fs::path(configured_source_dir()), cwd, cwd.parent_path()}) {
    std::error_code ec;
    if (fs::is_directory(dir / "configs", ec)) return dir.string();
  }
  return cwd.string();
}

// Every shipped deck (configs/*.yaml of the source tree), full paths, sorted.
inline std::vector<std::string> shipped_decks() {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(source_dir() + "/configs", ec))
    if (e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace mp::test
