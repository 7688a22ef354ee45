#include "cc/tools/timed_build.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace kdtree {
namespace {

absl::StatusOr<double> BuildKd(const TriangleSoup& soup, const Config& config, TimedBuilds* b) {
  b->tree = absl::UnknownError("rebuilding");  // the old tree is freed first
  b->tree = BuildKdTree(soup, config, b->limits);
  if (absl::IsResourceExhausted(b->tree.status())) {
    return absl::ResourceExhaustedError(absl::StrCat(
        b->tree.status().message(),
        " (what the memory budget leaves after the renders; kdrt --memory_budget_gb)"));
  }
  if (!b->tree.ok()) return b->tree.status();
  return b->tree->build_seconds;
}

absl::StatusOr<double> BuildEmbree(const TriangleSoup& soup, const EmbreeOptions& options, TimedBuilds* b) {
  b->embree.reset();
  absl::StatusOr<std::unique_ptr<EmbreeTracer>> e = EmbreeTracer::Create(soup, options);
  if (!e.ok()) return e.status();
  b->embree = *std::move(e);
  return b->embree->build_seconds();
}

}  // namespace

absl::Status WarmUpBuilds(const TriangleSoup& soup, const Config& config, const EmbreeOptions* embree,
                          TimedBuilds* b) {
  absl::StatusOr<double> s = BuildKd(soup, config, b);
  if (!s.ok()) return s.status();
  b->kd_warmup = *s;
  if (embree == nullptr) return absl::OkStatus();
  if (!(s = BuildEmbree(soup, *embree, b)).ok()) return s.status();
  b->embree_warmup = *s;
  return absl::OkStatus();
}

absl::Status TimeBuildRounds(const TriangleSoup& soup, const Config& config, const EmbreeOptions* embree,
                             int repeats, double budget_s, const StepFn& step, TimedBuilds* b) {
  std::vector<double> rounds;
  for (int i = 0; MoreRuns(rounds, repeats, budget_s); ++i) {
    if (step) step(absl::StrFormat("build round %d/%d", i + 1, repeats));
    absl::StatusOr<double> s = BuildKd(soup, config, b);
    if (!s.ok()) return s.status();
    b->kd_runs.push_back(*s);
    rounds.push_back(*s);
    if (embree == nullptr) continue;
    if (!(s = BuildEmbree(soup, *embree, b)).ok()) return s.status();
    b->embree_runs.push_back(*s);
    rounds.back() += *s;
  }
  return absl::OkStatus();
}

}  // namespace kdtree
