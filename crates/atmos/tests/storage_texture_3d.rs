//! wgpu's GL backend and a `texture_storage_3d` (the aerial-perspective volume's
//! bake, shaders/atmos/lut_aerial_perspective.wgsl): one dispatch writes z + 1 to every
//! texel of slice z of a 4×4×8 `rgba32float` 3-D storage texture, and the readback
//! shows which slices were written. Vulkan (lavapipe): every slice. GL (wgpu-hal
//! 30.0.1 on Mesa llvmpipe): wgpu-hal's GL bind group binds a `D3` storage view as
//! one layer (`glBindImageTexture(.., layered = GL_FALSE, layer = 0, ..)`: its
//! `ImageBinding::array_layer` is `None`, i.e. layered, only for `D2Array` and
//! `CubeArray` views), so every slice but the first keeps its zero initialisation.
//! On GL the test passes while that limitation holds and fails once wgpu writes every
//! slice, so that docs/render-methods.md's GL section gets updated.

const SIZE: [u32; 3] = [4, 4, 8];

const SHADER: &str = "
@group(0) @binding(0) var volume: texture_storage_3d<rgba32float, write>;

@compute @workgroup_size(4, 4, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    textureStore(volume, id, vec4<f32>(f32(id.z) + 1.0));
}
";

/// Each slice's value if all its texels agree, else NaN.
fn slices_written(gpu: &skyscape_harness::GpuContext) -> Vec<f32> {
    let device = &gpu.device;
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("storage 3d probe"),
        size: wgpu::Extent3d {
            width: SIZE[0],
            height: SIZE[1],
            depth_or_array_layers: SIZE[2],
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D3,
        format: wgpu::TextureFormat::Rgba32Float,
        usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("storage 3d probe"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format: wgpu::TextureFormat::Rgba32Float,
                view_dimension: wgpu::TextureViewDimension::D3,
            },
            count: None,
        }],
    });
    let view = texture.create_view(&Default::default());
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("storage 3d probe"),
        layout: &layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::TextureView(&view),
        }],
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("storage 3d probe"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("storage 3d probe"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("storage 3d probe"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(1, 1, SIZE[2]);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes =
        skyscape_harness::read_texture(gpu, "storage 3d probe", &texture).expect("readback");
    let values: &[f32] = bytemuck::cast_slice(&bytes);
    values
        .chunks((SIZE[0] * SIZE[1] * 4) as usize)
        .map(|slice| {
            if slice.iter().all(|v| *v == slice[0]) {
                slice[0]
            } else {
                f32::NAN
            }
        })
        .collect()
}

#[test]
fn every_slice_of_a_3d_storage_texture_is_written_except_on_gl() {
    let Some(gpu) = skyscape_harness::gpu_or_skip(
        "atmos::storage_texture_3d every_slice_of_a_3d_storage_texture_is_written_except_on_gl",
    ) else {
        return;
    };
    let got = slices_written(gpu);
    eprintln!(
        "{:?}: slice z holds {got:?} (written: z + 1)",
        gpu.info.backend
    );
    let expected: Vec<f32> = (0..SIZE[2]).map(|z| z as f32 + 1.0).collect();
    if gpu.info.backend == wgpu::Backend::Gl {
        assert!(
            got[1..].iter().all(|v| *v == 0.0),
            "wgpu's GL backend now writes slices beyond the first ({got:?}): update \
             docs/render-methods.md's GL section"
        );
    } else {
        assert_eq!(got, expected);
    }
}
