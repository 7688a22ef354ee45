#include "cc/render/ray_dump.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "cc/base/fnv.h"

namespace kdtree {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the dump is written in host order");

constexpr char kMagic[8] = {'K', 'D', 'R', 'A', 'Y', 'S', '0', '1'};
constexpr size_t kHeaderBytes = 32;

struct Header {
  char magic[8];
  uint32_t record_bytes;
  uint32_t width;
  uint32_t height;
  uint32_t reserved;
  uint64_t count;
};
static_assert(sizeof(Header) == kHeaderBytes, "32-byte header");

// FNV-1a over 64-bit words (cc/base/fnv.h; sizes here are multiples of 8).
struct Checksum {
  uint64_t h = kFnvOffset;
  void Add(const void* data, size_t size) { h = FnvWords(data, size, h); }
};

std::string Errno() { return std::strerror(errno); }

}  // namespace

absl::Status WriteRayDump(const std::string& path, const RayDump& dump) {
  Header hdr;
  std::memcpy(hdr.magic, kMagic, 8);
  hdr.record_bytes = sizeof(RayRecord);
  hdr.width = static_cast<uint32_t>(dump.width);
  hdr.height = static_cast<uint32_t>(dump.height);
  hdr.reserved = 0;
  hdr.count = dump.records.size();
  Checksum sum;
  sum.Add(reinterpret_cast<const char*>(&hdr) + 8, kHeaderBytes - 8);
  sum.Add(dump.records.data(), dump.records.size() * sizeof(RayRecord));

  const std::string tmp = absl::StrCat(path, ".tmp");
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) return absl::InternalError(absl::StrCat(path, ": cannot create: ", Errno()));
  bool ok = std::fwrite(&hdr, sizeof(hdr), 1, f) == 1;
  if (ok && !dump.records.empty()) {
    ok = std::fwrite(dump.records.data(), sizeof(RayRecord), dump.records.size(), f) ==
         dump.records.size();
  }
  ok = ok && std::fwrite(&sum.h, 8, 1, f) == 1;
  const std::string err = ok ? "" : Errno();
  ok = (std::fclose(f) == 0) && ok;
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = err.empty() ? Errno() : err;
    std::remove(tmp.c_str());
    return absl::InternalError(absl::StrCat(path, ": cannot write ray dump: ", reason));
  }
  return absl::OkStatus();
}

absl::StatusOr<RayDump> ReadRayDump(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return absl::NotFoundError(absl::StrCat(path, ": cannot open: ", Errno()));
  auto fail = [&](const std::string& reason) {
    std::fclose(f);
    return absl::DataLossError(absl::StrCat(path, ": ", reason));
  };
  Header hdr;
  if (std::fread(&hdr, sizeof(hdr), 1, f) != 1) return fail("truncated header");
  if (std::memcmp(hdr.magic, kMagic, 8) != 0) return fail("not a ray dump (bad magic)");
  if (hdr.record_bytes != sizeof(RayRecord)) {
    return fail(absl::StrCat("record size ", hdr.record_bytes, ", expected ", sizeof(RayRecord)));
  }
  if (std::fseek(f, 0, SEEK_END) != 0) return fail("cannot seek");
  const long size = std::ftell(f);
  const unsigned long long expected = kHeaderBytes + hdr.count * sizeof(RayRecord) + 8;
  if (hdr.count > (1ull << 40) || size < 0 || static_cast<unsigned long long>(size) != expected) {
    return fail(absl::StrCat("file has ", size, " bytes, the header implies ", expected,
                             " (truncated or trailing data)"));
  }
  std::fseek(f, kHeaderBytes, SEEK_SET);
  RayDump dump;
  dump.width = static_cast<int>(hdr.width);
  dump.height = static_cast<int>(hdr.height);
  dump.records.resize(hdr.count);
  if (hdr.count > 0 && std::fread(dump.records.data(), sizeof(RayRecord), hdr.count, f) != hdr.count) {
    return fail("truncated records");
  }
  uint64_t stored;
  if (std::fread(&stored, 8, 1, f) != 1) return fail("truncated checksum");
  std::fclose(f);
  Checksum sum;
  sum.Add(reinterpret_cast<const char*>(&hdr) + 8, kHeaderBytes - 8);
  sum.Add(dump.records.data(), dump.records.size() * sizeof(RayRecord));
  if (sum.h != stored) return absl::DataLossError(absl::StrCat(path, ": checksum mismatch"));
  for (size_t i = 0; i < dump.records.size(); ++i) {
    if (static_cast<uint8_t>(dump.records[i].kind) >= kNumRayKinds) {
      return absl::DataLossError(absl::StrCat(path, ": record ", i, " has an invalid kind"));
    }
  }
  return dump;
}

}  // namespace kdtree
