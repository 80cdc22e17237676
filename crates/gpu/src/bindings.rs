//! The bind-group layouts of every pipeline, in one place, as plain data: the pipelines
//! are built from them, and a test checks them against naga's reflection of the WGSL
//! (each `@group(g) @binding(b)` global: uniform, or storage read-only / read-write).

/// A uniform buffer at `binding`, visible to `stages`.
#[must_use]
pub fn uniform(binding: u32, stages: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A storage buffer at `binding`, visible to `stages`.
#[must_use]
pub fn storage(
    binding: u32,
    read_only: bool,
    stages: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// `shaders/tessellate.wgsl`, group 0: parameters (uniform), control points and records
/// (read), samples (read-write).
#[must_use]
pub fn tessellate() -> Vec<Vec<wgpu::BindGroupLayoutEntry>> {
    let c = wgpu::ShaderStages::COMPUTE;
    vec![vec![
        uniform(0, c),
        storage(1, true, c),
        storage(2, true, c),
        storage(3, false, c),
    ]]
}

/// `shaders/adaptive.wgsl`, group 0: the frame and the dispatch's range (uniforms), control
/// points and segments (read), the work buffer and the samples (read-write); group 1, the
/// comb pass's alone: its uniform, then the hairs, the envelope and the hairs' draw
/// arguments (read-write).
#[must_use]
pub fn adaptive() -> Vec<Vec<wgpu::BindGroupLayoutEntry>> {
    let c = wgpu::ShaderStages::COMPUTE;
    vec![
        vec![
            uniform(0, c),
            uniform(1, c),
            storage(2, true, c),
            storage(3, true, c),
            storage(4, false, c),
            storage(5, false, c),
        ],
        vec![
            uniform(0, c),
            storage(1, false, c),
            storage(2, false, c),
            storage(3, false, c),
        ],
    ]
}

/// `shaders/lines.wgsl` and `shaders/points.wgsl`: group 0 the camera (uniform), group 1
/// the vertices and the style table (read).
#[must_use]
pub fn draw() -> Vec<Vec<wgpu::BindGroupLayoutEntry>> {
    let v = wgpu::ShaderStages::VERTEX;
    vec![
        vec![uniform(0, v)],
        vec![storage(0, true, v), storage(1, true, v)],
    ]
}
