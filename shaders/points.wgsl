// Anti-aliased discs of a diameter in pixels (control points, markers), one instance per
// tagged vertex; the tag indexes the style table. A darker rim makes points readable on
// top of curves of the same colour.

@group(0) @binding(0) var<uniform> camera: Camera;
@group(1) @binding(0) var<storage, read> vertices: array<Vertex>;
@group(1) @binding(1) var<storage, read> styles: array<LineStyle>;

struct PointOut {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    @location(1) local_px: vec2<f32>,
    @location(2) @interpolate(flat) radius_px: f32,
}

@vertex
fn vs_point(@builtin(vertex_index) corner: u32, @builtin(instance_index) index: u32) -> PointOut {
    let v = vertices[index];
    let style = styles[v.id];
    let c = camera.clip_from_world * vec4<f32>(v.position, 1.0);
    var out: PointOut;
    if (c.w <= 1e-6) {
        out.position = vec4<f32>(-4.0, -4.0, 0.5, 1.0);
        return out;
    }
    let radius = 0.5 * style.width_px * camera.width_scale;
    let r = radius + 1.0;
    let offsets = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(-1.0, 1.0),
        vec2<f32>(-1.0, 1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0),
    );
    let offset = offsets[corner] * r;
    let ndc = c.xy / c.w;
    out.position = vec4<f32>(ndc + offset * 2.0 / camera.viewport_px * vec2<f32>(1.0, -1.0), 0.5, 1.0);
    out.color = style.color;
    out.local_px = offset;
    out.radius_px = radius;
    return out;
}

@fragment
fn fs_point(in: PointOut) -> @location(0) vec4<f32> {
    let dist = length(in.local_px);
    let coverage = clamp(in.radius_px + 0.5 - dist, 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    // Rim: the outer 1.5 px are darker.
    let rim = clamp(dist - (in.radius_px - 1.5), 0.0, 1.0);
    let rgb = mix(in.color.rgb, in.color.rgb * 0.45, rim);
    let alpha = in.color.a * coverage;
    return vec4<f32>(rgb * alpha, alpha);
}
