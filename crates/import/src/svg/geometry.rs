//! SVG geometry as path segments: path data (every command, relative and smooth forms
//! resolved), elliptical arcs as exact rational quadratics of at most 90° each, and the
//! basic shapes. Coordinates are the element's user units; the caller applies the
//! transforms (an affine map keeps every segment exact: a rational Bézier curve maps by
//! its control points, its weights unchanged).

use glam::{DAffine2, DVec2};
use splinescope_core::geom::PathSegment;

/// One subpath: its segments in order and whether it was closed (`Z`).
#[derive(Debug, Clone, PartialEq)]
pub struct Subpath {
    /// The segments, each starting where the one before ends.
    pub segments: Vec<Seg>,
    /// Whether it ends with `Z` (its last segment then ends at its first point).
    pub closed: bool,
}

/// A segment in 2D user units: its control points and, for an arc piece, its weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Seg {
    /// The control points.
    pub points: Vec<DVec2>,
    /// The weights of a rational segment.
    pub weights: Option<Vec<f64>>,
}

impl Seg {
    fn line(a: DVec2, b: DVec2) -> Seg {
        Seg {
            points: vec![a, b],
            weights: None,
        }
    }

    /// The segment mapped by `m`, as a path segment in the plane `z = 0`.
    #[must_use]
    pub fn mapped(&self, m: DAffine2) -> PathSegment {
        PathSegment {
            points: self
                .points
                .iter()
                .map(|&p| m.transform_point2(p).extend(0.0))
                .collect(),
            weights: self.weights.clone(),
        }
    }
}

/// What is wrong with an element's geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct GeometryError(pub String);

/// `√2 / 2`: the middle weight of a quarter circle.
const QUARTER: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The arc of the ellipse centred on `c`, radii `r`, its x axis rotated by `phi`
/// (radians), from angle `theta` over `delta` (radians, signed), as rational quadratics of
/// at most a quarter turn each: a piece of half-angle `h` has its middle control point
/// where the end tangents meet, weight `cos h` — the ellipse exactly (the unit circle's
/// arc, mapped by the ellipse's affine map). The first piece starts at `start` and the
/// last ends at `end` exactly (the caller's points), so the arc joins what is around it.
fn arc_pieces(
    c: DVec2,
    r: DVec2,
    phi: f64,
    theta: f64,
    delta: f64,
    start: DVec2,
    end: DVec2,
) -> Vec<Seg> {
    let n = ((delta.abs() / std::f64::consts::FRAC_PI_2) - 1e-9)
        .ceil()
        .max(1.0) as usize;
    let step = delta / n as f64;
    let h = 0.5 * step;
    let (sp, cp) = phi.sin_cos();
    let map = |u: DVec2| {
        let (x, y) = (r.x * u.x, r.y * u.y);
        c + DVec2::new(cp * x - sp * y, sp * x + cp * y)
    };
    let at = |a: f64| DVec2::new(a.cos(), a.sin());
    let mut out = Vec::with_capacity(n);
    let mut p0 = start;
    for i in 0..n {
        let a0 = theta + step * i as f64;
        let p2 = if i + 1 == n { end } else { map(at(a0 + step)) };
        let mid = map(at(a0 + h) / h.cos());
        out.push(Seg {
            points: vec![p0, mid, p2],
            weights: Some(vec![1.0, h.cos(), 1.0]),
        });
        p0 = p2;
    }
    out
}

/// The unit circle's arc from angle `a0` counter-clockwise over `sweep` radians
/// (`0 < sweep ≤ 2π`, a whole turn closing on its start point) as [`arc_pieces`] gives
/// it: what DXF and STEP conics map onto their own axes.
pub(crate) fn unit_arc(a0: f64, sweep: f64) -> Vec<Seg> {
    let at = |a: f64| DVec2::new(a.cos(), a.sin());
    let end = if sweep >= std::f64::consts::TAU {
        at(a0)
    } else {
        at(a0 + sweep)
    };
    arc_pieces(DVec2::ZERO, DVec2::ONE, 0.0, a0, sweep, at(a0), end)
}

/// The angle from `u` to `v` (radians, in `(−π, π]`).
fn angle(u: DVec2, v: DVec2) -> f64 {
    u.perp_dot(v).atan2(u.dot(v))
}

/// An SVG elliptical arc from `p1` to `p2` (the endpoint parametrisation of SVG's
/// implementation notes, F.6.5 and F.6.6: radii scaled up when too small, a zero radius a
/// straight line, equal end points nothing).
#[must_use]
pub fn svg_arc(
    p1: DVec2,
    p2: DVec2,
    rx: f64,
    ry: f64,
    rotation_deg: f64,
    large: bool,
    sweep: bool,
) -> Vec<Seg> {
    if p1 == p2 {
        return Vec::new();
    }
    let (mut rx, mut ry) = (rx.abs(), ry.abs());
    if rx == 0.0 || ry == 0.0 {
        return vec![Seg::line(p1, p2)];
    }
    let phi = rotation_deg.to_radians();
    let (sp, cp) = phi.sin_cos();
    let d = 0.5 * (p1 - p2);
    let x1 = cp * d.x + sp * d.y;
    let y1 = -sp * d.x + cp * d.y;
    let lambda = (x1 * x1) / (rx * rx) + (y1 * y1) / (ry * ry);
    if lambda > 1.0 {
        let s = lambda.sqrt();
        rx *= s;
        ry *= s;
    }
    let num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    let den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    let mut coef = (num / den).max(0.0).sqrt();
    if large == sweep {
        coef = -coef;
    }
    let (cx1, cy1) = (coef * rx * y1 / ry, -coef * ry * x1 / rx);
    let mid = 0.5 * (p1 + p2);
    let c = DVec2::new(cp * cx1 - sp * cy1, sp * cx1 + cp * cy1) + mid;
    let u = DVec2::new((x1 - cx1) / rx, (y1 - cy1) / ry);
    let v = DVec2::new((-x1 - cx1) / rx, (-y1 - cy1) / ry);
    let theta = angle(DVec2::X, u);
    let mut delta = angle(u, v);
    if !sweep && delta > 0.0 {
        delta -= std::f64::consts::TAU;
    } else if sweep && delta < 0.0 {
        delta += std::f64::consts::TAU;
    }
    if !(c.is_finite() && theta.is_finite() && delta.is_finite()) {
        return vec![Seg::line(p1, p2)];
    }
    arc_pieces(c, DVec2::new(rx, ry), phi, theta, delta, p1, p2)
}

/// The whole ellipse centred on `c` with radii `rx`, `ry`: four quarter arcs through its
/// axis ends, each corner an exact control point (no sines), closed.
#[must_use]
pub fn ellipse(c: DVec2, rx: f64, ry: f64) -> Subpath {
    let p = |x: f64, y: f64| c + DVec2::new(x * rx, y * ry);
    let corners = [
        (p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)),
        (p(0.0, 1.0), p(-1.0, 1.0), p(-1.0, 0.0)),
        (p(-1.0, 0.0), p(-1.0, -1.0), p(0.0, -1.0)),
        (p(0.0, -1.0), p(1.0, -1.0), p(1.0, 0.0)),
    ];
    Subpath {
        segments: corners
            .into_iter()
            .map(|(a, b, c)| Seg {
                points: vec![a, b, c],
                weights: Some(vec![1.0, QUARTER, 1.0]),
            })
            .collect(),
        closed: true,
    }
}

/// A rectangle, its corners rounded by quarter ellipses of radii `rx`, `ry` (already
/// resolved and clamped to half the sides), closed.
#[must_use]
pub fn rect(x: f64, y: f64, w: f64, h: f64, rx: f64, ry: f64) -> Subpath {
    let p = DVec2::new;
    if rx <= 0.0 || ry <= 0.0 {
        let c = [p(x, y), p(x + w, y), p(x + w, y + h), p(x, y + h)];
        return Subpath {
            segments: (0..4).map(|i| Seg::line(c[i], c[(i + 1) % 4])).collect(),
            closed: true,
        };
    }
    let corner = |a: DVec2, k: DVec2, b: DVec2| Seg {
        points: vec![a, k, b],
        weights: Some(vec![1.0, QUARTER, 1.0]),
    };
    let mut segs = Vec::new();
    let line = |segs: &mut Vec<Seg>, a: DVec2, b: DVec2| {
        if a != b {
            segs.push(Seg::line(a, b));
        }
    };
    line(&mut segs, p(x + rx, y), p(x + w - rx, y));
    segs.push(corner(p(x + w - rx, y), p(x + w, y), p(x + w, y + ry)));
    line(&mut segs, p(x + w, y + ry), p(x + w, y + h - ry));
    segs.push(corner(
        p(x + w, y + h - ry),
        p(x + w, y + h),
        p(x + w - rx, y + h),
    ));
    line(&mut segs, p(x + w - rx, y + h), p(x + rx, y + h));
    segs.push(corner(p(x + rx, y + h), p(x, y + h), p(x, y + h - ry)));
    line(&mut segs, p(x, y + h - ry), p(x, y + ry));
    segs.push(corner(p(x, y + ry), p(x, y), p(x + rx, y)));
    Subpath {
        segments: segs,
        closed: true,
    }
}

/// A polyline through `points` (closed for a polygon); nothing for fewer than two.
#[must_use]
pub fn polyline(points: &[DVec2], closed: bool) -> Option<Subpath> {
    if points.len() < 2 {
        return None;
    }
    let mut segments: Vec<Seg> = points.windows(2).map(|w| Seg::line(w[0], w[1])).collect();
    if closed && points[0] != points[points.len() - 1] {
        segments.push(Seg::line(points[points.len() - 1], points[0]));
    }
    Some(Subpath { segments, closed })
}

/// Path data (`d`) as subpaths: relative commands made absolute, `H`/`V` as lines, `S`/`T`
/// with their reflected control points, arcs exact, `Z` closing with a line where the
/// last point differs from the first, a command after `Z` starting at the subpath's
/// start. A subpath of a lone `M` draws nothing and is dropped.
///
/// # Errors
/// The first malformed command or non-finite number, with the path data's offset.
pub fn path_data(d: &str) -> Result<Vec<Subpath>, GeometryError> {
    use svgtypes::PathSegment as S;
    let mut out: Vec<Subpath> = Vec::new();
    let mut cur: Vec<Seg> = Vec::new();
    let (mut pos, mut start) = (DVec2::ZERO, DVec2::ZERO);
    // The last control point of a cubic (for S) or a quadratic (for T).
    let (mut last_cubic, mut last_quad): (Option<DVec2>, Option<DVec2>) = (None, None);
    let flush = |cur: &mut Vec<Seg>, out: &mut Vec<Subpath>, closed: bool| {
        if !cur.is_empty() {
            out.push(Subpath {
                segments: std::mem::take(cur),
                closed,
            });
        }
    };
    for (k, seg) in svgtypes::PathParser::from(d).enumerate() {
        let seg = seg.map_err(|e| GeometryError(format!("path data: {e}")))?;
        let rel = |abs: bool, p: DVec2, base: DVec2| if abs { p } else { base + p };
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        let (mut next_cubic, mut next_quad) = (None, None);
        match seg {
            S::MoveTo { abs, x, y } => {
                check(finite(&[x, y]), k)?;
                flush(&mut cur, &mut out, false);
                pos = rel(abs, DVec2::new(x, y), pos);
                start = pos;
            }
            S::LineTo { abs, x, y } => {
                check(finite(&[x, y]), k)?;
                let p = rel(abs, DVec2::new(x, y), pos);
                cur.push(Seg::line(pos, p));
                pos = p;
            }
            S::HorizontalLineTo { abs, x } => {
                check(finite(&[x]), k)?;
                let p = DVec2::new(if abs { x } else { pos.x + x }, pos.y);
                cur.push(Seg::line(pos, p));
                pos = p;
            }
            S::VerticalLineTo { abs, y } => {
                check(finite(&[y]), k)?;
                let p = DVec2::new(pos.x, if abs { y } else { pos.y + y });
                cur.push(Seg::line(pos, p));
                pos = p;
            }
            S::CurveTo {
                abs,
                x1,
                y1,
                x2,
                y2,
                x,
                y,
            } => {
                check(finite(&[x1, y1, x2, y2, x, y]), k)?;
                let (c1, c2, p) = (
                    rel(abs, DVec2::new(x1, y1), pos),
                    rel(abs, DVec2::new(x2, y2), pos),
                    rel(abs, DVec2::new(x, y), pos),
                );
                cur.push(cubic(pos, c1, c2, p));
                next_cubic = Some(c2);
                pos = p;
            }
            S::SmoothCurveTo { abs, x2, y2, x, y } => {
                check(finite(&[x2, y2, x, y]), k)?;
                let c1 = last_cubic.map_or(pos, |c| 2.0 * pos - c);
                let (c2, p) = (
                    rel(abs, DVec2::new(x2, y2), pos),
                    rel(abs, DVec2::new(x, y), pos),
                );
                cur.push(cubic(pos, c1, c2, p));
                next_cubic = Some(c2);
                pos = p;
            }
            S::Quadratic { abs, x1, y1, x, y } => {
                check(finite(&[x1, y1, x, y]), k)?;
                let (c, p) = (
                    rel(abs, DVec2::new(x1, y1), pos),
                    rel(abs, DVec2::new(x, y), pos),
                );
                cur.push(quadratic(pos, c, p));
                next_quad = Some(c);
                pos = p;
            }
            S::SmoothQuadratic { abs, x, y } => {
                check(finite(&[x, y]), k)?;
                let c = last_quad.map_or(pos, |q| 2.0 * pos - q);
                let p = rel(abs, DVec2::new(x, y), pos);
                cur.push(quadratic(pos, c, p));
                next_quad = Some(c);
                pos = p;
            }
            S::EllipticalArc {
                abs,
                rx,
                ry,
                x_axis_rotation,
                large_arc,
                sweep,
                x,
                y,
            } => {
                check(finite(&[rx, ry, x_axis_rotation, x, y]), k)?;
                let p = rel(abs, DVec2::new(x, y), pos);
                cur.extend(svg_arc(pos, p, rx, ry, x_axis_rotation, large_arc, sweep));
                pos = p;
            }
            S::ClosePath { .. } => {
                if !cur.is_empty() && pos != start {
                    cur.push(Seg::line(pos, start));
                }
                flush(&mut cur, &mut out, true);
                pos = start;
            }
        }
        last_cubic = next_cubic;
        last_quad = next_quad;
    }
    flush(&mut cur, &mut out, false);
    Ok(out)
}

fn check(ok: bool, command: usize) -> Result<(), GeometryError> {
    if ok {
        Ok(())
    } else {
        Err(GeometryError(format!(
            "path data command {command}: a number that is not finite"
        )))
    }
}

fn cubic(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Seg {
    Seg {
        points: vec![a, b, c, d],
        weights: None,
    }
}

fn quadratic(a: DVec2, b: DVec2, c: DVec2) -> Seg {
    Seg {
        points: vec![a, b, c],
        weights: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rational quadratic `(P0, P1, P2; 1, w, 1)` at `u`.
    fn eval(s: &Seg, u: f64) -> DVec2 {
        let w = s.weights.as_ref().map_or(1.0, |w| w[1]);
        let b = [(1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u) * w, u * u];
        let num = s.points[0] * b[0] + s.points[1] * b[1] + s.points[2] * b[2];
        num / (b[0] + b[1] + b[2])
    }

    #[test]
    fn an_arc_is_exact_pieces_of_at_most_a_quarter_turn_on_its_ellipse() {
        // Half of the circle of radius 5 about (5, 0), from (0, 0) to (10, 0).
        let segs = svg_arc(
            DVec2::ZERO,
            DVec2::new(10.0, 0.0),
            5.0,
            5.0,
            0.0,
            false,
            true,
        );
        assert_eq!(segs.len(), 2);
        assert_eq!(segs[0].points[0], DVec2::ZERO);
        assert_eq!(segs[1].points[2], DVec2::new(10.0, 0.0));
        for s in &segs {
            for k in 0..=64 {
                let p = eval(s, f64::from(k) / 64.0);
                assert!(
                    ((p - DVec2::new(5.0, 0.0)).length() - 5.0).abs() < 1e-13,
                    "{p}"
                );
            }
        }
        // Radii too small are scaled up: a half circle through the two points.
        let segs = svg_arc(
            DVec2::ZERO,
            DVec2::new(10.0, 0.0),
            1.0,
            1.0,
            0.0,
            false,
            true,
        );
        let p = eval(&segs[0], 1.0);
        assert!(((p - DVec2::new(5.0, 0.0)).length() - 5.0).abs() < 1e-13);
        // A zero radius is a line; equal end points nothing.
        assert_eq!(
            svg_arc(DVec2::ZERO, DVec2::ONE, 0.0, 3.0, 0.0, false, false).len(),
            1
        );
        assert!(svg_arc(DVec2::ONE, DVec2::ONE, 3.0, 3.0, 0.0, false, false).is_empty());
    }

    #[test]
    fn path_data_resolves_relative_and_smooth_commands() {
        let subs =
            path_data("m 1 1 h 2 v 2 H 1 z M 10 10 q 1 1 2 0 t 2 0 c 0 1 1 1 1 0 s 1 -1 1 0")
                .expect("valid");
        assert_eq!(subs.len(), 2);
        assert!(subs[0].closed);
        // The square: three lines and the closing one.
        assert_eq!(subs[0].segments.len(), 4);
        assert_eq!(
            subs[0].segments[3].points,
            vec![DVec2::new(1.0, 3.0), DVec2::new(1.0, 1.0)]
        );
        let s = &subs[1].segments;
        // T reflects the quadratic's control point: (11, 11) about (12, 10) is (13, 9).
        assert_eq!(s[1].points[1], DVec2::new(13.0, 9.0));
        // S reflects the cubic's second control point: (15, 11) about (15, 10).
        assert_eq!(s[3].points[1], DVec2::new(15.0, 9.0));
        assert!(path_data("M 0 0 L 1").is_err());
        assert!(path_data("M 0 0 L 1e999 0").is_err());
    }
}
