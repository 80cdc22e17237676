// Anti-aliased polylines of a width in pixels, read straight from a storage buffer of
// tagged vertices (the tessellator's samples, or CPU-made overlays). Instance i draws the
// piece from vertex i to vertex i + 1 as a screen-space quad around a capsule (round caps
// make round joins); pieces whose two vertices have different tags are skipped. The
// curvature comb is drawn as one-pixel line lists (`vs_hair_line`: vertex pairs;
// `vs_envelope_line`: consecutive vertices), cheap enough for a hair at every sample.

@group(0) @binding(0) var<uniform> camera: Camera;
@group(1) @binding(0) var<storage, read> vertices: array<Vertex>;
@group(1) @binding(1) var<storage, read> styles: array<LineStyle>;

struct LineOut {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
    // The fragment in the piece's frame: pixels along the piece from its start, across it.
    @location(1) local_px: vec2<f32>,
    @location(2) @interpolate(flat) length_px: f32,
    @location(3) @interpolate(flat) half_width_px: f32,
    @location(4) @interpolate(flat) dash_px: f32,
}


fn clip_from_pixel(p: vec2<f32>) -> vec4<f32> {
    let ndc = vec2<f32>(p.x / camera.viewport_px.x * 2.0 - 1.0,
                        1.0 - p.y / camera.viewport_px.y * 2.0);
    return vec4<f32>(ndc, 0.5, 1.0);
}

fn culled() -> LineOut {
    var out: LineOut;
    out.position = vec4<f32>(-4.0, -4.0, 0.5, 1.0);
    return out;
}

@vertex
fn vs_line(@builtin(vertex_index) corner: u32, @builtin(instance_index) piece: u32) -> LineOut {
    return piece_corner(vertices[piece], vertices[piece + 1u], corner);
}

// Corner `corner` of the quad around the piece from a to b.
fn piece_corner(a: Vertex, b: Vertex, corner: u32) -> LineOut {
    if (a.id != b.id) {
        return culled();
    }
    let ca = camera.clip_from_world * vec4<f32>(a.position, 1.0);
    let cb = camera.clip_from_world * vec4<f32>(b.position, 1.0);
    if (behind_eye(ca, cb)) {
        return culled();
    }
    let c = clip_to_eye(ca, cb);
    let style = styles[a.id];
    let pa = pixel_from_clip(c[0], camera.viewport_px);
    let pb = pixel_from_clip(c[1], camera.viewport_px);
    let delta = pb - pa;
    let len = length(delta);
    var dir = vec2<f32>(1.0, 0.0);
    if (len > 1e-6) {
        dir = delta / len;
    }
    let normal = vec2<f32>(-dir.y, dir.x);
    let half_width = half_width_px(style, camera, 0.5 * (ca.w + cb.w));
    // One pixel of margin for the anti-aliased edge.
    let r = half_width + 1.0;
    // A triangle strip of four corners: (start, -), (end, -), (start, +), (end, +).
    let at_end = corner == 1u || corner == 3u;
    let side = select(-1.0, 1.0, corner >= 2u);
    var p = pa - dir * r;
    if (at_end) {
        p = pb + dir * r;
    }
    p += normal * side * r;
    var out: LineOut;
    out.position = clip_from_pixel(p);
    out.color = style.color;
    out.local_px = vec2<f32>(dot(p - pa, dir), dot(p - pa, normal));
    out.length_px = len;
    out.half_width_px = half_width;
    out.dash_px = style.dash_px * camera.width_scale;
    return out;
}

@fragment
fn fs_line(in: LineOut) -> @location(0) vec4<f32> {
    let along = clamp(in.local_px.x, 0.0, in.length_px);
    let dist = length(vec2<f32>(in.local_px.x - along, in.local_px.y));
    var coverage = clamp(in.half_width_px + 0.5 - dist, 0.0, 1.0);
    if (in.dash_px > 0.0 && fract(along / in.dash_px) >= 0.5) {
        coverage = 0.0;
    }
    if (coverage <= 0.0) {
        discard;
    }
    let alpha = in.color.a * coverage;
    return vec4<f32>(in.color.rgb * alpha, alpha);
}

// A one-pixel line's end.
struct FlatOut {
    @builtin(position) position: vec4<f32>,
    @location(0) color: vec4<f32>,
}

// End `end` (0 or 1) of the line from a to b; nothing when their tags differ or both are
// behind the eye.
fn flat_end(a: Vertex, b: Vertex, end: u32) -> FlatOut {
    var out: FlatOut;
    out.position = vec4<f32>(-4.0, -4.0, 0.5, 1.0);
    if (a.id != b.id) {
        return out;
    }
    let ca = camera.clip_from_world * vec4<f32>(a.position, 1.0);
    let cb = camera.clip_from_world * vec4<f32>(b.position, 1.0);
    if (behind_eye(ca, cb)) {
        return out;
    }
    let c = clip_to_eye(ca, cb)[min(end, 1u)];
    out.position = vec4<f32>(c.xy / c.w, 0.5, 1.0);
    out.color = styles[a.id].color;
    return out;
}

// Hair v / 2 of a comb: vertices 2 h and 2 h + 1.
@vertex
fn vs_hair_line(@builtin(vertex_index) v: u32) -> FlatOut {
    let h = v / 2u;
    // A capped hair (its tip tagged 0x20000000, COMB_CAPPED) is drawn like the others.
    var tip = vertices[2u * h + 1u];
    tip.id = tip.id & ~0x20000000u;
    return flat_end(vertices[2u * h], tip, v % 2u);
}

// Piece v / 2 of a comb's envelope: vertices k and k + 1.
@vertex
fn vs_envelope_line(@builtin(vertex_index) v: u32) -> FlatOut {
    let k = v / 2u;
    return flat_end(vertices[k], vertices[k + 1u], v % 2u);
}

@fragment
fn fs_flat(in: FlatOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.color.rgb * in.color.a, in.color.a);
}
