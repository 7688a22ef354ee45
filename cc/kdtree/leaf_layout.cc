#include "cc/kdtree/leaf_layout.h"

#include <emmintrin.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "tbb/blocked_range.h"
#include "tbb/parallel_for.h"

namespace kdtree {

namespace {

// Nodes per chunk: the unit of work, and of the packet prefix sum.
constexpr size_t kChunkNodes = 16384;

uint32_t PacketsOf(uint32_t count) { return (count + kPacketLanes - 1) / kPacketLanes; }

// Writes the packets of the `count` > 0 triangles `tris` at `out` (16-byte
// aligned), the k-th triangle's 9 floats (a, b, c) at row(k). A packet's 36
// vertex floats are the transpose of its 4
// triangles' 9 floats each (float f of lane l at f * 4 + l): two 4x4
// transposes and a column, with zero rows for padding lanes. Non-temporal stores: the packets (hundreds
// of megabytes on the large scenes) are written whole and not read back by
// the build, so they bypass the caches and skip the read of each line before
// it is written (the caller fences).
template <class Row>
void WritePackets(const Row& row_of, const uint32_t* tris, uint32_t count, float* out) {
  static_assert(kPacketLanes == 4 && kPacketIds == 36, "the transpose below is 4 x 9");
  const uint32_t packets = PacketsOf(count);
  static const float kZero[9] = {};
  for (uint32_t j = 0; j < packets; ++j, out += kPacketFloats) {
    const float* row[kPacketLanes];
    alignas(16) uint32_t id[kPacketLanes];
    for (int lane = 0; lane < kPacketLanes; ++lane) {
      const uint32_t k = j * kPacketLanes + lane;
      row[lane] = k < count ? row_of(k) : kZero;
      id[lane] = k < count ? tris[k] : kPadLane;
    }
    if (j + 1 == packets) id[0] |= kLastPacket;
    for (int half = 0; half < 2; ++half) {
      __m128 r0 = _mm_loadu_ps(row[0] + 4 * half), r1 = _mm_loadu_ps(row[1] + 4 * half);
      __m128 r2 = _mm_loadu_ps(row[2] + 4 * half), r3 = _mm_loadu_ps(row[3] + 4 * half);
      _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
      float* o = out + 16 * half;
      _mm_stream_ps(o + 0, r0);
      _mm_stream_ps(o + 4, r1);
      _mm_stream_ps(o + 8, r2);
      _mm_stream_ps(o + 12, r3);
    }
    _mm_stream_ps(out + 32, _mm_setr_ps(row[0][8], row[1][8], row[2][8], row[3][8]));
    _mm_stream_si128(reinterpret_cast<__m128i*>(out + kPacketIds),
                     _mm_load_si128(reinterpret_cast<const __m128i*>(id)));
  }
}

// The packets of the `count` > 0 triangles `tris` of the soup's `vertices`.
void WriteLeafPacketsOf(const Vec3* vertices, const uint32_t* tris, uint32_t count, float* out) {
  static_assert(sizeof(Vec3) == 3 * sizeof(float), "a triangle is 9 packed floats");
  const float* verts = reinterpret_cast<const float*>(vertices);
  WritePackets([&](uint32_t k) { return verts + 9 * static_cast<size_t>(tris[k]); }, tris, count,
               out);
}

// The packets of leaf `node` of the lists.
void WriteLeaf(const ListTree& tree, const Vec3* vertices, const KdNode& node, float* out) {
  WriteLeafPacketsOf(vertices, tree.LeafBegin(node), tree.LeafCount(node), out);
}

// Runs body(chunk) for every chunk, on the calling thread or as tasks.
template <class Body>
void ForChunks(size_t chunks, bool parallel, const Body& body) {
  if (!parallel) {
    for (size_t c = 0; c < chunks; ++c) body(c);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t c = r.begin(); c != r.end(); ++c) body(c);
                    });
}

}  // namespace

bool LayoutLeafTriangles(const ListTree& lists, const Vec3* verts, bool parallel, KdTree* out) {
  HugeBuffer<KdNode>().swap(out->nodes);
  HugeBuffer<float>().swap(out->leaf_soa);
  if (lists.nodes.empty()) return true;
  // Packets per chunk of nodes, then each chunk's first packet (node order:
  // any packing of the refs lists, shared lists included, is covered).
  const size_t n = lists.nodes.size();
  const size_t chunks = (n + kChunkNodes - 1) / kChunkNodes;
  std::vector<size_t> first(chunks + 1, 0);
  ForChunks(chunks, parallel, [&](size_t c) {
    size_t packets = 0;
    for (size_t i = c * kChunkNodes, end = std::min(n, i + kChunkNodes); i < end; ++i) {
      const KdNode& node = lists.nodes[i];
      if (node.is_leaf()) packets += PacketsOf(lists.LeafCount(node));
    }
    first[c + 1] = packets;
  });
  for (size_t c = 0; c < chunks; ++c) first[c + 1] += first[c];
  if (first[chunks] >= kEmptyLeaf) return false;
  // Every word is written below: no zeroing pass first (HugeBuffer).
  out->leaf_soa.resize(first[chunks] * kPacketFloats);
  out->nodes.resize(n);
  ForChunks(chunks, parallel, [&](size_t c) {
    size_t next = first[c];
    for (size_t i = c * kChunkNodes, end = std::min(n, i + kChunkNodes); i < end; ++i) {
      const KdNode& node = lists.nodes[i];
      if (!node.is_leaf()) {
        out->nodes[i] = node;
        continue;
      }
      const uint32_t count = lists.LeafCount(node);
      if (count == 0) {
        out->nodes[i] = KdNode::Leaf(kEmptyLeaf);
        continue;
      }
      out->nodes[i] = KdNode::Leaf(static_cast<uint32_t>(next));
      WriteLeaf(lists, verts, node, out->leaf_soa.data() + next * kPacketFloats);
      next += PacketsOf(count);
    }
    _mm_sfence();  // the streaming stores of WriteLeaf are seen before the chunk ends
  });
  return true;
}

namespace {

// Calls f(triangle) for each triangle of the leaf, in list order.
template <class F>
void ForEachLeafTriangle(const KdTree& tree, const KdNode& leaf, const F& f) {
  if (leaf.index() == kEmptyLeaf) return;
  ForEachPacketLane(tree.leaf_soa.data() + size_t{leaf.index()} * kPacketFloats,
                    [&](const float*, int, uint32_t t) { f(t); });
}

}  // namespace

void WriteLeafPackets(const Vec3* verts, const uint32_t* ids, size_t count, float* out) {
  WriteLeafPacketsOf(verts, ids, static_cast<uint32_t>(count), out);
  _mm_sfence();  // its streaming stores are seen by whoever reads the packets next
}

void WriteLeafPacketsFromRows(const float* rows, const uint32_t* ids, size_t count, float* out) {
  WritePackets([&](uint32_t k) { return rows + 9 * static_cast<size_t>(k); }, ids,
               static_cast<uint32_t>(count), out);
  _mm_sfence();  // as WriteLeafPackets
}

std::vector<uint32_t> LeafTriangles(const KdTree& tree, const KdNode& leaf) {
  std::vector<uint32_t> tris;
  ForEachLeafTriangle(tree, leaf, [&](uint32_t t) { tris.push_back(t); });
  return tris;
}

uint32_t LeafTriangleCount(const KdTree& tree, const KdNode& leaf) {
  uint32_t count = 0;
  ForEachLeafTriangle(tree, leaf, [&](uint32_t) { ++count; });
  return count;
}

}  // namespace kdtree
