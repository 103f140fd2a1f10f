// celestial::dome — SimGear's SGSky dome (a centre fan and inner, middle, outer and
// skirt rings of 12 vertices, SimGear's 2002 dome.cxx geometry) drawn along a view ray:
// the triangle the ray meets and its barycentric weights (the vertex colours' blend).
// Twin: crates/celestial/src/dome.rs (`sky_dome_weights`, generic over the float type;
// this file mirrors its f32 instance operation for operation): same names, argument
// order and units. Directions are unit east/north/up vectors from the dome's centre;
// `spin` is vertex 0's azimuth from south toward east (radians); positions in km.

const DOME_SIDES: u32 = 12u;
const DOME_TAU: f32 = 6.283185307179586;

// (horizontal distance, height) of the centre, inner, middle, outer and skirt rings (km).
fn sky_dome_ring(ring: u32) -> vec2<f32> {
    switch ring {
        case 0u: { return vec2<f32>(0.0, 25.0); }
        case 1u: { return vec2<f32>(50.0, 20.0); }
        case 2u: { return vec2<f32>(70.0, 8.0); }
        case 3u: { return vec2<f32>(80.0, 0.0); }
        default: { return vec2<f32>(50.0, -2.0); }
    }
}

fn sky_dome_slot(ring: u32, index: u32) -> u32 {
    if ring == 0u {
        return 0u;
    }
    return 1u + (ring - 1u) * DOME_SIDES + index % DOME_SIDES;
}

fn sky_dome_vertex(ring: u32, index: u32, spin: f32) -> vec3<f32> {
    let size = sky_dome_ring(ring);
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

// The triangle a view ray meets: its three vertex slots and barycentric weights.
struct DomeWeights {
    slots: vec3<u32>,
    weights: vec3<f32>,
}

fn sky_dome_weights(view: vec3<f32>, spin: f32) -> DomeWeights {
    let step = DOME_TAU / f32(DOME_SIDES);
    var phi = (atan2(view.x, -view.y) - spin) % DOME_TAU;
    if phi < 0.0 {
        phi = phi + DOME_TAU;
    }
    let sector = u32(max(floor(phi / step), 0.0)) % DOME_SIDES;
    let h = view.xy;
    if h.x == 0.0 && h.y == 0.0 {
        // Straight up: the centre vertex; straight down: the skirt's vertex 0.
        var ring = 4u;
        if view.z > 0.0 {
            ring = 0u;
        }
        return DomeWeights(vec3<u32>(sky_dome_slot(ring, 0u)), vec3<f32>(1.0, 0.0, 0.0));
    }
    // The dome's cross-section in the ray's vertical half-plane: every ring's chord at
    // the same parameter `along`, at `reach` × h horizontally; the band ends at the first
    // ring whose chord point is on or below the ray.
    let phi_first = spin + f32(sector % DOME_SIDES) * step;
    let phi_second = spin + f32((sector + 1u) % DOME_SIDES) * step;
    let first = vec2<f32>(sin(phi_first), -cos(phi_first));
    let second = vec2<f32>(sin(phi_second), -cos(phi_second));
    let edge = second - first;
    let across = h.x * edge.y - h.y * edge.x;
    let along = (first.x * h.y - first.y * h.x) / across;
    let reach = (first.x * second.y - first.y * second.x) / across;
    var lower = 0u;
    for (var ring = 1u; ring < 5u; ring++) {
        let size = sky_dome_ring(ring);
        if size.y - view.z * size.x * reach <= 0.0 {
            lower = ring;
            break;
        }
    }
    if lower > 0u {
        // The centre fan's triangle, or the strip's two (the one the ray is least
        // outside of).
        var first_triangle = 0u;
        var count = 1u;
        if lower > 1u {
            first_triangle = 2u * lower - 3u;
            count = 2u;
        }
        var found = false;
        var best_inside = 0.0;
        var best = DomeWeights(vec3<u32>(0u), vec3<f32>(0.0));
        for (var k = first_triangle; k < first_triangle + count; k++) {
            let t = sky_dome_triangle(sector, k);
            let p0 = sky_dome_vertex(t[0].x, t[0].y, spin);
            let p1 = sky_dome_vertex(t[1].x, t[1].y, spin);
            let p2 = sky_dome_vertex(t[2].x, t[2].y, spin);
            let w = sky_dome_ray_triangle(view, p0, p1, p2);
            if w.w > 0.0 {
                let inside = min(min(w.x, w.y), w.z);
                if !found || inside > best_inside {
                    found = true;
                    best_inside = inside;
                    best = DomeWeights(
                        vec3<u32>(sky_dome_slot(t[0].x, t[0].y), sky_dome_slot(t[1].x, t[1].y), sky_dome_slot(t[2].x, t[2].y)),
                        w.xyz,
                    );
                }
            }
        }
        if found {
            return best;
        }
    }
    // Below the skirt.
    let t = clamp(along, 0.0, 1.0);
    return DomeWeights(
        vec3<u32>(sky_dome_slot(4u, sector), sky_dome_slot(4u, sector + 1u), sky_dome_slot(4u, sector)),
        vec3<f32>(1.0 - t, t, 0.0),
    );
}
