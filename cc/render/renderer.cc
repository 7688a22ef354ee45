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

RayRecord MakeRecord(const Ray& r, RayKind kind, uint32_t pixel, uint16_t index) {
  RayRecord rec;
  rec.origin = r.origin;
  rec.dir = r.dir;
  rec.tmin = r.tmin;
  rec.tmax = r.tmax;
  rec.kind = kind;
  rec.light = index;
  rec.pixel = pixel;
  return rec;
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

// ForBands over single rows: f(y, x0, x1).
template <typename F>
uint64_t ForPixels(int w, int h, int threads, int tile, bool rows, const F& f) {
  return ForBands(w, h, threads, tile, rows, 1,
                  [&](int y, int, int x0, int x1) { return f(y, x0, x1); });
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

RenderResult Render(const TriangleSoup& soup, const Tracer& tracer, const View& view,
                    const RenderOptions& options) {
  std::unique_ptr<tbb::global_control> cap;
  if (options.threads > 1) {
    cap = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                static_cast<size_t>(options.threads));
  }
  const int w = view.width, h = view.height, threads = options.threads;
  const size_t pixels = static_cast<size_t>(w) * h;
  const Camera camera(view.camera, w, h);
  const int n_lights = static_cast<int>(view.lights.size());
  const bool shadows = options.cast_shadow_rays && n_lights > 0;
  const int ao_samples = view.ao.enabled() ? view.ao.samples : 0;
  const bool record = options.record_rays;
  const int tile = options.tile_size;

  RenderResult res;
  res.width = w;
  res.height = h;
  res.primary_hits.resize(pixels);
  std::vector<uint8_t> occluded(shadows ? pixels * n_lights : 0);
  std::vector<uint16_t> ao_open(ao_samples > 0 ? pixels : 0);
  std::vector<std::vector<RayRecord>> rows(record ? h : 0);
  const Clock::time_point start = Clock::now();

  // Packets of 4x4 pixels (RenderOptions::packets); never when recording.
  const bool packets = options.packets && !record;
  // A shadow or AO ray leaving the surface of primary hit `hit`
  // (RenderOptions::skip_origin: the tracer may leave that triangle untested).
  const bool skip_origin = options.skip_origin;
  const auto secondary_occluded = [&](const Ray& ray, const Hit& hit) {
    return tracer.Occluded(ray, skip_origin ? hit.tri : kNoHit);
  };
  const auto pixel_ray = [&](size_t p) {
    return camera.PrimaryRay(static_cast<int>(p % w), static_cast<int>(p / w));
  };

  // 1. Primary rays.
  Clock::time_point t0 = Clock::now();
  if (packets) {
    res.p_hit = ForBands(w, h, threads, tile, false, kBlock, [&](int y0, int y1, int x0, int x1) {
      uint64_t hits = 0;
      for (int x = x0; x < x1; x += kBlock) {
        size_t pix[kTracerPacket];
        Ray rays[kTracerPacket];
        Hit out[kTracerPacket];
        const int n = BlockPixels(w, y0, y1, x, x1, pix);
        for (int i = 0; i < n; ++i) rays[i] = pixel_ray(pix[i]);
        tracer.IntersectPacket(rays, n, out);
        for (int i = 0; i < n; ++i) {
          res.primary_hits[pix[i]] = out[i];
          hits += out[i].hit();
        }
      }
      return hits;
    });
  } else {
    res.p_hit = ForPixels(w, h, threads, tile, record, [&](int y, int x0, int x1) {
      {
        uint64_t hits = 0;
        for (int x = x0; x < x1; ++x) {
          const size_t p = static_cast<size_t>(y) * w + x;
          const Ray ray = camera.PrimaryRay(x, y);
          const Hit hit = tracer.Intersect(ray);
          res.primary_hits[p] = hit;
          hits += hit.hit();
          if (record) {
            RayRecord rec = MakeRecord(ray, RayKind::kPrimary, static_cast<uint32_t>(p), 0);
            rec.hit = hit.hit();
            if (hit.hit()) {
              rec.tri = hit.tri;
              rec.t = hit.t;
              rec.u = hit.u;
              rec.v = hit.v;
            }
            rows[y].push_back(rec);
          }
        }
        return hits;
      }
    });
  }
  res.primary.seconds = Seconds(t0);
  res.primary.rays = pixels;
  res.p_miss = pixels - res.p_hit;
  if (record) Append(&rows, &res.rays);

  // 2. Shadow rays: one per primary hit and light.
  if (shadows) {
    t0 = Clock::now();
    if (packets) {
      // Per 4x4 block and light, the shadow rays of the block's hits together.
      res.s_hit = ForBands(w, h, threads, tile, false, kBlock, [&](int y0, int y1, int x0, int x1) {
        uint64_t blocked = 0;
        for (int x = x0; x < x1; x += kBlock) {
          size_t pix[kTracerPacket], lit[kTracerPacket];
          uint32_t origin[kTracerPacket];
          const int m = BlockPixels(w, y0, y1, x, x1, pix);
          SurfacePoint sp[kTracerPacket];
          int n = 0;
          for (int i = 0; i < m; ++i) {
            const Hit& hit = res.primary_hits[pix[i]];
            if (!hit.hit()) continue;
            sp[n] = MakeSurfacePoint(soup, pixel_ray(pix[i]), hit);
            origin[n] = hit.tri;
            lit[n++] = pix[i];
          }
          for (int l = 0; l < n_lights && n > 0; ++l) {
            Ray rays[kTracerPacket];
            bool occ[kTracerPacket];
            for (int i = 0; i < n; ++i) rays[i] = ShadowRay(sp[i], view.lights[l].position);
            tracer.OccludedPacket(rays, n, skip_origin ? origin : nullptr, occ);
            for (int i = 0; i < n; ++i) {
              occluded[lit[i] * n_lights + l] = occ[i];
              blocked += occ[i];
            }
          }
        }
        return blocked;
      });
    } else {
      res.s_hit = ForPixels(w, h, threads, tile, record, [&](int y, int x0, int x1) {
        {
          uint64_t blocked = 0;
          for (int x = x0; x < x1; ++x) {
            const size_t p = static_cast<size_t>(y) * w + x;
            const Hit& hit = res.primary_hits[p];
            if (!hit.hit()) continue;
            const SurfacePoint sp = MakeSurfacePoint(soup, camera.PrimaryRay(x, y), hit);
            for (int l = 0; l < n_lights; ++l) {
              const Ray ray = ShadowRay(sp, view.lights[l].position);
              const bool occ = secondary_occluded(ray, hit);
              occluded[p * n_lights + l] = occ;
              blocked += occ;
              if (record) {
                RayRecord rec = MakeRecord(ray, RayKind::kShadow, static_cast<uint32_t>(p),
                                           static_cast<uint16_t>(l));
                rec.hit = occ;
                rows[y].push_back(rec);
              }
            }
          }
          return blocked;
        }
      });
    }
    res.shadow.seconds = Seconds(t0);
    res.shadow.rays = res.p_hit * n_lights;
    res.s_miss = res.shadow.rays - res.s_hit;
    if (record) Append(&rows, &res.rays);
  }

  // 3. Ambient-occlusion rays.
  if (ao_samples > 0) {
    t0 = Clock::now();
    res.ao_hit = ForPixels(w, h, threads, tile, record, [&](int y, int x0, int x1) {
      {
        uint64_t blocked = 0;
        for (int x = x0; x < x1; ++x) {
          const size_t p = static_cast<size_t>(y) * w + x;
          const Hit& hit = res.primary_hits[p];
          if (!hit.hit()) continue;
          const SurfacePoint sp = MakeSurfacePoint(soup, camera.PrimaryRay(x, y), hit);
          int open = 0;
          for (int s = 0; s < ao_samples; ++s) {
            const Ray ray = AoRay(sp, static_cast<uint32_t>(p), s, view.ao.distance);
            const bool occ = secondary_occluded(ray, hit);
            open += !occ;
            if (record) {
              RayRecord rec = MakeRecord(ray, RayKind::kAo, static_cast<uint32_t>(p),
                                         static_cast<uint16_t>(s));
              rec.hit = occ;
              rows[y].push_back(rec);
            }
          }
          ao_open[p] = static_cast<uint16_t>(open);
          blocked += ao_samples - open;
        }
        return blocked;
      }
    });
    res.ao.seconds = Seconds(t0);
    res.ao.rays = res.p_hit * ao_samples;
    res.ao_miss = res.ao.rays - res.ao_hit;
    if (record) Append(&rows, &res.rays);
  }

  // 4. Shading.
  res.rgb.resize(pixels * 3);
  const uint8_t bg[3] = {ToByte(options.background.x), ToByte(options.background.y),
                         ToByte(options.background.z)};
  ForPixels(w, h, threads, tile, false, [&](int y, int x0, int x1) -> uint64_t {
    {
      for (int x = x0; x < x1; ++x) {
        const size_t p = static_cast<size_t>(y) * w + x;
        const Hit& hit = res.primary_hits[p];
        if (!hit.hit()) {
          res.rgb[3 * p] = bg[0];
          res.rgb[3 * p + 1] = bg[1];
          res.rgb[3 * p + 2] = bg[2];
          continue;
        }
        const Ray ray = camera.PrimaryRay(x, y);
        const SurfacePoint sp = MakeSurfacePoint(soup, ray, hit);
        const float ao = ao_samples > 0 ? static_cast<float>(ao_open[p]) / ao_samples : 1.0f;
        float direct = 0.0f;
        if (n_lights > 0) {
          for (int l = 0; l < n_lights; ++l) {
            if (shadows && occluded[p * n_lights + l]) continue;
            direct += std::fmax(0.0f, Dot(sp.normal, Normalize(view.lights[l].position - sp.p())));
          }
          direct /= static_cast<float>(n_lights);
        } else {
          direct = std::fabs(Dot(sp.normal, ray.dir));
        }
        const Vec3 c = options.albedo * (options.ambient * ao + (1.0f - options.ambient) * direct);
        res.rgb[3 * p] = ToByte(c.x);
        res.rgb[3 * p + 1] = ToByte(c.y);
        res.rgb[3 * p + 2] = ToByte(c.z);
      }
    }
    return 0;
  });
  res.seconds = Seconds(start);
  return res;
}

}  // namespace kdtree
