#include "cc/kdtree/collapse.h"

#include <algorithm>
#include <iterator>
#include <vector>

#include "cc/kdtree/sah_cost.h"

namespace kdtree {
namespace {

class Collapser {
 public:
  Collapser(const Config& config, const ListTree& tree)
      : config_(config), tree_(tree), collapse_(tree.nodes.size(), 0) {}

  struct Info {
    double cost = 0;
    bool small = false;            // tris holds the subtree's union
    std::vector<uint32_t> tris;    // sorted, unique
  };

  Info Analyze(uint32_t index, const AABB& box) {
    const KdNode& n = tree_.nodes[index];
    const double sa = box.SurfaceArea();
    Info info;
    if (n.is_leaf()) {
      const uint32_t count = tree_.LeafCount(n);
      info.cost = config_.intersection_cost * Packets(count, config_) * sa;
      if (count <= kMaxCollapsedLeaf) {
        info.small = true;
        info.tris.assign(tree_.LeafBegin(n), tree_.LeafBegin(n) + count);
        std::sort(info.tris.begin(), info.tris.end());
        info.tris.erase(std::unique(info.tris.begin(), info.tris.end()), info.tris.end());
      }
      return info;
    }
    Info l = Analyze(index + 1, box.LeftOf(n.axis(), n.split));
    Info r = Analyze(n.index(), box.RightOf(n.axis(), n.split));
    info.cost = config_.traversal_cost * sa + l.cost + r.cost;
    if (!l.small || !r.small) return info;
    std::vector<uint32_t> u;
    u.reserve(l.tris.size() + r.tris.size());
    std::set_union(l.tris.begin(), l.tris.end(), r.tris.begin(), r.tris.end(),
                   std::back_inserter(u));
    if (u.size() > kMaxCollapsedLeaf) return info;
    const double leaf_cost =
        config_.intersection_cost * Packets(static_cast<double>(u.size()), config_) * sa;
    if (leaf_cost <= info.cost) {
      collapse_[index] = 1;
      ++removed_;
      info.cost = leaf_cost;
      info.small = true;
      info.tris = std::move(u);
    }
    return info;
  }

  void Emit(uint32_t index, HugeBuffer<KdNode>* nodes, HugeBuffer<uint32_t>* refs) const {
    const KdNode& n = tree_.nodes[index];
    const size_t at = nodes->size();
    nodes->push_back(KdNode::Leaf(0));
    if (n.is_leaf() || collapse_[index]) {
      std::vector<uint32_t> tris;
      if (n.is_leaf()) {
        tris.assign(tree_.LeafBegin(n), tree_.LeafBegin(n) + tree_.LeafCount(n));
      } else {
        Gather(index, &tris);
        std::sort(tris.begin(), tris.end());
        tris.erase(std::unique(tris.begin(), tris.end()), tris.end());
      }
      if (tris.empty()) return;  // the shared empty list at refs[0]
      const uint32_t offset = static_cast<uint32_t>(refs->size());
      refs->push_back(static_cast<uint32_t>(tris.size()));
      refs->insert(refs->end(), tris.begin(), tris.end());
      (*nodes)[at] = KdNode::Leaf(offset);
      return;
    }
    Emit(index + 1, nodes, refs);
    (*nodes)[at] = KdNode::Inner(n.axis(), n.split, static_cast<uint32_t>(nodes->size()));
    Emit(n.index(), nodes, refs);
  }

  uint64_t removed() const { return removed_; }

 private:
  void Gather(uint32_t index, std::vector<uint32_t>* tris) const {
    const KdNode& n = tree_.nodes[index];
    if (n.is_leaf()) {
      tris->insert(tris->end(), tree_.LeafBegin(n), tree_.LeafBegin(n) + tree_.LeafCount(n));
      return;
    }
    Gather(index + 1, tris);
    Gather(n.index(), tris);
  }

  const Config& config_;
  const ListTree& tree_;
  std::vector<char> collapse_;
  uint64_t removed_ = 0;
};

}  // namespace

uint64_t CollapseTree(const Config& config, ListTree* tree) {
  if (tree->nodes.empty()) return 0;
  Collapser c(config, *tree);
  c.Analyze(0, tree->bounds);
  if (c.removed() == 0) return 0;
  HugeBuffer<KdNode> nodes;
  HugeBuffer<uint32_t> refs;
  nodes.reserve(tree->nodes.size());
  refs.reserve(tree->refs.size());
  refs.push_back(0);
  c.Emit(0, &nodes, &refs);
  const uint64_t before = tree->nodes.size();
  tree->nodes = std::move(nodes);
  tree->refs = std::move(refs);
  return (before - tree->nodes.size()) / 2;  // each removed inner node had 2 children
}

}  // namespace kdtree
