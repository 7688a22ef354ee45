#include "cc/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "cc/render/camera.h"
#include "cc/render/secondary_rays.h"
#include "oneapi/tbb/blocked_range.h"
#include "oneapi/tbb/global_control.h"
#include "oneapi/tbb/parallel_for.h"

namespace kdtree {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// Linear [0, 1] to gamma-1/2.2 bytes through a 4096-entry table (std::pow per
// channel would cost ~10% of a fast render's T_R).
uint8_t ToByte(float linear) {
  static const std::vector<uint8_t>* table = [] {
    auto* t = new std::vector<uint8_t>(4097);
    for (int i = 0; i <= 4096; ++i) {
      (*t)[i] = static_cast<uint8_t>(std::pow(i / 4096.0, 1.0 / 2.2) * 255.0 + 0.5);
    }
    return t;
  }();
  const float c = std::fmin(1.0f, std::fmax(0.0f, linear));
  return (*table)[static_cast<int>(c * 4096.0f + 0.5f)];
}

uint64_t Sum(const std::vector<uint64_t>& v) {
  uint64_t s = 0;
  for (uint64_t x : v) s += x;
  return s;
}

// Sum of f(y0, y1, x0, x1) over the image [0, w) x [0, h) cut into bands of
// `band` rows (the last band of a tile may be shorter): whole rows in order
// for one thread; whole rows in parallel when `rows` (the recorded rays are
// kept per row); else square tiles of side `tile` in parallel (Wald,
// Slusallek, Benthin & Wagner, "Interactive rendering with coherent ray
// tracing", CGF 20(3), 2001: tiles keep neighbouring rays, which visit the
// same nodes, on one core). Every count is an integer written by one task and
// summed afterwards, so results never depend on the schedule.
template <typename F>
uint64_t ForBands(int w, int h, int threads, int tile, bool rows, int band, const F& f) {
  if (threads <= 1) {
    uint64_t sum = 0;
    for (int y = 0; y < h; y += band) sum += f(y, std::min(h, y + band), 0, w);
    return sum;
  }
  if (rows || tile <= 0) {
    const int nb = (h + band - 1) / band;
    std::vector<uint64_t> counts(nb);
    tbb::parallel_for(tbb::blocked_range<int>(0, nb, 1), [&](const tbb::blocked_range<int>& r) {
      for (int b = r.begin(); b < r.end(); ++b) {
        counts[b] = f(b * band, std::min(h, (b + 1) * band), 0, w);
      }
    });
    return Sum(counts);
  }
  const int nx = (w + tile - 1) / tile, ny = (h + tile - 1) / tile;
  std::vector<uint64_t> counts(static_cast<size_t>(nx) * ny);
  tbb::parallel_for(tbb::blocked_range<int>(0, nx * ny, 1), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t < r.end(); ++t) {
      const int x0 = (t % nx) * tile, y0 = (t / nx) * tile;
      const int x1 = std::min(w, x0 + tile), y1 = std::min(h, y0 + tile);
      uint64_t c = 0;
      for (int y = y0; y < y1; y += band) c += f(y, std::min(y1, y + band), x0, x1);
      counts[t] = c;
    }
  });
  return Sum(counts);
}

// Side of the renderer's square pixel blocks traced as one packet.
constexpr int kBlock = 4;
static_assert(kBlock * kBlock == kTracerPacket, "one block, one packet");

// The pixels of the block at (x, y0) clipped to [x, x1) x [y0, y1), in
// row-major order; returns how many (1 to kTracerPacket).
int BlockPixels(int w, int y0, int y1, int x, int x1, size_t* pixels) {
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int xx = x; xx < x + kBlock && xx < x1; ++xx) {
      pixels[n++] = static_cast<size_t>(y) * w + xx;
    }
  }
  return n;
}

void Append(std::vector<std::vector<RayRecord>>* rows, std::vector<RayRecord>* out) {
  size_t total = 0;
  for (const auto& row : *rows) total += row.size();
  out->reserve(out->size() + total);
  for (auto& row : *rows) {
    out->insert(out->end(), row.begin(), row.end());
    std::vector<RayRecord>().swap(row);
  }
}

// What every pass reads: the frame and the options.
struct Frame {
  const TriangleSoup& soup;
  const Tracer& tracer;
  const View& view;
  const RenderOptions& options;
  Camera camera;
  int w, h, threads, tile, n_lights, ao_samples;

  Ray PixelRay(size_t p) const {
    return camera.PrimaryRay(static_cast<int>(p % w), static_cast<int>(p / w));
  }
  // The triangle a secondary ray of primary hit `hit` leaves
  // (RenderOptions::skip_origin), or kNoHit.
  uint32_t Origin(const Hit& hit) const { return options.skip_origin ? hit.tri : kNoHit; }
};

// body(x, y, p) over the pixels (p = y * w + x) in the packets' order, one at
// a time: bands of kBlock rows, in each band the kBlock x kBlock blocks left
// to right, each block row by row (as BlockPixels); returns the sum of what
// body returns.
// Single rays and packets so visit the pixels in the same order, and a
// single ray follows its neighbours through the tree while their nodes are
// still in the cache (a row of 800 pixels apart they may not be: row order
// made the kd-tree's single-ray shadow pass about 10 % slower on
// hairball-small, 5 % on rungholt-1m). With `rows` (recording, threads > 1)
// the bands run in parallel; each row's rays still come in pixel order.
template <typename F>
uint64_t ForBlockPixels(const Frame& f, bool rows, const F& body) {
  return ForBands(f.w, f.h, f.threads, f.tile, rows, kBlock, [&](int y0, int y1, int x0, int x1) {
    uint64_t sum = 0;
    for (int bx = x0; bx < x1; bx += kBlock) {
      const int bx1 = std::min(x1, bx + kBlock);
      for (int y = y0; y < y1; ++y) {
        const size_t row = static_cast<size_t>(y) * f.w;
        for (int x = bx; x < bx1; ++x) sum += body(x, y, row + x);
      }
    }
    return sum;
  });
}

// Ray recording (RenderOptions::record_rays) as a policy of the passes, not a
// branch in their loops: NoRecord compiles to nothing; RowRecorder keeps
// each ray and its result in its row's buffer (the passes then run bands of
// whole rows, so the rows' order is the pixels' order for any thread count).
struct NoRecord {
  static constexpr bool kOn = false;
  void Primary(int, size_t, const Ray&, const Hit&) {}
  void Secondary(int, RayKind, size_t, int, const Ray&, bool) {}
};

struct RowRecorder {
  static constexpr bool kOn = true;
  std::vector<std::vector<RayRecord>>* rows;
  void Primary(int y, size_t p, const Ray& ray, const Hit& hit) {
    (*rows)[y].push_back(PrimaryRecord(ray, hit, static_cast<uint32_t>(p)));
  }
  void Secondary(int y, RayKind kind, size_t p, int index, const Ray& ray, bool occluded) {
    (*rows)[y].push_back(SecondaryRecord(ray, kind, occluded, static_cast<uint32_t>(p),
                                         static_cast<uint16_t>(index)));
  }
};

// 1. Primary rays, one at a time (in the packets' order): the hits per
// pixel; returns the hit count.
template <class Sink>
uint64_t PrimaryRays(const Frame& f, Sink sink, std::vector<Hit>* hits) {
  return ForBlockPixels(f, Sink::kOn, [&](int x, int y, size_t p) -> uint64_t {
    const Ray ray = f.camera.PrimaryRay(x, y);
    const Hit hit = f.tracer.Intersect(ray);
    (*hits)[p] = hit;
    sink.Primary(y, p, ray, hit);
    return hit.hit();
  });
}

// 1. Primary rays in packets of 4x4 pixels (RenderOptions::packets).
uint64_t PrimaryPackets(const Frame& f, std::vector<Hit>* hits) {
  return ForBands(f.w, f.h, f.threads, f.tile, false, kBlock, [&](int y0, int y1, int x0, int x1) {
    uint64_t n = 0;
    for (int x = x0; x < x1; x += kBlock) {
      size_t pix[kTracerPacket];
      Ray rays[kTracerPacket];
      Hit out[kTracerPacket];
      const int m = BlockPixels(f.w, y0, y1, x, x1, pix);
      for (int i = 0; i < m; ++i) rays[i] = f.PixelRay(pix[i]);
      f.tracer.IntersectPacket(rays, m, out);
      for (int i = 0; i < m; ++i) {
        (*hits)[pix[i]] = out[i];
        n += out[i].hit();
      }
    }
    return n;
  });
}

// f(y, p, hit, surface point) over the pixels with a primary hit, one at a
// time in the packets' order (ForBlockPixels); returns the sum of what f
// returns.
template <class F>
uint64_t ForHitPixels(const Frame& f, bool rows, const std::vector<Hit>& hits, const F& body) {
  return ForBlockPixels(f, rows, [&](int x, int y, size_t p) -> uint64_t {
    const Hit& hit = hits[p];
    if (!hit.hit()) return 0;
    return body(y, p, hit, MakeSurfacePoint(f.soup, f.camera.PrimaryRay(x, y), hit));
  });
}

// 2. Shadow rays, one per primary hit and light, one at a time: occluded[p *
// n_lights + l]; returns the occluded count.
template <class Sink>
uint64_t ShadowRays(const Frame& f, Sink sink, const std::vector<Hit>& hits,
                    std::vector<uint8_t>* occluded) {
  return ForHitPixels(f, Sink::kOn, hits,
                      [&](int y, size_t p, const Hit& hit, const SurfacePoint& sp) {
                        uint64_t blocked = 0;
                        for (int l = 0; l < f.n_lights; ++l) {
                          const Ray ray = ShadowRay(sp, f.view.lights[l].position);
                          const bool occ = f.tracer.Occluded(ray, f.Origin(hit));
                          (*occluded)[p * f.n_lights + l] = occ;
                          blocked += occ;
                          sink.Secondary(y, RayKind::kShadow, p, l, ray, occ);
                        }
                        return blocked;
                      });
}

// 2. Shadow rays in packets: per 4x4 block and light, the shadow rays of the
// block's hits together.
uint64_t ShadowPackets(const Frame& f, const std::vector<Hit>& hits,
                       std::vector<uint8_t>* occluded) {
  return ForBands(f.w, f.h, f.threads, f.tile, false, kBlock, [&](int y0, int y1, int x0, int x1) {
    uint64_t blocked = 0;
    for (int x = x0; x < x1; x += kBlock) {
      size_t pix[kTracerPacket], lit[kTracerPacket];
      uint32_t origin[kTracerPacket];
      SurfacePoint sp[kTracerPacket];
      const int m = BlockPixels(f.w, y0, y1, x, x1, pix);
      int n = 0;
      for (int i = 0; i < m; ++i) {
        const Hit& hit = hits[pix[i]];
        if (!hit.hit()) continue;
        sp[n] = MakeSurfacePoint(f.soup, f.PixelRay(pix[i]), hit);
        origin[n] = hit.tri;
        lit[n++] = pix[i];
      }
      for (int l = 0; l < f.n_lights && n > 0; ++l) {
        Ray rays[kTracerPacket];
        bool occ[kTracerPacket];
        for (int i = 0; i < n; ++i) rays[i] = ShadowRay(sp[i], f.view.lights[l].position);
        f.tracer.OccludedPacket(rays, n, f.options.skip_origin ? origin : nullptr, occ);
        for (int i = 0; i < n; ++i) {
          (*occluded)[lit[i] * f.n_lights + l] = occ[i];
          blocked += occ[i];
        }
      }
    }
    return blocked;
  });
}

// 3. Ambient-occlusion rays, `ao_samples` per primary hit: the unoccluded
// count per pixel; returns the occluded count.
template <class Sink>
uint64_t AoRays(const Frame& f, Sink sink, const std::vector<Hit>& hits,
                std::vector<uint16_t>* open_count) {
  return ForHitPixels(f, Sink::kOn, hits,
                      [&](int y, size_t p, const Hit& hit, const SurfacePoint& sp) {
                        int open = 0;
                        for (int s = 0; s < f.ao_samples; ++s) {
                          const Ray ray =
                              AoRay(sp, static_cast<uint32_t>(p), s, f.view.ao.distance);
                          const bool occ = f.tracer.Occluded(ray, f.Origin(hit));
                          open += !occ;
                          sink.Secondary(y, RayKind::kAo, p, s, ray, occ);
                        }
                        (*open_count)[p] = static_cast<uint16_t>(open);
                        return static_cast<uint64_t>(f.ao_samples - open);
                      });
}

// 4. Shading: the image from the hits, occlusion flags and AO counts.
void Shade(const Frame& f, const std::vector<uint8_t>& occluded,
           const std::vector<uint16_t>& ao_open, RenderResult* res) {
  const RenderOptions& o = f.options;
  const bool shadows = !occluded.empty();
  res->rgb.resize(static_cast<size_t>(f.w) * f.h * 3);
  const uint8_t bg[3] = {ToByte(o.background.x), ToByte(o.background.y), ToByte(o.background.z)};
  ForBlockPixels(f, false, [&](int x, int y, size_t p) -> uint64_t {
    uint8_t* rgb = &res->rgb[3 * p];
    const Hit& hit = res->primary_hits[p];
    if (!hit.hit()) {
      for (int c = 0; c < 3; ++c) rgb[c] = bg[c];
      return 0;
    }
    const Ray ray = f.camera.PrimaryRay(x, y);
    const SurfacePoint sp = MakeSurfacePoint(f.soup, ray, hit);
    const float ao = f.ao_samples > 0 ? static_cast<float>(ao_open[p]) / f.ao_samples : 1.0f;
    float direct = 0.0f;
    if (f.n_lights > 0) {
      for (int l = 0; l < f.n_lights; ++l) {
        if (shadows && occluded[p * f.n_lights + l]) continue;
        direct += std::fmax(0.0f, Dot(sp.normal, Normalize(f.view.lights[l].position - sp.p())));
      }
      direct /= static_cast<float>(f.n_lights);
    } else {
      direct = std::fabs(Dot(sp.normal, ray.dir));
    }
    const Vec3 c = o.albedo * (o.ambient * ao + (1.0f - o.ambient) * direct);
    rgb[0] = ToByte(c.x);
    rgb[1] = ToByte(c.y);
    rgb[2] = ToByte(c.z);
    return 0;
  });
}

}  // namespace

uint64_t RenderBytes(const View& view, const RenderOptions& options) {
  const uint64_t pixels = static_cast<uint64_t>(view.width) * static_cast<uint64_t>(view.height);
  const uint64_t lights = options.cast_shadow_rays ? view.lights.size() : 0;
  const uint64_t ao = view.ao.enabled() ? static_cast<uint64_t>(view.ao.samples) : 0;
  uint64_t per_pixel = sizeof(Hit) + 3 + lights + (ao > 0 ? sizeof(uint16_t) : 0);
  // Recorded rays: the per-row buffers (grown by doubling: up to twice their
  // rays) and the result they are appended to.
  if (options.record_rays) per_pixel += 3 * (1 + lights + ao) * sizeof(RayRecord);
  return pixels * per_pixel;
}

// One pass per effect, each timed apart; recording (RowRecorder) or not
// (NoRecord), one ray at a time or in packets (never when recording).
RenderResult Render(const TriangleSoup& soup, const Tracer& tracer, const View& view,
                    const RenderOptions& options) {
  std::unique_ptr<tbb::global_control> cap;
  if (options.threads > 1) {
    cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                static_cast<size_t>(options.threads));
  }
  const int w = view.width, h = view.height;
  const size_t pixels = static_cast<size_t>(w) * h;
  const int n_lights = static_cast<int>(view.lights.size());
  const Frame f{soup, tracer, view, options, Camera(view.camera, w, h), w, h, options.threads,
                options.tile_size, n_lights, view.ao.enabled() ? view.ao.samples : 0};
  const bool shadows = options.cast_shadow_rays && n_lights > 0;
  const bool record = options.record_rays;
  const bool packets = options.packets && !record;

  RenderResult res;
  res.width = w;
  res.height = h;
  res.primary_hits.resize(pixels);
  std::vector<uint8_t> occluded(shadows ? pixels * n_lights : 0);
  std::vector<uint16_t> ao_open(f.ao_samples > 0 ? pixels : 0);
  std::vector<std::vector<RayRecord>> rows(record ? h : 0);
  const RowRecorder recorder{&rows};
  const Clock::time_point start = Clock::now();

  Clock::time_point t0 = Clock::now();
  res.p_hit = packets  ? PrimaryPackets(f, &res.primary_hits)
              : record ? PrimaryRays(f, recorder, &res.primary_hits)
                       : PrimaryRays(f, NoRecord(), &res.primary_hits);
  res.primary.seconds = Seconds(t0);
  res.primary.rays = pixels;
  res.p_miss = pixels - res.p_hit;
  if (record) Append(&rows, &res.rays);

  if (shadows) {
    t0 = Clock::now();
    const std::vector<Hit>& hits = res.primary_hits;
    res.s_hit = packets  ? ShadowPackets(f, hits, &occluded)
                : record ? ShadowRays(f, recorder, hits, &occluded)
                         : ShadowRays(f, NoRecord(), hits, &occluded);
    res.shadow.seconds = Seconds(t0);
    res.shadow.rays = res.p_hit * n_lights;
    res.s_miss = res.shadow.rays - res.s_hit;
    if (record) Append(&rows, &res.rays);
  }

  if (f.ao_samples > 0) {
    t0 = Clock::now();
    res.ao_hit = record ? AoRays(f, recorder, res.primary_hits, &ao_open)
                        : AoRays(f, NoRecord(), res.primary_hits, &ao_open);
    res.ao.seconds = Seconds(t0);
    res.ao.rays = res.p_hit * f.ao_samples;
    res.ao_miss = res.ao.rays - res.ao_hit;
    if (record) Append(&rows, &res.rays);
  }

  Shade(f, occluded, ao_open, &res);
  res.seconds = Seconds(start);
  return res;
}

}  // namespace kdtree
