// The terrain of a scene drawn with a rung without tables (`closed-form`,
// `closed-form-vertex`, `single`): the terrain pass of render::terrain (its vertices,
// shading and bindings in group 2) lit by the rung's light (render::rung_sky's
// terrain_light_irradiance, bound to the rung's module) instead of the precomputed
// tables. It writes the surface's own radiance, and render::rung_air then applies the
// aerial perspective per pixel (compute). Groups 0 and 1 (the tables) are declared by
// render::terrain but not read by these entry points; group 3 holds the light, the
// rung's parameters of its atmosphere, and the light tabulated over the terrain's
// elevations, with the geometry of the light's path from a terrain point to the top of
// the atmosphere as render::passes::terrain::lighting's light_irradiance_at builds the
// query for the rung's SkyModel. Twin: render::cpu_renderer's shade_terrain for rungs
// without tables, with the rung's SkyModel as the segment model.
#import render::terrain
#import render::rung_sky

// Layout identical to render::gpu::rungs::RungLightUniform.
struct RungLight {
    // The camera, planet-centred (m).
    camera_position: vec3<f32>,
    // The atmosphere's top (m from the planet's centre).
    top_radius: f32,
    // Unit direction toward the light (the sun, or the moon at night).
    direction: vec3<f32>,
    planet_radius: f32,
    // The terrain's lowest and highest elevation (m): the span of rung_light_table.
    elevation_range: vec2<f32>,
    padding: vec2<f32>,
}

@group(3) @binding(0) var<uniform> rung_light: RungLight;
// The rung's parameters of the light's atmosphere.
@group(3) @binding(1) var<uniform> rung_parameters: RungParameters;
// The light's irradiance at evenly spaced elevations over elevation_range, first to
// last (rungs whose light is tabulated per frame: single scattering).
@group(3) @binding(2) var<storage, read> rung_light_table: array<vec4<f32>>;

// The tabulated light at `elevation` (m): linear between the table's entries, clamped
// to its span. Twin: render::cpu_renderer's TerrainLight::sun_at_elevation.
fn rung_light_from_table(elevation: f32) -> vec3<f32> {
    let n = arrayLength(&rung_light_table);
    let low = rung_light.elevation_range.x;
    let high = rung_light.elevation_range.y;
    var f = 0.0;
    if high > low {
        f = clamp((elevation - low) / (high - low), 0.0, 1.0) * f32(n - 1u);
    }
    let k = min(u32(floor(f)), n - 2u);
    let t = f - f32(k);
    return mix(rung_light_table[k].xyz, rung_light_table[k + 1u].xyz, t);
}

// The light's path (render::air_segment's RungLightPath) from the point `elevation` metres above the camera's ground point (the
// terrain is flat in the world frame, so only the elevation matters). Twin: the
// geometry of render::cpu_renderer::light_irradiance_at.
fn rung_light_path(elevation: f32) -> RungLightPath {
    let point = vec3<f32>(rung_light.camera_position.x, rung_light.planet_radius + elevation, rung_light.camera_position.z);
    let r = length(point);
    let mu_s = dot(point, rung_light.direction) / r;
    let hidden = ray_sphere_intersect(r, mu_s, rung_light.planet_radius).x >= 0.0;
    let top = max(ray_sphere_intersect(r, mu_s, rung_light.top_radius).y, 0.0);
    return RungLightPath(r, mu_s, top, hidden);
}

// The light's irradiance at a terrain point `elevation` metres above the camera's
// ground point, the rung's (render::rung_sky's terrain_light_irradiance over the path
// and the table). Twin: render::passes::terrain::lighting::light_irradiance_at with the
// rung's SkyModel.
fn rung_light_at(elevation: f32) -> vec3<f32> {
    return terrain_light_irradiance(rung_light_path(elevation), rung_light_from_table(elevation), rung_parameters);
}

@fragment
fn terrain_rung_fragment(in: TerrainVarying) -> @location(0) vec4<f32> {
    return vec4<f32>(terrain_surface(in.world, rung_light_at(in.world.y)) * terrain.radiance_scale, 1.0);
}
