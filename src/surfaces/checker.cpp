// Checker surface (ID 107): cell size; surface A; surface B. Space is cut into cubes of the
// cell size aligned with the axes, and neighbouring cubes alternate between A and B: the cell
// floor(x/s) + floor(y/s) + floor(z/s) is A when even, B when odd.
#include <cmath>

#include "rt/reader.h"
#include "surfaces/surfaces.h"

namespace rt::checker_surface {

namespace {
struct Checker {
    double cell_size;
    SurfacePtr even;  // A: cells whose index sum is even, such as [0, s)^3
    SurfacePtr odd;   // B: their neighbours
};

// Cell boundaries sit this fraction of a cell below the multiples of the cell size. A surface
// lying exactly on a boundary (the floor y = 0, the commonest case) has hit points rounded to
// either side of it, which would speckle between the two cells; the nudge gives them all the
// cell above. POV-Ray's checker pattern does the same with its small tolerance.
constexpr double kBoundaryNudge = 1e-6;

// The index of the cell a coordinate falls in, along one axis.
double cell_index(double coordinate, double cell_size) {
    return std::floor(coordinate / cell_size + kBoundaryNudge);
}

bool is_odd_cell(double cell_size, const Vec3& point) {
    // The cell indices stay doubles: converting a huge or non-finite coordinate to an integer
    // type would overflow. Their sum is exact below 2^53, far beyond any pattern one can see.
    // fmod keeps the sign, so an odd negative sum gives -1, which is odd too.
    const double cells = cell_index(point.x, cell_size) + cell_index(point.y, cell_size) +
                         cell_index(point.z, cell_size);
    return std::fmod(cells, 2.0) != 0;
}
}  // namespace

SurfaceData read(SceneReader& reader) {
    const double cell_size = reader.positive("checker cell size");
    SurfacePtr even = reader.surface();
    SurfacePtr odd = reader.surface();
    return std::make_shared<const Checker>(Checker{cell_size, std::move(even), std::move(odd)});
}

Material evaluate(const void* surface, const Vec3& point) {
    const auto& c = *static_cast<const Checker*>(surface);
    return (is_odd_cell(c.cell_size, point) ? c.odd : c.even)->at(point);
}

}  // namespace rt::checker_surface
