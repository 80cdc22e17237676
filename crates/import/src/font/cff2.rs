//! A CFF2 font's outlines away from its default location, in `f64`.
//!
//! A CFF2 charstring's `blend` adds to each value its deltas times the scalars of their
//! regions at the location; `read-fonts` evaluates it in 16.16 fixed point, from a
//! location itself rounded to 2.14 (about 6·10⁻⁵ of an axis): a point can be off by
//! 10⁻³ font units. The outline is linear in the regions' scalars — every point is its
//! default plus, per region, the scalar times that region's delta — and the evaluator
//! is exact where every scalar is 0 or 1 (a product by 1 or 0 does not round, a sum of
//! 16.16 values does not either). So each glyph is evaluated by `read-fonts` once at the
//! default and once per region that counts at the location, through a variation store
//! made here whose regions each sit on an axis of their own (the font's region `r` is
//! 1 where that axis is 1 and 0 everywhere else; every other region is 0 everywhere):
//! the difference from the default is region `r`'s delta of every point, exactly. The
//! points are then summed in `f64` with the regions' scalars at the location normalised
//! in `f64` (`variable::normalized`, `variable::region_scalar`) — fontTools' reading of
//! the same font; a closed contour gets its closing line where, at the location, its
//! last point is not its first. The store is only the region list and the font's lists of which
//! regions each `vsindex` uses; the font's charstrings are evaluated as they are.

use glam::DVec3;
use skrifa::raw::ps::cff::CffFontRef;
use skrifa::raw::ps::cff::blend::BlendState;
use skrifa::raw::ps::cff::index::Index;
use skrifa::raw::ps::cs;
use skrifa::raw::tables::variations::ItemVariationStore;
use skrifa::raw::types::F2Dot14;
use skrifa::raw::{FontData, FontRead};
use skrifa::{FontRef, GlyphId};
use splinescope_core::geom::{PathSegment, SegmentPoints};

use super::{Contours, Exact, variable};

/// Regions that may count at one location: past this, the glyphs are evaluated by
/// `read-fonts` in 16.16 (a location where more count is one that nobody designs: each
/// glyph would be evaluated once per region).
pub(super) const MAX_REGIONS: usize = 64;

/// The regions that count at the location, and the store that isolates each.
pub(super) struct Cff2Blend {
    /// Per region that counts, its index in the font's region list and its scalar.
    regions: Vec<(usize, f64)>,
    /// The variation store made here (see the module docs).
    store: Vec<u8>,
}

/// A contour as the pen gives it: its segments, and whether it is closed.
type Contour = (Vec<PathSegment>, bool);

impl Cff2Blend {
    /// The plan for `cff` (a CFF2 font's table) at `location` (axis tag, user value):
    /// `Ok(None)` when the font has no variation store or no axes, `Err(n)` when `n`
    /// regions, more than [`MAX_REGIONS`], count there.
    pub(super) fn new(
        font: &FontRef<'_>,
        cff: &CffFontRef<'_>,
        location: &[(String, f64)],
    ) -> Result<Option<Cff2Blend>, usize> {
        let (Some(coords), Some(store)) = (variable::normalized(font, location), cff.var_store())
        else {
            return Ok(None);
        };
        let Ok(list) = store.variation_region_list() else {
            return Ok(None);
        };
        let mut regions = Vec::new();
        for (r, region) in list.variation_regions().iter().enumerate() {
            let Ok(region) = region else {
                return Ok(None);
            };
            let axes = region.region_axes().iter().enumerate().map(|(i, a)| {
                (
                    i,
                    f64::from(a.start_coord().to_f32()),
                    f64::from(a.peak_coord().to_f32()),
                    f64::from(a.end_coord().to_f32()),
                )
            });
            let s = variable::region_scalar(&coords, axes);
            if s != 0.0 {
                regions.push((r, s));
            }
        }
        if regions.len() > MAX_REGIONS {
            return Err(regions.len());
        }
        // The store: one axis per region that counts and one more that stays at 0;
        // region `regions[k].0` peaks on axis `k`, every other on the last axis.
        let axis_count = regions.len() + 1;
        let region_count = usize::from(list.region_count());
        let mut bytes: Vec<u8> = Vec::new();
        let data: Vec<Option<Vec<u16>>> = store
            .item_variation_data()
            .iter()
            .map(|d| {
                d.and_then(Result::ok)
                    .map(|d| d.region_indexes().iter().map(|i| i.get()).collect())
            })
            .collect();
        let u16be = |b: &mut Vec<u8>, v: usize| b.extend_from_slice(&(v as u16).to_be_bytes());
        let u32be = |b: &mut Vec<u8>, v: usize| b.extend_from_slice(&(v as u32).to_be_bytes());
        let header = 2 + 4 + 2 + 4 * data.len();
        let list_len = 4 + region_count * axis_count * 6;
        u16be(&mut bytes, 1);
        u32be(&mut bytes, header);
        u16be(&mut bytes, data.len());
        let mut at = header + list_len;
        for d in &data {
            match d {
                Some(d) => {
                    u32be(&mut bytes, at);
                    at += 6 + 2 * d.len();
                }
                None => u32be(&mut bytes, 0),
            }
        }
        u16be(&mut bytes, axis_count);
        u16be(&mut bytes, region_count);
        let one = F2Dot14::from_f32(1.0).to_bits().to_be_bytes();
        for r in 0..region_count {
            let own = regions
                .iter()
                .position(|&(q, _)| q == r)
                .unwrap_or(axis_count - 1);
            for axis in 0..axis_count {
                if axis == own {
                    bytes.extend_from_slice(&[0, 0]);
                    bytes.extend_from_slice(&one);
                    bytes.extend_from_slice(&one);
                } else {
                    bytes.extend_from_slice(&[0; 6]);
                }
            }
        }
        for d in data.iter().flatten() {
            u16be(&mut bytes, 0);
            u16be(&mut bytes, 0);
            u16be(&mut bytes, d.len());
            for &i in d {
                u16be(&mut bytes, usize::from(i));
            }
        }
        Ok(Some(Cff2Blend {
            regions,
            store: bytes,
        }))
    }

    /// Glyph `gid`'s contours at the location, each point moved by `offset`.
    ///
    /// # Errors
    /// The evaluator's, or an outline whose segments differ between evaluations (not a
    /// font a CFF2 reader can make: its charstring is the same at every location).
    pub(super) fn contours(
        &self,
        cff: &CffFontRef<'_>,
        gid: GlyphId,
        offset: DVec3,
    ) -> Result<Vec<Contour>, String> {
        let store = ItemVariationStore::read(FontData::new(&self.store))
            .map_err(|e| format!("the variation store: {e}"))?;
        let axis_count = self.regions.len() + 1;
        let zero = vec![F2Dot14::ZERO; axis_count];
        let index = cff.subfont_index(gid).unwrap_or(0);
        let subfont = cff.subfont(index, &zero).map_err(|e| e.to_string())?;
        let subrs = match subfont.subrs_offset() {
            0 => Index::Empty,
            at => Index::new(
                cff.data()
                    .get(at as usize..)
                    .ok_or("a private dict's subroutines past the table's end")?,
                true,
            )
            .map_err(|e| e.to_string())?,
        };
        let charstring = cff
            .charstrings()
            .get(gid.to_u32() as usize)
            .map_err(|e| e.to_string())?;
        let context = (cff.data(), cff.charstrings(), cff.global_subrs(), &subrs);
        let evaluate = |coords: &[F2Dot14]| -> Result<Vec<Contour>, String> {
            let blend = BlendState::new(store.clone(), coords, subfont.vs_index())
                .map_err(|e| e.to_string())?;
            let mut pen = Contours {
                no_closing_lines: true,
                ..Contours::default()
            };
            pen.reset(DVec3::ZERO);
            cs::evaluate(&context, Some(blend), charstring, &mut Exact(&mut pen))
                .map_err(|e| e.to_string())?;
            pen.finish(false);
            Ok(std::mem::take(&mut pen.done))
        };
        let mut out = evaluate(&zero)?;
        let base = out.clone();
        let mut coords = zero.clone();
        for (k, &(_, scalar)) in self.regions.iter().enumerate() {
            coords[k] = F2Dot14::from_f32(1.0);
            let moved = evaluate(&coords)?;
            coords[k] = F2Dot14::ZERO;
            if !same_shape(&moved, &base) {
                return Err("its outline differs between a region's peak and the default".into());
            }
            for ((o, m), b) in out.iter_mut().zip(&moved).zip(&base) {
                for ((os, ms), bs) in o.0.iter_mut().zip(&m.0).zip(&b.0) {
                    for ((op, mp), bp) in os.points.iter_mut().zip(&ms.points).zip(&bs.points) {
                        *op += (*mp - *bp) * scalar;
                    }
                }
            }
        }
        for (segments, closed) in &mut out {
            for s in segments.iter_mut() {
                for p in &mut s.points {
                    *p += offset;
                }
            }
            // A closing line only where the last point is not the first, at the location.
            if let (true, Some(first), Some(last)) = (*closed, segments.first(), segments.last()) {
                let (start, end) = (first.points[0], last.points[last.points.len() - 1]);
                if start != end {
                    segments.push(PathSegment::polynomial(SegmentPoints::from_slice(&[
                        end, start,
                    ])));
                }
            }
        }
        Ok(out)
    }
}

/// Whether two outlines have the same contours, segments and points per segment.
fn same_shape(a: &[Contour], b: &[Contour]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.1 == y.1
                && x.0.len() == y.0.len()
                && x.0
                    .iter()
                    .zip(&y.0)
                    .all(|(s, t)| s.points.len() == t.points.len())
        })
}
