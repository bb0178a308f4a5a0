// SPDX-License-Identifier: MIT
// Ordering a mesh's edges or faces by their first vertex: a counting sort by the vertex, then each
// vertex's few items by insertion. The order of a stable sort by (vertex, key), several times
// faster on a mesh (a vertex has about six edges), which validate() and every edge list make at
// each call.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace genflow::detail {

/// The items `for_each_item(visit)` visits, in the order (vertex(item), key(item), visiting
/// order). `for_each_item` is called twice, to count and to place, and visits the same items both
/// times; every vertex(item) is below `vertices`. No list of the items is made before the result.
template <class Item, class ForEachItem, class Vertex, class Key>
std::vector<Item> items_by_vertex(std::size_t vertices, ForEachItem&& for_each_item, Vertex vertex,
                                  Key key) {
    std::vector<std::size_t> start(vertices + 1, 0);
    for_each_item([&](const Item& item) { ++start[static_cast<std::size_t>(vertex(item)) + 1]; });
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<Item> sorted(start.back());
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for_each_item(
        [&](const Item& item) { sorted[next[static_cast<std::size_t>(vertex(item))]++] = item; });
    // A bucket holds a vertex's few items: insertion is the fastest stable sort of so few.
    for (std::size_t v = 0; v < vertices; ++v) {
        for (std::size_t i = start[v] + 1; i < start[v + 1]; ++i) {
            const Item item = sorted[i];
            std::size_t j = i;
            for (; j > start[v] && key(item) < key(sorted[j - 1]); --j) {
                sorted[j] = sorted[j - 1];
            }
            sorted[j] = item;
        }
    }
    return sorted;
}

/// `items` in the order (vertex(item), key(item), former order). A vertex at or above `vertices`
/// or below zero, as in a mesh with bad indices, is ordered too, by a plain stable sort.
template <class Item, class Vertex, class Key>
void sort_by_vertex(std::vector<Item>& items, std::size_t vertices, Vertex vertex, Key key) {
    const bool all_below = std::all_of(items.begin(), items.end(), [&](const Item& item) {
        const auto v = vertex(item);
        return v >= 0 && static_cast<std::size_t>(v) < vertices;
    });
    if (!all_below) {
        std::stable_sort(items.begin(), items.end(), [&](const Item& x, const Item& y) {
            return vertex(x) != vertex(y) ? vertex(x) < vertex(y) : key(x) < key(y);
        });
        return;
    }
    items = items_by_vertex<Item>(
        vertices,
        [&](auto&& visit) {
            for (const Item& item : items) {
                visit(item);
            }
        },
        vertex, key);
}

}  // namespace genflow::detail
