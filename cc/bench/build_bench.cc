// Build benchmark: every preset on one scene, single thread, optimised build.
//
//   bazel run --config=opt //cc/bench:build_bench -- --mesh PATH --out FILE
//
// For each preset the tree is first validated (tree invariants, and
// --check_rays seeded rays against the brute-force reference), then built
// --repeats times; one JSON line per preset and thread count goes to --out
// with the median T_B, every run's T_B, the throughput (triangles / T_B), the
// tree statistics (cc/kdtree/stats.h) and the tree's fingerprint; every timed
// build must write the validated tree (same fingerprint). With several
// --threads values the runs are interleaved (1, 2, 1, 2, ...) so that a slow
// stretch of the machine falls on both alike. Before them, --warmup builds per
// thread count run untimed (their times are recorded apart as
// T_B_warmup_runs): the first build of a thread count writes fresh pages,
// which the kernel zeroes at 0.5 to 1.5 GB/s on the measured VMs (huge_pages.h;
// a 2-thread build's fragments ask for other block sizes than the serial
// build), up to twice a warm build's time on the largest scenes, so T_B and
// the speed-up of 2 threads compare steady-state rebuilds.
//
// The timing method is kdrt's (issue 22): each timed build holds the
// machine-wide TimingLock (cc/base/timing_lock.h), so no other timed step of
// this project runs beside it; the validation, the warm-ups and each timed
// tree's fingerprint check run outside it. Every record carries "provenance"
// (cc/base/provenance.h: commit, dirty, source tree, compilation mode, CPU,
// the lock) of the workspace ($BUILD_WORKSPACE_DIRECTORY, else the current
// directory) and "timing" (method, rounds, warm-ups, seconds spent waiting for
// the lock). Relative --mesh, --out and --envs paths are taken from where
// `bazel run` was invoked, a relative --cache_dir from the workspace.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "cc/base/json_line.h"
#include "cc/base/median.h"
#include "cc/base/provenance.h"
#include "cc/base/timing_lock.h"
#include "cc/bench/bench_record.h"
#include "cc/tools/paths.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/builder.h"
#include "cc/kdtree/env_file.h"
#include "cc/kdtree/stats.h"
#include "cc/kdtree/traversal.h"

ABSL_FLAG(std::string, mesh, "", "mesh file to build on");
ABSL_FLAG(std::string, name, "", "scene name for the records (default: the file name)");
ABSL_FLAG(std::string, cache_dir, "data/cache/soups",
          "triangle-soup cache, relative to the workspace unless absolute ('' for none)");
ABSL_FLAG(std::string, presets, "", "comma-separated presets (default: the report's nine)");
ABSL_FLAG(std::string, envs, "",
          "comma-separated environment files: each is also built on top of every preset, "
          "recorded as preset 'PRESET+FILE' (for tuning a configuration before it becomes a "
          "preset)");
ABSL_FLAG(int, repeats, 5, "builds per preset; the median is reported");
ABSL_FLAG(std::string, threads, "1",
          "comma-separated build thread counts (Config::build_threads; 0 = all cores); "
          "each preset is timed with each, interleaved run by run");
ABSL_FLAG(int, check_rays, 200, "rays checked against brute force before timing");
ABSL_FLAG(int, warmup, 1,
          "untimed builds per preset and thread count before the timed ones (recorded as "
          "T_B_warmup_runs): a first build writes fresh pages, zeroed by the kernel");
ABSL_FLAG(std::string, out, "", "JSON-lines output file (appended)");
ABSL_FLAG(bool, list_presets, false,
          "print every preset --presets accepts, comma-separated, and exit");

namespace kdtree {
namespace {

// Rays from around the box towards random points of random triangles.
std::vector<Ray> CheckRays(const TriangleSoup& soup, int count) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const AABB box = soup.Bounds();
  const Vec3 centre = (box.lo + box.hi) * 0.5f;
  const float radius = Length(box.Extent());
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const size_t t = rng() % soup.size();
    float b1 = u(rng), b2 = u(rng);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const Vec3 target = soup.a(t) + (soup.b(t) - soup.a(t)) * b1 + (soup.c(t) - soup.a(t)) * b2;
    const Vec3 origin =
        centre + Normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f)) * radius;
    rays.push_back(Ray{origin, target - origin});
  }
  return rays;
}

// Thread counts of --threads; false on a bad entry.
bool ThreadCounts(std::vector<int>* counts) {
  for (absl::string_view t : absl::StrSplit(absl::GetFlag(FLAGS_threads), ',')) {
    int v = 1;
    if (!absl::SimpleAtoi(t, &v) || v < 0) {
      std::fprintf(stderr, "build_bench: bad --threads entry '%s'\n", std::string(t).c_str());
      return false;
    }
    counts->push_back(v);
  }
  return true;
}

int Run() {
  using bench::Json;
  if (absl::GetFlag(FLAGS_list_presets)) {
    std::printf("%s\n", absl::StrJoin(KnownPresetNames(), ",").c_str());
    return 0;
  }
  const std::string mesh = FromInvocationDir(absl::GetFlag(FLAGS_mesh));
  if (mesh.empty()) {
    std::fprintf(stderr, "build_bench: --mesh is required\n");
    return 2;
  }
  std::vector<int> thread_counts;
  if (!ThreadCounts(&thread_counts)) return 2;
  const int warmup = absl::GetFlag(FLAGS_warmup);
  const int repeats = absl::GetFlag(FLAGS_repeats);
  if (warmup < 0 || repeats < 1) {
    std::fprintf(stderr, "build_bench: --warmup must be >= 0 and --repeats >= 1\n");
    return 2;
  }
  LoadReport report;
  const std::string cache_dir = FromWorkspace(absl::GetFlag(FLAGS_cache_dir));
  absl::StatusOr<TriangleSoup> soup =
      cache_dir.empty() ? LoadMesh(mesh, &report) : LoadMeshCached(mesh, cache_dir, &report);
  if (!soup.ok()) {
    std::fprintf(stderr, "build_bench: %s\n", soup.status().ToString().c_str());
    return 1;
  }
  std::string name = absl::GetFlag(FLAGS_name);
  if (name.empty()) name = mesh.substr(mesh.find_last_of('/') + 1);
  std::vector<std::string> presets = PresetNames();
  if (!absl::GetFlag(FLAGS_presets).empty()) {
    presets = absl::StrSplit(absl::GetFlag(FLAGS_presets), ',');
  }
  std::FILE* out = stdout;
  const std::string out_path = FromInvocationDir(absl::GetFlag(FLAGS_out));
  if (!out_path.empty()) {
    out = std::fopen(out_path.c_str(), "a");
    if (!out) {
      std::fprintf(stderr, "build_bench: cannot open %s\n", out_path.c_str());
      return 1;
    }
  }
  // Where the numbers come from; the timed builds hold `lock`.
  TimingLock lock;
  // Untimed work holds the lock shared, timed rounds exclusively (timing_lock.h).
  if (const absl::Status st = lock.HoldShared(); !st.ok()) {
    std::fprintf(stderr, "%s\n", std::string(st.message()).c_str());
    return 1;
  }
  Provenance provenance = CollectProvenance(Workspace());
  provenance.timing_lock = lock.path();
  const Json provenance_json = provenance.ToJson();
  std::fprintf(stderr, "%s: %zu triangles (loaded in %.2f s%s)\n", name.c_str(), soup->size(),
               report.load_seconds, report.from_cache ? ", cached" : "");
  const std::vector<Ray> rays = CheckRays(*soup, absl::GetFlag(FLAGS_check_rays));
  const BruteForce brute(*soup);
  std::vector<Hit> reference;
  for (const Ray& r : rays) reference.push_back(brute.Intersect(r));

  // (name, configuration): each preset, then each --envs file on top of it.
  std::vector<std::pair<std::string, Config>> configs;
  for (const std::string& preset : presets) {
    absl::StatusOr<Config> config = Preset(preset);
    if (!config.ok()) {
      std::fprintf(stderr, "build_bench: %s\n", config.status().ToString().c_str());
      return 2;
    }
    configs.emplace_back(preset, *config);
    for (const std::string& path : std::vector<std::string>(
             absl::StrSplit(absl::GetFlag(FLAGS_envs), ',', absl::SkipEmpty()))) {
      absl::StatusOr<EnvResult> env = LoadEnvironmentFile(FromInvocationDir(path), *config);
      if (!env.ok()) {
        std::fprintf(stderr, "build_bench: %s\n", env.status().ToString().c_str());
        return 2;
      }
      configs.emplace_back(absl::StrCat(preset, "+", path.substr(path.find_last_of('/') + 1)),
                           env->config);
    }
  }
  for (const auto& [preset, config] : configs) {
    // Validate before timing (untimed, outside the lock).
    absl::StatusOr<KdTree> tree = BuildKdTree(*soup, config);
    if (!tree.ok()) {
      std::fprintf(stderr, "build_bench: %s: %s\n", preset.c_str(),
                   tree.status().ToString().c_str());
      return 1;
    }
    const TreeStats stats = ComputeStats(*tree);
    const uint64_t fingerprint = TreeFingerprint(*tree);
    int mismatches = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const Hit h = Intersect(*tree, rays[i]);
      if (h.hit() != reference[i].hit() ||
          (h.hit() && h.tri != reference[i].tri && h.t != reference[i].t)) {
        ++mismatches;
      }
    }
    if (mismatches > 0 || stats.invalid_leaf_boxes > 0 || stats.lost_planar > 0) {
      // Every reason, so that a tree refused for its structure alone (the
      // seed's float pruning losing planar references) does not read as
      // "0 rays differ".
      std::fprintf(stderr,
                   "build_bench: %s: validation failed (%d of %zu rays differ from brute force, "
                   "%llu leaves with an invalid box, %llu planar references lost)\n",
                   preset.c_str(), mismatches, rays.size(),
                   static_cast<unsigned long long>(stats.invalid_leaf_boxes),
                   static_cast<unsigned long long>(stats.lost_planar));
      return 1;
    }
    tree = absl::StatusOr<KdTree>();  // free it before timing
    std::vector<std::vector<double>> runs_by_threads(thread_counts.size());
    std::vector<std::vector<double>> warmup_by_threads(thread_counts.size());
    const double waited_before = lock.waited_seconds();
    // Warm-ups (r < 0) untimed; then each timed build alone under the lock.
    // Every build, warm-up or timed, must write the validated tree (the
    // parallel build writes the serial one byte for byte): checked after the
    // lock is released, and the tree freed, before the next build.
    for (int r = -warmup; r < repeats; ++r) {
      for (size_t k = 0; k < thread_counts.size(); ++k) {
        Config c = config;
        c.build_threads = thread_counts[k];
        const bool timed = r >= 0;
        if (timed) {
          if (const absl::Status st = lock.Acquire(); !st.ok()) {
            std::fprintf(stderr, "build_bench: %s\n", st.ToString().c_str());
            return 1;
          }
        }
        absl::StatusOr<KdTree> t = BuildKdTree(*soup, c);
        lock.Release();
        if (!t.ok() || TreeFingerprint(*t) != fingerprint) {
          std::fprintf(stderr, "build_bench: %s: %s build %d (threads %d) wrote another tree\n",
                       preset.c_str(), timed ? "timed" : "warm-up", timed ? r : r + warmup,
                       thread_counts[k]);
          return 1;
        }
        (timed ? runs_by_threads[k] : warmup_by_threads[k]).push_back(t->build_seconds);
      }
    }
    const Json stats_json = StatsToJson(stats);
    for (size_t k = 0; k < thread_counts.size(); ++k) {
      const std::vector<double>& runs = runs_by_threads[k];
      const double median = Median(runs);
      const double mtri_per_s = median > 0 ? soup->size() / median * 1e-6 : 0.0;
      Json rec = {{"scene", name},
                  {"mesh", mesh},
                  {"n_tri", soup->size()},
                  {"preset", preset},
                  {"threads", thread_counts[k]},
                  {"T_B", median},
                  {"T_B_runs", runs},
                  {"T_B_warmup_runs", warmup_by_threads[k]},
                  {"mtri_per_s", mtri_per_s},
                  {"checked_rays", rays.size()},
                  {"tree_fingerprint", absl::StrFormat("%016x", fingerprint)},
                  {"stats", stats_json}};
      rec["timing"] = {
          {"method", "warm-up builds excluded; then rounds alternating the thread counts, each "
                     "timed build alone under the timing lock"},
          {"rounds", runs.size()},
          {"warmup", warmup_by_threads[k].size()},
          {"lock_wait_s", lock.waited_seconds() - waited_before}};
      rec["provenance"] = provenance_json;
      if (!bench::WriteLine(out, JsonLine(rec))) {
        std::fprintf(stderr, "build_bench: cannot write %s\n",
                     out_path.empty() ? "stdout" : out_path.c_str());
        return 1;
      }
      std::fprintf(stderr,
                   "  %-18s threads %d  T_B %8.3f s  %6.3f Mtri/s  N_I %10llu  N_TP %11llu\n",
                   preset.c_str(), thread_counts[k], median, mtri_per_s,
                   static_cast<unsigned long long>(stats.inner),
                   static_cast<unsigned long long>(stats.leaf_refs));
    }
  }
  if (out != stdout && std::fclose(out) != 0) {
    std::fprintf(stderr, "build_bench: cannot write %s\n", out_path.c_str());
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace kdtree

int main(int argc, char** argv) {
  absl::ParseCommandLine(argc, argv);
  return kdtree::Run();
}
