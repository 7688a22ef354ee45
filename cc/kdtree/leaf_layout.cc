#include "cc/kdtree/leaf_layout.h"

namespace kdtree {

void LayoutLeafTriangles(KdTree* tree) {
  HugeVector<float>().swap(tree->leaf_soa);
  HugeVector<uint32_t>().swap(tree->leaf_packet);
  if (tree->verts.empty() || tree->nodes.empty()) return;
  // Packets needed, then filled per leaf node in node order (any packing of
  // the refs lists, shared lists included, is covered).
  size_t packets = 0;
  for (const KdNode& node : tree->nodes) {
    if (node.is_leaf()) packets += (tree->LeafCount(node) + kPacketLanes - 1) / kPacketLanes;
  }
  tree->leaf_soa.assign(packets * kPacketFloats, 0.0f);
  tree->leaf_packet.assign(tree->nodes.size(), 0);
  uint32_t next = 0;
  for (size_t n = 0; n < tree->nodes.size(); ++n) {
    const KdNode& node = tree->nodes[n];
    if (!node.is_leaf()) continue;
    tree->leaf_packet[n] = next;
    const uint32_t count = tree->LeafCount(node);
    if (count == 0) continue;
    const uint32_t* tris = tree->LeafBegin(node);
    for (uint32_t j = 0; j < count; ++j) {
      float* packet = &tree->leaf_soa[(static_cast<size_t>(next) + j / kPacketLanes) * kPacketFloats];
      const int lane = static_cast<int>(j % kPacketLanes);
      for (int v = 0; v < 3; ++v) {
        const Vec3& p = tree->verts[3 * static_cast<size_t>(tris[j]) + v];
        packet[(3 * v + 0) * kPacketLanes + lane] = p.x;
        packet[(3 * v + 1) * kPacketLanes + lane] = p.y;
        packet[(3 * v + 2) * kPacketLanes + lane] = p.z;
      }
    }
    next += (count + kPacketLanes - 1) / kPacketLanes;
  }
}

}  // namespace kdtree
