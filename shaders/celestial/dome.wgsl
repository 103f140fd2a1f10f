// celestial::dome — SimGear's SGSky dome (a centre fan and inner, middle, outer and
// skirt rings of 12 vertices, SimGear's 2002 dome.cxx geometry) drawn along a view ray:
// the barycentric blend of the vertex colours over the triangle the ray meets.
// Twin: crates/celestial/src/dome.rs (`sky_dome_radiance`, generic over the float type;
// this file mirrors its f32 instance operation for operation): same names, argument
// order and units. Directions are unit east/north/up vectors from the dome's centre;
// `spin` is vertex 0's azimuth from south toward east (radians); positions in km.

const DOME_SIDES: u32 = 12u;
const DOME_VERTICES: u32 = 49u;
const DOME_TAU: f32 = 6.283185307179586;

// (horizontal distance, height) of the centre, inner, middle, outer and skirt rings (km).
const DOME_RINGS_KM: array<vec2<f32>, 5> = array<vec2<f32>, 5>(
    vec2<f32>(0.0, 25.0),
    vec2<f32>(50.0, 20.0),
    vec2<f32>(70.0, 8.0),
    vec2<f32>(80.0, 0.0),
    vec2<f32>(50.0, -2.0),
);

fn sky_dome_slot(ring: u32, index: u32) -> u32 {
    if ring == 0u {
        return 0u;
    }
    return 1u + (ring - 1u) * DOME_SIDES + index % DOME_SIDES;
}

fn sky_dome_vertex(ring: u32, index: u32, spin: f32) -> vec3<f32> {
    var rings = DOME_RINGS_KM;
    let size = rings[ring];
    let phi = spin + f32(index % DOME_SIDES) * (DOME_TAU / f32(DOME_SIDES));
    return vec3<f32>(size.x * sin(phi), -size.x * cos(phi), size.y);
}

// Möller–Trumbore: (barycentric weights, 1) of the point where the ray from the origin
// along `d` meets the triangle's plane (negative weights outside the triangle),
// (0, 0, 0, 0) where the ray is parallel to the plane or the point behind the origin.
fn sky_dome_ray_triangle(d: vec3<f32>, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>) -> vec4<f32> {
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let h = cross(d, e2);
    let det = dot(e1, h);
    if det == 0.0 {
        return vec4<f32>(0.0);
    }
    let s = -p0;
    let a = dot(s, h) / det;
    let q = cross(s, e1);
    let b = dot(d, q) / det;
    let t = dot(e2, q) / det;
    if t <= 0.0 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(1.0 - a - b, a, b, 1.0);
}

// Triangle `k` (0–6) of sector `sector` as (ring, index) pairs, in the twin's order:
// the centre fan, then two triangles per strip between consecutive rings.
fn sky_dome_triangle(sector: u32, k: u32) -> array<vec2<u32>, 3> {
    let i = sector;
    let j = (sector + 1u) % DOME_SIDES;
    if k == 0u {
        return array<vec2<u32>, 3>(vec2<u32>(0u, 0u), vec2<u32>(1u, i), vec2<u32>(1u, j));
    }
    let upper = (k + 1u) / 2u;
    let lower = upper + 1u;
    if k % 2u == 1u {
        return array<vec2<u32>, 3>(vec2<u32>(lower, i), vec2<u32>(upper, i), vec2<u32>(lower, j));
    }
    return array<vec2<u32>, 3>(vec2<u32>(upper, i), vec2<u32>(lower, j), vec2<u32>(upper, j));
}

fn sky_dome_radiance(view: vec3<f32>, spin: f32, colours: array<vec4<f32>, 49>) -> vec3<f32> {
    var c = colours;
    let step = DOME_TAU / f32(DOME_SIDES);
    var phi = (atan2(view.x, -view.y) - spin) % DOME_TAU;
    if phi < 0.0 {
        phi = phi + DOME_TAU;
    }
    let sector = u32(max(floor(phi / step), 0.0)) % DOME_SIDES;
    let sectors = array<u32, 3>(sector, (sector + 1u) % DOME_SIDES, (sector + DOME_SIDES - 1u) % DOME_SIDES);
    // The first triangle that holds the ray; where rounding leaves a ray on a shared
    // edge outside both, the one it is least outside of (within 1024 ε).
    var found = false;
    var best_inside = 0.0;
    var best_weights = vec3<f32>(0.0);
    var best_triangle = array<vec2<u32>, 3>(vec2<u32>(0u), vec2<u32>(0u), vec2<u32>(0u));
    for (var n = 0u; n < 3u; n++) {
        for (var k = 0u; k < 7u; k++) {
            let t = sky_dome_triangle(sectors[n], k);
            let p0 = sky_dome_vertex(t[0].x, t[0].y, spin);
            let p1 = sky_dome_vertex(t[1].x, t[1].y, spin);
            let p2 = sky_dome_vertex(t[2].x, t[2].y, spin);
            let w = sky_dome_ray_triangle(view, p0, p1, p2);
            if w.w > 0.0 {
                let inside = min(min(w.x, w.y), w.z);
                if inside >= 0.0 {
                    return w.x * c[sky_dome_slot(t[0].x, t[0].y)].xyz
                        + w.y * c[sky_dome_slot(t[1].x, t[1].y)].xyz
                        + w.z * c[sky_dome_slot(t[2].x, t[2].y)].xyz;
                }
                if !found || inside > best_inside {
                    found = true;
                    best_inside = inside;
                    best_weights = w.xyz;
                    best_triangle = t;
                }
            }
        }
    }
    if found && best_inside >= -1.1920929e-7 * 1024.0 {
        let t = best_triangle;
        return best_weights.x * c[sky_dome_slot(t[0].x, t[0].y)].xyz
            + best_weights.y * c[sky_dome_slot(t[1].x, t[1].y)].xyz
            + best_weights.z * c[sky_dome_slot(t[2].x, t[2].y)].xyz;
    }
    // Below the skirt: along the sector's skirt chord where the ray's vertical plane
    // meets it; the skirt's mean straight down.
    let horizontal = view.xy;
    if horizontal.x == 0.0 && horizontal.y == 0.0 {
        var mean = vec3<f32>(0.0);
        for (var i = 0u; i < DOME_SIDES; i++) {
            mean = mean + c[sky_dome_slot(4u, i)].xyz;
        }
        return mean / f32(DOME_SIDES);
    }
    let start = sky_dome_vertex(4u, sector, spin);
    let end = sky_dome_vertex(4u, sector + 1u, spin);
    let edge = end.xy - start.xy;
    let along = clamp((start.x * horizontal.y - start.y * horizontal.x) / (horizontal.x * edge.y - horizontal.y * edge.x), 0.0, 1.0);
    return (1.0 - along) * c[sky_dome_slot(4u, sector)].xyz + along * c[sky_dome_slot(4u, sector + 1u)].xyz;
}
