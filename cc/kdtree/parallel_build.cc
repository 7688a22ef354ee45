#include "cc/kdtree/parallel_build.h"

#include <algorithm>

namespace kdtree {

int ParallelDepth(int threads) {
  int log2 = 0;
  while ((1 << log2) < threads) ++log2;
  return log2 + 3;
}

namespace {

class Stitcher {
 public:
  explicit Stitcher(KdTree* out) : out_(out) {}

  // Emits node i of `f` and its subtree in depth-first order; `next_child`
  // walks f.children, whose placeholders the walk meets in increasing order.
  void Emit(const Fragment& f, uint32_t i, size_t* next_child) {
    if (*next_child < f.children.size() && f.children[*next_child].first == i) {
      const Fragment& child = *f.children[(*next_child)++].second;
      size_t grandchild = 0;
      Emit(child, 0, &grandchild);
      return;
    }
    const KdNode& n = f.tree.nodes[i];
    if (n.is_leaf()) {
      if (n.index() == 0) {
        out_->nodes.push_back(n);  // the shared empty list
        return;
      }
      const size_t offset = out_->refs.size();
      const uint32_t* list = &f.tree.refs[n.index()];
      out_->refs.insert(out_->refs.end(), list, list + 1 + list[0]);
      if (offset > KdNode::kMaxIndex) overflow_ = true;
      out_->nodes.push_back(KdNode::Leaf(static_cast<uint32_t>(offset & KdNode::kMaxIndex)));
      return;
    }
    const size_t at = out_->nodes.size();
    out_->nodes.push_back(n);
    Emit(f, i + 1, next_child);
    const size_t right = out_->nodes.size();
    if (right > KdNode::kMaxIndex) overflow_ = true;
    out_->nodes[at] =
        KdNode::Inner(n.axis(), n.split, static_cast<uint32_t>(right & KdNode::kMaxIndex));
    Emit(f, n.index(), next_child);
  }

  void AddCounters(const Fragment& f) {
    BuildCounters& c = out_->counters;
    const BuildCounters& g = f.tree.counters;
    c.clipped += g.clipped;
    c.pruned_box += g.pruned_box;
    c.pruned_leaf += g.pruned_leaf;
    c.lost_planar += g.lost_planar;
    c.peak_build_refs = std::max(c.peak_build_refs, g.peak_build_refs);
    nodes_ += f.tree.nodes.size();
    refs_ += f.tree.refs.size();
    for (const auto& child : f.children) AddCounters(*child.second);
  }

  size_t nodes() const { return nodes_; }
  size_t refs() const { return refs_; }
  bool overflow() const { return overflow_; }

 private:
  KdTree* out_;
  // Capacity to reserve: at least the emitted sizes (placeholders and each
  // fragment's refs[0] are counted too). Indices are checked as emitted.
  size_t nodes_ = 0, refs_ = 0;
  bool overflow_ = false;
};

}  // namespace

bool Stitch(const Fragment& root, KdTree* out) {
  out->counters = BuildCounters();
  Stitcher s(out);
  s.AddCounters(root);
  HugeVector<KdNode>().swap(out->nodes);
  HugeVector<uint32_t>().swap(out->refs);
  out->nodes.reserve(s.nodes());
  out->refs.reserve(s.refs());
  out->refs.push_back(0);
  size_t next_child = 0;
  s.Emit(root, 0, &next_child);
  return !s.overflow();
}

}  // namespace kdtree
