//! The Rust GPU structs against naga's layout of their WGSL twins, and every shader
//! validated with naga (no adapter needed).

use naga::{Module, TypeInner};
use splinescope_gpu::layout::{
    ADAPTIVE_SEGMENT_LANES, COMB_ALL, COMB_CAPPED, COMB_HAIRS, COMB_HIDDEN, COMB_PARITY, GpuCamera,
    GpuComb, GpuControlPoint, GpuFrame, GpuLineStyle, GpuRecord, GpuSegment, GpuTessParams,
    GpuVertex, MAX_GPU_DEGREE, SCAN_BLOCK, TESSELLATE_KERNELS, TESSELLATE_WORKGROUP_SIZE,
    WORK_HEADER,
};
use splinescope_gpu::shaders::{self, ALL};

/// The WGSL struct `name`: its size and its members' (name, offset).
fn wgsl_struct(module: &Module, name: &str) -> (usize, Vec<(String, usize)>) {
    let ty = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("struct {name} not in the WGSL"))
        .1;
    match &ty.inner {
        TypeInner::Struct { members, span } => (
            *span as usize,
            members
                .iter()
                .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
                .collect(),
        ),
        other => panic!("{name} is not a struct: {other:?}"),
    }
}

macro_rules! assert_twin {
    ($module:expr, $wgsl:literal, $rust:ty, [$($field:ident),* $(,)?]) => {{
        let (span, members) = wgsl_struct($module, $wgsl);
        assert_eq!(span, size_of::<$rust>(), "size of {} vs {}", $wgsl, stringify!($rust));
        let rust: Vec<(String, usize)> =
            vec![$((stringify!($field).to_owned(), std::mem::offset_of!($rust, $field))),*];
        assert_eq!(members, rust, "members of {} vs {}", $wgsl, stringify!($rust));
    }};
}

fn constant_u32(module: &Module, name: &str) -> u32 {
    let c = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("const {name} not in the WGSL"))
        .1;
    match module.global_expressions[c.init] {
        naga::Expression::Literal(naga::Literal::U32(v)) => v,
        ref other => panic!("{name} is not a u32 literal: {other:?}"),
    }
}

#[test]
fn every_shader_validates() {
    for source in ALL {
        if let Err(e) = source.validate() {
            panic!("{e}");
        }
    }
}

#[test]
fn adaptive_constants_match_their_rust_twins() {
    // The comb's module holds the adaptive tessellator's text too.
    let (module, _) = shaders::COMB.validate().expect("valid");
    assert_eq!(constant_u32(&module, "SCAN_BLOCK"), SCAN_BLOCK);
    assert_eq!(
        constant_u32(&module, "SEGMENT_LANES"),
        ADAPTIVE_SEGMENT_LANES
    );
    assert_eq!(constant_u32(&module, "WORK_COUNTS") as usize, WORK_HEADER);
    assert_eq!(constant_u32(&module, "COMB_ALL"), COMB_ALL);
    assert_eq!(constant_u32(&module, "COMB_HIDDEN"), COMB_HIDDEN);
    assert_eq!(constant_u32(&module, "COMB_CAPPED"), COMB_CAPPED);
    assert_eq!(constant_u32(&module, "COMB_PARITY"), COMB_PARITY);
    assert_eq!(constant_u32(&module, "COMB_HAIRS"), COMB_HAIRS);
    let m = &module;
    assert_twin!(m, "Comb", GpuComb, [scale, cap, curve, _padding]);
}

#[test]
fn gpu_structs_match_their_wgsl_twins() {
    // Each pipeline composes the shared declarations, so check them in every module.
    for source in ALL {
        let (module, _) = source.validate().expect("valid");
        let m = &module;
        assert_twin!(m, "Vertex", GpuVertex, [position, id]);
        assert_twin!(m, "ControlPoint", GpuControlPoint, [position, weight]);
        assert_twin!(
            m,
            "Record",
            GpuRecord,
            [
                first_point,
                degree,
                curve,
                first_sample,
                sample_count,
                u0,
                u1,
                sample_offset,
                rational
            ]
        );
        assert_twin!(
            m,
            "Segment",
            GpuSegment,
            [first_point, degree, curve, fixed, rational]
        );
        assert_twin!(
            m,
            "Frame",
            GpuFrame,
            [
                clip_from_world,
                viewport_px,
                tolerance_px,
                cull_margin_px,
                segment_count,
                capacity,
                max_count,
                min_count
            ]
        );
        assert_twin!(
            m,
            "TessParams",
            GpuTessParams,
            [record_start, record_end, groups_x, _padding]
        );
        assert_twin!(
            m,
            "Camera",
            GpuCamera,
            [clip_from_world, viewport_px, width_scale, _padding]
        );
        assert_twin!(
            m,
            "LineStyle",
            GpuLineStyle,
            [color, width_px, dash_px, order, flags]
        );
        assert_eq!(constant_u32(m, "MAX_DEGREE") as usize, MAX_GPU_DEGREE);
        assert_eq!(
            constant_u32(m, "TESSELLATE_WORKGROUP_SIZE"),
            TESSELLATE_WORKGROUP_SIZE
        );
        assert_eq!(
            constant_u32(m, "LAYER_WORKGROUP"),
            splinescope_gpu::layout::LAYER_WORKGROUP
        );
        assert_eq!(
            constant_u32(m, "LAYER_GROUPS"),
            splinescope_gpu::layout::LAYER_GROUPS
        );
        assert_eq!(
            constant_u32(m, "LAYER_RUN"),
            splinescope_gpu::layout::LAYER_RUN
        );
    }
}

#[test]
fn kernel_workgroup_and_scratch_match_the_rust_constants() {
    let (module, _) = shaders::TESSELLATE.validate().expect("valid");
    for (entry, _, _) in TESSELLATE_KERNELS {
        let ep = module
            .entry_points
            .iter()
            .find(|e| e.name == entry)
            .unwrap_or_else(|| panic!("entry point {entry}"));
        assert_eq!(
            ep.workgroup_size,
            [TESSELLATE_WORKGROUP_SIZE, 1, 1],
            "{entry}"
        );
    }
    // Both tessellators' general kernels sum by Horner's rule (bezier.wgsl): no
    // tessellation kernel, and no evaluation function they call, keeps a scratch array.
    let evaluation = [
        "control_point",
        "cubic",
        "cubic_bernstein",
        "quartic",
        "bernstein_horner",
        "bernstein_horner4",
        "control_point4",
        "rational_point",
        "rational_quadratic",
        "rational_cubic",
        "general_point",
    ];
    for source in [shaders::TESSELLATE, shaders::ADAPTIVE, shaders::COMB] {
        let (module, _) = source.validate().expect("valid");
        for ep in module
            .entry_points
            .iter()
            .filter(|e| e.name.starts_with("tessellate"))
        {
            assert!(
                ep.function
                    .local_variables
                    .iter()
                    .all(|(_, v)| !matches!(module.types[v.ty].inner, TypeInner::Array { .. })),
                "{}: {} keeps no array",
                source.file,
                ep.name
            );
        }
        for (_, f) in module
            .functions
            .iter()
            .filter(|(_, f)| f.name.as_deref().is_some_and(|n| evaluation.contains(&n)))
        {
            assert!(
                f.local_variables
                    .iter()
                    .all(|(_, v)| !matches!(module.types[v.ty].inner, TypeInner::Array { .. })),
                "{}: {:?} keeps no array",
                source.file,
                f.name
            );
        }
        assert!(
            evaluation.iter().all(|name| module
                .functions
                .iter()
                .any(|(_, f)| f.name.as_deref() == Some(name))),
            "{}: the shared evaluation functions are in the module",
            source.file
        );
    }
}

#[test]
fn a_broken_shader_is_reported_with_its_file_and_span() {
    let broken = shaders::ShaderSource {
        file: "broken.wgsl",
        body: "fn f() -> f32 { return undefined_name; }",
        evaluates: false,
        follows: None,
    };
    let err = broken.validate().expect_err("must fail").to_string();
    assert!(err.contains("broken.wgsl"), "{err}");
    assert!(err.contains("undefined_name"), "{err}");
}

/// Errors point at the line of the file that holds them, not of the composed source
/// (`common.wgsl` is prepended): a parse error and a validation error on line 3 of the
/// body, and the body's first line, are reported at those lines.
#[test]
fn shader_errors_name_the_right_file_and_line() {
    let parse = shaders::ShaderSource {
        file: "parse.wgsl",
        body: "// one\n// two\nfn f() -> f32 { return 1.0 +; }\n",
        evaluates: false,
        follows: None,
    };
    let err = parse.validate().expect_err("must fail").to_string();
    assert!(err.starts_with("shaders/parse.wgsl:3:"), "{err}");
    assert!(err.contains("3 | fn f() -> f32 { return 1.0 +; }"), "{err}");
    let unknown = shaders::ShaderSource {
        file: "unknown.wgsl",
        body: "// one\n// two\nfn g() -> u32 { return h(); }\n",
        evaluates: false,
        follows: None,
    };
    let err = unknown.validate().expect_err("must fail").to_string();
    assert!(err.starts_with("shaders/unknown.wgsl:3:24:"), "{err}");
    // The mapping itself: the composed source's first line after common.wgsl is line 1.
    let common_lines = shaders::COMMON.lines().count() as u32;
    assert_eq!(parse.origin(1), ("common.wgsl", 1));
    assert_eq!(parse.origin(common_lines + 2), ("parse.wgsl", 1));
    let composed = parse.composed();
    assert_eq!(
        composed.lines().nth(common_lines as usize + 1),
        Some("// one")
    );
}

/// The bind-group layouts the pipelines are built from agree with naga's reflection of
/// each shader: the same (group, binding) pairs, uniform where the WGSL says uniform,
/// storage with the same access.
#[test]
fn bind_group_layouts_match_the_shaders() {
    use splinescope_gpu::bindings;
    type Binding = (u32, u32, String);
    fn from_layouts(groups: &[Vec<wgpu::BindGroupLayoutEntry>]) -> Vec<Binding> {
        let mut out = Vec::new();
        for (g, entries) in groups.iter().enumerate() {
            for e in entries {
                let kind = match e.ty {
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        ..
                    } => "uniform".to_owned(),
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only },
                        ..
                    } => format!("storage read_only={read_only}"),
                    ref other => format!("{other:?}"),
                };
                out.push((g as u32, e.binding, kind));
            }
        }
        out.sort();
        out
    }
    fn from_shader(source: &shaders::ShaderSource) -> Vec<Binding> {
        let (module, _) = source.validate().expect("valid");
        let mut out: Vec<Binding> = module
            .global_variables
            .iter()
            .filter_map(|(_, g)| {
                let b = g.binding.as_ref()?;
                let kind = match g.space {
                    naga::AddressSpace::Uniform => "uniform".to_owned(),
                    naga::AddressSpace::Storage { access } => format!(
                        "storage read_only={}",
                        !access.contains(naga::StorageAccess::STORE)
                    ),
                    ref other => format!("{other:?}"),
                };
                Some((b.group, b.binding, kind))
            })
            .collect();
        out.sort();
        out
    }
    assert_eq!(
        from_layouts(&bindings::tessellate()),
        from_shader(&shaders::TESSELLATE)
    );
    for s in [shaders::LINES, shaders::POINTS] {
        assert_eq!(
            from_layouts(&bindings::draw()),
            from_shader(&s),
            "{}",
            s.file
        );
    }
    assert_eq!(from_shader(&shaders::TESSELLATE).len(), 4);
    // The comb's kernels use both groups (the adaptive work's and the comb's own); the
    // adaptive tessellator's module declares the first alone.
    assert_eq!(
        from_layouts(&bindings::adaptive()),
        from_shader(&shaders::COMB)
    );
    assert_eq!(from_shader(&shaders::COMB).len(), 10);
    assert_eq!(
        from_layouts(&bindings::adaptive()[..1]),
        from_shader(&shaders::ADAPTIVE)
    );
    assert_eq!(
        from_layouts(&bindings::layer()),
        from_shader(&shaders::LAYER)
    );
    assert_eq!(from_shader(&shaders::LAYER).len(), 12);
}

#[test]
fn comb_rasterizer_workgroup_matches_its_rust_twin() {
    let (module, _) = shaders::LAYER.validate().expect("valid");
    let ep = module
        .entry_points
        .iter()
        .find(|e| e.name == "raster_comb")
        .expect("raster_comb");
    assert_eq!(
        ep.workgroup_size,
        [splinescope_gpu::layout::LAYER_WORKGROUP, 1, 1]
    );
}
