// The layer: curves and their curvature combs drawn without primitives. A buffer of one
// u32 per pixel; `raster_curves` writes each curve piece's anti-aliased pixels into it,
// `raster_comb` each comb hair and envelope piece (one-pixel lines), both by atomicMax of
// a packed value; `vs_layer`/`fs_layer` then blend the layer over the target in one
// full-screen triangle, where the line pipelines drew curves and combs before. A CPU
// rasterizer pays per primitive (a curve piece's quad, a comb line); this pays per pixel
// covered — on llvmpipe the 10,000-curve stress view went from 21 to 47 fps.
//
// A pixel shows one thing, whatever order they arrive in: a curve over a comb's envelope
// over its hairs; then a stroke's core (a curve covering at least half the pixel, a comb
// line) over an anti-aliased edge; then the later curve in the scene (its style's
// `order`, which also names its colour in the scene's style table); then the more
// opaque. So where curves cross or coincide the later one is on top, as drawn in order,
// an edge never cuts into another curve's core, and a curve's joints and translucent
// strokes that cross are not blended twice. A curve's coverage is
// the line pipeline's: `clamp(w/2 + 1/2 − d, 0, 1)`, d the pixel centre's distance to the
// piece (round caps, so round joins), dashes as there. Comb lines light the pixels of a
// line rasterized along its major axis at pixel centres (one pixel per column or row); a
// line that crosses no centre draws nothing, as a line primitive.

@group(0) @binding(0) var<uniform> camera: Camera;
@group(1) @binding(0) var<storage, read> hairs: array<Vertex>;
@group(1) @binding(1) var<storage, read> envelope: array<Vertex>;
@group(1) @binding(2) var<storage, read> hair_styles: array<LineStyle>;
@group(1) @binding(3) var<storage, read> envelope_styles: array<LineStyle>;
// The comb's draw arguments (adaptive.wgsl's comb_work): [0] two vertices per hair, [4]
// two per envelope piece.
@group(1) @binding(4) var<storage, read> comb_args: array<u32>;
@group(1) @binding(5) var<storage, read_write> layer_rw: array<atomic<u32>>;
// The same layer, read by the full-screen pass (its own bind group), with the scene's
// curve styles in their order (the colours the layer's pixels name).
@group(1) @binding(6) var<storage, read> layer: array<u32>;
@group(1) @binding(10) var<storage, read> layer_styles: array<LineStyle>;
// `raster_curves`' own group 1 (with the layer at 5): a chunk's samples, its style table
// and its work buffer (the pieces drawn: STAT_INSTANCES).
@group(1) @binding(7) var<storage, read> curve_samples: array<Vertex>;
@group(1) @binding(8) var<storage, read> curve_styles: array<LineStyle>;
@group(1) @binding(9) var<storage, read> curve_work: array<u32>;

// What a pixel holds (bits 31–30): the highest wins.
const KIND_HAIR: u32 = 1u;
// A capped hair's tip tag bit (COMB_CAPPED in adaptive.wgsl).
const COMB_CAPPED_TIP: u32 = 0x20000000u;
const KIND_ENVELOPE: u32 = 2u;
const KIND_CURVE: u32 = 3u;
// Twin: STAT_INSTANCES in adaptive.wgsl (the work buffer's piece count).
const PIECES_WORD: u32 = 1u;

// The layer's width and height in pixels.
fn layer_size() -> vec2<u32> {
    return vec2<u32>(camera.viewport_px);
}

// A pixel's value: bits 31–30 its kind, bit 29 set for a core, 28–6 its curve's place in
// the scene's style table (23 bits), 5–0 the alpha; 0 for an alpha that would not show.
// Twin: layer_twin.rs.
const ORDER_MASK: u32 = 0x7fffffu;
const CORE_BIT: u32 = 0x20000000u;

fn key_of(kind: u32, core: bool, order: u32, alpha: u32) -> u32 {
    return (kind << 30u) | select(0u, CORE_BIT, core) | ((order & ORDER_MASK) << 6u) | alpha;
}

// A comb line's value (a core, its style's alpha times `alpha_scale`).
fn packed(style: LineStyle, alpha_scale: f32, kind: u32) -> u32 {
    let alpha = u32(round(clamp(style.color.a * alpha_scale, 0.0, 1.0) * 63.0));
    if (alpha == 0u) {
        return 0u;
    }
    return key_of(kind, true, style.order, alpha);
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

// The ends of the piece from a to b in pixels, clipped to the plane in front of the eye
// (3D only; w = 1 in 2D); `ok` false when both are behind it or an end is not finite.
struct PixelEnds {
    p: vec2<f32>,
    q: vec2<f32>,
    ok: bool,
}

fn pixel_ends(a: Vertex, b: Vertex) -> PixelEnds {
    let ca = camera.clip_from_world * vec4<f32>(a.position, 1.0);
    let cb = camera.clip_from_world * vec4<f32>(b.position, 1.0);
    return clip_ends(ca, cb);
}

// `pixel_ends` of ends already in clip space.
fn clip_ends(ca: vec4<f32>, cb: vec4<f32>) -> PixelEnds {
    var out: PixelEnds;
    out.ok = false;
    if (ca.w == 1.0 && cb.w == 1.0) {
        // In front of the eye with w = 1 (every 2D view): nothing to clip, and dividing
        // by w would change nothing.
        out.p = pixel_from_ndc(ca.xy, camera.viewport_px);
        out.q = pixel_from_ndc(cb.xy, camera.viewport_px);
    } else {
        if (behind_eye(ca, cb)) {
            return out;
        }
        let c = clip_to_eye(ca, cb);
        out.p = pixel_from_clip(c[0], camera.viewport_px);
        out.q = pixel_from_clip(c[1], camera.viewport_px);
    }
    // Not finite (x − x is NaN for ±∞ and NaN): nothing to draw.
    out.ok = all((out.p - out.p) == vec2<f32>(0.0)) && all((out.q - out.q) == vec2<f32>(0.0));
    return out;
}

// `a` and `b` with the major axis first (`x_major`: x), in order along it: the
// rasterizers below step along the first coordinate and swap each pixel back.
// Twin: along_major in layer_twin.rs.
fn along_major(a: vec2<f32>, b: vec2<f32>, x_major: bool) -> array<vec2<f32>, 2> {
    let s = select(a.yx, a, x_major);
    let e = select(b.yx, b, x_major);
    if (s.x > e.x) {
        return array<vec2<f32>, 2>(e, s);
    }
    return array<vec2<f32>, 2>(s, e);
}

// The one-pixel line from a to b into the layer; nothing when both are behind the eye.
fn raster_line(a: Vertex, b: Vertex, key: u32) {
    if (key == 0u) {
        return;
    }
    let ends = pixel_ends(a, b);
    if (!ends.ok) {
        return;
    }
    let p = ends.p;
    let q = ends.q;
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
    let major = along_major(p + range.x * d, p + range.y * d, x_major);
    let s = major[0];
    let e = major[1];
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
@compute @workgroup_size(LAYER_WORKGROUP)
fn raster_comb(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let hair_count = comb_args[0] / 2u;
    let piece_count = comb_args[4] / 2u;
    let stride = groups.x * LAYER_WORKGROUP;
    for (var p = id.x; p < hair_count; p += stride) {
        let foot = hairs[2u * p];
        let tip = hairs[2u * p + 1u];
        // Tags that differ (another curve, a hidden comb) draw nothing; equal ones index
        // the style tables.
        if (foot.id == tip.id) {
            raster_line(foot, tip, packed(hair_styles[foot.id], 1.0, KIND_HAIR));
        } else if (foot.id == (tip.id & ~COMB_CAPPED_TIP)) {
            // A capped hair: in the envelope's stroke, so that it reads as cut.
            raster_line(foot, tip, packed(envelope_styles[foot.id], 1.0, KIND_ENVELOPE));
        }
        if (p < piece_count) {
            let a = envelope[p];
            let b = envelope[p + 1u];
            if (a.id == b.id) {
                raster_line(a, b, packed(envelope_styles[a.id], 1.0, KIND_ENVELOPE));
            }
        }
    }
}

// Pieces LAYER_RUN q … LAYER_RUN (q + 1) − 1 (piece p: samples p and p + 1 of the chunk,
// when their tags agree), for q = the invocation's index, then every stride after it: a
// run's samples are projected once each, its style read once per curve (with one piece
// an invocation, the projections and reads were a third of the pass on llvmpipe).
@compute @workgroup_size(LAYER_WORKGROUP)
fn raster_curves(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let pieces = min(curve_work[PIECES_WORD], max(arrayLength(&curve_samples), 1u) - 1u);
    let runs = (pieces + LAYER_RUN - 1u) / LAYER_RUN;
    let stride = groups.x * LAYER_WORKGROUP;
    let styles = max(arrayLength(&curve_styles), 1u) - 1u;
    for (var q = id.x; q < runs; q += stride) {
        let first = q * LAYER_RUN;
        let end = min(first + LAYER_RUN, pieces);
        var a = curve_samples[first];
        var ca = camera.clip_from_world * vec4<f32>(a.position, 1.0);
        var style_id = a.id;
        var style = curve_styles[min(a.id, styles)];
        for (var p = first; p < end; p++) {
            let b = curve_samples[p + 1u];
            let cb = camera.clip_from_world * vec4<f32>(b.position, 1.0);
            if (a.id == b.id) {
                if (a.id != style_id) {
                    style = curve_styles[min(a.id, styles)];
                    style_id = a.id;
                }
                let ends = clip_ends(ca, cb);
                let w = 0.5 * (ca.w + cb.w);
                if ((style.flags & LINE_SHAPE_MASK) == 0u) {
                    raster_piece(ends, style, w, END_ROUND, END_ROUND);
                } else {
                    raster_shaped(p, pieces, ends, style, w);
                }
            }
            a = b;
            ca = cb;
        }
    }
}

// How a piece's end is drawn (twins: the END_* constants in layer_twin.rs): a half disc
// (a round cap, and the round join of two pieces), cut at the end point with its edge
// anti-aliased (a butt cap), cut half the width beyond it (a square cap), or cut at the
// end point with a hard edge (where a miter or bevel join meets it: the pixels on
// either side of the cut belong to one piece each, so no seam shows).
const END_ROUND: u32 = 0u;
const END_BUTT: u32 = 1u;
const END_SQUARE: u32 = 2u;
const END_HARD: u32 = 3u;
const JOIN_ROUND: u32 = 0u;
const JOIN_MITER: u32 = 1u;

// The sample before sample `p` on its run at another place (where two segments meet
// the sample is written twice: one repeat is passed over); `p` itself where the run
// starts at p. Twin: before in layer_twin.rs.
fn before(p: u32) -> u32 {
    let s = curve_samples[p];
    var i = p;
    for (var k = 0u; k < 2u && i > 0u; k++) {
        let q = curve_samples[i - 1u];
        if (q.id != s.id) {
            return p;
        }
        i -= 1u;
        if (any(q.position != s.position)) {
            return i;
        }
    }
    return p;
}

// The sample after sample `p` (at most `last`) on its run at another place; `p` where
// the run ends at p. Twin: after in layer_twin.rs.
fn after(p: u32, last: u32) -> u32 {
    let s = curve_samples[p];
    var i = p;
    for (var k = 0u; k < 2u && i < last; k++) {
        let q = curve_samples[i + 1u];
        if (q.id != s.id) {
            return p;
        }
        i += 1u;
        if (any(q.position != s.position)) {
            return i;
        }
    }
    return p;
}

// Piece p (samples p and p + 1 of `last` + 1) of a curve whose style has a cap or a join
// other than round: each end a cap where its run ends (round where the run goes on in
// another chunk, hard where a closed curve's run meets itself), a join where another
// piece follows — the piece ending at a miter or bevel join also fills the join's wedge.
fn raster_shaped(p: u32, last: u32, ends: PixelEnds, style: LineStyle, w: f32) {
    let cap = (style.flags >> LINE_CAP_SHIFT) & 3u;
    let join = (style.flags >> LINE_JOIN_SHIFT) & 3u;
    let closed = (style.flags & LINE_CLOSED) != 0u;
    let at_join = select(END_HARD, END_ROUND, join == JOIN_ROUND);
    var start = cap;
    if (before(p) != p) {
        start = at_join;
    } else if (closed) {
        start = END_HARD;
    } else if ((style.flags & LINE_CONTINUES_BEFORE) != 0u) {
        start = END_ROUND;
    }
    var end = cap;
    let next = after(p + 1u, last);
    if (next != p + 1u) {
        end = at_join;
    } else if (closed) {
        end = END_HARD;
    } else if ((style.flags & LINE_CONTINUES_AFTER) != 0u) {
        end = END_ROUND;
    }
    raster_piece(ends, style, w, start, end);
    if (next != p + 1u && join != JOIN_ROUND && ends.ok) {
        let following = pixel_ends(curve_samples[p + 1u], curve_samples[next]);
        let d1 = ends.q - ends.p;
        let d2 = following.q - following.p;
        if (following.ok && length(d1) > 1e-6 && length(d2) > 1e-6) {
            raster_join(ends.q, normalize(d1), normalize(d2), style, half_width_px(style, camera, w));
        }
    }
}

// The wedge of a miter or bevel join at `at` (pixels) between a piece going along `d1`
// and the next going along `d2` (unit vectors): the pixels past the first piece's end
// and before the next one's start (the two hard cuts: no pixel is in two), inside the
// outer edges extended to their meeting point (a miter, when its length over the width,
// 1 / cos(θ/2) for a turn θ, is within the limit) or the line joining the outer corners
// (a bevel), that edge anti-aliased. Twin: raster_join in layer_twin.rs.
fn raster_join(at: vec2<f32>, d1: vec2<f32>, d2: vec2<f32>, style: LineStyle, half_width: f32) {
    let turn = d1.x * d2.y - d1.y * d2.x;
    let cosine = dot(d1, d2);
    if (abs(turn) < 1e-6 && cosine > 0.0) {
        return;
    }
    // The outer side's normals: away from the turn.
    var n1 = vec2<f32>(-d1.y, d1.x);
    if (dot(n1, d2) > 0.0) {
        n1 = -n1;
    }
    var n2 = vec2<f32>(-d2.y, d2.x);
    if (dot(n2, d1) < 0.0) {
        n2 = -n2;
    }
    let limit = f32(style.flags >> LINE_MITER_SHIFT) / 1024.0;
    let miter = ((style.flags >> LINE_JOIN_SHIFT) & 3u) == JOIN_MITER
        && 2.0 <= limit * limit * (1.0 + cosine);
    let a = at + half_width * n1;
    let b = at + half_width * n2;
    var lo = min(at, min(a, b));
    var hi = max(at, max(a, b));
    var bevel = vec2<f32>(0.0);
    if (miter) {
        let tip = at + half_width * (n1 + n2) / (1.0 + cosine);
        lo = min(lo, tip);
        hi = max(hi, tip);
    } else {
        bevel = normalize(n1 + n2);
    }
    let size = vec2<f32>(layer_size());
    let x0 = max(floor(lo.x - 1.0), 0.0);
    let x1 = min(ceil(hi.x + 1.0), size.x - 1.0);
    let y0 = max(floor(lo.y - 1.0), 0.0);
    let y1 = min(ceil(hi.y + 1.0), size.y - 1.0);
    let opacity = clamp(style.color.a, 0.0, 1.0) * 63.0;
    for (var y = y0; y <= y1; y += 1.0) {
        for (var x = x0; x <= x1; x += 1.0) {
            let pixel = vec2<f32>(x + 0.5, y + 0.5);
            let v = pixel - at;
            if (dot(v, d1) < 0.0 || dot(v, d2) >= 0.0) {
                continue;
            }
            var inside = 0.0;
            if (miter) {
                inside = min(half_width - dot(v, n1), half_width - dot(v, n2));
            } else {
                inside = half_width * dot(n1, bevel) - dot(v, bevel);
            }
            let coverage = clamp(0.5 + inside, 0.0, 1.0);
            let alpha = u32(round(opacity * coverage));
            if (alpha > 0u) {
                let index = u32(y) * u32(size.x) + u32(x);
                if (index < arrayLength(&layer_rw)) {
                    atomicMax(&layer_rw[index], key_of(KIND_CURVE, coverage >= 0.5, style.order, alpha));
                }
            }
        }
    }
}

// The anti-aliased pixels of one curve piece: along its major axis, the columns within
// reach of its capsule (or of its square ends), and in each the rows within reach of
// the piece there; each end drawn as `start` and `end` (END_*).
fn raster_piece(ends: PixelEnds, style: LineStyle, w: f32, start: u32, end: u32) {
    if (!ends.ok) {
        return;
    }
    let opacity = clamp(style.color.a, 0.0, 1.0) * 63.0;
    let half_width = half_width_px(style, camera, w);
    let dash = style.dash_px * camera.width_scale;
    // Coverage is above 0 only within `reach` of the piece.
    let reach = half_width + 0.5;
    let pa = ends.p;
    let d = ends.q - pa;
    let len = length(d);
    var dir = vec2<f32>(1.0, 0.0);
    if (len > 1e-6) {
        dir = d / len;
    } else if (start != END_ROUND || end != END_ROUND) {
        // A piece of no length has no direction to cut it square by.
        return;
    }
    // The pixels scanned: the piece, lengthened by half the width at a square end.
    let sa = pa - select(0.0, half_width, start == END_SQUARE) * dir;
    let sb = ends.q + select(0.0, half_width, end == END_SQUARE) * dir;
    let size = layer_size();
    // The major axis first (swapped back for the pixel).
    let x_major = abs(d.x) >= abs(d.y);
    let major = along_major(sa, sb, x_major);
    let s = major[0];
    let e = major[1];
    let extent = select(vec2<f32>(size).yx, vec2<f32>(size), x_major);
    let slope = (e.y - s.y) / max(e.x - s.x, 1e-30);
    // Across the piece, within reach: `reach √(1 + slope²)` rows either side of it.
    let across = reach * sqrt(1.0 + slope * slope);
    let first = max(ceil(s.x - reach - 0.5), 0.0);
    let last = min(floor(e.x + reach - 0.5), extent.x - 1.0);
    if (!(first <= last)) {
        return;
    }
    for (var column = first; column <= last; column += 1.0) {
        let xc = column + 0.5;
        let yc = s.y + (clamp(xc, s.x, e.x) - s.x) * slope;
        let top = max(ceil(yc - across - 0.5), 0.0);
        let bottom = min(floor(yc + across - 0.5), extent.y - 1.0);
        for (var row = top; row <= bottom; row += 1.0) {
            var pixel = vec2<f32>(xc, row + 0.5);
            if (!x_major) {
                pixel = pixel.yx;
            }
            let t = dot(pixel - pa, dir);
            var along = clamp(t, 0.0, len);
            // Past a cut end, the distance is to the piece's line.
            if ((t < 0.0 && start != END_ROUND) || (t > len && end != END_ROUND)) {
                along = t;
            }
            let dist = length(pixel - (pa + along * dir));
            var coverage = clamp(half_width + 0.5 - dist, 0.0, 1.0);
            coverage = min(coverage, end_coverage(t, start, half_width));
            coverage = min(coverage, end_coverage(len - t, end, half_width));
            if (dash > 0.0 && fract(along / dash) >= 0.5) {
                coverage = 0.0;
            }
            let alpha = u32(round(opacity * coverage));
            if (alpha > 0u) {
                let at = vec2<u32>(pixel);
                let index = at.y * size.x + at.x;
                if (index < arrayLength(&layer_rw)) {
                    let key = key_of(KIND_CURVE, coverage >= 0.5, style.order, alpha);
                    atomicMax(&layer_rw[index], key);
                }
            }
        }
    }
}

// How much of a pixel `t` pixels inside a piece's end (negative: outside) an end drawn
// as `mode` leaves (a round end is the capsule's: 1).
fn end_coverage(t: f32, mode: u32, half_width: f32) -> f32 {
    if (mode == END_BUTT) {
        return clamp(0.5 + t, 0.0, 1.0);
    }
    if (mode == END_SQUARE) {
        return clamp(0.5 + t + half_width, 0.0, 1.0);
    }
    if (mode == END_HARD) {
        return select(0.0, 1.0, t >= 0.0);
    }
    return 1.0;
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
    let alpha = f32(key & 0x3fu) / 63.0;
    let index = min((key >> 6u) & ORDER_MASK, max(arrayLength(&layer_styles), 1u) - 1u);
    let rgb = clamp(layer_styles[index].color.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
    return vec4<f32>(rgb * alpha, alpha);
}
