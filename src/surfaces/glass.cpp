// Glass surface (ID 114): colour; ks; ke; kd; ior; absorption. A dielectric: the tracer
// weighs the reflected and refracted rays by the Fresnel reflectance F and 1 - F, and the light
// that travels inside decays as exp(-absorption * distance). Colour, ks, ke and kd give the
// ambient, diffuse and highlight terms as on the simple surface. It holds a Material as the
// simple surface does, and the table evaluates it with the simple surface's function.
#include "rt/reader.h"
#include "surfaces/surfaces.h"

namespace rt::glass_surface {

SurfaceData read(SceneReader& reader) {
    Material m = read_shading(reader);
    m.ior = reader.positive("glass ior (refractive index)");
    m.absorption = read_non_negative_spectrum(reader, "glass absorption");
    m.fresnel = true;
    reader.note_splitting_surface();  // F and 1 - F: both rays, short of total reflection
    return reader.shape_data(m);      // in the reader's arena, as a shape's parameters
}

}  // namespace rt::glass_surface
