//! The cloud shadow-map pass on a GPU against its f32 CPU twin, and the twin against the
//! exact f64 reference (skipped without an adapter, see skyscape-harness: adapter → run;
//! none and SKYSCAPE_REQUIRE_GPU=1 → fail; none → a visible SKIPPED line).
#![cfg(feature = "gpu")]

use cloudlight::CloudVolume;
use cloudlight::gpu::{ShadowMapGpuError, ShadowMapPass};
use cloudlight::shadow_map::{
    DEFAULT_STEPS, ShadowGrid, ShadowMapPlan, map_error, shadow_map, shadow_map_reference,
};

/// A lumpy blob on a non-cubic grid (13×10×7 cells of 30 m, σ_t 0.02 /m).
fn volume() -> CloudVolume {
    let dims = [13u32, 10, 7];
    let mut density = Vec::new();
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let p = [x, y, z].map(f64::from);
                let c = [6.0, 4.5, 3.0];
                let r2: f64 = (0..3).map(|a| ((p[a] - c[a]) / c[a]).powi(2)).sum();
                let wobble = 0.2 * ((x * 7 + y * 3 + z * 5) % 4) as f64 / 3.0;
                density.push((0.8 * (1.0 + wobble) * (1.0 - r2).max(0.0)) as f32);
            }
        }
    }
    CloudVolume::new(dims, [-50.0, 20.0, 1000.0], 30.0, 0.02, density).unwrap()
}

fn sun(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// The minimum corner of a 37×29 grid of 12 m texels centred under the blob's centre
/// (145, 170, 1105) along the sun ray (straight under it for a sun at or below the horizon).
fn shadow_corner(l: [f64; 3], ground: f64) -> [f64; 2] {
    let lift = if l[2] > 0.0 {
        (1105.0 - ground) / l[2]
    } else {
        0.0
    };
    [145.0 - lift * l[0] - 222.0, 170.0 - lift * l[1] - 174.0]
}

fn run(
    gpu: &skyscape_harness::GpuContext,
    pass: &mut ShadowMapPass,
    v: &CloudVolume,
    plan: &ShadowMapPlan,
) -> Vec<f32> {
    pass.prepare(&gpu.device, &gpu.queue, v, plan).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let bytes =
        skyscape_harness::read_texture(gpu, "cloudlight shadow map", pass.texture().unwrap())
            .unwrap();
    pass.decode(&bytes).unwrap()
}

#[test]
fn shadow_map_pass_matches_the_f32_twin() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("shadow_map_pass_matches_the_f32_twin") else {
        return;
    };
    let v = volume();
    let mut pass = ShadowMapPass::new(&gpu.device).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    assert!(matches!(
        pass.encode(&mut encoder),
        Err(ShadowMapGpuError::EncodeBeforePrepare)
    ));
    // A 37×29 grid (not a multiple of the 8×8 workgroup) of 12 m texels under the blob and
    // beyond it; ground at 0 m, and once at 1050 m (inside the cloud's lower cells).
    for (ground, elevation, azimuth, steps) in [
        (0.0, 90.0, 0.0, DEFAULT_STEPS),
        (0.0, 60.0, 30.0, DEFAULT_STEPS),
        (0.0, 10.0, 200.0, 32),
        (0.0, 2.0, 75.0, DEFAULT_STEPS),
        (0.0, -10.0, 30.0, 8),
        (1050.0, -20.0, 120.0, DEFAULT_STEPS),
        (1050.0, 45.0, 0.0, 1),
    ] {
        let grid = ShadowGrid::new(
            shadow_corner(sun(elevation, azimuth), ground),
            12.0,
            [37, 29],
            ground,
        )
        .unwrap();
        let plan = ShadowMapPlan::new(grid, sun(elevation, azimuth), steps).unwrap();
        let gpu_map = run(gpu, &mut pass, &v, &plan);
        let twin = shadow_map::<f32, _>(&v, &plan);
        let worst = gpu_map
            .iter()
            .zip(&twin)
            .map(|(g, c)| (g - c).abs())
            .fold(0.0f32, f32::max);
        let shaded = twin.iter().filter(|&&t| t < 0.99).count();
        eprintln!(
            "ground {ground} m, sun {elevation}° az {azimuth}°, {steps} steps: {shaded} texels \
             shaded, worst |GPU − twin| {worst:e}"
        );
        // Same march, same order; they differ in the density lookup (WGSL in f32, the twin
        // in f64 rounded once: a sample's cell coordinate carries ~3 ULP of |p|/voxel, i.e.
        // ≤ 1e-5 cell here, moving ρ ≤ 1e-5·Δρ per cell), in WGSL's exp (3 + 2τ ULP) and
        // division (2.5 ULP). With τ ≤ 10 every one of these is below 1e-5 of the light.
        assert!(worst <= 1e-5, "worst {worst:e}");
        if elevation > 0.0 && ground == 0.0 && elevation > 5.0 {
            assert!(shaded > 20, "the blob shades the grid ({shaded})");
        }
    }
}

/// The f32 twin (the GPU's march) against the exact f64 reference at the default steps.
#[test]
fn the_twin_against_the_exact_reference() {
    let v = volume();
    for (elevation, azimuth) in [(60.0, 30.0), (10.0, 200.0)] {
        let grid = ShadowGrid::new(
            shadow_corner(sun(elevation, azimuth), 0.0),
            12.0,
            [37, 29],
            0.0,
        )
        .unwrap();
        let plan = ShadowMapPlan::new(grid, sun(elevation, azimuth), DEFAULT_STEPS).unwrap();
        let exact = shadow_map_reference(&v, &plan).unwrap();
        let (rmse, max) = map_error(&shadow_map::<f32, _>(&v, &plan), &exact).unwrap();
        eprintln!("sun {elevation}°: twin vs exact RMSE {rmse:.2e}, max {max:.2e}");
        assert!(rmse < 2e-3 && max < 1e-2, "rmse {rmse}, max {max}");
    }
}

/// Huge densities (f32::MAX) with σ_t 0 and 1 /m, and zero density: the pass stays
/// finite and in [0, 1] and agrees with the twin (saturation at 1e30, never 0·∞).
#[test]
fn shadow_map_pass_survives_extreme_volumes() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("shadow_map_pass_survives_extreme_volumes")
    else {
        return;
    };
    let mut pass = ShadowMapPass::new(&gpu.device).unwrap();
    for (value, sigma) in [(f32::MAX, 0.0), (f32::MAX, 1.0), (0.0, 1.0), (1e30, 1e-3)] {
        let v =
            CloudVolume::new([3, 2, 2], [0.0, 0.0, 100.0], 10.0, sigma, vec![value; 12]).unwrap();
        let grid = ShadowGrid::new([-20.0, -20.0], 5.0, [16, 12], 0.0).unwrap();
        let plan = ShadowMapPlan::new(grid, sun(70.0, 10.0), 16).unwrap();
        let gpu_map = run(gpu, &mut pass, &v, &plan);
        let twin = shadow_map::<f32, _>(&v, &plan);
        for (g, c) in gpu_map.iter().zip(&twin) {
            assert!(
                (0.0..=1.0).contains(g),
                "density {value}, σ {sigma}: GPU {g}"
            );
            assert!(
                (g - c).abs() <= 1e-6,
                "density {value}, σ {sigma}: {g} vs {c}"
            );
        }
        eprintln!(
            "density {value:e}, σ_t {sigma}: GPU min {}",
            gpu_map.iter().copied().fold(1.0f32, f32::min)
        );
    }
}
