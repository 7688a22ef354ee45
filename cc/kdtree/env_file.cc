#include "cc/kdtree/env_file.h"

#include <cctype>
#include <cmath>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "cc/base/block_tokens.h"
#include "cc/base/read_file.h"

namespace kdtree {
namespace {

using Token = BlockToken;

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string filename, const Config& base)
      : tokens_(std::move(tokens)), filename_(std::move(filename)) {
    result_.config = base;
  }

  absl::StatusOr<EnvResult> Parse() {
    while (pos_ < tokens_.size()) {
      const Token name = tokens_[pos_++];
      if (name.text == "{" || name.text == "}") return Error(name.line, "unexpected '" + name.text + "'");
      if (!Expect("{", name)) return status_;
      if (name.text == "RTCore" || name.text == "KDTree") {
        if (absl::Status s = Block(name.text, name.line); !s.ok()) return s;
      } else {
        if (absl::Status s = Skip(name); !s.ok()) return s;
        result_.skipped_blocks.push_back(name.text);
      }
    }
    if (absl::Status s = result_.config.Validate(); !s.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(filename_, ": ", s.message()));
    }
    return result_;
  }

 private:
  absl::Status Error(int line, const std::string& reason) {
    status_ = absl::InvalidArgumentError(absl::StrCat(filename_, ":", line, ": ", reason));
    return status_;
  }

  bool Expect(const std::string& what, const Token& after) {
    if (pos_ >= tokens_.size()) {
      (void)Error(after.line, "expected '" + what + "' after '" + after.text + "', got end of file");
      return false;
    }
    if (tokens_[pos_].text != what) {
      (void)Error(tokens_[pos_].line, "expected '" + what + "' after '" + after.text + "', got '" +
                                    tokens_[pos_].text + "'");
      return false;
    }
    ++pos_;
    return true;
  }

  // Skips a block of another nanoGOLEM module, nested braces included.
  absl::Status Skip(const Token& name) {
    int depth = 1;
    while (pos_ < tokens_.size() && depth > 0) {
      const std::string& t = tokens_[pos_++].text;
      if (t == "{") ++depth;
      if (t == "}") --depth;
    }
    if (depth > 0) return Error(name.line, "block '" + name.text + "' is not closed");
    return absl::OkStatus();
  }

  absl::Status Block(const std::string& block, int open_line) {
    Config& c = result_.config;
    for (;;) {
      if (pos_ >= tokens_.size()) return Error(open_line, "block '" + block + "' is not closed");
      const Token key = tokens_[pos_++];
      if (key.text == "}") return absl::OkStatus();
      if (key.text == "{") return Error(key.line, "unexpected '{' in block '" + block + "'");
      if (block == "KDTree" && key.text == "Binning") {
        if (!Expect("{", key)) return status_;
        if (absl::Status s = Block("Binning", key.line); !s.ok()) return s;
        continue;
      }
      if (pos_ >= tokens_.size() || tokens_[pos_].text == "}" || tokens_[pos_].text == "{") {
        return Error(key.line, "option '" + key.text + "' has no value");
      }
      const Token value = tokens_[pos_++];
      absl::Status s;
      if (block == "RTCore" && key.text == "castShadowRays") {
        s = Bool(value, &c.cast_shadow_rays);
      } else if (block == "KDTree" && key.text == "maxDepth") {
        s = Int(value, &c.max_depth);
      } else if (block == "KDTree" && key.text == "maxLeafSize") {
        s = Int(value, &c.max_leaf_size);
      } else if (block == "KDTree" && key.text == "useClipping") {
        s = Bool(value, &c.use_clipping);
      } else if (block == "KDTree" && key.text == "usePruning") {
        s = Bool(value, &c.use_pruning);
      } else if (block == "KDTree" && key.text == "seedCompatible") {
        s = Bool(value, &c.seed_compatible);
      } else if (block == "KDTree" && key.text == "fullSah") {
        s = Bool(value, &c.full_sah);
      } else if (block == "KDTree" && key.text == "autoDepth") {
        s = Bool(value, &c.auto_depth);
      } else if (block == "KDTree" && key.text == "splitMethod") {
        const std::string m = absl::AsciiStrToLower(value.text);
        if (m == "binned") {
          c.split_method = Config::SplitMethod::kBinned;
        } else if (m == "sweep") {
          c.split_method = Config::SplitMethod::kSweep;
        } else if (m == "hybrid") {
          c.split_method = Config::SplitMethod::kHybrid;
        } else {
          s = Error(value.line, "expected binned, sweep or hybrid, got '" + value.text + "'");
        }
      } else if (block == "KDTree" && key.text == "hybridBins") {
        s = Int(value, &c.hybrid_bins);
      } else if (block == "KDTree" && key.text == "hybridThreshold") {
        s = Int(value, &c.hybrid_threshold);
      } else if (block == "KDTree" && key.text == "perfectSplits") {
        s = Bool(value, &c.perfect_splits);
      } else if (block == "KDTree" && key.text == "exactPruning") {
        s = Bool(value, &c.exact_pruning);
      } else if (block == "KDTree" && key.text == "collapse") {
        s = Bool(value, &c.collapse);
      } else if (block == "KDTree" && key.text == "traversalCost") {
        s = Double(value, &c.traversal_cost);
      } else if (block == "KDTree" && key.text == "intersectionCost") {
        s = Double(value, &c.intersection_cost);
      } else if (block == "KDTree" && key.text == "emptyBonus") {
        s = Double(value, &c.empty_bonus);
      } else if (block == "KDTree" && key.text == "sahPacket") {
        s = Int(value, &c.sah_packet);
      } else if (block == "KDTree" && key.text == "buildThreads") {
        s = Int(value, &c.build_threads);
      } else if (block == "Binning" && (key.text == "useBinning" || key.text == "useBining")) {
        s = Bool(value, &c.use_binning);  // "useBining" is the report's spelling in its prose
      } else if (block == "Binning" && key.text == "useDrivingAxis") {
        s = Bool(value, &c.use_driving_axis);
      } else if (block == "Binning" && key.text == "bins") {
        s = Int(value, &c.bins);
      } else {
        return Error(key.line, "unknown option '" + key.text + "' in block '" + block + "'");
      }
      if (!s.ok()) return s;
    }
  }

  absl::Status Bool(const Token& v, bool* out) {
    const std::string t = absl::AsciiStrToLower(v.text);
    if (t == "on" || t == "true" || t == "1" || t == "yes") {
      *out = true;
    } else if (t == "off" || t == "false" || t == "0" || t == "no") {
      *out = false;
    } else {
      return Error(v.line, "expected ON or OFF, got '" + v.text + "'");
    }
    return absl::OkStatus();
  }

  absl::Status Double(const Token& v, double* out) {
    if (!absl::SimpleAtod(v.text, out) || !std::isfinite(*out)) {
      return Error(v.line, "expected a number, got '" + v.text + "'");
    }
    return absl::OkStatus();
  }

  absl::Status Int(const Token& v, int* out) {
    if (!absl::SimpleAtoi(v.text, out)) return Error(v.line, "expected an integer, got '" + v.text + "'");
    return absl::OkStatus();
  }

  std::vector<Token> tokens_;
  std::string filename_;
  size_t pos_ = 0;
  EnvResult result_;
  absl::Status status_;
};

}  // namespace

absl::StatusOr<EnvResult> ParseEnvironment(const std::string& text, const std::string& filename,
                                           const Config& base) {
  return Parser(TokenizeBlocks(text), filename, base).Parse();
}

absl::StatusOr<EnvResult> LoadEnvironmentFile(const std::string& path, const Config& base) {
  absl::StatusOr<std::string> text = ReadTextInput(path, "environment file");
  if (!text.ok()) return text.status();
  return ParseEnvironment(*text, path, base);
}

}  // namespace kdtree
