//! The deprecated forms kept for one release (CHANGELOG.md) are the items at their one
//! path: the same values, the same results, the same types. A forwarding function that
//! forwarded to the wrong item, or an alias that named another type, fails here.
#![allow(deprecated)]

use glam::DVec3;

#[test]
fn scene_format_forms_are_the_encodings_items() {
    use splinescope_scene::format as old;
    let rgba = [0.25, 0.5, 0.75, 1.0];
    let c: splinescope_encoding::Color = old::Color(rgba);
    assert_eq!(c, splinescope_encoding::Color(rgba));
    let shape: old::StrokeShape = splinescope_encoding::StrokeShape::default();
    assert_eq!(shape.cap, old::Cap::Round);
    assert_eq!(shape.join, splinescope_encoding::Join::Round);
    assert_eq!(
        old::MAX_SAMPLES_PER_SEGMENT,
        splinescope_encoding::MAX_SAMPLES_PER_SEGMENT
    );
    assert_eq!(
        old::AUTO_SAMPLES_TOLERANCE.to_bits(),
        splinescope_encoding::AUTO_SAMPLES_TOLERANCE.to_bits()
    );
    assert_eq!(
        old::MAX_MITER_LIMIT.to_bits(),
        splinescope_encoding::MAX_MITER_LIMIT.to_bits()
    );
    // A curved cubic needs more samples than a line: the forwarded function is the same.
    for pts in [
        vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::Y * 3.0,
        ],
        vec![DVec3::ZERO, DVec3::X],
        vec![DVec3::ZERO, DVec3::new(1.0, 1e3, 0.0), DVec3::X * 2.0],
    ] {
        assert_eq!(
            old::auto_samples(&pts),
            splinescope_encoding::auto_samples(&pts)
        );
    }
}

#[test]
fn draw_list_forms_are_the_encodings_items() {
    use splinescope_encoding::draw as new;
    use splinescope_scene::format::draw as old;
    let c = splinescope_encoding::Color([0.1, 0.2, 0.3, 1.0]);
    for kind in new::MarkerKind::ALL {
        assert_eq!(old::marker_style(kind, c), new::marker_style(kind, c));
    }
    assert_eq!(old::comb_strokes(c), new::comb_strokes(c));
    for kind in [
        new::OverlayKind::ControlPolygon,
        new::OverlayKind::DualPolygon,
        new::OverlayKind::BumpVector,
    ] {
        assert_eq!(old::overlay_style(kind, c), new::overlay_style(kind, c));
        assert_eq!(
            old::overlay_point_style(kind, c),
            new::overlay_point_style(kind, c)
        );
    }
    let switches: old::Switches = new::Switches::ALL;
    assert_eq!(switches, new::Switches::ALL);
    assert_eq!(old::POINT_DIAMETER_PX, new::POINT_DIAMETER_PX);
    assert_eq!(old::DUAL_COLOR, new::DUAL_COLOR);
    let kind: splinescope_scene::format::shape::MarkerKind = new::MarkerKind::Inflection;
    assert_eq!(kind, new::MarkerKind::Inflection);
}

#[test]
fn core_forms_are_the_moved_items() {
    use splinescope_core::{analysis, poly};
    // (1 − 2t)(t − ¼) in Bernstein form on [0, 1]: roots at ¼ and ½.
    let c = [-0.25, 0.5, -0.75];
    let old = analysis::bernstein_roots(&c);
    let new = poly::roots::bernstein_roots(&c);
    assert_eq!(old, new);
    assert_eq!(new.roots.len(), 2, "{new:?}");
    assert_eq!(
        analysis::bernstein_roots_with_noise(&c, 1e-9),
        poly::roots::bernstein_roots_with_noise(&c, 1e-9)
    );
    for (n, k) in [(5, 2), (10, 0), (3, 4), (30, 15)] {
        assert_eq!(
            poly::binomial(n, k).to_bits(),
            splinescope_core::geom::bernstein::binomial(n, k).to_bits()
        );
    }
    assert_eq!(poly::binomial(5, 2), 10.0);
}

#[test]
fn gpu_forms_are_the_moved_items() {
    use splinescope_gpu::{chunks, layout, pack, pack_error, renderer};
    let limits: pack::ChunkLimits = pack::ChunkLimits::for_binding_size(1 << 20);
    assert_eq!(limits, chunks::ChunkLimits::for_binding_size(1 << 20));
    assert_eq!(
        pack::GPU_COORDINATE_LIMIT.to_bits(),
        pack_error::GPU_COORDINATE_LIMIT.to_bits()
    );
    assert_eq!(
        pack::GPU_WEIGHT_RATIO.to_bits(),
        pack_error::GPU_WEIGHT_RATIO.to_bits()
    );
    assert_eq!(renderer::LINE_CORNERS, layout::LINE_CORNERS);
}
