#include "cc/kdtree/leaf_layout.h"

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

// Writes the packets of leaf `node` (count > 0) at `out`.
void WriteLeaf(const KdTree& tree, const KdNode& node, float* out) {
  const uint32_t count = tree.LeafCount(node);
  const uint32_t* tris = tree.LeafBegin(node);
  const uint32_t packets = PacketsOf(count);
  for (uint32_t j = 0; j < packets; ++j, out += kPacketFloats) {
    for (int lane = 0; lane < kPacketLanes; ++lane) {
      const uint32_t k = j * kPacketLanes + lane;
      uint32_t id = kPadLane;
      for (int v = 0; v < 3; ++v) {
        // Padding lanes: zero vertices.
        const Vec3 p = k < count ? tree.verts[3 * static_cast<size_t>(tris[k]) + v] : Vec3();
        out[(3 * v + 0) * kPacketLanes + lane] = p.x;
        out[(3 * v + 1) * kPacketLanes + lane] = p.y;
        out[(3 * v + 2) * kPacketLanes + lane] = p.z;
      }
      if (k < count) id = tris[k];
      if (lane == 0 && j + 1 == packets) id |= kLastPacket;
      std::memcpy(&out[kPacketIds + lane], &id, sizeof(id));
    }
  }
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

void LayoutLeafTriangles(KdTree* tree, bool parallel) {
  HugeBuffer<float>().swap(tree->leaf_soa);
  HugeBuffer<KdNode>().swap(tree->leaf_nodes);
  if (tree->verts.empty() || tree->nodes.empty()) return;
  // Packets per chunk of nodes, then each chunk's first packet (node order:
  // any packing of the refs lists, shared lists included, is covered).
  const size_t n = tree->nodes.size();
  const size_t chunks = (n + kChunkNodes - 1) / kChunkNodes;
  std::vector<size_t> first(chunks + 1, 0);
  ForChunks(chunks, parallel, [&](size_t c) {
    size_t packets = 0;
    for (size_t i = c * kChunkNodes, end = std::min(n, i + kChunkNodes); i < end; ++i) {
      const KdNode& node = tree->nodes[i];
      if (node.is_leaf()) packets += PacketsOf(tree->LeafCount(node));
    }
    first[c + 1] = packets;
  });
  for (size_t c = 0; c < chunks; ++c) first[c + 1] += first[c];
  if (first[chunks] >= kEmptyLeaf) return;
  // Every word is written below: no zeroing pass first (HugeBuffer).
  tree->leaf_soa.resize(first[chunks] * kPacketFloats);
  tree->leaf_nodes.resize(n);
  ForChunks(chunks, parallel, [&](size_t c) {
    size_t next = first[c];
    for (size_t i = c * kChunkNodes, end = std::min(n, i + kChunkNodes); i < end; ++i) {
      const KdNode& node = tree->nodes[i];
      if (!node.is_leaf()) {
        tree->leaf_nodes[i] = node;
        continue;
      }
      const uint32_t count = tree->LeafCount(node);
      if (count == 0) {
        tree->leaf_nodes[i] = KdNode::Leaf(kEmptyLeaf);
        continue;
      }
      tree->leaf_nodes[i] = KdNode::Leaf(static_cast<uint32_t>(next));
      WriteLeaf(*tree, node, tree->leaf_soa.data() + next * kPacketFloats);
      next += PacketsOf(count);
    }
  });
}

}  // namespace kdtree
