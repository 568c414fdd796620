// Hub labels for microsecond point-to-point queries (bake --hub-labels), in the manner of
// route planners' separator-based hub labelling, built on the baked graph itself.
//
// The first-layer patches are split in two again and again (a binary tree of patch sets,
// leaves single patches). Every first-layer node (a vertex shared by first-layer patches)
// becomes the "hub" of the tree node where its patches part ways: the hubs of a tree node
// separate its two halves, since an overlay edge never leaves one first-layer patch. A
// shortest path's highest hub therefore lies on the tree path of every node on it, so:
//
//   * label of hub b: its overlay distance to every hub on the tree path from the root to
//     b's own tree node (a tree node's hubs in a chain along its separator, in blocks of
//     16, each block stored as one matrix over the hubs of the node's subtree, so that
//     neighbouring hubs' entries lie together). The entry for hub h of tree node t is
//     the distance over the patches of t's subtree only: a path that leaves the subtree
//     crosses a hub of a tree node above t, which every query reading h reads as well. So
//     the highest hub of a shortest path still gets its exact distances from both ends,
//     and each label run searches a subtree instead of the whole overlay;
//   * inner rows of first-layer patch P: the distance inside P (over its second-layer node
//     graph) from each of P's second-layer nodes to each of P's first-layer nodes.
//
// A query from vertex s in P to t in another patch reads s's patch row to its patch's
// nodes, the inner rows (s's distance to every node of P), the labels of P's nodes
// (s's distance to every hub on P's tree path), and the same backwards from t: a few
// ten thousand additions instead of a graph search. The distances are those of the
// runtime's point-to-point graph (first-layer overlay away from the endpoints, second
// layer inside their first-layer patches), read from the same quantised rows.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vorogeo {

struct HubTreeNode {
    uint32_t parent;     // UINT32_MAX at the root (tree nodes are in preorder: parent first)
    uint32_t hubBegin;   // its hubs [hubBegin, hubBegin + hubCount) in hub order
    uint32_t hubCount;
    uint32_t pathBegin;  // position of its first hub on its tree path (sum over its ancestors)
};

struct HubLabels {
    std::vector<HubTreeNode> tree;
    std::vector<uint32_t> firstLeaf;     // per first-layer patch: its leaf tree node
    std::vector<uint32_t> nodeHub;       // per graph node: hub number, UINT32_MAX if none
    float labelScale = 1.0f;             // distance per step, of labels and inner rows alike
    uint32_t hubCount = 0;
    // The labels by tree node (vorogeo.fbs hub_columns): per block of kHubBlock hubs of tree
    // node t, the steps from every hub of t's subtree to each of the block's hubs (a padded
    // block's missing hubs: kHubUnreachable), kHubBlock entries per subtree hub.
    std::vector<uint64_t> columnBegin;   // tree nodes + 1 offsets into columns
    std::vector<uint16_t> columns;
    std::vector<uint32_t> innerBegin;    // first-layer patches + 1 offsets into innerNode
    std::vector<uint32_t> innerNode;     // per first-layer patch: its active second-layer nodes, sorted
    std::vector<uint64_t> innerMatrixBegin;  // first-layer patches + 1 offsets into inner
    std::vector<uint16_t> inner;         // per first-layer patch: inner node x first-layer slot
    // Per hub its landmark distances in the labels' metric, hub-major, in landmark steps
    // (hub_landmarks.h; vorogeo.fbs hub_landmarks).
    std::vector<uint16_t> landmarks;
    // Per block of kHubBlock consecutive hubs of a tree node (tree order, a node's last block
    // shorter): a bounding sphere (centre x, y, z, radius), then per landmark the smallest and
    // largest of its hubs' `landmarks` (-inf, +inf where one is unreachable). The runtime
    // reads a label only over the blocks that can lie near a shortest path.
    std::vector<float> blockBounds;
    // Per second-layer patch q, the exits a query needs in each block of q's tree path
    // (hub_exit_lists.h): exitPatchBegin (second-layer patches + 1) into exitListBegin,
    // q's lists for its path's blocks from the root down (a tree node's blocks in order),
    // each [exitListBegin[i], exitListBegin[i + 1]) in exitLists: the exits' indices among
    // q's first-layer patch's slots that are hubs, in hub order, increasing. Empty: none.
    std::vector<uint32_t> exitPatchBegin;
    std::vector<uint32_t> exitListBegin;
    std::vector<uint16_t> exitLists;
    double seconds = 0;
};

constexpr uint16_t kHubUnreachable = 65535;
// Hubs per bounded block (HubLabels::blockBounds; vorogeo.fbs hub_block_bounds).
constexpr uint32_t kHubBlock = 16;

using HubProgress = std::function<void(double fraction)>;

// The sizes of the tables computeHubLabels will build (HubLabels::columns, inner and
// innerNode), known from the separator tree before any label is computed.
struct HubLabelSizes {
    uint64_t labelEntries = 0;
    uint64_t innerEntries = 0;
    uint64_t innerNodes = 0;
};
// Called once with the planned sizes; it may throw to refuse them (bake_limits.h).
using HubPlanCheck = std::function<void(const HubLabelSizes&)>;

// How the labels are computed: a search per block of hubs over each subtree (the bake's),
// or, as references for the tests, a Dijkstra per hub over its subtree or over the whole
// overlay (the same answers, slower).
enum class HubLabelRuns { blocks, perHub, perHubWholeOverlay };

// Builds the labels of `flatbuffer` (a verified Graph buffer, distances not coded).
// Deterministic for any number of threads.
HubLabels computeHubLabels(const std::vector<uint8_t>& flatbuffer, const HubProgress& progress = HubProgress(),
                           const HubPlanCheck& checkPlan = HubPlanCheck(), HubLabelRuns runs = HubLabelRuns::blocks);

// For a blob that leaves its inner rows to the readers (bake --inner-rows-at-open,
// schema/vorogeo_inner_rows.h): empty when every first-layer patch of the graph buffer
// (labelled or not yet) keeps within the format's limits for a reader's search, else what
// passes them. `limits` other than the format's are for the tests.
struct InnerRowsAtOpenLimits {
    uint64_t nodes, children, childNodes;
};
std::string innerRowsAtOpenExcess(const std::vector<uint8_t>& flatbuffer,
                                  const InnerRowsAtOpenLimits& limits = InnerRowsAtOpenLimits{
                                      16384, 4096, 65536});

}  // namespace vorogeo
