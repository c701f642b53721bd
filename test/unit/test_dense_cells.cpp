// The counting sort behind both grids against a direct build: every item under every cell it
// names, in item order within a cell, with empty cells anywhere, items without cells, no items and
// no cells; and buffers reused from a larger sort.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "stocs/geometry/dense_cells.h"

namespace stocs {
namespace {

using CellLists = std::vector<std::vector<size_t>>;

/// Runs sortIntoCells into `start` and `list` (which may hold an earlier sort) and returns its
/// lists per cell.
CellLists sorted(size_t cells, const CellLists& cells_of_item, std::vector<uint32_t>& start,
                 std::vector<uint32_t>& list) {
  sortIntoCells(
      cells, static_cast<uint32_t>(cells_of_item.size()),
      [&](uint32_t i, auto&& emit) {
        for (size_t c : cells_of_item[i]) emit(c);
      },
      start, list);
  EXPECT_EQ(start.size(), cells + 1);
  EXPECT_EQ(start.front(), 0u);
  EXPECT_EQ(start.back(), list.size());
  CellLists out(cells);
  for (size_t c = 0; c < cells; ++c) {
    EXPECT_LE(start[c], start[c + 1]) << "cell " << c;
    for (uint32_t k = start[c]; k < start[c + 1]; ++k) out[c].push_back(list[k]);
  }
  return out;
}

CellLists direct(size_t cells, const CellLists& cells_of_item) {
  CellLists out(cells);
  for (size_t i = 0; i < cells_of_item.size(); ++i) {
    for (size_t c : cells_of_item[i]) out[c].push_back(i);
  }
  return out;
}

TEST(SortIntoCells, ListsEveryItemUnderItsCellsInItemOrder) {
  // Cells 0 and 5 empty (first and last), item 2 in no cell, item 3 in three cells.
  const CellLists cells_of_item = {{1}, {3, 1}, {}, {2, 4, 1}, {4}};
  std::vector<uint32_t> start, list;
  const CellLists got = sorted(6, cells_of_item, start, list);
  EXPECT_EQ(got, direct(6, cells_of_item));
  EXPECT_EQ(got[1], (std::vector<size_t>{0, 1, 3}));
}

TEST(SortIntoCells, RandomSortsReusingTheBuffersMatchTheDirectBuild) {
  std::mt19937 rng(7);
  std::vector<uint32_t> start, list;
  // Sizes shrink and grow, so stale entries of an earlier sort would show.
  for (const size_t cells : {300u, 20u, 1u, 500u, 37u}) {
    std::uniform_int_distribution<size_t> cell(0, cells - 1), count(0, 4);
    CellLists cells_of_item(cells * 2);
    for (std::vector<size_t>& item : cells_of_item) {
      for (size_t k = count(rng); k > 0; --k) item.push_back(cell(rng));
    }
    EXPECT_EQ(sorted(cells, cells_of_item, start, list), direct(cells, cells_of_item))
        << cells << " cells";
  }
}

TEST(SortIntoCells, NoItemsOrNoCells) {
  std::vector<uint32_t> start = {9, 9, 9}, list = {9};
  EXPECT_EQ(sorted(4, {}, start, list), CellLists(4));
  EXPECT_TRUE(list.empty());
  EXPECT_EQ(sorted(0, {{}, {}}, start, list), CellLists());
  EXPECT_EQ(start, std::vector<uint32_t>{0});
}

}  // namespace
}  // namespace stocs
