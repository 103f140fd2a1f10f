// The GPU terrain of a scene: the quadtree's tiles (render::terrain_mesh) drawn
// instanced, each vertex reading the heightfield; each fragment shaded as the CPU
// reference renderer shades a ray's hit (render::cpu_renderer): bilinear normal and
// horizon angles, Hoffman and Preetham's terrain term with a soft self-shadow, the sun through the
// precomputed rung's transmittance, the sky's irradiance, then the aerial perspective
// between the camera and the point (atmos::aerial_perspective).
//
// Bindings: the LUTs in groups 0 and 1 (atmos::lut_bindings), the terrain in group 2.
// World frame: metres, x east, y up, z south, the camera's planet frame's axes; the
// map frame: x east from texel 0, y south from row 0 (texels × spacing).
#import atmos::aerial_perspective
#import terrain::shadow
#import render::terrain_shading
#import render::terrain_materials
#import celestial::clouds
#import cloudlight::shadow_map
#import render::volume_shadow

struct TerrainUniform {
    view_projection: mat4x4<f32>,
    // The camera's world position (m).
    camera: vec3<f32>,
    // Metres per texel.
    spacing: f32,
    // World (x, z) + map_offset = map (x, y) in metres.
    map_offset: vec2<f32>,
    map_size: vec2<u32>,
    // The sun in the terrain's east–north–up frame.
    sun_enu: vec3<f32>,
    sun_angular_radius: f32,
    // The sky's irradiance on a horizontal surface (atmos::ground_irradiance).
    sky_irradiance: vec3<f32>,
    sun_elevation: f32,
    sun_azimuth: f32,
    // 0: Hoffman and Preetham's east/west pair (horizons holds east then west); N: N azimuth layers.
    horizon_layers: u32,
    // The viewer's distance from the planet's centre (m): celestial's cloud frame.
    viewer_radius: f32,
    cloud_layer_count: u32,
    albedo: AlbedoRamp,
    // Multiplies the radiance written (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    // Radians per pixel (the camera's vertical field over its rows): the footprint
    // that band-limits the materials' detail.
    pixel_angle: f32,
    // 1: the procedural materials; 0: the albedo ramp.
    procedural: u32,
    // 1: colour_texels holds [terrain.colour]'s texture (colour_size pixels).
    colour_enabled: u32,
    colour_size: vec2<u32>,
    colour_texels_per_metre: f32,
    padding0: f32,
    materials: MaterialParams,
}

@group(2) @binding(0) var<uniform> terrain: TerrainUniform;
@group(2) @binding(1) var<storage, read> heights: array<f32>;
// Unit normals (east, north, up, 0).
@group(2) @binding(2) var<storage, read> normals: array<vec4<f32>>;
// Horizon angles (rad): layer k of texel i at i + k·width·height.
@group(2) @binding(3) var<storage, read> horizons: array<f32>;
// The scene's cloud layers (celestial::clouds), casting shadows on the terrain.
@group(2) @binding(4) var<storage, read> cloud_layers: array<CloudLayerUniforms>;

// One marched cloud's shadow map (render::volume_clouds::CloudShadow, layout identical
// to VolumeShadowUniform): texel (0, 0)'s corner east/north, the texel edge, the plane's
// altitude, the direction toward the light (east/north/up), whether a map is bound (0:
// no such cloud, or none toward this draw's light), the texels east × north, where its
// values start in volume_shadow_values, the casting cloud's top altitude.
struct VolumeShadowUniform {
    origin: vec2<f32>,
    cell_size: f32,
    plane: f32,
    to_sun: vec3<f32>,
    enabled: u32,
    resolution: vec2<u32>,
    offset: u32,
    top: f32,
}
// The marched clouds' shadow maps: [0] the volume's (or its billboards'), [1] the
// [clouds.shell] deck's; the terrain reads their product.
@group(2) @binding(5) var<uniform> volume_shadow: array<VolumeShadowUniform, 2>;
// Transmittance toward the light per texel, east fastest, each map's from its offset
// (one element when none).
@group(2) @binding(6) var<storage, read> volume_shadow_values: array<f32>;
// [terrain.colour]'s linear albedo per pixel (rgb, 0), x fastest, row 0 north (one
// element without a texture).
@group(2) @binding(7) var<storage, read> colour_texels: array<vec4<f32>>;

struct TerrainVarying {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}

fn height_at(texel: vec2<u32>) -> f32 {
    let t = min(texel, terrain.map_size - vec2<u32>(1u));
    return heights[t.x + terrain.map_size.x * t.y];
}

// A tile vertex's world position (its grid vertex, tile and skirt: render::terrain_mesh).
// Twin: render::aerial_vertex's vertex_world (grid vertices).
fn tile_vertex_world(grid: vec4<u32>, tile_origin: vec2<u32>, tile_step: u32, tile_skirt: f32) -> vec3<f32> {
    let texel = min(tile_origin + grid.xy * tile_step, terrain.map_size - vec2<u32>(1u));
    var elevation = height_at(texel);
    if grid.z != 0u {
        elevation -= tile_skirt;
    }
    let map = vec2<f32>(texel) * terrain.spacing;
    return vec3<f32>(map.x - terrain.map_offset.x, elevation, map.y - terrain.map_offset.y);
}

@vertex
fn terrain_vertex(@location(0) grid: vec4<u32>, @location(1) tile_origin: vec2<u32>, @location(2) tile_step: u32, @location(3) tile_skirt: f32) -> TerrainVarying {
    let world = tile_vertex_world(grid, tile_origin, tile_step, tile_skirt);
    return TerrainVarying(terrain.view_projection * vec4<f32>(world, 1.0), world);
}

// Bilinear footprint of a fractional texel position: the four texel indices and the
// weights (texel x, y clamped so the footprint stays inside the map). Twin:
// render::cpu_renderer's bilinear_texels.
struct TexelFootprint {
    index: vec4<u32>,
    weight: vec4<f32>,
}

fn texel_footprint(texel: vec2<f32>) -> TexelFootprint {
    let w = terrain.map_size.x;
    let h = terrain.map_size.y;
    let i = min(u32(max(floor(texel.x), 0.0)), w - 2u);
    let j = min(u32(max(floor(texel.y), 0.0)), h - 2u);
    let fx = texel.x - f32(i);
    let fy = texel.y - f32(j);
    return TexelFootprint(
        vec4<u32>(j * w + i, j * w + i + 1u, (j + 1u) * w + i, (j + 1u) * w + i + 1u),
        vec4<f32>((1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy),
    );
}

fn filtered_horizon(f: TexelFootprint, layer: u32) -> f32 {
    let base = layer * terrain.map_size.x * terrain.map_size.y;
    return horizons[base + f.index.x] * f.weight.x + horizons[base + f.index.y] * f.weight.y
        + horizons[base + f.index.z] * f.weight.z + horizons[base + f.index.w] * f.weight.w;
}

// A texel's horizon angle toward the sun's azimuth, between its two neighbouring
// layers (terrain::AzimuthHorizonMaps::horizon_angle).
fn azimuth_horizon(texel: u32, layers: AzimuthLayers) -> f32 {
    let size = terrain.map_size.x * terrain.map_size.y;
    let a = horizons[layers.lower * size + texel];
    let b = horizons[layers.upper * size + texel];
    return a + (b - a) * layers.weight;
}

// The direct sun's fraction through every cloud layer at `offset` (world axes, metres
// from the camera): celestial's cloud_shadow per layer. Twin: render::clouds::cloud_shadow_at.
fn cloud_shadow_at(offset: vec3<f32>) -> f32 {
    let point = vec3<f32>(offset.x, -offset.z, offset.y);
    var shadow = 1.0;
    for (var i = 0u; i < terrain.cloud_layer_count; i++) {
        shadow *= cloud_shadow(point, terrain.viewer_radius, cloud_layers[i]);
    }
    return shadow;
}

// The map's value at flat index `index` (cloudlight's shadow_map_taps), 1 for −1
// (outside it).
fn volume_shadow_value(map: VolumeShadowUniform, index: i32) -> f32 {
    if index < 0 {
        return 1.0;
    }
    return volume_shadow_values[map.offset + u32(index)];
}

// One cloud's shadow at world position `world` (x east, y up, z south). Twin:
// render::volume_clouds::CloudShadow::on_terrain (the same map; cloudlight's lookup,
// shadow_map_taps then shadow_map_bilinear: between texel centres, 1 outside it; above
// the plane, exp(−τ) of cloudlight's shadow_depth_above fade, 1 above the top).
fn shadow_map_at(map: VolumeShadowUniform, world: vec3<f32>) -> f32 {
    if map.enabled == 0u {
        return 1.0;
    }
    let texel = volume_shadow_texel(vec3<f32>(world.x, -world.z, world.y), map.to_sun, map.plane, map.origin, map.cell_size);
    let taps = shadow_map_taps(texel, map.resolution);
    let transmittance = shadow_map_bilinear(vec4<f32>(volume_shadow_value(map, taps.index.x), volume_shadow_value(map, taps.index.y), volume_shadow_value(map, taps.index.z), volume_shadow_value(map, taps.index.w)), taps.fraction);
    if world.y <= map.plane {
        return transmittance;
    }
    return exp(-shadow_depth_above(transmittance, world.y, map.plane, map.top));
}

// The marched clouds' shadow at `world`: the volume's times the shell's. Twin:
// render::cpu_renderer's volume_shadow_at.
fn volume_cloud_shadow(world: vec3<f32>) -> f32 {
    return shadow_map_at(volume_shadow[0], world) * shadow_map_at(volume_shadow[1], world);
}

// The colour texture's linear albedo at map position `map` (m east and south of texel
// (0, 0)), bilinear between pixel centres. Twin: render::terrain_colour's
// ColourTexture::colour_at.
fn terrain_colour_at(map: vec2<f32>) -> vec3<f32> {
    let taps = colour_taps(map * terrain.colour_texels_per_metre, terrain.colour_size);
    return colour_texels[taps.index.x].xyz * taps.weight.x + colour_texels[taps.index.y].xyz * taps.weight.y
        + colour_texels[taps.index.z].xyz * taps.weight.z + colour_texels[taps.index.w].xyz * taps.weight.w;
}

// The terrain's albedo at map position `map` (m), `elevation` (m), with unit normal
// `normal` (east, north, up), seen from the camera at `offset` (world axes, camera →
// point): the colour texture or the ramp, or the procedural materials over the colour
// texture's or the grass's albedo with the detail band-limited by the pixel's
// footprint. Twin: render::passes::terrain::cpu's surface_albedo.
fn surface_albedo(map: vec2<f32>, elevation: f32, normal: vec3<f32>, offset: vec3<f32>) -> vec3<f32> {
    var ground = terrain.materials.grass_albedo;
    if terrain.colour_enabled != 0u {
        ground = terrain_colour_at(map);
    }
    if terrain.procedural == 0u {
        if terrain.colour_enabled != 0u {
            return ground;
        }
        return terrain_albedo(terrain.albedo, elevation, normal.z);
    }
    let distance = max(length(offset), 1e-3);
    let cos_incidence = (offset.x * normal.x - offset.z * normal.y + offset.y * normal.z) / distance;
    let footprint = pixel_footprint(distance, terrain.pixel_angle, cos_incidence);
    let detail = detail_noise(map.x, map.y, footprint, terrain.materials.seed);
    return procedural_albedo(normal, elevation, detail, ground, terrain.materials);
}

// The terrain's own radiance at world position `world`, lit by `light_at_point` (the
// light's irradiance through the atmosphere there, from the scene's rung) and the sky's
// irradiance. Rungs without tables call it with their own light and aerial perspective
// (render::terrain_rung).
fn terrain_surface(world: vec3<f32>, light_at_point: vec3<f32>) -> vec3<f32> {
    let map = vec2<f32>(world.x, world.z) + terrain.map_offset;
    let f = texel_footprint(map / terrain.spacing);
    let n = normals[f.index.x] * f.weight.x + normals[f.index.y] * f.weight.y
        + normals[f.index.z] * f.weight.z + normals[f.index.w] * f.weight.w;
    var normal = vec3<f32>(0.0, 0.0, 1.0);
    if dot(n.xyz, n.xyz) > 0.0 {
        normal = normalize(n.xyz);
    }
    var self_shadow: f32;
    if terrain.horizon_layers == 0u {
        self_shadow = self_shadow_east_west(filtered_horizon(f, 0u), filtered_horizon(f, 1u), terrain.sun_enu, terrain.sun_angular_radius);
    } else {
        let layers = azimuth_layers(terrain.sun_azimuth, terrain.horizon_layers);
        let horizon = azimuth_horizon(f.index.x, layers) * f.weight.x + azimuth_horizon(f.index.y, layers) * f.weight.y
            + azimuth_horizon(f.index.z, layers) * f.weight.z + azimuth_horizon(f.index.w, layers) * f.weight.w;
        self_shadow = soft_shadow(terrain.sun_elevation, horizon, terrain.sun_angular_radius);
    }
    let offset = world - terrain.camera;
    let albedo = surface_albedo(map, world.y, normal, offset);
    let cloud_shadow = cloud_shadow_at(offset) * volume_cloud_shadow(world);
    return surface_radiance(normal, normal.z, terrain.sun_enu, albedo, self_shadow, cloud_shadow, light_at_point, terrain.sky_irradiance);
}

// Radiance of the terrain at world position `world`, seen from the camera (the
// precomputed rung: the sun and the aerial perspective from its tables).
fn terrain_radiance(world: vec3<f32>) -> vec3<f32> {
    let offset = world - terrain.camera;
    return apply_aerial_perspective(terrain_surface(world, sunlight_at(offset)), offset);
}

@fragment
fn terrain_fragment(in: TerrainVarying) -> @location(0) vec4<f32> {
    return vec4<f32>(terrain_radiance(in.world) * terrain.radiance_scale, 1.0);
}
