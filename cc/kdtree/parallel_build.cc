#include "cc/kdtree/parallel_build.h"

#include <algorithm>

namespace kdtree {

bool AppendFragment(const KdTree& fragment, KdTree* tree) {
  const size_t node_base = tree->nodes.size();
  const size_t ref_base = tree->refs.size() - 1;  // the fragment's refs[0] is dropped
  if (node_base + fragment.nodes.size() > KdNode::kMaxIndex ||
      ref_base + fragment.refs.size() > KdNode::kMaxIndex) {
    return false;
  }
  for (const KdNode& n : fragment.nodes) {
    if (n.is_leaf()) {
      tree->nodes.push_back(
          n.index() == 0 ? n : KdNode::Leaf(static_cast<uint32_t>(n.index() + ref_base)));
    } else {
      tree->nodes.push_back(
          KdNode::Inner(n.axis(), n.split, static_cast<uint32_t>(n.index() + node_base)));
    }
  }
  tree->refs.insert(tree->refs.end(), fragment.refs.begin() + 1, fragment.refs.end());
  BuildCounters& c = tree->counters;
  const BuildCounters& f = fragment.counters;
  c.clipped += f.clipped;
  c.pruned_box += f.pruned_box;
  c.pruned_leaf += f.pruned_leaf;
  c.lost_planar += f.lost_planar;
  c.peak_build_refs = std::max(c.peak_build_refs, f.peak_build_refs);
  return true;
}

}  // namespace kdtree
