// Simple surface (ID 100): colour; ks; ke; kd; kt; ior. The same parameters everywhere.
#include <string>

#include "rt/reader.h"
#include "surfaces/surfaces.h"

namespace rt {

Spectrum read_non_negative_spectrum(SceneReader& reader, std::string_view what) {
    const Location where = reader.next_location();
    const Vec3 v = reader.vec3(what);
    if (v.x < 0 || v.y < 0 || v.z < 0)
        reader.fail(where, std::string(what) + " components must be >= 0");
    return {v.x, v.y, v.z};
}

Material read_shading(SceneReader& reader) {
    Material m;
    m.colour = read_non_negative_spectrum(reader, "surface colour");
    m.ks = reader.non_negative("surface ks (specular coefficient)");
    m.ke = reader.non_negative("surface ke (specular exponent)");
    m.kd = reader.non_negative("surface kd (diffuse coefficient)");
    return m;
}

Material read_material(SceneReader& reader) {
    Material m = read_shading(reader);
    m.kt = reader.non_negative("surface kt (transmission coefficient)");
    // The original's own example gives ior 0 on an opaque surface, so the index is only
    // checked where light passes through.
    const Location ior_at = reader.next_location();
    m.ior = reader.number("surface ior (refractive index)");
    if (m.kt > 0 && !(m.ior > 0))
        reader.fail(ior_at,
                    "surface ior must be > 0 when kt > 0, got " + reader.last_number_text());
    if (m.ks > 0 && m.kt > 0) reader.note_splitting_surface();
    return m;
}

}  // namespace rt

namespace rt::simple_surface {

SurfaceData read(SceneReader& reader) {
    return reader.shape_data(read_material(reader));  // in the reader's arena
}

Material evaluate(const void* surface, const Vec3&) {
    return *static_cast<const Material*>(surface);
}

}  // namespace rt::simple_surface
