#include "cc/bench/render_scene.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <utility>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "cc/base/json_line.h"
#include "cc/base/quiet_cpu.h"
#include "cc/bench/packet_counts.h"
#include "cc/bench/ray_classes.h"
#include "cc/bench/render_check.h"
#include "cc/bench/render_times.h"
#include "cc/bench/render_variants.h"
#include "cc/bench/twice_tracer.h"
#include "cc/embree/embree_tracer.h"
#include "cc/io/soup_cache.h"
#include "cc/kdtree/brute_force.h"
#include "cc/kdtree/config.h"
#include "cc/kdtree/leaf_layout.h"
#include "cc/kdtree/ray_packet.h"
#include "cc/render/framing.h"
#include "cc/render/kdtree_tracer.h"
#include "cc/render/manifest.h"
#include "cc/render/renderer.h"
#include "cc/render/replay_tracer.h"
#include "cc/render/view.h"
#include "cc/tools/paths.h"

namespace kdtree {
namespace bench {
namespace {

// The scene, its view and its trees, and the kd-tree entries --variants names.
struct Scene {
  std::string name;
  TriangleSoup soup;
  View view;
  Config config;
  std::unique_ptr<SceneTrees> trees;
  std::vector<Entry> variants;
  const KdTreeTracer& kd() const { return *trees->kd; }
};

absl::StatusOr<Scene> LoadScene(const std::string& name, const RenderBenchOptions& o) {
  const std::string repo = o.repo.empty() ? Workspace() : FromInvocationDir(o.repo);
  absl::StatusOr<SceneRef> ref = ResolveScene(repo, name);
  if (!ref.ok()) return ref.status();
  // Relative to --repo; an absolute directory as given (experiments/bench.py
  // passes one: joined to the repository, it made a second cache under
  // <repo>/<its own path>).
  const std::string cache_dir = o.cache_dir.empty() || o.cache_dir[0] == '/'
                                    ? o.cache_dir
                                    : absl::StrCat(repo, "/", o.cache_dir);
  Scene s;
  s.name = name;
  absl::StatusOr<TriangleSoup> soup = LoadMeshCached(ref->mesh_path, cache_dir);
  if (!soup.ok()) return soup.status();
  s.soup = *std::move(soup);
  s.view = ref->has_view ? ref->view : AutoView(s.soup.Bounds());
  absl::StatusOr<Config> config = Preset(o.preset);
  if (!config.ok()) return config.status();
  s.config = *config;
  std::vector<std::string> envs;
  for (const std::string& path : o.envs) envs.push_back(FromInvocationDir(path));
  bool triangle_bvh = false;  // built only for the variants that trace it
  for (const std::string& v : o.variants) triangle_bvh |= v.rfind("tri_bvh", 0) == 0;
  absl::StatusOr<std::unique_ptr<SceneTrees>> trees =
      BuildSceneTrees(s.soup, s.config, envs, o.env_variant, triangle_bvh);
  if (!trees.ok()) return trees.status();
  s.trees = *std::move(trees);
  absl::StatusOr<std::vector<Entry>> variants =
      VariantEntries(*s.trees, o.variants, o.env_variant);
  if (!variants.ok()) return variants.status();
  s.variants = *std::move(variants);
  return s;
}

// What the untimed validation found: the recorded render (every ray), each
// variant's mismatches against it, the packet kernel's counts, and the
// brute-force sample.
struct Validation {
  RenderResult recorded;
  Json variants = Json::object();
  Json packet_counts = Json::object();
  uint64_t checked = 0;
  uint64_t bf_bad = 0;
};

absl::StatusOr<Validation> Validate(const Scene& s, const RenderOptions& ropt,
                                    const RenderBenchOptions& o) {
  Validation v;
  RenderOptions rec_opt = ropt;
  rec_opt.record_rays = true;
  v.recorded = Render(s.soup, s.kd(), s.view, rec_opt);
  for (const Entry& e : s.variants) {
    uint64_t bad = 0;
    absl::Status st = CheckVariant(s.name, s.soup, s.view, ropt, v.recorded, e, &bad);
    if (!st.ok()) return st;
    v.variants[e.name] = bad;
  }
  // What the packet kernels do: the packet variants through the kd-tree,
  // through the BVH over its leaves and through the BVH over whole
  // triangles.
  for (const Entry& e : s.variants) {
    if (!e.packets) continue;
    CountThrough through;
    std::shared_ptr<const LeafBvh> tri;
    if (e.tracer == &s.kd()) {
      through = CountThrough::kKdTree;
    } else if (e.tracer == s.trees->bvh.get()) {
      through = CountThrough::kLeafBvh;
    } else if (s.trees->tri_bvh != nullptr && e.tracer == s.trees->tri_bvh.get()) {
      through = CountThrough::kTriangleBvh;
      tri = s.trees->tri_bvh->bvh();
    } else {
      continue;  // an environment tree
    }
    absl::StatusOr<Json> counts =
        CountPackets(s.soup, s.trees->tree, s.view, ropt, e, through, tri);
    if (!counts.ok()) return counts.status();
    v.packet_counts[e.name] = *std::move(counts);
  }
  const BruteForce bf(s.soup);
  v.bf_bad = BruteForceMismatches(v.recorded.rays, bf, o.check_rays, &v.checked);
  if (v.bf_bad != 0) {
    return absl::InternalError(absl::StrCat(s.name, ": ", v.bf_bad, " rays differ from brute force"));
  }
  return v;
}

// A thread count's tracers: the kd-tree variants, Embree's (default flags,
// then robust), the --twice wrappers, then the replays; and what they own.
struct Lineup {
  std::vector<Entry> entries;
  size_t n_kd = 0;      // entries[0, n_kd) are kd-trees
  size_t n_traced = 0;  // entries[n_traced, ...) are the replays
  std::vector<std::unique_ptr<EmbreeTracer>> embrees;
  std::vector<std::unique_ptr<TwiceTracer>> twice;
  std::vector<std::unique_ptr<ReplayTracer>> replays;
  Json disagree = nullptr, disagree_robust = nullptr;

  bool IsEmbree(const Entry& e) const {
    const auto* w = dynamic_cast<const TwiceTracer*>(e.tracer);
    const Tracer* tracer = w != nullptr ? &w->inner() : e.tracer;
    return std::any_of(embrees.begin(), embrees.end(),
                       [&](const auto& t) { return t.get() == tracer; });
  }
};

absl::Status AddEmbrees(const Scene& s, const RenderResult& recorded, int threads,
                        const RenderBenchOptions& o, Lineup* l) {
  absl::StatusOr<EmbreeQuality> q = ParseEmbreeQuality(o.embree);
  if (!q.ok()) return q.status();
  EmbreeOptions eo;
  eo.quality = *q;
  eo.threads = threads;
  for (const bool robust : {false, true}) {
    if (robust && !o.embree_robust) break;
    eo.robust = robust;
    absl::StatusOr<std::unique_ptr<EmbreeTracer>> e =
        AddEmbree(s.soup, eo, robust ? "embree_robust" : "embree", o.embree_packets,
                  recorded.rays, s.kd(), &l->entries, robust ? &l->disagree_robust : &l->disagree);
    if (!e.ok()) return e.status();
    l->embrees.push_back(*std::move(e));
  }
  return absl::OkStatus();
}

absl::StatusOr<std::unique_ptr<Lineup>> MakeLineup(const Scene& s, const RenderResult& recorded,
                                                   int threads, const RenderBenchOptions& o) {
  auto l = std::make_unique<Lineup>();
  l->entries = s.variants;
  l->n_kd = s.variants.size();
  if (o.embree != "off") {
    if (absl::Status st = AddEmbrees(s, recorded, threads, o, l.get()); !st.ok()) return st;
  }
  // Each traced entry again, tracing every query twice (--twice).
  if (o.twice && threads == 1) {
    for (size_t k = 0, n = l->entries.size(); k < n; ++k) {
      l->twice.push_back(std::make_unique<TwiceTracer>(l->entries[k].tracer));
      Entry e = l->entries[k];
      e.name = absl::StrCat(e.name, "_twice");
      e.tracer = l->twice.back().get();
      l->entries.push_back(std::move(e));
    }
  }
  l->n_traced = l->entries.size();
  if (o.replay && threads == 1) {
    for (const bool packets : {false, true}) {
      l->replays.push_back(std::make_unique<ReplayTracer>(s.kd()));
      l->entries.emplace_back(packets ? "replay_packet" : "replay", l->replays.back().get(),
                              packets, true);
      l->entries.back().replay = l->replays.back().get();
    }
  }
  return l;
}

// Renders one entry of the lineup; kd-tree variants must reproduce the
// validated image exactly (Embree may differ on grazing rays: its
// disagreements are recorded).
class EntryRenderer {
 public:
  EntryRenderer(const Scene& s, const Lineup& l, const RenderResult& recorded,
                const RenderOptions& topt)
      : s_(s), l_(l), recorded_(recorded), topt_(topt) {}

  RenderOptions OptionsOf(const Entry& e) const {
    RenderOptions o = topt_;
    o.packets = e.packets;
    o.skip_origin = e.skip_origin;
    return o;
  }

  absl::StatusOr<RenderResult> Render(const Entry& e) const {
    std::optional<ScopedPacketKernelTarget> kernel;
    if (!e.kernel.empty()) kernel.emplace(e.kernel);  // checked in validation
    if (e.replay != nullptr) e.replay->Rewind();
    RenderResult r = ::kdtree::Render(s_.soup, *e.tracer, s_.view, OptionsOf(e));
    if (!l_.IsEmbree(e) && r.rgb != recorded_.rgb) {
      return absl::InternalError(absl::StrCat(e.name, ": image differs"));
    }
    if (e.replay != nullptr && e.replay->overran()) {
      return absl::InternalError(absl::StrCat(e.name, ": more queries than recorded"));
    }
    return r;
  }

  // The replays' answers: one render of kd in their mode, recorded.
  absl::Status RecordReplays(std::vector<Entry>* entries) const {
    for (Entry& e : *entries) {
      if (e.replay == nullptr) continue;
      e.replay->Record();
      if (::kdtree::Render(s_.soup, *e.tracer, s_.view, OptionsOf(e)).rgb != recorded_.rgb) {
        return absl::InternalError(absl::StrCat(e.name, ": recorded image differs"));
      }
    }
    return absl::OkStatus();
  }

 private:
  const Scene& s_;
  const Lineup& l_;
  const RenderResult& recorded_;
  const RenderOptions topt_;
};

// What the timed part adds to a record beside the entries' times.
struct Timed {
  Json cpu;
  double lock_wait_s = 0;
  Json ray_classes;
};

// The warm-ups outside the lock, then the rounds (every entry once, in an
// order rotating per round) and the ray classes (--classes) under it.
absl::StatusOr<Timed> TimeRounds(const Scene& s, const RenderResult& recorded,
                                 const EntryRenderer& renderer, int threads,
                                 const RenderBenchOptions& o, const RenderBenchContext& ctx,
                                 Lineup* l) {
  for (int w = 0; w < o.warmup; ++w) {
    for (Entry& e : l->entries) {
      absl::StatusOr<RenderResult> r = renderer.Render(e);
      if (!r.ok()) return r.status();
      e.warmup.push_back(r->seconds);
    }
  }
  Timed t;
  const double waited_before = ctx.lock->waited_seconds();
  if (absl::Status st = ctx.lock->Acquire(); !st.ok()) return st;
  // One thread: the rounds on the quieter CPU (quiet_cpu.h).
  std::optional<ScopedQuietCpu> quiet;
  if (threads == 1) quiet.emplace();
  for (int round = 0; round < o.repeats; ++round) {
    for (size_t k = 0; k < l->entries.size(); ++k) {
      Entry& e = l->entries[(k + round) % l->entries.size()];
      absl::StatusOr<RenderResult> r = renderer.Render(e);
      if (!r.ok()) {
        ctx.lock->Release();
        return r.status();
      }
      e.runs.push_back(r->seconds);
      e.primary.push_back(r->primary.seconds);
      e.secondary.push_back(r->shadow.seconds + r->ao.seconds);
      e.rays = r->total_rays();
    }
  }
  // Per class of ray, the single-ray tracers alone (--classes).
  if (o.classes && threads == 1) {
    std::vector<RenderVariant> single;
    for (size_t k = 0; k < l->n_traced; ++k) {
      const Entry& e = l->entries[k];
      if (!e.packets && dynamic_cast<const TwiceTracer*>(e.tracer) == nullptr) single.push_back(e);
    }
    t.ray_classes = TimeRayClasses(ClassifyRays(recorded.rays, s.trees->tree), single, "embree",
                                   o.warmup, o.repeats);
  }
  t.cpu = QuietCpuJson(quiet ? &*quiet : nullptr);
  quiet.reset();
  ctx.lock->Release();
  t.lock_wait_s = ctx.lock->waited_seconds() - waited_before;
  return t;
}

// The record of one thread count.
Json MakeRecord(const Scene& s, const Validation& v, const Lineup& l, const Timed& t,
                int threads, int tile, const RenderBenchOptions& o) {
  Json tracers = TracerTimes(l.entries);
  // Ratios of each kd-tree tracer to Embree's single rays and, when timed,
  // to its packets; with the replays, of the tracing times alone too.
  Json ratios = Json::object(), packet_ratios = Json::object(), trace_only = Json::object();
  for (size_t k = l.n_kd; k < l.n_traced; ++k) {
    if (l.entries[k].name == "embree") ratios = RatiosTo(l.entries, l.n_kd, l.entries[k]);
    if (l.entries[k].name == "embree_packet") {
      packet_ratios = RatiosTo(l.entries, l.n_kd, l.entries[k]);
    }
  }
  if (!l.replays.empty()) trace_only = TraceOnly(l.entries, l.n_kd, l.n_traced, &tracers);
  const KdTree& tree = s.trees->tree;
  const RenderResult& rec = v.recorded;
  const CameraCoverage coverage = CameraCoverageOf(rec.primary_hits);
  const bool embree = !l.embrees.empty();
  Json out = {{"bench", "render"}, {"scene", s.name}, {"n_tri", s.soup.size()},
              {"preset", o.preset}, {"threads", threads}, {"tile", tile},
              {"repeats", o.repeats}, {"rays", rec.total_rays()},
              {"primary", rec.primary.rays}, {"shadow", rec.shadow.rays}, {"ao", rec.ao.rays},
              // What the camera sees (render_check.h CameraCoverage), and
              // how many shadow rays are occluded.
              {"camera_hits", coverage.hits}, {"camera_triangles", coverage.triangles},
              {"shadow_occluded", rec.s_hit},
              // The leaf packets' bytes (before 4c5d23d, also a second
              // node array of 8 bytes a node).
              {"leaf_layout_bytes", LeafLayoutBytes(tree)},
              // The whole tree (its nodes too) and Embree's BVH (its memory
              // monitor, embree_tracer.h bvh_bytes), null without Embree.
              {"tree_bytes", TreeBytes(tree)},
              {"embree_bvh_bytes", embree ? Json(l.embrees[0]->bvh_bytes()) : Json()},
              // kd_bvh's nodes, its own leaf packets (since 2026-12-07,
              // session 47: the kd leaves regrouped, leaf_bvh.h) and its
              // build from the finished tree.
              {"bvh_bytes", s.trees->bvh->bvh().node_bytes()},
              {"bvh_packet_bytes", s.trees->bvh->bvh().packet_bytes()},
              {"bvh_build_s", s.trees->bvh_build_seconds},
              // tri_bvh's nodes and leaf packets, and their build; null
              // without it.
              {"tri_bvh_bytes", s.trees->tri_bvh ? Json(s.trees->tri_bvh->bvh()->bytes()) : Json()},
              {"tri_bvh_build_s",
               s.trees->tri_bvh ? Json(s.trees->tri_bvh->build_seconds()) : Json()},
              {"tracers", std::move(tracers)},
              {"ratio_kd_over_embree", std::move(ratios)},
              {"ratio_kd_over_embree_packet", std::move(packet_ratios)},
              {"ratio_trace_only", std::move(trace_only)},
              {"embree_native_ray16", embree && l.embrees[0]->native_ray16()},
              {"packet_counts", v.packet_counts},
              {"ray_classes", t.ray_classes}};
  out["validation"] = {{"variants_vs_kd_mismatches", v.variants},
                       {"brute_force_checked", v.checked},
                       {"brute_force_mismatches", v.bf_bad},
                       {"embree_disagreements", l.disagree},
                       {"embree_robust_disagreements", l.disagree_robust}};
  out["timing"] = {{"method", "warm-up excluded; then rounds rendering every tracer once, in an "
                              "order rotating per round, alone under the timing lock (one "
                              "thread: on the quieter CPU); ratios paired per round"},
                   {"rounds", o.repeats},
                   {"warmup", o.warmup},
                   {"lock_wait_s", t.lock_wait_s},
                   // With one thread, the CPU the rounds ran on and each
                   // CPU's probe (quiet_cpu.h, ms); null otherwise.
                   {"cpu", t.cpu["cpu"]},
                   {"cpu_probe_ms", t.cpu["cpu_probe_ms"]}};
  return out;
}

}  // namespace

absl::Status RunScene(const std::string& name, const RenderBenchOptions& o,
                      const RenderBenchContext& ctx, FILE* out) {
  absl::StatusOr<Scene> scene = LoadScene(name, o);
  if (!scene.ok()) return scene.status();
  RenderOptions ropt;
  ropt.cast_shadow_rays = scene->config.cast_shadow_rays;
  absl::StatusOr<Validation> v = Validate(*scene, ropt, o);
  if (!v.ok()) return v.status();
  for (const int threads : o.threads) {
    absl::StatusOr<std::unique_ptr<Lineup>> l = MakeLineup(*scene, v->recorded, threads, o);
    if (!l.ok()) return l.status();
    RenderOptions topt = ropt;
    topt.threads = threads;
    topt.tile_size = o.tile;
    const EntryRenderer renderer(*scene, **l, v->recorded, topt);
    if (absl::Status st = renderer.RecordReplays(&(*l)->entries); !st.ok()) return st;
    absl::StatusOr<Timed> t = TimeRounds(*scene, v->recorded, renderer, threads, o, ctx, l->get());
    if (!t.ok()) return t.status();
    Json rec = MakeRecord(*scene, *v, **l, *t, threads, o.tile, o);
    rec["provenance"] = ctx.provenance;
    const std::string line = JsonLine(rec);
    if (!WriteLine(stdout, line) || !WriteLine(out, line)) {
      return absl::InternalError("cannot write the record");
    }
  }
  return absl::OkStatus();
}

}  // namespace bench
}  // namespace kdtree
