#include "cc/kdtree/leaf_layout.h"

#include <cstring>

namespace kdtree {

void LayoutLeafTriangles(KdTree* tree) {
  HugeVector<float>().swap(tree->leaf_soa);
  HugeVector<KdNode>().swap(tree->leaf_nodes);
  if (tree->verts.empty() || tree->nodes.empty()) return;
  // Packets needed, then filled per leaf node in node order (any packing of
  // the refs lists, shared lists included, is covered).
  size_t packets = 0;
  for (const KdNode& node : tree->nodes) {
    if (node.is_leaf()) packets += (tree->LeafCount(node) + kPacketLanes - 1) / kPacketLanes;
  }
  if (packets >= kEmptyLeaf) return;
  // Each packet is assembled here and appended: the array is written once
  // (a resize would zero it first, a second pass over hundreds of MB).
  tree->leaf_soa.reserve(packets * kPacketFloats);
  tree->leaf_nodes = tree->nodes;
  uint32_t next = 0;
  for (size_t n = 0; n < tree->nodes.size(); ++n) {
    const KdNode& node = tree->nodes[n];
    if (!node.is_leaf()) continue;
    const uint32_t count = tree->LeafCount(node);
    if (count == 0) {
      tree->leaf_nodes[n] = KdNode::Leaf(kEmptyLeaf);
      continue;
    }
    tree->leaf_nodes[n] = KdNode::Leaf(next);
    const uint32_t* tris = tree->LeafBegin(node);
    const uint32_t leaf_packets = (count + kPacketLanes - 1) / kPacketLanes;
    for (uint32_t j = 0; j < leaf_packets; ++j) {
      float packet[kPacketFloats] = {};  // padding lanes: zero vertices
      for (int lane = 0; lane < kPacketLanes; ++lane) {
        const uint32_t k = j * kPacketLanes + lane;
        uint32_t id = kPadLane;
        if (k < count) {
          id = tris[k];
          for (int v = 0; v < 3; ++v) {
            const Vec3& p = tree->verts[3 * static_cast<size_t>(id) + v];
            packet[(3 * v + 0) * kPacketLanes + lane] = p.x;
            packet[(3 * v + 1) * kPacketLanes + lane] = p.y;
            packet[(3 * v + 2) * kPacketLanes + lane] = p.z;
          }
        }
        if (lane == 0 && j + 1 == leaf_packets) id |= kLastPacket;
        std::memcpy(&packet[kPacketIds + lane], &id, sizeof(id));
      }
      tree->leaf_soa.insert(tree->leaf_soa.end(), packet, packet + kPacketFloats);
    }
    next += leaf_packets;
  }
}

}  // namespace kdtree
