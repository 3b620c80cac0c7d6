// box_tree.cpp: SweepSAH recursion (see box_tree.hpp). Boxes are held as two SSE registers so growing is one
// minps + maxps and the half area one multiply with a lane rotation.
#include "bvh/box_tree.hpp"

#include "bvh/radix_sort.hpp"

#include <immintrin.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace idk::bvh {
namespace {

struct SweepBox {
    __m128 min;
    __m128 max;

    static SweepBox empty() {
        return {_mm_setr_ps(kInfinity, kInfinity, kInfinity, 0.0f), _mm_setr_ps(-kInfinity, -kInfinity, -kInfinity, 0.0f)};
    }
    static SweepBox from(const Box& b) {
        return {_mm_setr_ps(b.min.x, b.min.y, b.min.z, 0.0f), _mm_setr_ps(b.max.x, b.max.y, b.max.z, 0.0f)};
    }
    void grow(const SweepBox& b) {
        min = _mm_min_ps(min, b.min);
        max = _mm_max_ps(max, b.max);
    }
    // dx*dy + dy*dz + dz*dx (lane 3 is 0 in every box). Only called on grown, hence non-empty, boxes.
    float halfArea() const {
        const __m128 d = _mm_sub_ps(max, min);
        const __m128 rotated = _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1));  // (dy, dz, dx, 0)
        const __m128 p = _mm_mul_ps(d, rotated);
        const __m128 s = _mm_add_ps(p, _mm_movehl_ps(p, p));                    // (p0 + p2, p1 + p3, ...)
        return _mm_cvtss_f32(_mm_add_ss(s, _mm_shuffle_ps(s, s, 1)));
    }
    Box toBox() const {
        alignas(16) float lo[4];
        alignas(16) float hi[4];
        _mm_store_ps(lo, min);
        _mm_store_ps(hi, max);
        return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
    }
};

// The cost buffer of the sweeps doubles as the scratch array of the stable partition (readme: "Alloc free stable
// partition"); a union makes the reuse explicit.
union CostOrIndex {
    float cost;
    uint32_t index;
};

struct Task {
    uint32_t slot;      // node index in the uncompacted array (its box is already written by the parent)
    uint32_t start;     // primitive range [start, end) in the sorted arrays
    uint32_t end;
    uint32_t freeBase;  // first slot reserved for this node's descendants (2 * count - 2 of them)
};

struct Context {
    const BoxTreeOptions* options = nullptr;
    std::vector<SweepBox> boxes;
    std::vector<uint32_t> sorted[3];
    std::vector<CostOrIndex> scratch;
    std::vector<uint8_t> isLeft;  // indexed by primitive id; each id belongs to exactly one task's range
    std::vector<Node> work;       // 2N - 1 slots, compacted at the end
};

struct Split {
    float cost;
    int axis = -1;
    uint32_t index = 0;          // first primitive of the right child
    uint32_t imbalance = 0;      // |left - right|: among equal costs the more balanced split wins (0 at first, so
                                 // a split that only ties the leaf cost bound is never taken)
};

void sweepAxis(Context& ctx, int axis, uint32_t start, uint32_t end, Split& best) {
    const uint32_t* idx = ctx.sorted[axis].data();
    const SweepBox* boxes = ctx.boxes.data();
    CostOrIndex* cost = ctx.scratch.data();

    // Right-to-left: rightCost[i] = area(box of [i, end)) * (end - i). It grows as i decreases, so once it exceeds
    // the best cost no split with a first right primitive <= i can win (first early-out).
    // Counts are converted from the index (off the loop-carried chain, unlike a float counter's 4-cycle add).
    SweepBox acc = SweepBox::empty();
    uint32_t firstSplit = start + 1;
    for (uint32_t i = end - 1; i > start; --i) {
        acc.grow(boxes[idx[i]]);
        const float rightCost = acc.halfArea() * float(end - i);
        if (rightCost > best.cost) {
            firstSplit = i + 1;
            break;
        }
        cost[i].cost = rightCost;
    }
    if (firstSplit >= end) return;

    // Left-to-right: the left side must still accumulate from `start`, but costs are only evaluated from
    // firstSplit, and the sweep stops once the left cost alone exceeds the best (second early-out).
    acc = SweepBox::empty();
    const uint32_t mid2 = start + end;
    for (uint32_t i = start; i + 1 < firstSplit; ++i) acc.grow(boxes[idx[i]]);
    for (uint32_t i = firstSplit - 1; i + 1 < end; ++i) {
        acc.grow(boxes[idx[i]]);
        const uint32_t split = i + 1;
        const float leftCost = acc.halfArea() * float(split - start);
        if (leftCost > best.cost) break;
        const float c = leftCost + cost[split].cost;
        const uint32_t imbalance = 2 * split > mid2 ? 2 * split - mid2 : mid2 - 2 * split;
        if (c < best.cost || (c == best.cost && imbalance < best.imbalance)) {
            best.cost = c;
            best.axis = axis;
            best.index = split;
            best.imbalance = imbalance;
        }
    }
}

// Moves the entries flagged left before the others, keeping the relative order on both sides.
void stablePartition(Context& ctx, int axis, uint32_t start, uint32_t end) {
    uint32_t* arr = ctx.sorted[axis].data();
    CostOrIndex* scratch = ctx.scratch.data() + start;
    uint32_t write = start;
    uint32_t right = 0;
    for (uint32_t i = start; i < end; ++i) {
        const uint32_t id = arr[i];
        if (ctx.isLeft[id] != 0) {
            arr[write++] = id;
        } else {
            scratch[right++].index = id;
        }
    }
    for (uint32_t j = 0; j < right; ++j) arr[write + j] = scratch[j].index;
}

// Processes one node: either makes it a leaf or splits it and returns the two child tasks.
bool processNode(Context& ctx, const Task& task, Task& leftTask, Task& rightTask) {
    const BoxTreeOptions& opt = *ctx.options;
    Node& node = ctx.work[task.slot];
    const uint32_t n = task.end - task.start;
    auto makeLeaf = [&] {
        node.first = task.start;
        node.count = n;
        return false;
    };
    if (n <= 1) return makeLeaf();

    // Split SAH = Ct + Ci * sweepCost / parentArea beats the leaf cost Ci * n exactly when
    // sweepCost < (Ci * n - Ct) * parentArea / Ci; above the maximum leaf size any split is taken.
    Split best;
    const float parentArea = node.box().halfArea();
    const float ci = opt.primitiveCost;
    best.cost = n > opt.maxLeafSize ? kInfinity : (ci * float(n) - kTraversalCost) * parentArea / ci;
    // The largest axis first: it usually holds the best split, so the early-outs of the other two start sooner.
    const int first = node.box().largestAxis();
    for (int k = 0; k < 3; ++k) sweepAxis(ctx, (first + k) % 3, task.start, task.end, best);
    if (best.axis < 0) {
        if (n <= opt.maxLeafSize) return makeLeaf();
        best.axis = 0;  // only reachable when every cost is infinite (coordinates near FLT_MAX): median split
        best.index = task.start + n / 2;
    }

    const uint32_t* bestIdx = ctx.sorted[best.axis].data();
    SweepBox leftBox = SweepBox::empty();
    SweepBox rightBox = SweepBox::empty();
    for (uint32_t i = task.start; i < best.index; ++i) {
        ctx.isLeft[bestIdx[i]] = 1;
        leftBox.grow(ctx.boxes[bestIdx[i]]);
    }
    for (uint32_t i = best.index; i < task.end; ++i) {
        ctx.isLeft[bestIdx[i]] = 0;
        rightBox.grow(ctx.boxes[bestIdx[i]]);
    }
    stablePartition(ctx, (best.axis + 1) % 3, task.start, task.end);
    stablePartition(ctx, (best.axis + 2) % 3, task.start, task.end);

    const uint32_t leftCount = best.index - task.start;
    node.first = task.freeBase;
    node.count = 0;
    ctx.work[task.freeBase].setBox(leftBox.toBox());
    ctx.work[task.freeBase + 1].setBox(rightBox.toBox());
    leftTask = {task.freeBase, task.start, best.index, task.freeBase + 2};
    rightTask = {task.freeBase + 1, best.index, task.end, task.freeBase + 2 + 2 * (leftCount - 1)};
    return true;
}

// A minimal pool: subtrees big enough go to a shared queue, everything else stays on the worker's own stack.
struct TaskQueue {
    std::mutex mutex;
    std::condition_variable wake;
    std::vector<Task> tasks;
    uint32_t outstanding = 0;  // queued tasks plus tasks whose subtree a worker is still building
};

void runWorker(Context& ctx, TaskQueue& queue, bool parallel) {
    std::vector<Task> local;
    for (;;) {
        {
            std::unique_lock lock(queue.mutex);
            queue.wake.wait(lock, [&] { return !queue.tasks.empty() || queue.outstanding == 0; });
            if (queue.tasks.empty()) return;
            local.push_back(queue.tasks.back());
            queue.tasks.pop_back();
        }
        while (!local.empty()) {
            const Task task = local.back();
            local.pop_back();
            Task left{}, right{};
            if (!processNode(ctx, task, left, right)) continue;
            const uint32_t threshold = ctx.options->parallelThreshold;
            if (parallel && left.end - left.start >= threshold && right.end - right.start >= threshold) {
                {
                    std::lock_guard lock(queue.mutex);
                    queue.tasks.push_back(left);
                    ++queue.outstanding;
                }
                queue.wake.notify_one();
            } else {
                local.push_back(left);
            }
            local.push_back(right);
        }
        std::lock_guard lock(queue.mutex);
        if (--queue.outstanding == 0) queue.wake.notify_all();
    }
}

uint32_t resolveThreadCount(uint32_t requested) {
    if (requested != 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace

std::vector<Node> compactDepthFirst(std::span<const Node> nodes) {
    std::vector<Node> out;
    if (nodes.empty()) return out;
    out.push_back(nodes[0]);
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        const uint32_t ni = stack.back();
        stack.pop_back();
        if (out[ni].isLeaf()) continue;
        const uint32_t old = out[ni].first;
        const uint32_t child = uint32_t(out.size());
        out.push_back(nodes[old]);
        out.push_back(nodes[old + 1]);
        out[ni].first = child;
        stack.push_back(child + 1);
        stack.push_back(child);
    }
    return out;
}

BoxTree buildBoxTree(std::span<const Box> boxes, const BoxTreeOptions& options) {
    BoxTree tree;
    const uint32_t n = uint32_t(boxes.size());
    if (n == 0) return tree;
    const uint32_t threads = resolveThreadCount(options.threadCount);
    const BoxTreeOptions opt = [&] {
        BoxTreeOptions o = options;
        o.maxLeafSize = std::max(1u, o.maxLeafSize);
        o.parallelThreshold = std::max(2u, o.parallelThreshold);
        return o;
    }();

    Context ctx;
    ctx.options = &opt;
    ctx.boxes.resize(n);
    Box root;
    for (uint32_t i = 0; i < n; ++i) {
        ctx.boxes[i] = SweepBox::from(boxes[i]);
        root.grow(boxes[i]);
    }
    // One sort per axis by box centre (min + max: the factor 0.5 is elided), the three axes in parallel.
    auto sortAxis = [&](int axis) {
        std::vector<uint32_t> keys(n);
        for (uint32_t i = 0; i < n; ++i) keys[i] = sortableFloatKey(boxes[i].min[axis] + boxes[i].max[axis]);
        ctx.sorted[axis].resize(n);
        radixSortIndices(keys, ctx.sorted[axis]);
    };
    if (threads > 1 && n >= 65536) {
        std::thread t1(sortAxis, 1);
        std::thread t2(sortAxis, 2);
        sortAxis(0);
        t1.join();
        t2.join();
    } else {
        for (int axis = 0; axis < 3; ++axis) sortAxis(axis);
    }
    ctx.scratch.resize(n);
    ctx.isLeft.resize(n);
    ctx.work.resize(2 * size_t(n) - 1);
    ctx.work[0].setBox(root);

    TaskQueue queue;
    queue.tasks.push_back({0, 0, n, 1});
    queue.outstanding = 1;
    const bool parallel = threads > 1 && n >= 2 * opt.parallelThreshold;
    std::vector<std::thread> workers;
    if (parallel) {
        for (uint32_t i = 1; i < threads; ++i) workers.emplace_back(runWorker, std::ref(ctx), std::ref(queue), true);
    }
    runWorker(ctx, queue, parallel);
    for (std::thread& w : workers) w.join();

    tree.nodes = compactDepthFirst(ctx.work);
    tree.primOrder = std::move(ctx.sorted[0]);
    return tree;
}

}  // namespace idk::bvh
