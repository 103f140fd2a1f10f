// A CloudVolume's density grid as the density field a march reads (the source bound to
// cloudlight::density_source): the cells at binding 5, x fastest, read with manual
// trilinear interpolation between cell centres in f32; the box and σ_t at binding 4.
// Twin: DensityField for CloudVolume (whose lookup is f64 rounded once).
#import cloudlight::ray_spans

struct DensityGrid {
    // The box's minimum corner (xyz, m); w: cell edge (m).
    box_lo: vec4<f32>,
    // The box's maximum corner (xyz, m); w: σ_t per unit density (1/m).
    box_hi: vec4<f32>,
    // Cells along x, y, z; w unused.
    dims: vec4<u32>,
}

@group(0) @binding(4) var<uniform> density_grid: DensityGrid;
@group(0) @binding(5) var<storage, read> density_grid_cells: array<f32>;

fn grid_cell_density(x: u32, y: u32, z: u32) -> f32 {
    let dims = density_grid.dims.xyz;
    return density_grid_cells[x + dims.x * (y + dims.y * z)];
}

// The volume's trilinear density at p: zero outside, cell-centre values interpolated
// inside, clamped to the outermost centres (CloudVolume::density_at in f32).
fn field_density(p: vec3<f32>) -> f32 {
    var base = vec3<u32>(0u);
    var frac = vec3<f32>(0.0);
    for (var a = 0; a < 3; a++) {
        let n = density_grid.dims[a];
        let u = (p[a] - density_grid.box_lo[a]) / density_grid.box_lo.w;
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
            cell[a] = min(base[a] + bit, density_grid.dims[a] - 1u);
            if bit == 1u {
                weight = weight * frac[a];
            } else {
                weight = weight * (1.0 - frac[a]);
            }
        }
        if weight != 0.0 {
            sum = sum + weight * grid_cell_density(cell.x, cell.y, cell.z);
        }
    }
    return sum;
}

fn field_extinction_per_density() -> f32 {
    return density_grid.box_hi.w;
}

// The ray's one span inside the box (slab method), none when it misses.
fn field_ray_spans(origin: vec3<f32>, direction: vec3<f32>) -> RaySpans {
    var spans = ray_spans_none();
    var enter = 0.0;
    var exit = INFINITE_DISTANCE;
    for (var a = 0; a < 3; a++) {
        let lo = density_grid.box_lo[a];
        let hi = density_grid.box_hi[a];
        if direction[a] == 0.0 {
            if origin[a] < lo || origin[a] > hi {
                return spans;
            }
            continue;
        }
        let t0 = (lo - origin[a]) / direction[a];
        let t1 = (hi - origin[a]) / direction[a];
        enter = max(enter, min(t0, t1));
        exit = min(exit, max(t0, t1));
    }
    if enter <= exit {
        spans.spans[0] = vec2<f32>(enter, exit);
        spans.count = 1u;
    }
    return spans;
}
