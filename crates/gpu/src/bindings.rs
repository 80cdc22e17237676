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

/// The camera uniform's stages: the line and point pipelines' vertices, the comb layer's
/// rasterizer and its full-screen pass.
const CAMERA_STAGES: wgpu::ShaderStages = wgpu::ShaderStages::VERTEX
    .union(wgpu::ShaderStages::FRAGMENT)
    .union(wgpu::ShaderStages::COMPUTE);

/// `shaders/lines.wgsl` and `shaders/points.wgsl`: group 0 the camera (uniform), group 1
/// the vertices and the style table (read).
#[must_use]
pub fn draw() -> Vec<Vec<wgpu::BindGroupLayoutEntry>> {
    let v = wgpu::ShaderStages::VERTEX;
    vec![
        vec![uniform(0, CAMERA_STAGES)],
        vec![storage(0, true, v), storage(1, true, v)],
    ]
}

/// `shaders/layer.wgsl` (the layer): group 0 the camera; group 1 split among its entry
/// points — the comb rasterizer's hairs, envelope, their two style tables and the comb's
/// arguments (read) and the layer (read-write; bindings 0–5, [`comb_raster`]), the
/// full-screen pass's layer and the scene's curve styles (read; bindings 6 and 10,
/// [`layer_blend`]) and the curve rasterizer's
/// layer, samples, styles and work buffer (5 and 7–9, [`curve_raster`]). This is their
/// union, as the shader declares them.
#[must_use]
pub fn layer() -> Vec<Vec<wgpu::BindGroupLayoutEntry>> {
    let mut group = comb_raster();
    group.extend(layer_blend());
    group.extend(curve_raster().into_iter().filter(|e| e.binding != 5));
    vec![vec![uniform(0, CAMERA_STAGES)], group]
}

/// Group 1 of `raster_comb` in `shaders/layer.wgsl`.
#[must_use]
pub fn comb_raster() -> Vec<wgpu::BindGroupLayoutEntry> {
    let c = wgpu::ShaderStages::COMPUTE;
    let mut group: Vec<_> = (0..5).map(|b| storage(b, true, c)).collect();
    group.push(storage(5, false, c));
    group
}

/// Group 1 of `vs_layer`/`fs_layer` in `shaders/layer.wgsl`.
#[must_use]
pub fn layer_blend() -> Vec<wgpu::BindGroupLayoutEntry> {
    let f = wgpu::ShaderStages::FRAGMENT;
    vec![storage(6, true, f), storage(10, true, f)]
}

/// Group 1 of `raster_curves` in `shaders/layer.wgsl`: the layer (read-write), then a
/// chunk's samples, styles and work buffer (read).
#[must_use]
pub fn curve_raster() -> Vec<wgpu::BindGroupLayoutEntry> {
    let c = wgpu::ShaderStages::COMPUTE;
    vec![
        storage(5, false, c),
        storage(7, true, c),
        storage(8, true, c),
        storage(9, true, c),
    ]
}
