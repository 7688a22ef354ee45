#include "cc/kdtree/parallel_build.h"

#include <algorithm>
#include <atomic>
#include <cassert>

#include "tbb/task_group.h"

namespace kdtree {

int ParallelDepth(int threads) {
  int log2 = 0;
  while ((1 << log2) < threads) ++log2;
  return log2 + 3;
}

namespace {

// A fragment with what its whole subtree emits (its nested fragments
// included), and the same for each of its children, in f.children's order.
struct Sized {
  const Fragment* f = nullptr;
  size_t nodes = 0, refs = 0;
  std::vector<Sized> kids;
};

// Sizes `f`'s subtree; the children are sized at once, as tasks. A
// placeholder is a leaf without a list, so it adds no refs; it is replaced by
// its child's nodes.
void Size(const Fragment& f, Sized* out) {
  out->f = &f;
  out->kids.resize(f.children.size());
  tbb::task_group group;
  for (size_t k = 0; k < f.children.size(); ++k) {
    group.run([&f, out, k] { Size(*f.children[k].second, &out->kids[k]); });
  }
  size_t refs = 0;
  for (const KdNode& n : f.tree.nodes) {
    if (n.is_leaf() && n.index() != 0) refs += 1 + f.tree.refs[n.index()];
  }
  group.wait();
  out->nodes = f.tree.nodes.size() - f.children.size();
  out->refs = refs;
  for (const Sized& kid : out->kids) {
    out->nodes += kid.nodes;
    out->refs += kid.refs;
  }
}

// Writes a fragment's subtree in depth-first order (left, then right) from
// out->nodes[node_at] and out->refs[ref_at], as the serial build writes it; a
// nested fragment starts where its placeholder is met, and is written by a
// task of its own meanwhile (its size is known: Size).
class Stitcher {
 public:
  Stitcher(ListTree* out, std::atomic<bool>* overflow) : out_(out), overflow_(overflow) {}

  void Run(const Sized& s, size_t node_at, size_t ref_at) {
    node_at_ = node_at;
    ref_at_ = ref_at;
    next_child_ = 0;
    sized_ = &s;
    tbb::task_group group;
    group_ = &group;
    Emit(*s.f, 0);
    group.wait();
    // Every node and list of the fragment's subtree was written, no more.
    assert(node_at_ == node_at + s.nodes && ref_at_ == ref_at + s.refs);
  }

 private:
  void Emit(const Fragment& f, uint32_t i) {
    if (next_child_ < f.children.size() && f.children[next_child_].first == i) {
      const Sized& kid = sized_->kids[next_child_++];
      const size_t node_at = node_at_, ref_at = ref_at_;
      ListTree* out = out_;
      std::atomic<bool>* overflow = overflow_;
      group_->run([&kid, node_at, ref_at, out, overflow] {
        Stitcher(out, overflow).Run(kid, node_at, ref_at);
      });
      node_at_ += kid.nodes;
      ref_at_ += kid.refs;
      return;
    }
    const KdNode& n = f.tree.nodes[i];
    if (n.is_leaf()) {
      if (n.index() == 0) {
        out_->nodes[node_at_++] = n;  // the shared empty list
        return;
      }
      const uint32_t* list = &f.tree.refs[n.index()];
      std::copy(list, list + 1 + list[0], out_->refs.begin() + ref_at_);
      if (ref_at_ > KdNode::kMaxIndex) overflow_->store(true, std::memory_order_relaxed);
      out_->nodes[node_at_++] = KdNode::Leaf(static_cast<uint32_t>(ref_at_ & KdNode::kMaxIndex));
      ref_at_ += 1 + list[0];
      return;
    }
    const size_t at = node_at_++;
    Emit(f, i + 1);
    const size_t right = node_at_;
    if (right > KdNode::kMaxIndex) overflow_->store(true, std::memory_order_relaxed);
    out_->nodes[at] =
        KdNode::Inner(n.axis(), n.split, static_cast<uint32_t>(right & KdNode::kMaxIndex));
    Emit(f, n.index());
  }

  ListTree* out_;
  std::atomic<bool>* overflow_;
  const Sized* sized_ = nullptr;
  tbb::task_group* group_ = nullptr;
  size_t node_at_ = 0, ref_at_ = 0, next_child_ = 0;
};

void AddCounters(const Fragment& f, BuildCounters* c) {
  const BuildCounters& g = f.tree.counters;
  c->clipped += g.clipped;
  c->pruned_box += g.pruned_box;
  c->pruned_leaf += g.pruned_leaf;
  c->lost_planar += g.lost_planar;
  c->peak_build_refs = std::max(c->peak_build_refs, g.peak_build_refs);
  c->peak_build_bytes = std::max(c->peak_build_bytes, g.peak_build_bytes);
  for (const auto& child : f.children) AddCounters(*child.second, c);
}

}  // namespace

bool Stitch(const Fragment& root, ListTree* out) {
  out->counters = BuildCounters();
  AddCounters(root, &out->counters);
  Sized sized;
  Size(root, &sized);
  HugeBuffer<KdNode>().swap(out->nodes);
  HugeBuffer<uint32_t>().swap(out->refs);
  out->nodes.resize(sized.nodes);  // HugeBuffers: each element is written once
  out->refs.resize(1 + sized.refs);
  out->refs[0] = 0;
  std::atomic<bool> overflow{false};
  Stitcher(out, &overflow).Run(sized, 0, 1);
  return !overflow.load();
}

}  // namespace kdtree
