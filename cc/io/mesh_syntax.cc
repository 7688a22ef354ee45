#include "cc/io/mesh_syntax.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"

namespace kdtree {
namespace {

absl::Status LineError(const std::string& name, size_t line, const std::string& why) {
  return absl::InvalidArgumentError(absl::StrCat(name, ":", line, ": ", why));
}

// Lines of `data` ('\n' or "\r\n") with 1-based numbers; '#' comments removed
// when asked; tokens separated by spaces and tabs. A line with another
// control character (assimp's readers end a line at '\r', '\f' or '\0') stops
// the reading: Next() returns false and bad() is set.
class Lines {
 public:
  Lines(absl::string_view data, bool strip_comments) : data_(data), strip_(strip_comments) {}
  // Next line's tokens (may be empty); false at the end or on a bad line.
  bool Next(std::vector<absl::string_view>* tokens) {
    if (pos_ >= data_.size() || bad_) return false;
    size_t end = data_.find('\n', pos_);
    if (end == absl::string_view::npos) end = data_.size();
    absl::string_view line = data_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    for (char c : line) {
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) {
        bad_ = true;
        bad_char_ = static_cast<unsigned char>(c);
        return false;
      }
    }
    if (strip_) line = line.substr(0, line.find('#'));
    *tokens = absl::StrSplit(line, absl::ByAnyChar(" \t"), absl::SkipEmpty());
    return true;
  }
  size_t number() const { return number_; }
  size_t offset() const { return pos_ > data_.size() ? data_.size() : pos_; }
  bool bad() const { return bad_; }
  // The error of a line that stopped Next(), or `otherwise`.
  absl::Status Error(const std::string& name, const std::string& otherwise) const {
    if (!bad_) return LineError(name, number_, otherwise);
    return LineError(name, number_,
                     absl::StrFormat("control character 0x%02x in a text line", bad_char_));
  }

 private:
  absl::string_view data_;
  bool strip_;
  size_t pos_ = 0, number_ = 0;
  bool bad_ = false;
  unsigned bad_char_ = 0;
};

std::string Quote(absl::string_view t) {
  return absl::StrCat("'", t.substr(0, 40), t.size() > 40 ? "...'" : "'");
}

bool IsNumber(absl::string_view t) {
  double d;
  return absl::SimpleAtod(t, &d);
}

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

// ---------------------------------------------------------------- PLY
struct PlyProperty {
  int size = 0;        // scalar size, or the list's item size
  int count_size = 0;  // list count size; 0 for a scalar
  bool count_signed = false, item_float = false, item_signed = false;
  bool is_index = false;  // face vertex_indices / vertex_index
};
struct PlyElement {
  std::string name;
  int64_t count = 0;
  size_t line = 0;
  std::vector<PlyProperty> props;
};

// Size in bytes, signedness and floatness of a PLY type name (0: unknown).
int TypeSize(absl::string_view t, bool* is_signed, bool* is_float) {
  *is_float = t == "float" || t == "float32" || t == "double" || t == "float64";
  *is_signed = !(t == "uchar" || t == "uint8" || t == "ushort" || t == "uint16" || t == "uint" ||
                 t == "uint32");
  if (t == "char" || t == "int8" || t == "uchar" || t == "uint8") return 1;
  if (t == "short" || t == "int16" || t == "ushort" || t == "uint16") return 2;
  if (t == "int" || t == "int32" || t == "uint" || t == "uint32" || t == "float" ||
      t == "float32") {
    return 4;
  }
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// An integer of `size` bytes at p (float types truncated), either endianness.
int64_t ReadValue(const char* p, int size, bool is_signed, bool is_float, bool big) {
  unsigned char b[8];
  for (int i = 0; i < size; ++i) b[i] = static_cast<unsigned char>(p[big ? size - 1 - i : i]);
  if (is_float) {
    double d;
    if (size == 4) {
      float f;
      std::memcpy(&f, b, 4);
      d = f;
    } else {
      std::memcpy(&d, b, 8);
    }
    return d >= -9e18 && d <= 9e18 ? static_cast<int64_t>(d) : -1;  // NaN -> -1
  }
  uint64_t u = 0;
  for (int i = size - 1; i >= 0; --i) u = (u << 8) | b[i];
  if (is_signed && size < 8 && (u >> (8 * size - 1)) != 0) u |= ~uint64_t{0} << (8 * size);
  return static_cast<int64_t>(u);
}

absl::Status CheckPly(absl::string_view data, const std::string& name) {
  Lines lines(data, false);
  std::vector<absl::string_view> tok;
  if (!lines.Next(&tok) || tok.size() != 1 || tok[0] != "ply") {
    return LineError(name, 1, "a PLY file starts with the line 'ply'");
  }
  std::string format;
  std::vector<PlyElement> elements;
  bool end = false;
  while (!end && lines.Next(&tok)) {
    if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
    const size_t ln = lines.number();
    if (tok[0] == "format") {
      if (tok.size() != 3 || (tok[1] != "ascii" && tok[1] != "binary_little_endian" &&
                              tok[1] != "binary_big_endian")) {
        return LineError(name, ln, "expected 'format ascii|binary_little_endian|"
                                   "binary_big_endian 1.0'");
      }
      format = std::string(tok[1]);
    } else if (tok[0] == "element") {
      PlyElement e;
      if (tok.size() != 3 || !absl::SimpleAtoi(tok[2], &e.count) || e.count < 0) {
        return LineError(name, ln, "expected 'element NAME COUNT' with COUNT >= 0");
      }
      e.name = std::string(tok[1]);
      e.line = ln;
      elements.push_back(e);
    } else if (tok[0] == "property") {
      if (elements.empty()) return LineError(name, ln, "property before any element");
      PlyProperty p;
      bool f;
      if (tok.size() == 5 && tok[1] == "list") {
        p.count_size = TypeSize(tok[2], &p.count_signed, &f);
        p.size = TypeSize(tok[3], &p.item_signed, &p.item_float);
        if (p.count_size == 0 || f || p.size == 0) {
          return LineError(name, ln, "bad list property types");
        }
        p.is_index = elements.back().name == "face" &&
                     (tok[4] == "vertex_indices" || tok[4] == "vertex_index");
      } else if (tok.size() == 3) {
        p.size = TypeSize(tok[1], &p.item_signed, &p.item_float);
        if (p.size == 0) return LineError(name, ln, absl::StrCat("unknown type ", Quote(tok[1])));
      } else {
        return LineError(name, ln, "expected 'property TYPE NAME' or 'property list T T NAME'");
      }
      elements.back().props.push_back(p);
    } else if (tok[0] == "end_header") {
      end = true;
    } else {
      return LineError(name, lines.number(), absl::StrCat("unknown header line ", Quote(tok[0])));
    }
  }
  if (!end) return lines.Error(name, "no end_header");
  if (format.empty()) return LineError(name, lines.number(), "no format line in the header");
  const size_t body_start = lines.offset();
  const size_t body = data.size() - body_start;
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  int64_t vertices = -1;
  for (const PlyElement& e : elements) {
    if (e.name == "vertex") vertices = e.count;
    size_t min_bytes = 0;
    for (const PlyProperty& p : e.props) min_bytes += ascii ? 2 : (p.count_size ? p.count_size : p.size);
    if (min_bytes > 0 && static_cast<uint64_t>(e.count) > body / min_bytes) {
      return LineError(name, e.line,
                       absl::StrCat("element '", e.name, "' declares ", e.count,
                                    " items, more than the ", body,
                                    " bytes after the header can hold"));
    }
  }
  auto index_ok = [vertices](int64_t v) { return vertices < 0 || (v >= 0 && v < vertices); };
  if (!ascii) {
    size_t pos = body_start;
    for (const PlyElement& e : elements) {
      for (int64_t i = 0; i < e.count; ++i) {
        for (const PlyProperty& p : e.props) {
          auto truncated = [&]() {
            return absl::InvalidArgumentError(
                absl::StrCat(name, ": byte ", pos, ": file ends inside element '", e.name,
                             "' item ", i, " of ", e.count, " (truncated)"));
          };
          if (p.count_size == 0) {
            if (data.size() - pos < static_cast<size_t>(p.size)) return truncated();
            pos += p.size;
            continue;
          }
          if (data.size() - pos < static_cast<size_t>(p.count_size)) return truncated();
          const int64_t n = ReadValue(data.data() + pos, p.count_size, p.count_signed, false, big);
          if (n < 0) {
            return absl::InvalidArgumentError(absl::StrCat(
                name, ": byte ", pos, ": negative list length in element '", e.name, "'"));
          }
          if (p.is_index && n < 3) {
            return absl::InvalidArgumentError(absl::StrCat(
                name, ": byte ", pos, ": face ", i, " has ", n, " vertices, needs at least 3"));
          }
          pos += p.count_size;
          if (static_cast<uint64_t>(n) > (data.size() - pos) / p.size) return truncated();
          for (int64_t k = 0; p.is_index && k < n; ++k) {
            const int64_t v = ReadValue(data.data() + pos + k * p.size, p.size, p.item_signed,
                                        p.item_float, big);
            if (!index_ok(v)) {
              return absl::InvalidArgumentError(absl::StrCat(
                  name, ": byte ", pos + k * p.size, ": face ", i, " vertex index ", v,
                  " is not in [0, ", vertices, ") (wrong endianness?)"));
            }
          }
          pos += static_cast<size_t>(n) * p.size;
        }
      }
    }
    return absl::OkStatus();
  }
  // ASCII body: one item per line (assimp reads it line by line): one token
  // per scalar, a list's length then its items.
  for (const PlyElement& e : elements) {
    for (int64_t i = 0; i < e.count; ++i) {
      do {
        if (!lines.Next(&tok)) {
          return lines.Error(name, absl::StrCat("file ends inside element '", e.name, "' item ",
                                                i, " of ", e.count));
        }
      } while (tok.empty());
      size_t next = 0;
      auto too_few = [&]() {
        return LineError(name, lines.number(),
                         absl::StrCat("element '", e.name, "' item ", i,
                                      ": too few values on the line"));
      };
      for (const PlyProperty& p : e.props) {
        int64_t n = 1;
        if (p.count_size != 0) {
          if (next >= tok.size()) return too_few();
          if (!absl::SimpleAtoi(tok[next], &n) || n < 0) {
            return LineError(name, lines.number(),
                             absl::StrCat("bad list length ", Quote(tok[next])));
          }
          ++next;
          if (p.is_index && n < 3) {
            return LineError(name, lines.number(),
                             absl::StrCat("face ", i, " has ", n, " vertices, needs at least 3"));
          }
        }
        for (int64_t k = 0; k < n; ++k) {
          if (next >= tok.size()) return too_few();
          const absl::string_view t = tok[next++];
          double d;
          if (!absl::SimpleAtod(t, &d)) {
            return LineError(name, lines.number(),
                             absl::StrCat("expected a number, got ", Quote(t)));
          }
          if (p.is_index && (!(d >= 0 && d < 9e18) || d != std::floor(d) ||
                             !index_ok(static_cast<int64_t>(d)))) {
            return LineError(name, lines.number(),
                             absl::StrCat("face ", i, ": vertex index ", Quote(t),
                                          " is not in [0, ", vertices, ")"));
          }
        }
      }
      if (next != tok.size()) {
        return LineError(name, lines.number(),
                         absl::StrCat("element '", e.name, "' item ", i,
                                      ": too many values on the line"));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status CheckMeshSyntax(absl::string_view data, absl::string_view format,
                             const std::string& name) {
  if (format == "obj") return CheckObj(data, name);
  if (format == "off") return CheckOff(data, name);
  if (format == "ply") return CheckPly(data, name);
  return absl::OkStatus();
}

}  // namespace kdtree
