// The memory a run may use, checked before large allocations are made (issue
// 24: a request that would not fit is refused at once, saying what it needs,
// instead of paging the machine to a halt or being killed half-way).
#ifndef KDTREE_CC_BASE_MEMORY_BUDGET_H_
#define KDTREE_CC_BASE_MEMORY_BUDGET_H_

#include <cstdint>
#include <string>

#include "absl/status/status.h"

namespace kdtree {

// Physical memory of the machine (sysconf), 0 when unknown.
uint64_t PhysicalMemoryBytes();

// The default budget: half of physical memory (12 GiB on this project's
// 24 GiB machines), 8 GiB when that is unknown.
uint64_t DefaultMemoryBudget();

// OK when `bytes` fit in `budget`; else ResourceExhausted "WHAT needs about
// X GB, more than the memory budget of Y GB (HOW_TO_RAISE)".
absl::Status CheckMemoryBudget(uint64_t bytes, uint64_t budget, const std::string& what,
                               const std::string& how_to_raise);

}  // namespace kdtree

#endif  // KDTREE_CC_BASE_MEMORY_BUDGET_H_
