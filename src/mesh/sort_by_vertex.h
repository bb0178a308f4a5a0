// SPDX-License-Identifier: MIT
// Sorting a mesh's edges or faces by their first vertex: a counting sort by the vertex, then each
// vertex's few items by the full order. The same order as std::sort, several times faster on a
// mesh (a vertex has about six edges), which validate(), mean_edge_length() and every edge list
// sort at each call.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace genflow::detail {

/// `items` in the order of `less`, whose first criterion is `vertex(item)`: an index below
/// `vertices` (any other, as in a mesh with bad indices, and std::sort orders them all).
template <class Item, class Vertex, class Less>
void sort_by_vertex(std::vector<Item>& items, std::size_t vertices, Vertex vertex, Less less) {
    std::vector<std::size_t> start(vertices + 1, 0);
    for (const Item& item : items) {
        const auto v = vertex(item);
        if (v < 0 || static_cast<std::size_t>(v) >= vertices) {
            std::sort(items.begin(), items.end(), less);
            return;
        }
        ++start[static_cast<std::size_t>(v) + 1];
    }
    for (std::size_t v = 0; v < vertices; ++v) {
        start[v + 1] += start[v];
    }
    std::vector<Item> sorted(items.size());
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (const Item& item : items) {
        sorted[next[static_cast<std::size_t>(vertex(item))]++] = item;
    }
    for (std::size_t v = 0; v < vertices; ++v) {
        std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(start[v]),
                  sorted.begin() + static_cast<std::ptrdiff_t>(start[v + 1]), less);
    }
    items = std::move(sorted);
}

}  // namespace genflow::detail
