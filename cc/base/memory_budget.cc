#include "cc/base/memory_budget.h"

#include <unistd.h>

#include "absl/strings/str_format.h"

namespace kdtree {

uint64_t PhysicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(size) : 0;
}

uint64_t DefaultMemoryBudget() {
  const uint64_t physical = PhysicalMemoryBytes();
  return physical > 0 ? physical / 2 : uint64_t{8} << 30;
}

absl::Status CheckMemoryBudget(uint64_t bytes, uint64_t budget, const std::string& what,
                               const std::string& how_to_raise) {
  if (bytes <= budget) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrFormat(
      "%s needs about %.1f GB, more than the memory budget of %.1f GB (%s)", what, bytes / 1e9,
      budget / 1e9, how_to_raise));
}

}  // namespace kdtree
