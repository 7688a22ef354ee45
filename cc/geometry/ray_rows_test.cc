#include "cc/geometry/ray_rows.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "gtest/gtest.h"
#include "hwy/targets.h"

namespace kdtree {
namespace {

// Every target's RayRows against the rays' floats, for every packet size,
// the rays ending where a page no process may read begins (a read past ray
// n - 1 would crash the test), the rows' other lanes zero.
TEST(RayRows, EveryTargetEverySize) {
  const size_t page = static_cast<size_t>(sysconf(_SC_PAGESIZE));
  void* map = mmap(nullptr, 2 * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(map, MAP_FAILED);
  char* const guard = static_cast<char*>(map) + page;
  ASSERT_EQ(mprotect(guard, page, PROT_NONE), 0);
  const std::vector<int64_t> targets = RayRowsTargets();
  EXPECT_GE(targets.size(), 2u);  // this machine's AVX-512 path and the gathers' at least
  for (const int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    for (int n = 0; n <= 16; ++n) {
      Ray* const storage = reinterpret_cast<Ray*>(guard) - n;
      for (int i = 0; i < n; ++i) {
        const float b = 100.0f * static_cast<float>(i);
        storage[i] = Ray{{b + 1, b + 2, b + 3}, {b + 4, b + 5, b + 6}, b + 7, b + 8};
      }
      alignas(64) float rows[8][16];
      std::memset(rows, 0xFF, sizeof(rows));  // NaNs: every lane must be written
      float* const ptr[8] = {rows[0], rows[1], rows[2], rows[3],
                             rows[4], rows[5], rows[6], rows[7]};
      RayRows(storage, n, ptr);
      for (int k = 0; k < 8; ++k) {
        for (int i = 0; i < 16; ++i) {
          const float want = i < n ? 100.0f * static_cast<float>(i) + static_cast<float>(k + 1) : 0;
          EXPECT_EQ(rows[k][i], want) << hwy::TargetName(target) << " n " << n << " row " << k
                                      << " lane " << i;
        }
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  munmap(map, 2 * page);
}

}  // namespace
}  // namespace kdtree
