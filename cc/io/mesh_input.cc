#include "cc/io/mesh_input.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <new>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "cc/base/read_file.h"

namespace kdtree {

absl::Status FileError(absl::StatusCode code, const std::string& path, const std::string& why) {
  return absl::Status(code, absl::StrCat(path, ": ", why));
}

bool NeedsSyntaxCheck(const std::string& format) {
  return format == "obj" || format == "off" || format == "ply";
}

namespace {

std::string BudgetNote(size_t max_bytes) {
  return absl::StrCat("the input budget of ", max_bytes,
                      " bytes (LoadOptions::max_input_bytes; kdrt --max_mesh_bytes)");
}

bool IsGzip(absl::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

// A zlib inflate stream, ended on every return path.
struct Inflater {
  z_stream zs;
  bool ok;
  Inflater() {
    std::memset(&zs, 0, sizeof(zs));
    ok = inflateInit2(&zs, 16 + MAX_WBITS) == Z_OK;  // gzip members only
  }
  ~Inflater() {
    if (ok) inflateEnd(&zs);
  }
};

// One pass over the gzip members of `gz`: their inflated size in *total,
// appended to `out` unless it is null; stops past max_bytes. Bytes after the
// last member that do not start another one are ignored, as zlib's gzread
// does.
absl::Status InflatePass(absl::string_view gz, const std::string& path, size_t max_bytes,
                         std::string* out, size_t* total) {
  *total = 0;
  Inflater in;
  if (!in.ok) return FileError(absl::StatusCode::kResourceExhausted, path, "zlib cannot start inflating");
  z_stream& zs = in.zs;
  std::vector<char> chunk(size_t{1} << 20);
  size_t fed = 0;  // bytes of gz handed to zlib so far
  for (;;) {
    if (zs.avail_in == 0 && fed < gz.size()) {  // zlib counts in 32 bits: feed in pieces
      const size_t n = std::min<size_t>(gz.size() - fed, size_t{1} << 30);
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gz.data() + fed));
      zs.avail_in = static_cast<uInt>(n);
      fed += n;
    }
    zs.next_out = reinterpret_cast<Bytef*>(chunk.data());
    zs.avail_out = static_cast<uInt>(chunk.size());
    const int rc = inflate(&zs, Z_NO_FLUSH);
    const size_t n = chunk.size() - zs.avail_out;
    if (*total + n > max_bytes) {
      return FileError(absl::StatusCode::kResourceExhausted, path,
                       absl::StrCat("inflates to more than ", BudgetNote(max_bytes)));
    }
    *total += n;
    if (out != nullptr) out->append(chunk.data(), n);
    if (rc == Z_STREAM_END) {
      const size_t left = zs.avail_in + (gz.size() - fed);
      if (!IsGzip(gz.substr(gz.size() - left))) break;  // the end, or trailing bytes
      inflateReset(&zs);  // another gzip member follows
    } else if (rc == Z_MEM_ERROR) {
      return FileError(absl::StatusCode::kResourceExhausted, path, "out of memory while inflating");
    } else if (rc != Z_OK) {
      const char* why = rc == Z_BUF_ERROR ? "unexpected end of file" : zs.msg;
      return FileError(absl::StatusCode::kDataLoss, path,
                       absl::StrCat("corrupt or truncated gzip data (zlib: ",
                                    why != nullptr ? why : "unknown error", ")"));
    }
  }
  return absl::OkStatus();
}

// Inflates `gz` into `out` within max_bytes: a first pass measures (and
// refuses a file over the budget holding no more than one 1 MiB chunk), the
// second fills a buffer of exactly that size, so memory never exceeds the
// budget by the slack of a growing string.
absl::Status Inflate(absl::string_view gz, const std::string& path, size_t max_bytes,
                     std::string* out) {
  if (!IsGzip(gz)) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     "name ends in .gz but the file is not gzip-compressed");
  }
  size_t total = 0;
  if (absl::Status st = InflatePass(gz, path, max_bytes, nullptr, &total); !st.ok()) return st;
  if (total == 0) {
    return FileError(absl::StatusCode::kInvalidArgument, path, "file is empty after gzip decompression");
  }
  out->clear();
  out->reserve(total);
  return InflatePass(gz, path, max_bytes, out, &total);
}

}  // namespace

std::string Extension(absl::string_view path) {
  const size_t slash = path.find_last_of('/');
  const size_t start = slash == absl::string_view::npos ? 0 : slash + 1;
  const size_t dot = path.find_last_of('.');
  if (dot == absl::string_view::npos || dot < start || dot + 1 == path.size()) return "";
  return absl::AsciiStrToLower(path.substr(dot + 1));
}

std::string SniffMeshFormat(absl::string_view bytes) {
  if (absl::StartsWith(bytes, "glTF")) return "glb";
  const size_t end = bytes.find_first_of("\r\n");
  const absl::string_view first = absl::StripAsciiWhitespace(bytes.substr(0, end));
  if (first == "ply") return "ply";
  if (absl::EndsWith(first.substr(0, first.find_first_of(" \t")), "OFF")) return "off";
  // OBJ: the first statement that is not a comment or blank.
  for (absl::string_view rest = bytes; !rest.empty();) {
    const size_t eol = rest.find('\n');
    const absl::string_view line = absl::StripAsciiWhitespace(rest.substr(0, eol));
    rest = eol == absl::string_view::npos ? absl::string_view() : rest.substr(eol + 1);
    if (line.empty() || line[0] == '#') continue;
    const absl::string_view word = line.substr(0, line.find_first_of(" \t"));
    for (const char* w : {"v", "vn", "vt", "f", "o", "g", "s", "mtllib", "usemtl"}) {
      if (word == w) return "obj";
    }
    return "";
  }
  return "";
}

absl::StatusOr<MeshInput> ReadMeshInput(const std::string& path, size_t max_bytes) {
  absl::StatusOr<InputFile> in = InputFile::Open(path, "mesh file");
  if (!in.ok()) return in.status();
  if (in->regular() && in->size() == 0) {
    return FileError(absl::StatusCode::kInvalidArgument, path, "file is empty");
  }
  if (in->regular() && in->size() > max_bytes) {
    return FileError(absl::StatusCode::kResourceExhausted, path,
                     absl::StrCat("is ", in->size(), " bytes, more than ", BudgetNote(max_bytes)));
  }
  MeshInput m;
  const bool gz_name = absl::EndsWithIgnoreCase(path, ".gz");
  m.format = Extension(gz_name ? path.substr(0, path.size() - 3) : path);
  m.in_memory = gz_name || !in->regular();
  if (!m.in_memory && !NeedsSyntaxCheck(m.format)) return m;  // the importer reads it
  try {
    absl::StatusOr<std::string> raw = in->ReadAll(max_bytes);
    if (absl::IsResourceExhausted(raw.status())) {
      return FileError(absl::StatusCode::kResourceExhausted, path,
                       absl::StrCat("is longer than ", BudgetNote(max_bytes)));
    }
    if (!raw.ok()) return raw.status();
    if (raw->empty()) return FileError(absl::StatusCode::kInvalidArgument, path, "file is empty");
    if (gz_name || (!in->regular() && IsGzip(*raw))) {
      if (absl::Status st = Inflate(*raw, path, max_bytes, &m.bytes); !st.ok()) return st;
    } else {
      m.bytes = *std::move(raw);
    }
  } catch (const std::bad_alloc&) {
    return FileError(absl::StatusCode::kResourceExhausted, path, "out of memory while reading");
  }
  if (m.in_memory && m.format.empty()) m.format = SniffMeshFormat(m.bytes);
  if (m.in_memory && m.format.empty()) {
    return FileError(absl::StatusCode::kInvalidArgument, path,
                     "cannot tell the mesh format: the name has no extension and the bytes are "
                     "not gzip, PLY, OFF, binary glTF or OBJ");
  }
  return m;
}

}  // namespace kdtree
