// The ground's cloud shadow map as a compute pass: one invocation per texel marches the
// sun ray through a CloudVolume's trilinear density and writes exp(−τ) into an R32Float
// storage texture. Twin: cloudlight::shadow_map::shadow_map::<f32> on a CloudVolume
// (whose density lookup is f64 rounded once; this one is f32).

#import cloudlight::shadow_map
#import cloudlight::cone

struct ShadowParams {
    // The grid's minimum corner (x, y), texel edge and ground height, metres.
    origin: vec2<f32>,
    cell_size: f32,
    ground_height: f32,
    // Unit direction toward the sun; σ_t per unit density (1/m).
    to_sun: vec3<f32>,
    sigma_t: f32,
    // The volume's box (minimum corner = the volume's origin) and cell edge, metres.
    box_lo: vec3<f32>,
    voxel_size: f32,
    box_hi: vec3<f32>,
    // Midpoint steps per span.
    steps: u32,
    // Cells along x, y, z; the map's width.
    dims: vec3<u32>,
    width: u32,
    // The map's height and padding.
    height: u32,
    unused0: u32,
    unused1: u32,
    unused2: u32,
}

@group(0) @binding(0) var<uniform> params: ShadowParams;
@group(0) @binding(1) var<storage, read> density: array<f32>;
@group(0) @binding(2) var shadow_out: texture_storage_2d<r32float, write>;

fn cell_density(x: u32, y: u32, z: u32) -> f32 {
    return density[x + params.dims.x * (y + params.dims.y * z)];
}

// The volume's trilinear density at p: zero outside, cell-centre values interpolated
// inside, clamped to the outermost centres (CloudVolume::density_at in f32).
fn volume_density(p: vec3<f32>) -> f32 {
    var base = vec3<u32>(0u);
    var frac = vec3<f32>(0.0);
    for (var a = 0; a < 3; a++) {
        let n = params.dims[a];
        let u = (p[a] - params.box_lo[a]) / params.voxel_size;
        if !(u >= 0.0 && u <= f32(n)) {
            return 0.0;
        }
        let c = clamp(u - 0.5, 0.0, f32(n - 1u));
        let i = min(u32(floor(c)), max(n, 2u) - 2u);
        base[a] = i;
        if n == 1u {
            frac[a] = 0.0;
        } else {
            frac[a] = c - f32(i);
        }
    }
    var sum = 0.0;
    for (var corner = 0u; corner < 8u; corner++) {
        var weight = 1.0;
        var cell = vec3<u32>(0u);
        for (var a = 0; a < 3; a++) {
            let bit = (corner >> u32(a)) & 1u;
            cell[a] = min(base[a] + bit, params.dims[a] - 1u);
            if bit == 1u {
                weight = weight * frac[a];
            } else {
                weight = weight * (1.0 - frac[a]);
            }
        }
        if weight != 0.0 {
            sum = sum + weight * cell_density(cell.x, cell.y, cell.z);
        }
    }
    return sum;
}

@compute @workgroup_size(8, 8)
fn shadow_map_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.width || gid.y >= params.height {
        return;
    }
    let p = shadow_texel_centre(gid.xy, params.origin, params.cell_size, params.ground_height);
    let l = params.to_sun;
    let span = shadow_box_span(p, l, params.box_lo, params.box_hi);
    var tau = 0.0;
    if span.x <= span.y {
        var sum = 0.0;
        for (var k = 0u; k < params.steps; k++) {
            sum = shadow_accumulate(sum, volume_density(shadow_march_point(p, l, span, k, params.steps)));
        }
        tau = min(0.0 + shadow_span_optical_depth(sum, span, params.steps, params.sigma_t), SHADOW_SATURATION);
    }
    textureStore(shadow_out, vec2<i32>(gid.xy), vec4<f32>(beer_lambert(tau), 0.0, 0.0, 1.0));
}
