//! A variable TrueType font's outlines away from its default location, in `f64`: the
//! location normalised in `f64` (fvar's ranges, then avar's maps), each `gvar` tuple's
//! scalar in `f64` (OpenType's region rule), its deltas scaled and summed in `f64`, the
//! deltas of points a tuple leaves out inferred by OpenType's interpolation of untouched
//! points (IUP), composite glyphs through their components' moved offsets and transforms,
//! and the outline placed by its moved left phantom point — fontTools' reading of the
//! same font, unrounded (skrifa's FreeType-compatible scaler rounds it to whole units).
//! Tables are read by `read-fonts`.

use glam::DVec2;
use skrifa::GlyphId;
use skrifa::raw::tables::glyf::{Anchor, CompositeGlyphFlags, Glyf, Glyph};
use skrifa::raw::tables::gvar::Gvar;
use skrifa::raw::tables::loca::Loca;
use skrifa::raw::{FontRef, TableProvider};

/// One contour: its points and which are on the curve.
pub(super) type Contour = (Vec<DVec2>, Vec<bool>);

/// What the outlines are read from.
pub(super) struct Variable<'a> {
    glyf: Glyf<'a>,
    loca: Loca<'a>,
    gvar: Gvar<'a>,
    hmtx: skrifa::raw::tables::hmtx::Hmtx<'a>,
    /// The normalised location, one value per axis.
    coords: Vec<f64>,
}

/// Outlines one glyph may load, components included.
const BUDGET: u32 = 4096;

/// Composite nesting this deep is refused (a cycle, or a hostile font).
const MAX_DEPTH: usize = 32;

impl<'a> Variable<'a> {
    /// The reader for `font` at `location` (axis tag, user value), or `None` for a font
    /// without `glyf` and `gvar`.
    pub(super) fn new(font: &FontRef<'a>, location: &[(String, f64)]) -> Option<Variable<'a>> {
        let glyf = font.glyf().ok()?;
        let loca = font.loca(None).ok()?;
        let gvar = font.gvar().ok()?;
        let hmtx = font.hmtx().ok()?;
        let coords = normalized(font, location)?;
        Some(Variable {
            glyf,
            loca,
            gvar,
            hmtx,
            coords,
        })
    }

    /// Glyph `gid`'s contours at the location, placed as fontTools places an instance:
    /// by its left side bearing and box in whole units (the moved left phantom point
    /// gives the bearing, `round(xMin − left)`, and the outline moves by that bearing less
    /// `round(xMin)`); the outline's own coordinates are unrounded.
    ///
    /// # Errors
    /// A table that does not read, a component anchored by point numbers (left to the
    /// caller's other reader), or composites nested past [`MAX_DEPTH`].
    pub(super) fn contours(&self, gid: GlyphId) -> Result<Vec<Contour>, String> {
        // Glyph outlines the glyph may still load (its components': a composite that
        // uses itself twice over would double at every level).
        let mut budget = BUDGET;
        let (mut contours, left) = self.outline(gid, 0, &mut budget)?;
        let x_min = contours
            .iter()
            .flat_map(|(pts, _)| pts.iter().map(|p| p.x))
            .fold(f64::INFINITY, f64::min);
        if x_min.is_finite() {
            let round = |x: f64| (x + 0.5).floor();
            let shift = round(x_min - left) - round(x_min);
            for (pts, _) in &mut contours {
                for p in pts.iter_mut() {
                    p.x += shift;
                }
            }
        }
        Ok(contours)
    }

    /// The contours and the moved left phantom point's x.
    fn outline(
        &self,
        gid: GlyphId,
        depth: usize,
        budget: &mut u32,
    ) -> Result<(Vec<Contour>, f64), String> {
        if depth > MAX_DEPTH {
            return Err(format!("composite glyphs nested deeper than {MAX_DEPTH}"));
        }
        if *budget == 0 {
            return Err(format!(
                "more than {BUDGET} component outlines in one glyph"
            ));
        }
        *budget -= 1;
        let glyph = self
            .loca
            .get_glyf(gid, &self.glyf)
            .map_err(|e| e.to_string())?;
        let lsb = f64::from(self.hmtx.side_bearing(gid).unwrap_or(0));
        let Some(glyph) = glyph else {
            return Ok((Vec::new(), -lsb));
        };
        let x_min = f64::from(glyph.x_min());
        let left = x_min - lsb;
        match glyph {
            Glyph::Simple(g) => {
                let mut pts: Vec<DVec2> = g
                    .points()
                    .map(|p| DVec2::new(f64::from(p.x), f64::from(p.y)))
                    .collect();
                let on: Vec<bool> = g.points().map(|p| p.on_curve).collect();
                let ends: Vec<usize> = g
                    .end_pts_of_contours()
                    .iter()
                    .map(|e| usize::from(e.get()))
                    .collect();
                let n = pts.len();
                let deltas = self.deltas(gid, n + 4, Some((&pts, &ends)))?;
                for (p, d) in pts.iter_mut().zip(&deltas) {
                    *p += *d;
                }
                let mut out = Vec::with_capacity(ends.len());
                let mut start = 0;
                for &end in &ends {
                    if end < start || end >= n {
                        return Err(format!("contour end {end} out of order"));
                    }
                    out.push((pts[start..=end].to_vec(), on[start..=end].to_vec()));
                    start = end + 1;
                }
                Ok((out, left + deltas[n].x))
            }
            Glyph::Composite(c) => {
                let comps: Vec<_> = c.components().collect();
                let deltas = self.deltas(gid, comps.len() + 4, None)?;
                let mut out = Vec::new();
                for (k, comp) in comps.iter().enumerate() {
                    let Anchor::Offset { x, y } = comp.anchor else {
                        return Err("a component anchored by point numbers".to_owned());
                    };
                    let offset = DVec2::new(f64::from(x), f64::from(y)) + deltas[k];
                    let t = comp.transform;
                    let (xx, yx, xy, yy) = (
                        f64::from(t.xx.to_f32()),
                        f64::from(t.yx.to_f32()),
                        f64::from(t.xy.to_f32()),
                        f64::from(t.yy.to_f32()),
                    );
                    let offset = if comp
                        .flags
                        .contains(CompositeGlyphFlags::SCALED_COMPONENT_OFFSET)
                    {
                        DVec2::new(xx * offset.x + xy * offset.y, yx * offset.x + yy * offset.y)
                    } else {
                        offset
                    };
                    let (child, _) = self.outline(comp.glyph.into(), depth + 1, budget)?;
                    for (pts, on) in child {
                        let moved = pts
                            .iter()
                            .map(|p| DVec2::new(xx * p.x + xy * p.y, yx * p.x + yy * p.y) + offset)
                            .collect();
                        out.push((moved, on));
                    }
                }
                Ok((out, left + deltas[comps.len()].x))
            }
        }
    }

    /// The summed deltas of glyph `gid`'s `count` points (its outline's and four phantom
    /// points, or its components' offsets and four), untouched outline points inferred
    /// when `iup` gives the outline and its contour ends.
    fn deltas(
        &self,
        gid: GlyphId,
        count: usize,
        iup: Option<(&[DVec2], &[usize])>,
    ) -> Result<Vec<DVec2>, String> {
        let mut total = vec![DVec2::ZERO; count];
        let Some(data) = self
            .gvar
            .glyph_variation_data(gid)
            .map_err(|e| e.to_string())?
        else {
            return Ok(total);
        };
        for tuple in data.tuples() {
            let scalar = self.scalar(
                &tuple.peak(),
                tuple.intermediate_start().as_ref(),
                tuple.intermediate_end().as_ref(),
            );
            if scalar == 0.0 {
                continue;
            }
            let mut d: Vec<Option<DVec2>> = vec![None; count];
            for delta in tuple.deltas() {
                if let Some(slot) = d.get_mut(usize::from(delta.position)) {
                    *slot = Some(DVec2::new(
                        f64::from(delta.x_delta),
                        f64::from(delta.y_delta),
                    ));
                }
            }
            if let Some((pts, ends)) = iup
                && !tuple.has_deltas_for_all_points()
            {
                infer_untouched(&mut d, pts, ends);
            }
            for (t, x) in total.iter_mut().zip(&d) {
                if let Some(x) = x {
                    *t += *x * scalar;
                }
            }
        }
        Ok(total)
    }

    /// A region's scalar at the location (fontTools' `supportScalar`, OpenType's rule).
    fn scalar(
        &self,
        peak: &skrifa::raw::tables::variations::Tuple<'_>,
        start: Option<&skrifa::raw::tables::variations::Tuple<'_>>,
        end: Option<&skrifa::raw::tables::variations::Tuple<'_>>,
    ) -> f64 {
        let f = |t: Option<&skrifa::raw::tables::variations::Tuple<'_>>, i: usize| {
            t.and_then(|t| t.get(i)).map(|x| f64::from(x.to_f32()))
        };
        region_scalar(
            &self.coords,
            (0..self.coords.len()).filter_map(|i| {
                let p = f(Some(peak), i)?;
                let (lo, hi) = match (f(start, i), f(end, i)) {
                    (Some(a), Some(b)) => (a, b),
                    _ => (p.min(0.0), p.max(0.0)),
                };
                Some((i, lo, p, hi))
            }),
        )
    }
}

/// A region's scalar at the normalised location `coords` (fontTools' `supportScalar`,
/// OpenType's rule), in `f64`: the product over its axes `(axis, start, peak, end)` of
/// the tent's height; an axis with peak 0, or with an invalid or zero-straddling range,
/// does not count; an axis past `coords` reads 0.
pub(super) fn region_scalar(
    coords: &[f64],
    axes: impl Iterator<Item = (usize, f64, f64, f64)>,
) -> f64 {
    let mut s = 1.0;
    for (i, lo, p, hi) in axes {
        let v = coords.get(i).copied().unwrap_or(0.0);
        if p == 0.0 || lo > p || p > hi || (lo < 0.0 && hi > 0.0) || v == p {
            continue;
        }
        if v <= lo || hi <= v {
            return 0.0;
        }
        s *= if v < p {
            (v - lo) / (p - lo)
        } else {
            (v - hi) / (p - hi)
        };
    }
    s
}

/// The location `location` (axis tag, user value; an axis not named at its default)
/// normalised in `f64` as fontTools normalises it: by the axis's range, then through
/// avar's map; `None` for a font without `fvar`.
pub(super) fn normalized(font: &FontRef<'_>, location: &[(String, f64)]) -> Option<Vec<f64>> {
    let fvar = font.fvar().ok()?;
    let axes = fvar.axes().ok()?;
    let avar = font.avar().ok();
    let mut coords = Vec::with_capacity(axes.len());
    for (i, axis) in axes.iter().enumerate() {
        let (min, default, max) = (
            f64::from(axis.min_value().to_f32()),
            f64::from(axis.default_value().to_f32()),
            f64::from(axis.max_value().to_f32()),
        );
        let tag = axis.axis_tag().to_string();
        let v = location
            .iter()
            .rev()
            .find(|(t, _)| *t == tag)
            .map_or(default, |(_, v)| *v)
            .clamp(min, max);
        let mut n = if v < default {
            (v - default) / (default - min)
        } else if v > default {
            (v - default) / (max - default)
        } else {
            0.0
        };
        if let Some(map) = avar
            .as_ref()
            .and_then(|a| a.axis_segment_maps().iter().nth(i))
            .and_then(Result::ok)
        {
            let pairs: Vec<(f64, f64)> = map
                .axis_value_maps()
                .iter()
                .map(|m| {
                    (
                        f64::from(m.from_coordinate().to_f32()),
                        f64::from(m.to_coordinate().to_f32()),
                    )
                })
                .collect();
            n = piecewise_linear(n, &pairs);
        }
        coords.push(n);
    }
    Some(coords)
}

/// fontTools' `piecewiseLinearMap`: `v` through the map's pairs (from → to), linear
/// between them, shifted beyond the ends.
fn piecewise_linear(v: f64, pairs: &[(f64, f64)]) -> f64 {
    if pairs.is_empty() {
        return v;
    }
    if let Some(&(_, to)) = pairs.iter().find(|(from, _)| *from == v) {
        return to;
    }
    let (first, last) = (pairs[0], pairs[pairs.len() - 1]);
    if v < first.0 {
        return v + first.1 - first.0;
    }
    if v > last.0 {
        return v + last.1 - last.0;
    }
    for w in pairs.windows(2) {
        let ((a, b), (c, d)) = (w[0], w[1]);
        if a < v && v < c {
            return b + (d - b) * (v - a) / (c - a);
        }
    }
    v
}

/// OpenType's inference of the deltas of points a tuple leaves out, contour by contour:
/// none touched, none moves; one touched, all move by its delta; otherwise each untouched
/// point, per coordinate, between its nearest touched neighbours before and after it: the
/// nearer's delta outside their span, interpolated by the original coordinates inside it,
/// and where the two coordinates are equal their common delta (0 when they differ).
fn infer_untouched(d: &mut [Option<DVec2>], pts: &[DVec2], ends: &[usize]) {
    let mut start = 0;
    for &end in ends {
        if end >= pts.len() || end < start {
            return;
        }
        let range = start..=end;
        let touched: Vec<usize> = range.clone().filter(|&i| d[i].is_some()).collect();
        if touched.is_empty() {
            start = end + 1;
            continue;
        }
        if touched.len() == 1 {
            let only = d[touched[0]];
            for i in range {
                d[i] = only;
            }
            start = end + 1;
            continue;
        }
        let n = end - start + 1;
        let mut filled = Vec::new();
        for (k, &a) in touched.iter().enumerate() {
            let b = touched[(k + 1) % touched.len()];
            // The untouched points after a, up to b (cyclically in the contour).
            let mut i = a;
            loop {
                i = start + (i - start + 1) % n;
                if i == b {
                    break;
                }
                let (pa, pb, p) = (pts[a], pts[b], pts[i]);
                let (da, db) = (d[a].unwrap_or_default(), d[b].unwrap_or_default());
                let one = |c: f64, ca: f64, cb: f64, xa: f64, xb: f64| -> f64 {
                    if ca == cb {
                        return if xa == xb { xa } else { 0.0 };
                    }
                    let (lo, hi, dlo, dhi) = if ca < cb {
                        (ca, cb, xa, xb)
                    } else {
                        (cb, ca, xb, xa)
                    };
                    if c <= lo {
                        dlo
                    } else if c >= hi {
                        dhi
                    } else {
                        dlo + (c - lo) / (hi - lo) * (dhi - dlo)
                    }
                };
                filled.push((
                    i,
                    DVec2::new(
                        one(p.x, pa.x, pb.x, da.x, db.x),
                        one(p.y, pa.y, pb.y, da.y, db.y),
                    ),
                ));
            }
        }
        for (i, v) in filled {
            d[i] = Some(v);
        }
        start = end + 1;
    }
}
