// Simple surface (ID 100): colour; ks; ke; kd; kt; ior. The same parameters everywhere.
#include "rt/reader.h"
#include "surfaces/surfaces.h"

namespace rt {

Material read_material(SceneReader& reader) {
    Material m;
    const Location colour_at = reader.next_location();
    const Vec3 colour = reader.vec3("surface colour");
    if (colour.x < 0 || colour.y < 0 || colour.z < 0)
        reader.fail(colour_at, "surface colour components must be >= 0");
    m.colour = Spectrum(colour.x, colour.y, colour.z);
    m.ks = reader.non_negative("surface ks (specular coefficient)");
    m.ke = reader.non_negative("surface ke (specular exponent)");
    m.kd = reader.non_negative("surface kd (diffuse coefficient)");
    m.kt = reader.non_negative("surface kt (transmission coefficient)");
    // The original's own example gives ior 0 on an opaque surface, so the index is only
    // checked where light passes through.
    const Location ior_at = reader.next_location();
    m.ior = reader.number("surface ior (refractive index)");
    if (m.kt > 0 && !(m.ior > 0))
        reader.fail(ior_at, "surface ior must be > 0 when kt > 0, got " + format_number(m.ior));
    return m;
}

}  // namespace rt

namespace rt::simple_surface {

SurfaceData read(SceneReader& reader) {
    return std::make_shared<const Material>(read_material(reader));
}

Material evaluate(const void* surface, const Vec3&) {
    return *static_cast<const Material*>(surface);
}

}  // namespace rt::simple_surface
