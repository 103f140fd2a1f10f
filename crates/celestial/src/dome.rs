//! SGSky's low-cost sky: SimGear's 12-sided dome — a centre fan and inner, middle and
//! outer rings (plus SimGear's skirt below the horizon) — whose vertex colours are
//! blended across the triangles, rotated so that vertex 0 of every ring faces the sun.
//!
//! Geometry (SimGear's 2002 `dome.cxx`, in metres around the viewer): the centre 25 km
//! overhead; the inner ring 50 km out at 20 km (21.8° elevation), the middle ring 70 km
//! out at 8 km (6.5°), the outer ring 80 km out on the horizon (0°), the skirt 50 km out
//! 2 km below (−2.3°); 12 vertices per ring, 30° apart.
//!
//! Two colourings:
//! * [`DomeColouring::SeedWeights`] — exactly SimGear's SGSky: the centre gets the sky colour,
//!   the inner ring 70 % sky + 30 % fog, the middle ring 10 % sky + 90 % fog, the outer
//!   ring (and the skirt) the fog colour. The `Sky` facade passes the atmosphere's
//!   zenith radiance as the sky colour and its horizon radiance in each ring vertex's
//!   azimuth as that vertex's fog colour, so the sunset glow lands on vertex 0.
//! * [`DomeColouring::Model`] — each vertex coloured by an atmos [`SkyModel`] in its
//!   own direction, so the dome's error against the same model per pixel is its
//!   interpolation alone (`cargo xtask tradeoff sky-dome`).
//!
//! Per pixel, a view ray from the dome's centre meets one triangle; its colour is the
//! barycentric blend of the triangle's vertex colours (what a GPU's perspective-correct
//! Gouraud shading of the dome gives). Below the skirt the dome is open: the skirt's
//! (fog) colour.
//!
//! **Rotation.** [`tangent_plane_spin`] is SGSky's construction: project the vector
//! toward the sub-solar point `S` onto the tangent plane at the viewer, project the
//! Earth's south axis `(0, 0, −1)` likewise to get local south `w`, take
//! `θ = acos(v̂·ŵ)`, and resolve the sign with local east `n̂ × ŵ` (w rotated by 90°
//! about the up vector): positive toward east. That is the sun's azimuth measured from
//! south toward east, `180° − A` for the azimuth A from north ([`spin_from_azimuth`]);
//! the construction is undefined at the poles (no south) and with the sun overhead
//! (no direction), where the facade uses the azimuth form.

use atmos::Atmosphere;
use atmos::ladder::{SkyModel, SkyQuery};
use glam::DVec3;
use num_traits::Float;

use crate::angle::Angle;
use crate::error::{CelestialError, Result};

/// Vertices per ring.
pub const DOME_SIDES: usize = 12;

/// The dome's rings from the top, as (horizontal distance, height) in metres from the
/// viewer (SimGear 2002): centre, inner, middle, outer, skirt.
pub const DOME_RINGS_M: [(f64, f64); 5] = [
    (0.0, 25_000.0),
    (50_000.0, 20_000.0),
    (70_000.0, 8_000.0),
    (80_000.0, 0.0),
    (50_000.0, -2_000.0),
];

/// SGSky's sky weights of the centre, inner, middle and outer rings (the fog takes
/// the rest); the skirt is fog.
pub const SEED_SKY_WEIGHTS: [f64; 5] = [1.0, 0.7, 0.1, 0.0, 0.0];

/// The sun's azimuth from south toward east: the dome's rotation.
pub fn spin_from_azimuth(azimuth_from_north: Angle) -> Angle {
    (Angle::from_degrees(180.0) - azimuth_from_north).wrapped_signed()
}

/// SGSky's tangent-plane construction of the dome's rotation, from the viewer's
/// position `view_position` and the sub-solar point `sun_point` (both planet-centred,
/// in an Earth-fixed frame with +z toward the north pole; only directions matter).
/// Errors: non-finite input; the viewer at a pole (local south undefined); the sun
/// overhead (no direction on the tangent plane).
pub fn tangent_plane_spin(view_position: [f64; 3], sun_point: [f64; 3]) -> Result<Angle> {
    for (field, v) in [("view_position", view_position), ("sun_point", sun_point)] {
        for c in v {
            if !c.is_finite() {
                return Err(CelestialError::NotFinite { field, value: c });
            }
        }
    }
    let p = DVec3::from_array(view_position);
    let n = p.normalize_or_zero();
    if n == DVec3::ZERO {
        return Err(CelestialError::OutOfRange {
            field: "|view_position|",
            value: 0.0,
            min: f64::MIN_POSITIVE,
            max: f64::MAX,
            unit: "m",
        });
    }
    // u = PS; u₁ = (n·u)n its normal part; v = u − u₁ on the tangent plane.
    let u = DVec3::from_array(sun_point) - p;
    let v = u - n * n.dot(u);
    // Local south: (0, 0, −1) onto the tangent plane.
    let down = DVec3::new(0.0, 0.0, -1.0);
    let w = down - n * n.dot(down);
    let pole = w.length();
    if pole < 1e-12 {
        return Err(CelestialError::OutOfRange {
            field: "view_position (distance from the polar axis, relative)",
            value: pole,
            min: 1e-12,
            max: 1.0,
            unit: "",
        });
    }
    let length = v.length();
    if length <= 1e-9 * u.length().max(1.0) {
        return Err(CelestialError::OutOfRange {
            field: "sun_point (horizontal distance from the viewer, relative)",
            value: length,
            min: 1e-9,
            max: f64::MAX,
            unit: "",
        });
    }
    let (v, w) = (v / length, w / pole);
    let theta = v.dot(w).clamp(-1.0, 1.0).acos();
    let east = n.cross(w);
    Ok(Angle::from_radians(if v.dot(east) < 0.0 {
        -theta
    } else {
        theta
    }))
}

/// Unit east/north/up direction of ring `ring` (0 = centre … 4 = skirt), vertex
/// `index`, for a dome rotated by `spin` (vertex 0 at azimuth `spin` from south toward
/// east), and its position in metres.
pub fn dome_vertex(ring: usize, index: usize, spin: Angle) -> DVec3 {
    let (horizontal, height) = DOME_RINGS_M[ring];
    let phi =
        spin.radians() + (index % DOME_SIDES) as f64 * std::f64::consts::TAU / DOME_SIDES as f64;
    // From south (0, −1) toward east (1, 0).
    DVec3::new(horizontal * phi.sin(), -horizontal * phi.cos(), height)
}

/// How the dome's vertices are coloured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DomeColouring {
    /// SGSky's weights between the sky colour (the model's zenith) and a fog colour
    /// per azimuth (the model's horizon in that vertex's azimuth)
    /// ([`SkyDome::seed_weights`]).
    #[default]
    SeedWeights,
    /// Each vertex from the sky model in its own direction ([`SkyDome::from_model`]).
    Model,
}

/// What [`SkyDome::paint`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct PaintedDome {
    /// The coloured dome.
    pub dome: SkyDome,
    /// Radiance at the zenith.
    pub sky_colour: [f64; 3],
    /// Radiance at the horizon in the 12 vertex azimuths.
    pub fog_colours: [[f64; 3]; DOME_SIDES],
}

/// A coloured, rotated 12-sided dome.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyDome {
    spin: Angle,
    /// Vertex colours: centre, then rings 1–4 × 12.
    colours: Vec<[f64; 3]>,
}

/// `colour` less `aureole(direction)`, per channel, not below 0.
fn without_aureole(
    direction: [f64; 3],
    colour: [f64; 3],
    aureole: impl Fn([f64; 3]) -> [f64; 3],
) -> [f64; 3] {
    let a = aureole(direction);
    std::array::from_fn(|i| (colour[i] - a[i]).max(0.0))
}

impl SkyDome {
    /// SGSky's colouring.
    pub fn seed_weights(sky: [f64; 3], fog: [[f64; 3]; DOME_SIDES], spin: Angle) -> Self {
        let mut colours = vec![[0.0; 3]; 1 + 4 * DOME_SIDES];
        colours[0] = sky;
        for ring in 1..5 {
            let w = SEED_SKY_WEIGHTS[ring];
            for (i, fog_colour) in fog.iter().enumerate() {
                colours[sky_dome_slot(ring, i)] =
                    std::array::from_fn(|c| w * sky[c] + (1.0 - w) * fog_colour[c]);
            }
        }
        Self { spin, colours }
    }

    /// SGSky's colouring of the full radiances `sky` (zenith) and `fog` (horizon, in
    /// the 12 vertex azimuths) less `aureole(direction)` at the zenith and at each
    /// horizon vertex (the aureole is drawn per pixel over the dome): what
    /// [`SkyDome::paint`] builds with [`DomeColouring::SeedWeights`].
    pub fn seed_weights_less_aureole(
        sky: [f64; 3],
        fog: [[f64; 3]; DOME_SIDES],
        spin: Angle,
        aureole: impl Fn([f64; 3]) -> [f64; 3],
    ) -> Self {
        let mut fog = fog;
        for (i, f) in fog.iter_mut().enumerate() {
            *f = without_aureole(dome_vertex(3, i, spin).normalize().to_array(), *f, &aureole);
        }
        SkyDome::seed_weights(without_aureole([0.0, 0.0, 1.0], sky, &aureole), fog, spin)
    }

    /// Every vertex coloured by `colour(direction)` (unit east/north/up direction).
    pub fn from_fn(
        spin: Angle,
        mut colour: impl FnMut([f64; 3]) -> Result<[f64; 3]>,
    ) -> Result<Self> {
        let mut colours = vec![[0.0; 3]; 1 + 4 * DOME_SIDES];
        for ring in 0..5 {
            let count = if ring == 0 { 1 } else { DOME_SIDES };
            for i in 0..count {
                colours[sky_dome_slot(ring, i)] =
                    colour(dome_vertex(ring, i, spin).normalize().to_array())?;
            }
        }
        Ok(Self { spin, colours })
    }

    /// Every vertex coloured by `model` (built from `atmosphere`) for a viewer
    /// `altitude_m` up, lit along `light` (east/north/up, unit), times `scale` per
    /// channel — call once per light source and [`SkyDome::plus`] them (radiance is
    /// linear in the source).
    pub fn from_model(
        model: &dyn SkyModel,
        atmosphere: &Atmosphere,
        altitude_m: f64,
        light: [f64; 3],
        scale: [f64; 3],
        spin: Angle,
    ) -> Result<Self> {
        let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + altitude_m);
        Self::from_fn(spin, |view| {
            let query = SkyQuery::new(
                atmosphere.planet_radius,
                position,
                DVec3::from_array(view),
                DVec3::from_array(light),
            )
            .map_err(|source| CelestialError::Atmos {
                field: "dome vertex query",
                source,
            })?;
            let radiance = model.evaluate(&query).radiance;
            Ok(std::array::from_fn(|c| radiance[c] * scale[c]))
        })
    }

    /// The dome the `Sky` facade paints: from `sky(direction)` (sunlit + moonlit
    /// radiance) minus `aureole(direction)` at each vertex (the aureole's forward peak is
    /// drawn per pixel over the dome, which cannot resolve it), coloured as
    /// `colouring` says. Returns the dome, the zenith's radiance and the horizon's in
    /// the 12 vertex azimuths (the full radiances, for fog).
    pub fn paint(
        colouring: DomeColouring,
        spin: Angle,
        mut sky: impl FnMut([f64; 3]) -> Result<[f64; 3]>,
        aureole: impl Fn([f64; 3]) -> [f64; 3],
    ) -> Result<PaintedDome> {
        let residual =
            |direction: [f64; 3], colour: [f64; 3]| without_aureole(direction, colour, &aureole);
        let zenith = [0.0, 0.0, 1.0];
        let sky_colour = sky(zenith)?;
        let mut fog_colours = [[0.0; 3]; DOME_SIDES];
        for (i, fog) in fog_colours.iter_mut().enumerate() {
            *fog = sky(dome_vertex(3, i, spin).normalize().to_array())?;
        }
        let dome = match colouring {
            DomeColouring::SeedWeights => {
                SkyDome::seed_weights_less_aureole(sky_colour, fog_colours, spin, &aureole)
            }
            DomeColouring::Model => {
                SkyDome::from_fn(spin, |direction| Ok(residual(direction, sky(direction)?)))?
            }
        };
        Ok(PaintedDome {
            dome,
            sky_colour,
            fog_colours,
        })
    }

    /// The sum of two domes with the same rotation (sunlit + moonlit).
    pub fn plus(mut self, other: &SkyDome) -> Self {
        for (a, b) in self.colours.iter_mut().zip(&other.colours) {
            for c in 0..3 {
                a[c] += b[c];
            }
        }
        self
    }

    /// Every vertex's colour replaced by `f(direction, colour)` (unit east/north/up
    /// direction of the vertex).
    pub fn map_vertices(mut self, f: impl Fn([f64; 3], [f64; 3]) -> [f64; 3]) -> Self {
        for ring in 0..5 {
            let count = if ring == 0 { 1 } else { DOME_SIDES };
            for i in 0..count {
                let direction = dome_vertex(ring, i, self.spin).normalize().to_array();
                let k = sky_dome_slot(ring, i);
                self.colours[k] = f(direction, self.colours[k]);
            }
        }
        self
    }

    /// The rotation.
    pub fn spin(&self) -> Angle {
        self.spin
    }

    /// Colour of ring `ring` (0 = centre … 4 = skirt), vertex `index`.
    pub fn vertex_colour(&self, ring: usize, index: usize) -> [f64; 3] {
        self.colours[sky_dome_slot(ring, index)]
    }

    /// The dome's triangles as (ring, index) triples: the centre fan, then the three
    /// strips between consecutive rings split as GL triangle strips split them.
    pub fn triangles() -> Vec<[(usize, usize); 3]> {
        (0..DOME_SIDES).flat_map(sector_triangles).collect()
    }

    /// The dome's colour along `view` (east/north/up, from the dome's centre):
    /// [`sky_dome_radiance`] over this dome's vertex colours.
    pub fn radiance(&self, view: [f64; 3]) -> [f64; 3] {
        sky_dome_radiance(view, self.spin.radians(), &self.vertex_colours())
    }

    /// The vertex colours in [`sky_dome_radiance`]'s order: the centre, then rings 1–4
    /// (inner, middle, outer, skirt) of [`DOME_SIDES`] vertices each, vertex 0 first.
    pub fn vertex_colours(&self) -> [[f64; 3]; DOME_VERTICES] {
        std::array::from_fn(|k| self.colours[k])
    }
}

/// Vertices of the dome: the centre and four rings of [`DOME_SIDES`].
pub const DOME_VERTICES: usize = 1 + 4 * DOME_SIDES;

fn constant<F: Float>(x: f64) -> F {
    F::from(x).expect("a float type holds the dome's constants")
}

fn sub<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot<F: Float>(a: [F; 3], b: [F; 3]) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Position (km) of ring `ring`, vertex `index` of a dome rotated by `spin` (radians,
/// from south toward east): [`dome_vertex`] in kilometres, over the float type.
fn sky_dome_vertex<F: Float>(ring: usize, index: usize, spin: F) -> [F; 3] {
    let (horizontal, height) = DOME_RINGS_M[ring];
    let step = constant::<F>(std::f64::consts::TAU) / F::from(DOME_SIDES).expect("12");
    let phi = spin + F::from(index % DOME_SIDES).expect("a small integer") * step;
    let horizontal = constant::<F>(horizontal / 1000.0);
    [
        horizontal * phi.sin(),
        -horizontal * phi.cos(),
        constant(height / 1000.0),
    ]
}

/// Barycentric weights of the point where the ray from the origin along `d` meets the
/// plane of triangle `p` (Möller–Trumbore), or `None` where it is parallel to the plane
/// or behind the origin. The weights are negative outside the triangle.
fn sky_dome_ray_triangle<F: Float>(d: [F; 3], p: [[F; 3]; 3]) -> Option<[F; 3]> {
    let e1 = sub(p[1], p[0]);
    let e2 = sub(p[2], p[0]);
    let h = cross(d, e2);
    let det = dot(e1, h);
    if det == F::zero() {
        return None;
    }
    let s = sub([F::zero(); 3], p[0]);
    let a = dot(s, h) / det;
    let q = cross(s, e1);
    let b = dot(d, q) / det;
    let t = dot(e2, q) / det;
    if t <= F::zero() {
        return None;
    }
    Some([F::one() - a - b, a, b])
}

/// The slot of ring `ring` (0 = centre … 4 = skirt), vertex `index` in
/// [`SkyDome::vertex_colours`]' order.
pub fn sky_dome_slot(ring: usize, index: usize) -> usize {
    if ring == 0 {
        0
    } else {
        1 + (ring - 1) * DOME_SIDES + index % DOME_SIDES
    }
}

/// Where a view ray meets SGSky's dome: the three vertex slots
/// ([`sky_dome_slot`]) of the triangle it meets and its barycentric weights there,
/// for `view` (unit, east/north/up, from the dome's centre) and a dome rotated by
/// `spin` (radians: vertex 0's azimuth from south toward east). The dome's colour
/// along the ray is the weights' blend of those vertices' colours
/// ([`sky_dome_radiance`]), as a rasteriser's Gouraud shading of the mesh gives.
///
/// The ray's azimuth picks its sector exactly (every triangle of a sector lies between
/// the vertical planes through its two vertex azimuths); within the sector, the ray's
/// elevation against each ring's chord picks the band (the strips are planar
/// trapezoids), and Möller–Trumbore gives the weights over the band's one or two
/// triangles: a constant cost per ray, as a rasteriser's. Below the skirt the dome is
/// open: the skirt's chord where the ray's vertical plane crosses it (continuous with
/// the skirt's edge). Straight up is the centre vertex; straight down, a direction
/// with no azimuth, the skirt's vertex 0.
///
/// The WGSL twin is `sky_dome_weights` in `shaders/celestial/dome.wgsl` (parity case
/// `celestial::sky_dome_weights`).
pub fn sky_dome_weights<F: Float>(view: [F; 3], spin: F) -> ([usize; 3], [F; 3]) {
    let tau = constant::<F>(std::f64::consts::TAU);
    let step = tau / F::from(DOME_SIDES).expect("12");
    let mut phi = (view[0].atan2(-view[1]) - spin) % tau;
    if phi < F::zero() {
        phi = phi + tau;
    }
    let sector = (phi / step).floor().to_usize().unwrap_or(0) % DOME_SIDES;
    let (zero, one) = (F::zero(), F::one());
    let h = [view[0], view[1]];
    if h[0] == zero && h[1] == zero {
        let ring = if view[2] > zero { 0 } else { 4 };
        return ([sky_dome_slot(ring, 0); 3], [one, zero, zero]);
    }
    // The sector's vertices on the unit circle: every ring's chord in the ray's vertical
    // half-plane sits at the same parameter `along` and at `reach` × h horizontally
    // (the rings are scaled copies), so the dome's cross-section there is the polyline
    // centre → ring 1 → … → skirt, and the ray's band ends at the first ring whose chord
    // point is on or below the ray.
    let unit = |index: usize| {
        let phi = spin + F::from(index % DOME_SIDES).expect("a small integer") * step;
        [phi.sin(), -phi.cos()]
    };
    let cross2 = |a: [F; 2], b: [F; 2]| a[0] * b[1] - a[1] * b[0];
    let (first, second) = (unit(sector), unit(sector + 1));
    let edge = [second[0] - first[0], second[1] - first[1]];
    let across = cross2(h, edge);
    let along = cross2(first, h) / across;
    let reach = cross2(first, second) / across;
    let band = (1..5).find(|&ring| {
        let (radius, height) = DOME_RINGS_M[ring];
        constant::<F>(height / 1000.0) - view[2] * constant::<F>(radius / 1000.0) * reach <= zero
    });
    if let Some(lower) = band {
        // The centre fan's triangle, or the strip's two (the one the ray is least
        // outside of: rounding at their shared diagonal or a sector's edge leaves
        // weights a few ULP below zero, where the blend is continuous).
        let triangles = sector_triangles(sector);
        let candidates: &[DomeTriangle] = if lower == 1 {
            &triangles[..1]
        } else {
            &triangles[2 * lower - 3..2 * lower - 1]
        };
        let mut best: Option<(DomeTriangle, [F; 3])> = None;
        for &t in candidates {
            let p = t.map(|(ring, i)| sky_dome_vertex(ring, i, spin));
            if let Some(w) = sky_dome_ray_triangle(view, p) {
                let inside = w[0].min(w[1]).min(w[2]);
                if best.is_none_or(|(_, b)| inside > b[0].min(b[1]).min(b[2])) {
                    best = Some((t, w));
                }
            }
        }
        if let Some((t, w)) = best {
            return (t.map(|(ring, i)| sky_dome_slot(ring, i)), w);
        }
    }
    // Below the skirt.
    let along = along.max(zero).min(one);
    (
        [
            sky_dome_slot(4, sector),
            sky_dome_slot(4, sector + 1),
            sky_dome_slot(4, sector),
        ],
        [one - along, along, zero],
    )
}

/// SGSky's dome's colour along `view` with `colours` at its vertices (centre, then
/// rings 1–4 × [`DOME_SIDES`]; [`SkyDome::vertex_colours`]): [`sky_dome_weights`]'
/// blend.
pub fn sky_dome_radiance<F: Float>(
    view: [F; 3],
    spin: F,
    colours: &[[F; 3]; DOME_VERTICES],
) -> [F; 3] {
    let (slots, w) = sky_dome_weights(view, spin);
    let c = slots.map(|k| colours[k]);
    std::array::from_fn(|k| w[0] * c[0][k] + w[1] * c[1][k] + w[2] * c[2][k])
}

/// A triangle of the dome as (ring, index) pairs.
type DomeTriangle = [(usize, usize); 3];

/// The 7 triangles of sector `sector` (between vertices `sector` and `sector + 1`), in
/// [`SkyDome::triangles`]' order.
fn sector_triangles(sector: usize) -> [DomeTriangle; 7] {
    let (i, j) = (sector, (sector + 1) % DOME_SIDES);
    [
        [(0, 0), (1, i), (1, j)],
        [(2, i), (1, i), (2, j)],
        [(1, i), (2, j), (1, j)],
        [(3, i), (2, i), (3, j)],
        [(2, i), (3, j), (2, j)],
        [(4, i), (3, i), (4, j)],
        [(3, i), (4, j), (3, j)],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fog colour that varies around the horizon (periodic, like a real one).
    fn fog_ramp() -> [[f64; 3]; DOME_SIDES] {
        std::array::from_fn(|i| {
            [
                1.0 + (i as f64 * std::f64::consts::TAU / 12.0).cos(),
                1.0,
                2.0,
            ]
        })
    }

    #[test]
    fn seed_weights_exactly() {
        let sky = [0.2, 0.4, 0.8];
        let dome = SkyDome::seed_weights(sky, fog_ramp(), Angle::ZERO);
        assert_eq!(dome.vertex_colour(0, 0), sky);
        for i in 0..DOME_SIDES {
            let fog = fog_ramp()[i];
            let inner = dome.vertex_colour(1, i);
            let middle = dome.vertex_colour(2, i);
            for c in 0..3 {
                assert!((inner[c] - (0.7 * sky[c] + 0.3 * fog[c])).abs() < 1e-15);
                assert!((middle[c] - (0.1 * sky[c] + 0.9 * fog[c])).abs() < 1e-15);
            }
            assert_eq!(dome.vertex_colour(3, i), fog);
            assert_eq!(dome.vertex_colour(4, i), fog);
        }
    }

    #[test]
    fn interpolation_hits_vertices_and_is_continuous() {
        let spin = Angle::from_degrees(37.0);
        let dome = SkyDome::seed_weights([0.2, 0.4, 0.8], fog_ramp(), spin);
        // At each vertex direction the colour is the vertex's.
        for ring in 0..5 {
            for i in 0..DOME_SIDES {
                let v = dome_vertex(ring, i, spin).normalize();
                // Nudge inside the dome's surface so the ray is not on an edge.
                let c = dome.radiance((v * 1.0).to_array());
                let expected = dome.vertex_colour(ring, i);
                for k in 0..3 {
                    assert!(
                        (c[k] - expected[k]).abs() < 1e-6,
                        "ring {ring} vertex {i}: {c:?} vs {expected:?}"
                    );
                }
            }
        }
        // Continuity: neighbouring directions differ little.
        let mut last = dome.radiance([0.0, 1.0, 0.3]);
        for k in 1..=3600 {
            let a = f64::from(k) * std::f64::consts::TAU / 3600.0;
            let c = dome.radiance([a.sin(), a.cos(), 0.3]);
            for m in 0..3 {
                assert!((c[m] - last[m]).abs() < 5e-3, "{a}: {c:?} vs {last:?}");
            }
            last = c;
        }
    }

    /// SGSky's construction is the sun's azimuth from south toward east, with the
    /// east/west sign resolved, everywhere but the poles.
    #[test]
    fn tangent_plane_spin_is_the_azimuth_from_south() {
        use crate::{Instant, Observer, sidereal::greenwich_apparent_sidereal_time, sun_position};
        let ecef = |lat: f64, lon: f64| {
            [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()].map(|c| c * 6.371e6)
        };
        let mut checked = 0;
        for (lat, lon) in [
            (0.0, 0.0),
            (52.0, 4.9),
            (-33.9, 151.2),
            (71.0, -156.8),
            (-89.0, 30.0),
            (10.0, 180.0),
        ] {
            for hour in [0, 5, 9, 13, 18, 22] {
                let instant = Instant::parse(&format!("2024-03-10T{hour:02}:00:00Z")).unwrap();
                let observer =
                    Observer::new(Angle::from_degrees(lat), Angle::from_degrees(lon), 0.0).unwrap();
                let sun = sun_position(&instant, &observer).unwrap();
                let gast = greenwich_apparent_sidereal_time(&instant);
                let sub_lon = (sun.right_ascension - gast).wrapped_signed().radians();
                let spin = tangent_plane_spin(
                    ecef(lat.to_radians(), lon.to_radians()),
                    ecef(sun.declination.radians(), sub_lon),
                )
                .unwrap();
                // The tangent-plane direction toward the sub-solar point is the great
                // circle's initial bearing: the sun's (geocentric) azimuth.
                let expected = spin_from_azimuth(sun.airless.azimuth);
                let diff = (spin - expected).wrapped_signed().degrees();
                // Topocentric vs geocentric and the sphere vs the ellipsoid: < 0.2°.
                assert!(
                    diff.abs() < 0.2,
                    "φ {lat} λ {lon} {hour}h: {} vs {}",
                    spin.degrees(),
                    expected.degrees()
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 36);
        // The poles and the sun overhead are typed errors, not NaN.
        assert!(tangent_plane_spin([0.0, 0.0, 6.4e6], [6.4e6, 0.0, 0.0]).is_err());
        assert!(tangent_plane_spin([6.4e6, 0.0, 0.0], [6.4e6, 0.0, 0.0]).is_err());
        assert!(tangent_plane_spin([f64::NAN, 0.0, 0.0], [6.4e6, 0.0, 0.0]).is_err());
        // East positive, west negative.
        assert!((spin_from_azimuth(Angle::from_degrees(90.0)).degrees() - 90.0).abs() < 1e-12);
        assert!((spin_from_azimuth(Angle::from_degrees(270.0)).degrees() + 90.0).abs() < 1e-12);
    }
}
