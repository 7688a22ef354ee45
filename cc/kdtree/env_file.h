// The report's environment-file syntax (nanoGOLEM), section "Configuration":
//
//   RTCore {
//       castShadowRays ON
//   }
//   KDTree {
//       maxDepth 24
//       maxLeafSize 4
//       Binning { useBinning ON useDrivingAxis ON bins 16 }
//       useClipping ON
//       usePruning ON
//   }
//
// Blocks are `Name { ... }`, entries `key value`, booleans ON/OFF (also
// true/false, 1/0), comments from `#` or `//` to the end of the line. Keys of
// the RTCore, KDTree and Binning blocks are checked; other top-level blocks of
// a nanoGOLEM file are skipped and listed in `skipped_blocks`. Options absent
// from the file keep their value in `base`. Errors name file, line and reason.
#ifndef KDTREE_CC_KDTREE_ENV_FILE_H_
#define KDTREE_CC_KDTREE_ENV_FILE_H_

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "cc/kdtree/config.h"

namespace kdtree {

struct EnvResult {
  Config config;
  std::vector<std::string> skipped_blocks;
};

absl::StatusOr<EnvResult> ParseEnvironment(const std::string& text, const std::string& filename,
                                           const Config& base = Config());

absl::StatusOr<EnvResult> LoadEnvironmentFile(const std::string& path,
                                              const Config& base = Config());

}  // namespace kdtree

#endif  // KDTREE_CC_KDTREE_ENV_FILE_H_
