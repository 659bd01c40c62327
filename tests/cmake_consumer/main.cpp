// Uses an installed igaparam through its C++17 wrapper: one Q4 cell, relocated. Returns 0 on
// success.
#include <cstdio>
#include <vector>

#include "igaparam.hpp"

int main() {
  try {
    igaparam::Mesh mesh(IGAPARAM_CELL_QUAD4, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 3});
    const igaparam_relocate_report report = mesh.relocate();
    std::printf("igaparam %s (C++): %zu cell, %zu invalid\n", igaparam::version().c_str(), report.cells,
                report.invalid_after);
    return report.cells == 1 && report.invalid_after == 0 ? 0 : 1;
  } catch (const igaparam::Error& e) {
    std::fprintf(stderr, "consumer_cpp: %s (status %d)\n", e.what(), static_cast<int>(e.status()));
    return 1;
  }
}
