//! The WGSL sources, composed with the shared declarations and validated with naga.

use thiserror::Error;

/// `shaders/common.wgsl`: the structs and constants every pipeline shares.
pub const COMMON: &str = include_str!("../../shaders/common.wgsl");

/// One pipeline's shader file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShaderSource {
    /// The file name under `shaders/`.
    pub file: &'static str,
    /// Its text (without the shared declarations).
    pub body: &'static str,
}

/// `shaders/tessellate.wgsl`: the de Casteljau compute kernel.
pub const TESSELLATE: ShaderSource = ShaderSource {
    file: "tessellate.wgsl",
    body: include_str!("../../shaders/tessellate.wgsl"),
};

/// `shaders/lines.wgsl`: anti-aliased polylines.
pub const LINES: ShaderSource = ShaderSource {
    file: "lines.wgsl",
    body: include_str!("../../shaders/lines.wgsl"),
};

/// `shaders/points.wgsl`: anti-aliased discs.
pub const POINTS: ShaderSource = ShaderSource {
    file: "points.wgsl",
    body: include_str!("../../shaders/points.wgsl"),
};

/// Every pipeline shader.
pub const ALL: [ShaderSource; 3] = [TESSELLATE, LINES, POINTS];

/// A shader that naga rejects, with the message and source span it printed.
#[derive(Debug, Clone, Error)]
#[error("shaders/{file}: {message}")]
pub struct ShaderError {
    /// The file.
    pub file: &'static str,
    /// naga's report, with the offending source lines.
    pub message: String,
}

impl ShaderSource {
    /// The full source: the shared declarations, then this file.
    #[must_use]
    pub fn composed(&self) -> String {
        format!("{COMMON}\n{}", self.body)
    }

    /// Parses and validates the composed source with naga (no adapter needed).
    ///
    /// # Errors
    /// [`ShaderError`] with naga's report and source span.
    pub fn validate(&self) -> Result<(naga::Module, naga::valid::ModuleInfo), ShaderError> {
        let source = self.composed();
        let module = naga::front::wgsl::parse_str(&source).map_err(|e| ShaderError {
            file: self.file,
            message: e.emit_to_string_with_path(&source, self.file),
        })?;
        let info = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .map_err(|e| ShaderError {
            file: self.file,
            message: e.emit_to_string_with_path(&source, self.file),
        })?;
        Ok((module, info))
    }

    /// The shader module on `device`.
    #[must_use]
    pub fn module(&self, device: &wgpu::Device) -> wgpu::ShaderModule {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(self.file),
            source: wgpu::ShaderSource::Wgsl(self.composed().into()),
        })
    }
}
