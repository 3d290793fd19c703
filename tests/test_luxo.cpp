// The Luxo lamp (scenes/luxo.in): its light sits exactly at the focus of the paraboloid shade,
// so every ray from the light that meets the shade's mirror inside leaves parallel to the
// paraboloid's axis, which the test works out from the shade's coefficients in the file.
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "rt/optics.h"
#include "rt/reader.h"
#include "rt/trace.h"
#include "scene_util.h"

using namespace rt;
using namespace rt_test;

namespace {

const std::string kScene = std::string(RT_SOURCE_DIR) + "/scenes/luxo.in";

// The scene's tokens, comments dropped.
std::vector<std::string> tokens(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::string> result;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line.substr(0, line.find('#')));
        for (std::string word; words >> word;) result.push_back(word);
    }
    return result;
}

// The sixteen numbers of each quadric object in the file: an ID 13 whose numbers are followed
// by the surface ID 100 (the scene gives every object a simple surface).
std::vector<std::vector<double>> quadric_numbers(const std::vector<std::string>& t) {
    std::vector<std::vector<double>> found;
    for (std::size_t i = 0; i + 17 < t.size(); ++i) {
        if (t[i] != "13" || t[i + 17] != "100") continue;
        std::vector<double> numbers;
        for (std::size_t k = 1; k <= 16; ++k) numbers.push_back(std::stod(t[i + k]));
        found.push_back(numbers);
    }
    return found;
}

// A paraboloid's axis from its coefficients: Q (the second-order part) is singular along
// it, so it is the cross product of two rows of Q; it points where the paraboloid opens,
// where f falls (g·axis < 0).
std::optional<Vec3> paraboloid_axis(const std::vector<double>& k) {
    const Vec3 rows[3] = {{k[0], k[3], k[4]}, {k[3], k[1], k[5]}, {k[4], k[5], k[2]}};
    Vec3 best;
    for (int i = 0; i < 3; ++i) {
        const Vec3 c = cross(rows[i], rows[(i + 1) % 3]);
        if (length(c) > length(best)) best = c;
    }
    if (length(best) == 0) return std::nullopt;
    Vec3 axis = normalized(best);
    for (const Vec3& row : rows)
        if (std::fabs(dot(row, axis)) > 1e-12 * length(row))
            return std::nullopt;  // not singular: not a paraboloid
    const Vec3 g{k[6], k[7], k[8]};
    if (dot(g, axis) > 0) axis = -axis;
    return axis;
}

}  // namespace

TEST(light_from_the_focus_leaves_the_shade_along_its_axis) {
    const Scene scene = read_scene_file(kScene);
    // The point light (101).
    std::optional<Vec3> light;
    for (const Light& l : scene.lights)
        if (l.type->id == 101) {
            const LightSample s = l.sample({}, 0);
            light = s.direction * s.distance;
        }
    CHECK(light.has_value());
    if (!light) return;
    // The shade: the paraboloid whose box holds the light, the first in the file (its inside).
    const Object* shade = nullptr;
    for (const Object& o : scene.objects)
        if (o.shape.type->id == 13 && o.shape.bounds().contains(*light)) {
            shade = &o;
            break;
        }
    CHECK(shade != nullptr);
    std::optional<Vec3> axis;
    for (const auto& k : quadric_numbers(tokens(kScene)))
        if (Bounds{{k[10], k[11], k[12]}, {k[13], k[14], k[15]}}.contains(*light)) {
            axis = paraboloid_axis(k);
            break;
        }
    CHECK(axis.has_value());
    if (!shade || !axis) return;
    // The scene says the axis is (3, -12, 4) / 13.
    CHECK_NEAR(*axis, Vec3(3, -12, 4) / 13, 1e-15);

    Random random(7);
    int reflected = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        const Ray ray{*light, random.unit_vector()};
        Hit hit;
        if (!shade->shape.intersect(ray, {hit_tolerance(*light), kInfinity}, hit)) continue;
        const Vec3 point = ray.at(hit.t);
        const Vec3 normal = shade->shape.normal(point, hit);
        CHECK(dot(normal, ray.direction) > 0);  // the inside: the outward normal faces away
        const Vec3 out = reflect(ray.direction, normal);
        worst = std::fmax(worst, length(out - *axis));
        ++reflected;
    }
    CHECK(reflected > 5000);
    if (!(worst <= 1e-9))
        record_failure(__FILE__, __LINE__,
                       join("reflected directions differ from the axis by ", worst));
}

TEST(the_light_is_at_the_focus) {
    // The focus of |x - V|^2 - (a.(x - V))^2 - 4p a.(x - V) = 0 is V + p a. Along the axis
    // through the light, f is linear (-4p s, scaled), zero at the vertex p behind the light.
    const Scene scene = read_scene_file(kScene);
    const auto quadrics = quadric_numbers(tokens(kScene));
    CHECK(!quadrics.empty());
    if (quadrics.empty()) return;
    const auto& k = quadrics.front();
    const Vec3 axis = *paraboloid_axis(k);
    const Vec3 light{-0.885, 2.64, -1.08};
    const double scale = (k[0] + k[1] + k[2]) / 2;  // Q = scale (I - a aᵀ)
    const Vec3 g{k[6], k[7], k[8]};
    const double p = -dot(g, axis) / (2 * scale);
    const Vec3 vertex = light - p * axis;
    {
        // f at the vertex is zero, and the gradient there points back along the axis.
        const double x = vertex.x, y = vertex.y, z = vertex.z;
        const double f = k[0] * x * x + k[1] * y * y + k[2] * z * z +
                         2 * (k[3] * x * y + k[4] * x * z + k[5] * y * z) +
                         2 * (k[6] * x + k[7] * y + k[8] * z) + k[9];
        CHECK_NEAR(f, 0, 1e-12 * scale);
    }
    CHECK_NEAR(p, 0.065, 1e-15);
    bool light_found = false;
    for (const Light& l : scene.lights)
        if (l.type->id == 101) {
            const LightSample s = l.sample({}, 0);
            CHECK_NEAR(s.direction * s.distance, light, 1e-15);
            light_found = true;
        }
    CHECK(light_found);
}
