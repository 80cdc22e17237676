// The curvature comb drawn without line primitives. The comb pass (adaptive.wgsl) writes a
// hair (two vertices) and an envelope vertex per sample; `raster_comb` draws every hair
// and every envelope piece as a one-pixel line into the comb layer, a buffer of one u32
// per pixel, by atomicMax of the line's packed colour; `vs_layer`/`fs_layer` then blend
// the layer over the target in one full-screen triangle, where the line pipelines drew
// the comb before. A CPU rasterizer pays per primitive (two more per sample: the comb cost
// 0.6 of the frame as line lists on llvmpipe); this pays per pixel the comb covers.
//
// A pixel shows one line: the envelope over the hairs, then the more opaque, then the
// larger colour — the same result in any order the lines arrive (translucent hairs that
// cross do not darken each other). Pixels are those of a line rasterized along its major
// axis at pixel centres (one pixel per column or row); a line that crosses no centre
// draws nothing, as a line primitive.

@group(0) @binding(0) var<uniform> camera: Camera;
@group(1) @binding(0) var<storage, read> hairs: array<Vertex>;
@group(1) @binding(1) var<storage, read> envelope: array<Vertex>;
@group(1) @binding(2) var<storage, read> hair_styles: array<LineStyle>;
@group(1) @binding(3) var<storage, read> envelope_styles: array<LineStyle>;
// The comb's draw arguments (adaptive.wgsl's comb_work): [0] two vertices per hair, [4]
// two per envelope piece.
@group(1) @binding(4) var<storage, read> comb_args: array<u32>;
@group(1) @binding(5) var<storage, read_write> layer_rw: array<atomic<u32>>;
// The same layer, read by the full-screen pass (its own bind group).
@group(1) @binding(6) var<storage, read> layer: array<u32>;

const ENVELOPE_BIT: u32 = 0x80000000u;
// Clip-space w below which a point counts as behind the eye (as lines.wgsl).
const NEAR_W: f32 = 1e-6;

// The layer's width and height in pixels.
fn layer_size() -> vec2<u32> {
    return vec2<u32>(camera.viewport_px);
}

// A line's colour in the layer: bit 31 the envelope's, 30–24 the alpha (7 bits), then
// 8-bit red, green and blue; 0 for a colour that would not show.
fn packed(color: vec4<f32>, is_envelope: bool) -> u32 {
    let c = clamp(color, vec4<f32>(0.0), vec4<f32>(1.0));
    let alpha = u32(round(c.a * 127.0));
    if (alpha == 0u) {
        return 0u;
    }
    let rgb = vec3<u32>(round(c.rgb * 255.0));
    return select(0u, ENVELOPE_BIT, is_envelope) | (alpha << 24u) | (rgb.r << 16u)
        | (rgb.g << 8u) | rgb.b;
}

fn pixel_from_clip(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>((ndc.x * 0.5 + 0.5) * camera.viewport_px.x,
                     (0.5 - ndc.y * 0.5) * camera.viewport_px.y);
}

// Narrows `range` (of t along p + t d) to where p_k t ≤ q: one side of the layer, in
// Liang–Barsky's form. An empty range comes back with x > y.
fn clip_range(range: vec2<f32>, p_k: f32, q: f32) -> vec2<f32> {
    var r = range;
    if (p_k == 0.0) {
        if (q < 0.0) {
            r = vec2<f32>(1.0, 0.0);
        }
    } else {
        let t = q / p_k;
        if (p_k < 0.0) {
            r.x = max(r.x, t);
        } else {
            r.y = min(r.y, t);
        }
    }
    return r;
}

// Writes `key` at pixel (x, y) when it is in the layer.
fn plot(x: i32, y: i32, size: vec2<u32>, key: u32) {
    if (x >= 0 && y >= 0 && u32(x) < size.x && u32(y) < size.y) {
        let index = u32(y) * size.x + u32(x);
        if (index < arrayLength(&layer_rw)) {
            atomicMax(&layer_rw[index], key);
        }
    }
}

// The one-pixel line from a to b into the layer; nothing when both are behind the eye.
fn raster_line(a: Vertex, b: Vertex, key: u32) {
    if (key == 0u) {
        return;
    }
    var ca = camera.clip_from_world * vec4<f32>(a.position, 1.0);
    var cb = camera.clip_from_world * vec4<f32>(b.position, 1.0);
    if (ca.w < NEAR_W && cb.w < NEAR_W) {
        return;
    }
    if (ca.w < NEAR_W) {
        ca = mix(ca, cb, (NEAR_W - ca.w) / (cb.w - ca.w));
    } else if (cb.w < NEAR_W) {
        cb = mix(cb, ca, (NEAR_W - cb.w) / (ca.w - cb.w));
    }
    let p = pixel_from_clip(ca);
    let q = pixel_from_clip(cb);
    // Not finite (x − x is NaN for ±∞ and NaN): nothing to draw.
    if (!(all((p - p) == vec2<f32>(0.0)) && all((q - q) == vec2<f32>(0.0)))) {
        return;
    }
    // Clipped to the layer (Liang–Barsky), so that the loop below never runs past it.
    let size = layer_size();
    let extent = vec2<f32>(size);
    let d = q - p;
    var range = vec2<f32>(0.0, 1.0);
    range = clip_range(range, -d.x, p.x);
    range = clip_range(range, d.x, extent.x - p.x);
    range = clip_range(range, -d.y, p.y);
    range = clip_range(range, d.y, extent.y - p.y);
    if (range.x > range.y) {
        return;
    }
    // Along the major axis (the first coordinate of s and e, swapped back in `plot`).
    let x_major = abs(d.x) >= abs(d.y);
    var s = p + range.x * d;
    var e = p + range.y * d;
    if (!x_major) {
        s = s.yx;
        e = e.yx;
    }
    if (s.x > e.x) {
        let t = s;
        s = e;
        e = t;
    }
    // The columns whose centres the line crosses; the row where it crosses each.
    let first = i32(ceil(s.x - 0.5));
    let last = i32(floor(e.x - 0.5));
    if (last < first) {
        return;
    }
    let slope = (e.y - s.y) / max(e.x - s.x, 1e-30);
    let limit = i32(size.x + size.y);
    for (var i = 0; i <= min(last - first, limit); i++) {
        let column = first + i;
        let row = i32(floor(s.y + (f32(column) + 0.5 - s.x) * slope));
        if (x_major) {
            plot(column, row, size, key);
        } else {
            plot(row, column, size, key);
        }
    }
}

// Sample p's hair and the envelope piece from its tip to the next sample's, for p = the
// invocation's index, then every stride after it.
@compute @workgroup_size(COMB_RASTER_WORKGROUP)
fn raster_comb(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let hair_count = comb_args[0] / 2u;
    let piece_count = comb_args[4] / 2u;
    let stride = groups.x * COMB_RASTER_WORKGROUP;
    for (var p = id.x; p < hair_count; p += stride) {
        let foot = hairs[2u * p];
        let tip = hairs[2u * p + 1u];
        // Tags that differ (another curve, a hidden comb) draw nothing; equal ones index
        // the style tables.
        if (foot.id == tip.id) {
            raster_line(foot, tip, packed(hair_styles[foot.id].color, false));
        }
        if (p < piece_count) {
            let a = envelope[p];
            let b = envelope[p + 1u];
            if (a.id == b.id) {
                raster_line(a, b, packed(envelope_styles[a.id].color, true));
            }
        }
    }
}

struct LayerOut {
    @builtin(position) position: vec4<f32>,
}

// One triangle over the whole target.
@vertex
fn vs_layer(@builtin(vertex_index) v: u32) -> LayerOut {
    var out: LayerOut;
    let x = f32(v & 1u) * 4.0 - 1.0;
    let y = f32(v >> 1u) * 4.0 - 1.0;
    out.position = vec4<f32>(x, y, 0.5, 1.0);
    return out;
}

// The layer's line at this pixel, premultiplied; nothing where no line is.
@fragment
fn fs_layer(in: LayerOut) -> @location(0) vec4<f32> {
    let size = layer_size();
    let x = u32(in.position.x);
    let y = u32(in.position.y);
    var key = 0u;
    if (x < size.x && y < size.y) {
        let index = y * size.x + x;
        if (index < arrayLength(&layer)) {
            key = layer[index];
        }
    }
    if (key == 0u) {
        discard;
    }
    let alpha = f32((key >> 24u) & 0x7fu) / 127.0;
    let rgb = vec3<f32>(vec3<u32>((key >> 16u) & 0xffu, (key >> 8u) & 0xffu, key & 0xffu))
        / 255.0;
    return vec4<f32>(rgb * alpha, alpha);
}
