#include "cc/tools/run_info.h"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/strip.h"
#include "cc/render/json.h"

// Set by cc/tools/BUILD from Bazel's $(COMPILATION_MODE).
#define KDTREE_STRINGIFY2(x) #x
#define KDTREE_STRINGIFY(x) KDTREE_STRINGIFY2(x)

namespace kdtree {
namespace {

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
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

}  // namespace

RunInfo CollectRunInfo(const std::string& repo_root) {
  RunInfo info;
#ifdef KDTREE_COMPILATION_MODE
  info.compilation_mode = KDTREE_STRINGIFY(KDTREE_COMPILATION_MODE);
#else
  info.compilation_mode = "unknown";
#endif
#ifdef __OPTIMIZE__
  info.optimized = true;
#endif
#ifdef NDEBUG
  info.ndebug = true;
#endif
#ifdef __AVX2__
  info.avx2 = true;
#endif
#ifdef __AVX512F__
  info.avx512f = true;
#endif
#ifdef __FMA__
  info.fma = true;
#endif
  info.timing_build = info.compilation_mode == "opt" && info.optimized && info.ndebug;
  info.compiler = __VERSION__;

  if (const char* env = std::getenv("KDTREE_GIT_COMMIT"); env != nullptr && *env != '\0') {
    info.git_commit = env;
  } else {
    const std::string git = absl::StrCat("git -C ", ShellQuote(repo_root.empty() ? "." : repo_root));
    bool ok;
    std::string head = RunCommand(git + " rev-parse HEAD 2>/dev/null", &ok);
    if (ok) {
      info.git_commit = std::string(absl::StripAsciiWhitespace(head));
      const std::string status = RunCommand(git + " status --porcelain --untracked-files=no 2>/dev/null", &ok);
      info.git_dirty = ok && !absl::StripAsciiWhitespace(status).empty();
    }
  }
  std::ifstream cpu("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpu, line)) {
    if (absl::StartsWith(line, "model name")) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) {
        info.cpu_model = std::string(absl::StripAsciiWhitespace(line.substr(colon + 1)));
      }
      break;
    }
  }
  const std::time_t now = std::time(nullptr);
  std::tm tm;
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  info.timestamp_utc = buf;
  return info;
}

std::string RunInfo::ToJson() const {
  auto b = [](bool v) { return v ? "true" : "false"; };
  return absl::StrFormat(
      "\"build\": {\"compilation_mode\": %s, \"optimized\": %s, \"ndebug\": %s, \"avx2\": %s, "
      "\"avx512f\": %s, \"fma\": %s, \"timing_build\": %s, \"compiler\": %s}, "
      "\"git_commit\": %s, \"git_dirty\": %s, \"cpu_model\": %s, \"timestamp_utc\": %s",
      JsonQuote(compilation_mode), b(optimized), b(ndebug), b(avx2), b(avx512f), b(fma),
      b(timing_build), JsonQuote(compiler),
      git_commit.empty() ? "null" : JsonQuote(git_commit), b(git_dirty),
      cpu_model.empty() ? "null" : JsonQuote(cpu_model), JsonQuote(timestamp_utc));
}

}  // namespace kdtree
