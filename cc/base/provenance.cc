#include "cc/base/provenance.h"

#include <limits.h>
#include <sched.h>
#include <stdlib.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

// Set by cc/base/BUILD from Bazel's $(COMPILATION_MODE).
#define KDTREE_STRINGIFY2(x) #x
#define KDTREE_STRINGIFY(x) KDTREE_STRINGIFY2(x)

namespace kdtree {
namespace {

// stdout of a shell command, and whether it exited 0.
std::string RunCommand(const std::string& cmd, bool* ok) {
  *ok = false;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return "";
  std::string out;
  char buf[256];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), p)) > 0) out.append(buf, n);
  *ok = pclose(p) == 0;
  return out;
}

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string Env(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? v : "";
}

// The value of the first line of `cpuinfo` whose key is `key` ("" if none).
std::string CpuInfoValue(const std::string& cpuinfo, const std::string& key) {
  std::ifstream cpu(cpuinfo);
  std::string line;
  while (std::getline(cpu, line)) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const size_t end = line.find_last_not_of(" \t", colon == 0 ? 0 : colon - 1);
    if (end == std::string::npos || line.substr(0, end + 1) != key) continue;
    const size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "" : line.substr(start);
  }
  return "";
}

// The first line of a small file, without its newline ("" if unreadable).
std::string FirstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

std::string CpuIdentity(const std::string& cpuinfo) {
  const std::string vendor = CpuInfoValue(cpuinfo, "vendor_id");
  const std::string family = CpuInfoValue(cpuinfo, "cpu family");
  const std::string model = CpuInfoValue(cpuinfo, "model");
  const std::string stepping = CpuInfoValue(cpuinfo, "stepping");
  if (family.empty() || model.empty()) return "";
  std::string id = vendor.empty() ? "" : vendor + " ";
  id += "family " + family + " model " + model;
  if (!stepping.empty()) id += " stepping " + stepping;
  return id;
}

std::string CpuCaches(const std::string& cache_dir) {
  std::string out;
  for (int i = 0; i < 16; ++i) {
    const std::string dir = cache_dir + "/index" + std::to_string(i) + "/";
    const std::string level = FirstLine(dir + "level");
    const std::string size = FirstLine(dir + "size");
    if (level.empty() || size.empty()) break;
    const std::string type = FirstLine(dir + "type");
    const std::string suffix = type == "Data" ? "d" : type == "Instruction" ? "i" : "";
    out += (out.empty() ? "" : ", ") + ("L" + level + suffix + " " + size);
  }
  return out;
}

namespace {

int Cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
  return static_cast<int>(std::thread::hardware_concurrency());
}

std::string NowUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm;
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Whether this process's executable lies in `root`'s Bazel output tree
// (root/bazel-out, the symlink Bazel leaves in a workspace), that is, was
// built from that checkout. True when /proc/self/exe cannot be resolved.
bool BuiltInCheckout(const std::string& root) {
  char exe[PATH_MAX], out[PATH_MAX];
  if (realpath("/proc/self/exe", exe) == nullptr) return true;
  if (realpath((root + "/bazel-out").c_str(), out) == nullptr) return false;
  return std::string(exe).rfind(std::string(out) + "/", 0) == 0;
}

void SetCodeIdentity(const std::string& repo_root, Provenance* p) {
  const std::string root = repo_root.empty() ? "." : repo_root;
  // Pinned by the runner when it built the tools (source_id.sh's line): the
  // code the binary was built from, not whatever the checkout holds by now.
  std::string line = Env("KDTREE_SOURCE_ID");
  bool ok = !line.empty();
  // Unpinned, the checkout's identity is the binary's only if the binary was
  // built there: a copy, or a build of another worktree run with --repo
  // pointing here, would otherwise claim this checkout's code. Unknown then.
  if (!ok && BuiltInCheckout(root)) {
    line = RunCommand("sh " + ShellQuote(root + "/cc/base/source_id.sh") + " " + ShellQuote(root) + " 2>/dev/null",
                      &ok);
  }
  std::istringstream words(line);
  std::string commit, dirty, tree;
  if (ok && (words >> commit >> dirty >> tree)) {
    p->commit = commit;
    p->dirty = dirty == "true";
    p->source_tree = tree;
  }
  if (!Env("KDTREE_GIT_COMMIT").empty()) p->commit = Env("KDTREE_GIT_COMMIT");
  if (!Env("KDTREE_SOURCE_TREE").empty()) p->source_tree = Env("KDTREE_SOURCE_TREE");
}

nlohmann::ordered_json OrNull(const std::string& s) { return s.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(s); }

}  // namespace

Provenance CollectProvenance(const std::string& repo_root) {
  Provenance p;
#ifdef KDTREE_COMPILATION_MODE
  p.compilation_mode = KDTREE_STRINGIFY(KDTREE_COMPILATION_MODE);
#else
  p.compilation_mode = "unknown";
#endif
#ifdef __OPTIMIZE__
  p.optimized = true;
#endif
#ifdef NDEBUG
  p.ndebug = true;
#endif
#ifdef __AVX2__
  p.avx2 = true;
#endif
#ifdef __AVX512F__
  p.avx512f = true;
#endif
#ifdef __FMA__
  p.fma = true;
#endif
  p.timing_build = p.compilation_mode == "opt" && p.optimized && p.ndebug;
  p.compiler = __VERSION__;
  SetCodeIdentity(repo_root, &p);
  p.cpu_model = CpuInfoValue("/proc/cpuinfo", "model name");
  p.cpu_id = CpuIdentity("/proc/cpuinfo");
  p.cpu_caches = CpuCaches("/sys/devices/system/cpu/cpu0/cache");
  p.cores = Cores();
  p.timestamp_utc = NowUtc();
  return p;
}

nlohmann::ordered_json Provenance::ToJson() const {
  return {{"commit", OrNull(commit)},
          {"dirty", dirty},
          {"source_tree", OrNull(source_tree)},
          {"compilation_mode", compilation_mode},
          {"optimized", optimized},
          {"ndebug", ndebug},
          {"avx2", avx2},
          {"avx512f", avx512f},
          {"fma", fma},
          {"timing_build", timing_build},
          {"compiler", compiler},
          {"cpu_model", OrNull(cpu_model)},
          {"cpu_id", OrNull(cpu_id)},
          {"cpu_caches", OrNull(cpu_caches)},
          {"cores", cores},
          {"timing_lock", OrNull(timing_lock)},
          {"timed_beside", timing_lock.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(0)},
          {"timestamp_utc", timestamp_utc}};
}

}  // namespace kdtree
