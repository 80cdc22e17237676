//! The WGSL sources, composed with the shared declarations and validated with naga.

use thiserror::Error;

/// `shaders/common.wgsl`: the structs and constants every pipeline shares.
pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");

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
    body: include_str!("../../../shaders/tessellate.wgsl"),
};

/// `shaders/adaptive.wgsl`: per-frame sample counts, their prefix sum, and the de Casteljau
/// kernels writing exactly those samples.
pub const ADAPTIVE: ShaderSource = ShaderSource {
    file: "adaptive.wgsl",
    body: include_str!("../../../shaders/adaptive.wgsl"),
};

/// `shaders/lines.wgsl`: anti-aliased polylines.
pub const LINES: ShaderSource = ShaderSource {
    file: "lines.wgsl",
    body: include_str!("../../../shaders/lines.wgsl"),
};

/// `shaders/points.wgsl`: anti-aliased discs.
pub const POINTS: ShaderSource = ShaderSource {
    file: "points.wgsl",
    body: include_str!("../../../shaders/points.wgsl"),
};

/// Every pipeline shader.
pub const ALL: [ShaderSource; 4] = [TESSELLATE, ADAPTIVE, LINES, POINTS];

/// A shader that naga rejects, with the message and source span it printed.
#[derive(Debug, Clone, Error)]
#[error("{message}")]
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

    /// Where line `line` (1-based) of [`ShaderSource::composed`] comes from: the file and
    /// its own line there (`common.wgsl` is prepended, then one joining newline).
    #[must_use]
    pub fn origin(&self, line: u32) -> (&'static str, u32) {
        let common_lines = COMMON.lines().count() as u32 + 1;
        if line <= common_lines {
            ("common.wgsl", line)
        } else {
            (self.file, line - common_lines)
        }
    }

    /// `shaders/FILE:LINE:COLUMN: MESSAGE` and the offending line, with the line counted
    /// in the file that holds it (not in the composed source).
    fn report(&self, source: &str, message: &str, at: Option<naga::SourceLocation>) -> String {
        match at {
            Some(loc) => {
                let (file, line) = self.origin(loc.line_number);
                let text = source
                    .lines()
                    .nth(loc.line_number as usize - 1)
                    .unwrap_or_default();
                format!(
                    "shaders/{file}:{line}:{}: {message}\n  {line} | {text}",
                    loc.line_position
                )
            }
            None => format!("shaders/{}: {message}", self.file),
        }
    }

    /// Parses and validates the composed source with naga (no adapter needed).
    ///
    /// # Errors
    /// [`ShaderError`] with naga's message, located at the file and line that hold the
    /// fault.
    pub fn validate(&self) -> Result<(naga::Module, naga::valid::ModuleInfo), ShaderError> {
        let source = self.composed();
        let module = naga::front::wgsl::parse_str(&source).map_err(|e| ShaderError {
            file: self.file,
            // The first label with a real span (some errors carry an empty primary one).
            message: self.report(
                &source,
                e.message(),
                e.labels()
                    .find(|(span, _)| span.to_range().is_some_and(|r| !r.is_empty()))
                    .map(|(span, _)| span.location(&source)),
            ),
        })?;
        let info = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .map_err(|e| ShaderError {
            file: self.file,
            message: self.report(&source, &e.as_inner().to_string(), e.location(&source)),
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
