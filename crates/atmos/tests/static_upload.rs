//! The static tables written from a CPU bake (`AtmosphereTables::write_static_luts`)
//! instead of baked on the GPU: the textures then hold the CPU twin's texels exactly,
//! and tables of another atmosphere or other settings are refused naming the field.

use atmos::Atmosphere;
use atmos::gpu::AtmosphereLuts;
use atmos::lut::{LutSettings, StaticLuts};

fn texels(gpu: &skyscape_harness::GpuContext, texture: &wgpu::Texture) -> Vec<f32> {
    let bytes = skyscape_harness::read_texture(gpu, "atmos static LUT", texture).expect("readback");
    bytemuck::cast_slice::<u8, f32>(&bytes).to_vec()
}

#[test]
fn written_tables_hold_the_cpu_texels_exactly() {
    let Some(gpu) =
        skyscape_harness::gpu_or_skip("atmos::static_upload written_tables_hold_the_cpu_texels")
    else {
        return;
    };
    let earth = Atmosphere::earth();
    let settings = LutSettings::small();
    let cpu = StaticLuts::bake(&earth, &settings).unwrap();
    let gpu_luts = AtmosphereLuts::new(&gpu.device, &earth, &settings).unwrap();
    // Never baked on the GPU: whatever the textures hold comes from the write.
    gpu_luts.write_static_luts(&gpu.queue, &cpu).unwrap();
    let flat =
        |lut: &atmos::lut::Lut2d| -> Vec<f32> { lut.texels.iter().flatten().copied().collect() };
    let transmittance = texels(gpu, gpu_luts.transmittance_texture());
    let multiple_scattering = texels(gpu, gpu_luts.multiple_scattering_texture());
    assert_eq!(transmittance, flat(&cpu.transmittance));
    assert_eq!(multiple_scattering, flat(&cpu.multiple_scattering));
    assert!(multiple_scattering.iter().any(|&v| v > 0.0));
}

#[test]
fn tables_of_another_atmosphere_or_size_are_refused() {
    let Some(gpu) =
        skyscape_harness::gpu_or_skip("atmos::static_upload tables_of_another_atmosphere")
    else {
        return;
    };
    let earth = Atmosphere::earth();
    let settings = LutSettings::small();
    let gpu_luts = AtmosphereLuts::new(&gpu.device, &earth, &settings).unwrap();
    let hazy = Atmosphere {
        mie_scale_height: 2.0 * earth.mie_scale_height,
        ..earth.clone()
    };
    let other_air = StaticLuts::bake(&hazy, &settings).unwrap();
    let message = gpu_luts
        .write_static_luts(&gpu.queue, &other_air)
        .unwrap_err()
        .to_string();
    assert!(message.contains("`atmosphere`"), "{message}");
    let larger = StaticLuts::bake(&earth, &LutSettings::default()).unwrap();
    let message = gpu_luts
        .write_static_luts(&gpu.queue, &larger)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("settings.transmittance_width"),
        "{message}"
    );
}
