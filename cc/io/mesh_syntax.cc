#include "cc/io/mesh_syntax.h"

#include <cstdint>
#include <string>
#include <vector>

#include "absl/strings/ascii.h"
#include "cc/io/syntax_lines.h"

namespace kdtree {
namespace syntax {
namespace {

// ---------------------------------------------------------------- OBJ
absl::Status CheckObj(absl::string_view data, const std::string& name) {
  std::vector<absl::string_view> tok;
  int64_t total = 0;
  for (Lines lines(data, true); lines.Next(&tok);) total += !tok.empty() && tok[0] == "v";
  int64_t seen = 0;
  Lines lines(data, true);
  while (lines.Next(&tok)) {
    if (tok.empty()) continue;
    if (tok[0] == "v") {
      if (tok.size() < 4) return LineError(name, lines.number(), "vertex needs three coordinates");
      for (size_t i = 1; i < 4; ++i) {
        if (!IsNumber(tok[i])) {
          return LineError(name, lines.number(),
                           absl::StrCat("vertex coordinate ", Quote(tok[i]), " is not a number"));
        }
      }
      ++seen;
    } else if (tok[0] == "f") {
      if (tok.size() < 4) {
        return LineError(name, lines.number(),
                         absl::StrCat("face has ", tok.size() - 1, " vertices, needs at least 3"));
      }
      for (size_t i = 1; i < tok.size(); ++i) {
        const std::vector<absl::string_view> parts = absl::StrSplit(tok[i], '/');
        int64_t idx = 0;
        bool ok = parts.size() <= 3 && absl::SimpleAtoi(parts[0], &idx);
        for (size_t k = 1; ok && k < parts.size(); ++k) {
          int64_t other;
          ok = parts[k].empty() || absl::SimpleAtoi(parts[k], &other);
        }
        if (!ok) {
          return LineError(name, lines.number(),
                           absl::StrCat("malformed face vertex ", Quote(tok[i])));
        }
        if (idx == 0) {
          return LineError(name, lines.number(), "vertex index 0 (OBJ indices start at 1)");
        }
        if (idx > total || (idx < 0 && -idx > seen)) {
          return LineError(name, lines.number(),
                           absl::StrCat("vertex index ", idx, " out of range (",
                                        idx > 0 ? total : seen, " vertices",
                                        idx > 0 ? " in the file)" : " so far)"));
        }
      }
    }
  }
  if (lines.bad()) return lines.Error(name, "");
  return absl::OkStatus();
}

// ---------------------------------------------------------------- OFF
absl::Status CheckOff(absl::string_view data, const std::string& name) {
  // No comments: assimp's OFF reader does not skip them.
  Lines lines(data, false);
  std::vector<absl::string_view> tok;
  auto comment = [&]() {
    return !tok.empty() && tok[0][0] == '#'
               ? LineError(name, lines.number(), "comment lines are not supported in OFF files")
               : absl::OkStatus();
  };
  if (!lines.Next(&tok)) return lines.Error(name, "");  // (empty: LoadMesh's own check)
  const std::string head = tok.empty() ? "" : absl::AsciiStrToUpper(tok[0]);
  if (head != "OFF" && head != "COFF" && head != "NOFF" && head != "CNOFF") {
    // Other variants, header-less files and comments before the header are
    // refused: assimp 5.2 reads some of them wrongly and aborts on others
    // (found by the fuzz smoke run).
    return LineError(name, lines.number(),
                     absl::StrCat("expected the header OFF, COFF, NOFF or CNOFF on the first "
                                  "line, got ",
                                  tok.empty() ? std::string("nothing") : Quote(tok[0])));
  }
  if (tok.size() > 1 && absl::AsciiStrToUpper(tok[1]) == "BINARY") {
    return LineError(name, lines.number(), "binary OFF is not supported");
  }
  std::vector<absl::string_view> counts(tok.begin() + 1, tok.end());
  while (counts.empty() && lines.Next(&tok)) {
    if (absl::Status st = comment(); !st.ok()) return st;
    counts = tok;
  }
  int64_t nv = -1, nf = -1;
  if (lines.bad()) return lines.Error(name, "");
  if (counts.size() < 2 || !absl::SimpleAtoi(counts[0], &nv) ||
      !absl::SimpleAtoi(counts[1], &nf) || nv < 0 || nf < 0) {
    return LineError(name, lines.number(), "expected the counts 'vertices faces [edges]'");
  }
  const int64_t cap = static_cast<int64_t>(data.size() / 2);
  if (nv > cap || nf > cap) {
    return LineError(name, lines.number(),
                     absl::StrCat("counts ", nv, " vertices and ", nf,
                                  " faces cannot fit in a file of ", data.size(), " bytes"));
  }
  for (int64_t i = 0; i < nv;) {
    if (!lines.Next(&tok)) {
      return lines.Error(name, absl::StrCat("file ends after ", i, " of ", nv, " vertices"));
    }
    if (tok.empty()) continue;
    if (absl::Status st = comment(); !st.ok()) return st;
    if (tok.size() < 3 || !IsNumber(tok[0]) || !IsNumber(tok[1]) || !IsNumber(tok[2])) {
      return LineError(name, lines.number(), absl::StrCat("vertex ", i, " needs three numbers"));
    }
    ++i;
  }
  for (int64_t i = 0; i < nf;) {
    if (!lines.Next(&tok)) {
      return lines.Error(name, absl::StrCat("file ends after ", i, " of ", nf, " faces"));
    }
    if (tok.empty()) continue;
    if (absl::Status st = comment(); !st.ok()) return st;
    int64_t k = 0;
    if (!absl::SimpleAtoi(tok[0], &k) || k < 3 || static_cast<size_t>(k) + 1 > tok.size()) {
      return LineError(name, lines.number(),
                       absl::StrCat("face ", i, ": bad vertex count ", Quote(tok[0]), " for ",
                                    tok.size() - 1, " values"));
    }
    for (int64_t j = 1; j <= k; ++j) {
      int64_t idx = -1;
      if (!absl::SimpleAtoi(tok[j], &idx) || idx < 0 || idx >= nv) {
        return LineError(name, lines.number(),
                         absl::StrCat("face ", i, ": vertex index ", Quote(tok[j]),
                                      " is not in [0, ", nv, ")"));
      }
    }
    ++i;
  }
  return absl::OkStatus();
}

}  // namespace
}  // namespace syntax

absl::Status CheckMeshSyntax(absl::string_view data, absl::string_view format,
                             const std::string& name) {
  if (format == "obj") return syntax::CheckObj(data, name);
  if (format == "off") return syntax::CheckOff(data, name);
  if (format == "ply") return syntax::CheckPly(data, name);
  return absl::OkStatus();
}

}  // namespace kdtree
