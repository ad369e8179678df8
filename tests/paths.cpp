// The source tree CMake configured (tests/paths.hpp), compiled in this file alone: as a define on
// every test's and benchmark's command line it made each of their compiles differ from one
// clone to another, so that a fresh clone's build missed the compiler cache for all of them.
// (paths.hpp is not included: its inline functions need each program's own MP_EXE_FROM_TESTS.)
namespace mp::test {

const char* configured_source_dir();

const char* configured_source_dir() {
  return MP_SOURCE_DIR;
}

}  // namespace mp::test
