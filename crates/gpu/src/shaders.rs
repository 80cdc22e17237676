//! The WGSL sources, composed with the shared declarations and validated with naga.
//!
//! Every pipeline's source is `common.wgsl` (the structs and constants every pipeline
//! shares), then, for the two tessellators, `bezier.wgsl` (the evaluation both kernels
//! share), then the pipeline's own file.

use thiserror::Error;

/// `shaders/common.wgsl`: the structs and constants every pipeline shares.
pub const COMMON: &str = include_str!("../../../shaders/common.wgsl");

/// `shaders/bezier.wgsl`: the Bézier evaluation both tessellators share (the cubic's
/// Bernstein form, the quartic's de Casteljau, Horner's rule for every other degree).
pub const BEZIER: &str = include_str!("../../../shaders/bezier.wgsl");

/// One pipeline's shader file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShaderSource {
    /// The file name under `shaders/`.
    pub file: &'static str,
    /// Its text (without the shared declarations).
    pub body: &'static str,
    /// Whether `bezier.wgsl` goes before it (the tessellators).
    pub evaluates: bool,
    /// Another shader whose text goes before this one's, after the shared files (the
    /// comb's kernels read the adaptive tessellator's work and bindings).
    pub follows: Option<&'static ShaderSource>,
}

/// `shaders/tessellate.wgsl`: the de Casteljau compute kernel.
pub const TESSELLATE: ShaderSource = ShaderSource {
    file: "tessellate.wgsl",
    body: include_str!("../../../shaders/tessellate.wgsl"),
    evaluates: true,
    follows: None,
};

/// `shaders/adaptive.wgsl`: per-frame sample counts, their prefix sum, and the kernels
/// writing exactly those samples.
pub const ADAPTIVE: ShaderSource = ShaderSource {
    file: "adaptive.wgsl",
    body: include_str!("../../../shaders/adaptive.wgsl"),
    evaluates: true,
    follows: None,
};

/// `shaders/comb.wgsl`: the curvature comb's kernels, composed after `adaptive.wgsl`
/// (whose work ranges and bindings they read). CPU twin: [`crate::twin::comb_point_and_curvature`]
/// and [`crate::twin::comb_hair`].
pub const COMB: ShaderSource = ShaderSource {
    file: "comb.wgsl",
    body: include_str!("../../../shaders/comb.wgsl"),
    evaluates: true,
    follows: Some(&ADAPTIVE),
};

/// `shaders/lines.wgsl`: anti-aliased polylines.
pub const LINES: ShaderSource = ShaderSource {
    file: "lines.wgsl",
    body: include_str!("../../../shaders/lines.wgsl"),
    evaluates: false,
    follows: None,
};

/// `shaders/points.wgsl`: anti-aliased discs.
pub const POINTS: ShaderSource = ShaderSource {
    file: "points.wgsl",
    body: include_str!("../../../shaders/points.wgsl"),
    evaluates: false,
    follows: None,
};

/// `shaders/layer.wgsl`: curves and curvature combs rasterized into the layer, and the
/// pass blending the layer over the target.
pub const LAYER: ShaderSource = ShaderSource {
    file: "layer.wgsl",
    body: include_str!("../../../shaders/layer.wgsl"),
    evaluates: false,
    follows: None,
};

/// Every pipeline shader.
pub const ALL: [ShaderSource; 6] = [TESSELLATE, ADAPTIVE, COMB, LINES, POINTS, LAYER];

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
    /// The shared files that go before this one, in order, with their names.
    #[must_use]
    pub fn preludes(&self) -> Vec<(&'static str, &'static str)> {
        let mut out = vec![("common.wgsl", COMMON)];
        if self.evaluates {
            out.push(("bezier.wgsl", BEZIER));
        }
        if let Some(before) = self.follows {
            out.push((before.file, before.body));
        }
        out
    }

    /// The full source: the shared declarations, then this file.
    #[must_use]
    pub fn composed(&self) -> String {
        self.composed_with(self.body)
    }

    /// The full source with `body` in place of this file's text (the self-test's tests
    /// compose deliberately broken kernels this way).
    #[must_use]
    pub fn composed_with(&self, body: &str) -> String {
        let mut out = String::new();
        for (_, text) in self.preludes() {
            out.push_str(text);
            out.push('\n');
        }
        out.push_str(body);
        out
    }

    /// Where line `line` (1-based) of [`ShaderSource::composed`] comes from: the file and
    /// its own line there (each prelude is followed by one joining newline).
    #[must_use]
    pub fn origin(&self, line: u32) -> (&'static str, u32) {
        let mut line = line;
        for (file, text) in self.preludes() {
            let lines = text.lines().count() as u32 + 1;
            if line <= lines {
                return (file, line);
            }
            line -= lines;
        }
        (self.file, line)
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
