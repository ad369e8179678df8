// Running the real minipagosa executable (MINIPAGOSA_EXE) from a test, in a fresh temporary
// directory and a clean environment (the child must not inherit the OMPI_*/PMIX_* variables
// that would make it part of the test's own MPI job).
#pragma once
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "paths.hpp"

namespace mp::cli {

namespace fs = std::filesystem;

inline std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}
inline std::string exe() {
  return test::minipagosa_exe();
}
inline std::string source_dir() {
  return test::source_dir();
}
inline std::string config(const std::string& name) {
  return source_dir() + "/configs/" + name;
}

inline std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
inline bool holds(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

struct Result {
  int status = -1;  // exit status; -1 if killed by a signal or timed out
  bool timed_out = false;
  std::string out, err;
  long max_rss_kib = 0;  // the child's peak resident memory (wait4's ru_maxrss), KiB
};

// The clean environment of a child run.
inline std::vector<std::string> child_env() {
  std::vector<std::string> env = {"PATH=" + env_or("PATH", "/usr/bin:/bin"),
                                  "HOME=" + env_or("HOME", "/tmp"),
                                  "OMPI_ALLOW_RUN_AS_ROOT=1",
                                  "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                                  "OMPI_MCA_rmaps_base_oversubscribe=1",
                                  "OMP_NUM_THREADS=1",
                                  "OMP_PROC_BIND=false",
                                  "OMP_WAIT_POLICY=passive"};
  if (std::getenv("LD_LIBRARY_PATH"))
    env.push_back("LD_LIBRARY_PATH=" + env_or("LD_LIBRARY_PATH", ""));
  return env;
}

// A child process running `argv` in `dir`, its stdout and stderr going to files there.
class Child {
 public:
  // `extra_env`: NAME=value entries added to the clean environment.
  Child(const fs::path& dir, const std::vector<std::string>& argv, const std::string& tag = "",
        const std::vector<std::string>& extra_env = {})
      : dir_(dir), out_(dir / (".stdout" + tag)), err_(dir / (".stderr" + tag)) {
    pid_ = fork();
    if (pid_ == 0) {
      if (chdir(dir.c_str()) != 0) _exit(127);
      const int in = open("/dev/null", O_RDONLY);
      const int o = open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(in, 0);
      dup2(o, 1);
      dup2(e, 2);
      setpgid(0, 0);  // its own process group: a signal to the group reaches mpiexec's children
      std::vector<std::string> env = child_env();
      env.insert(env.end(), extra_env.begin(), extra_env.end());
      std::vector<char*> a, en;
      for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
      a.push_back(nullptr);
      for (const auto& s : env) en.push_back(const_cast<char*>(s.c_str()));
      en.push_back(nullptr);
      execvpe(a[0], a.data(), en.data());
      _exit(127);
    }
  }
  ~Child() {
    if (pid_ > 0 && !done_) {
      kill(-pid_, SIGKILL);
      int st = 0;
      waitpid(pid_, &st, 0);
    }
  }
  pid_t pid() const { return pid_; }
  std::string out() const { return read(out_); }
  // Waits until stdout holds `text` (true) or the process ended / the time ran out (false).
  bool wait_for_output(const std::string& text, double seconds) {
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds) {
      if (holds(read(out_), text)) return true;
      int st = 0;
      if (!done_ && wait4(pid_, &st, WNOHANG, &usage_) == pid_) {
        done_ = true;
        status_ = st;
        return holds(read(out_), text);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }
  void signal(int sig, bool group = false) const { kill(group ? -pid_ : pid_, sig); }
  // Waits for the end (killing the process group after `seconds`).
  Result finish(double seconds) {
    Result r;
    const auto t0 = std::chrono::steady_clock::now();
    while (!done_) {
      int st = 0;
      if (wait4(pid_, &st, WNOHANG, &usage_) == pid_) {
        done_ = true;
        status_ = st;
        break;
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > seconds) {
        kill(-pid_, SIGKILL);
        waitpid(pid_, &st, 0);
        done_ = true;
        status_ = st;
        r.timed_out = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (!r.timed_out && WIFEXITED(status_)) r.status = WEXITSTATUS(status_);
    r.out = read(out_);
    r.err = read(err_);
    r.max_rss_kib = usage_.ru_maxrss;
    std::error_code ec;
    fs::remove(out_, ec);
    fs::remove(err_, ec);
    return r;
  }

 private:
  fs::path dir_, out_, err_;
  pid_t pid_ = -1;
  bool done_ = false;
  int status_ = 0;
  struct rusage usage_ {};
};

// A file's dataset names, in the file's order (H5Literate by name); empty if it cannot be opened.
inline std::vector<std::string> dataset_names(const std::string& file) {
  std::vector<std::string> names;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return names;
  H5Literate(
      f, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->push_back(name);
        return 0;
      },
      &names);
  H5Fclose(f);
  return names;
}

// A fresh temporary directory per test, removed unless the test failed.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = (fs::temp_directory_path() / "minipagosa_cli_XXXXXX").string();
    ASSERT_NE(mkdtemp(name.data()), nullptr);
    dir_ = name;
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure())
      fs::remove_all(dir_, ec);
    else
      std::fprintf(stderr, "kept %s for inspection\n", dir_.c_str());
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }
  // Runs minipagosa with `args` (prefixed by `launcher`, e.g. {"mpiexec", "-np", "2"}) and
  // waits at most `seconds`.
  Result run(const std::vector<std::string>& args, double seconds = 120,
             const std::vector<std::string>& launcher = {}) const {
    std::vector<std::string> argv = launcher;
    argv.push_back(exe());
    argv.insert(argv.end(), args.begin(), args.end());
    Child c(dir_, argv);
    return c.finish(seconds);
  }
  // Files (names) in a directory below the test's, sorted.
  std::vector<std::string> files(const std::string& sub) const {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir_ / sub, ec))
      out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path dir_;
};

}  // namespace mp::cli
