// A fill-reducing elimination order for a mesh's node graph from the node coordinates: nested dissection by cuts
// across a coordinate axis, several times faster than METIS_NodeND on small 2D meshes (docs/performance.md).
#pragma once

#include <cstdint>
#include <vector>

namespace signorini {

/// Nested dissection of the graph with n = x.size() / dim nodes (compressed adjacency xadj, adjncy; symmetric, no
/// self loops) whose node v sits at x[v * dim + i]. Each subgraph is cut across the coordinate axis and at the
/// position (between 30 % and 70 % of its nodes along that axis) that minimise |S| / (f (1 - f)), S the nodes of
/// the smaller side with a neighbour on the other side, f the fraction on one side; S is eliminated after both sides,
/// which are ordered the same way down to 8 nodes. Returns the order: position k holds the node eliminated k-th.
/// Any permutation is a valid order; a straight cut through a graded mesh is longer than METIS's separators (about
/// 30 % more elimination flops on the 2D Hertz meshes).
std::vector<int64_t> CoordinateNestedDissection(const std::vector<int64_t> &xadj, const std::vector<int64_t> &adjncy,
                                                const std::vector<double> &x, int dim);

} // namespace signorini
