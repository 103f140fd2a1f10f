// celestial::sky_objects — the render pass drawing the sun, the moon, planets and stars
// into the caller's colour target (additive radiance, depth writes off).
// Twin: crates/celestial/src/objects.rs (render_sky_objects_cpu), pixel for pixel: discs
// per pixel through disc_object_radiance, point sources as Gaussian sprites of
// point_source_irradiance.

#import celestial::draw
#import atmos::frame

// Twin of celestial::objects::SkyObjectsUniforms.
struct SkyObjectsUniforms {
    camera: FrameCamera,
    planet_radius: f32,
    lux_per_unit: f32,
    sprite_sigma_px: f32,
    far_depth: f32,
}

@group(0) @binding(0) var<uniform> frame: SkyObjectsUniforms;
@group(0) @binding(1) var<storage, read> discs: array<DiscObject>;
@group(0) @binding(2) var<storage, read> points: array<PointSource>;

// The quad's corners, two triangles.
fn quad_corner(vertex: u32) -> vec2<f32> {
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(-1.0, 1.0),
        vec2<f32>(-1.0, 1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
    );
    return corners[vertex];
}

// Pixel coordinates (y down) to clip space at the objects' depth.
fn pixel_to_clip(p: vec2<f32>) -> vec4<f32> {
    let x = p.x / f32(frame.camera.width) * 2.0 - 1.0;
    let y = 1.0 - p.y / f32(frame.camera.height) * 2.0;
    return vec4<f32>(x, y, frame.far_depth, 1.0);
}

// A vertex that rasterises nothing (all six on one point outside the view).
const HIDDEN = vec4<f32>(2.0, 2.0, 0.5, 1.0);

struct DiscVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) index: u32,
}

@vertex
fn disc_vertex(@builtin(vertex_index) vertex: u32, @builtin(instance_index) index: u32) -> DiscVarying {
    var out: DiscVarying;
    out.index = index;
    let disc = discs[index];
    let p = project_direction(disc.direction, frame.camera);
    if disc.kind == DISC_NONE || p.z <= disc.sin_radius {
        out.position = HIDDEN;
        return out;
    }
    // Half size: the radius in pixels, stretched up to 1/cos² off axis, plus 2 px.
    let pixel = 2.0 * frame.camera.tan_half_fov_y / f32(frame.camera.height);
    let half = disc.sin_radius / pixel / (p.z * p.z) + 2.0;
    out.position = pixel_to_clip(p.xy + quad_corner(vertex) * half);
    return out;
}

@fragment
fn disc_fragment(in: DiscVarying) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(floor(in.position.xy));
    let view = frame_view_direction(pixel, frame.camera);
    let c = frame.camera.position;
    let r = sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
    let zenith = vec3<f32>(c.x / r, c.y / r, c.z / r);
    let l = disc_object_radiance(view, discs[in.index], zenith, r, frame.planet_radius);
    return vec4<f32>(l, 0.0);
}

struct PointVarying {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) centre: vec2<f32>,
    @location(1) @interpolate(flat) irradiance: vec3<f32>,
    @location(2) @interpolate(flat) solid_angle: f32,
}

@vertex
fn point_vertex(@builtin(vertex_index) vertex: u32, @builtin(instance_index) index: u32) -> PointVarying {
    var out: PointVarying;
    let point = points[index];
    let p = project_direction(point.direction, frame.camera);
    out.centre = p.xy;
    out.solid_angle = 1.0;
    out.irradiance = vec3<f32>(0.0);
    if p.z <= 0.0 {
        out.position = HIDDEN;
        return out;
    }
    let e = point_source_irradiance(
        point.illuminance_lux,
        point.colour,
        point.transmittance,
        point.background_luminance,
        point.scintillation,
        frame.lux_per_unit,
    );
    if e.x == 0.0 && e.y == 0.0 && e.z == 0.0 {
        out.position = HIDDEN;
        return out;
    }
    out.irradiance = e;
    out.solid_angle = pixel_solid_angle(frame.camera.tan_half_fov_y, frame.camera.height, p.z);
    let half = SPRITE_CUTOFF_SIGMAS * frame.sprite_sigma_px + 1.0;
    out.position = pixel_to_clip(p.xy + quad_corner(vertex) * half);
    return out;
}

@fragment
fn point_fragment(in: PointVarying) -> @location(0) vec4<f32> {
    let dx = in.position.x - in.centre.x;
    let dy = in.position.y - in.centre.y;
    let r2 = dx * dx + dy * dy;
    let cutoff = SPRITE_CUTOFF_SIGMAS * frame.sprite_sigma_px;
    if r2 > cutoff * cutoff {
        discard;
    }
    let w = point_sprite_weight(r2, frame.sprite_sigma_px) / in.solid_angle;
    return vec4<f32>(in.irradiance * w, 0.0);
}
