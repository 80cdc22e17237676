//! Every intersecting pair among many curves.
//!
//! 1. **Copies.** Curves whose lowered segments are identical (to the bit) and cover the
//!    same parameter domain coincide entirely: they are grouped, reported once as a group
//!    (not as `N²` coincident pairs), and only the first of each group enters what follows
//!    — in time proportional to the number of curves.
//! 2. **Pairs of boxes.** The segments' control boxes (widened by the resolution) are laid
//!    on a uniform grid whose cell is the boxes' median size; two boxes sharing a cell are
//!    a candidate pair, reported once — in the cell that holds the lower corner of their
//!    common part. Boxes spanning many cells are paired with every other box directly.
//! 3. **Pairs of segments** are intersected on every core (rayon), gathered per pair of
//!    curves, cleaned (`tidy`, `settle`), and the pairs of the groups'
//!    first curves passed on to every member of the groups.

use std::borrow::Borrow;
use std::hash::{Hash, Hasher};

use glam::DVec2;
use rayon::prelude::*;

use super::pair::piece_pair;
use super::{Intersections, PairIntersections, hit, overlap, refuse_crowded, settle, tidy};
use crate::analysis::curve::{AnalysisError, CurveAnalysis};
use crate::analysis::piece::Piece;

/// Curves that coincide entirely: the same segments over the same domain.
#[derive(Debug, Clone, PartialEq)]
pub struct Copies {
    /// The curves' indices, increasing (two or more).
    pub curves: Vec<usize>,
    /// The parameter domain they share (every point of it is common to all).
    pub domain: (f64, f64),
}

/// What many curves have in common.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AllIntersections {
    /// Every pair of curves that meet (not copies of each other), `i < j`, by `(i, j)`.
    pub pairs: Vec<PairIntersections>,
    /// The groups of copies, by their first curve.
    pub copies: Vec<Copies>,
}

/// Boxes spanning more cells than this in either direction are paired directly.
const WIDE: i64 = 16;

/// Every intersecting pair among `curves` (2D; 3D curves are refused) and the groups of
/// copies among them (see the module docs). Self-intersections are not included.
///
/// # Errors
/// [`AnalysisError::NotPlanar`] when a curve is 3D.
pub fn all_intersections<C: Borrow<CurveAnalysis> + Sync>(
    curves: &[C],
) -> Result<AllIntersections, AnalysisError> {
    let curves: Vec<&CurveAnalysis> = curves.iter().map(Borrow::borrow).collect();
    if curves.iter().any(|c| !c.is_planar()) {
        return Err(AnalysisError::NotPlanar {
            what: "intersections",
        });
    }
    for c in &curves {
        c.require_moderate("intersections")?;
    }
    let (groups, first) = copies(&curves);
    // The groups' first curves (and every curve that has no copy), in the order of their
    // boxes along a Z curve, and their segments copied in that order: neighbours in the
    // plane are neighbours in memory, so that the pairs, taken in that order, read memory
    // close to what they read last (the narrow phase was bound by cache misses).
    let mut reps: Vec<usize> = (0..curves.len()).filter(|&c| first[c] == c).collect();
    let centre = |c: usize| {
        let b = curves[c].control_box();
        0.5 * (b.min.truncate() + b.max.truncate())
    };
    let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
    for &c in &reps {
        let m = centre(c);
        if m.is_finite() {
            lo = lo.min(m);
            hi = hi.max(m);
        }
    }
    let span = (hi - lo).max(DVec2::splat(f64::MIN_POSITIVE));
    let z = |c: usize| {
        let q = ((centre(c) - lo) / span).clamp(DVec2::ZERO, DVec2::ONE) * 65535.0;
        morton(q.x as u32, q.y as u32)
    };
    let keys: Vec<u32> = reps.par_iter().map(|&c| z(c)).collect();
    let mut order: Vec<usize> = (0..reps.len()).collect();
    order.sort_unstable_by_key(|&k| keys[k]);
    reps = order.iter().map(|&k| reps[k]).collect();
    let starts: Vec<usize> = reps
        .iter()
        .scan(0, |acc, &c| {
            let here = *acc;
            *acc += curves[c].pieces().len();
            Some(here)
        })
        .collect();
    let local: Vec<Piece> = reps
        .par_iter()
        .flat_map_iter(|&c| curves[c].pieces().iter().map(Piece::geometry))
        .collect();
    let mut items: Vec<Item> = Vec::with_capacity(local.len());
    for (rank, &c) in reps.iter().enumerate() {
        for pi in 0..curves[c].pieces().len() {
            let (lo, hi) = local[starts[rank] + pi].bounds();
            // Widened by the resolution, so that an end on the other's boundary is paired.
            let m = 64.0 * f64::EPSILON * lo.abs().max(hi.abs()).max_element();
            items.push(Item {
                lo: lo - m,
                hi: hi + m,
                curve: rank,
                piece: starts[rank] + pi,
            });
        }
    }
    let mut pairs = box_pairs(&items);
    // By pair of curves (in Z order), then by their segments: every pair of curves is one
    // run, however many segments each has.
    pairs.par_sort_unstable_by_key(|&(ci, ka, cj, kb)| (ci, cj, ka, kb));
    let results: Vec<(usize, usize, PairIntersections)> = pairs
        .par_chunk_by(|x, y| x.0 == y.0 && x.2 == y.2)
        .filter_map(|run| {
            let (ri, rj) = (run[0].0, run[0].2);
            let (ci, cj) = (reps[ri], reps[rj]);
            let mut found = Intersections::default();
            for &(_, ka, _, kb) in run {
                let (a, b) = (&local[ka], &local[kb]);
                let ph = piece_pair(a, (0.0, 1.0), b, (0.0, 1.0));
                if let Err(e) = refuse_crowded(a, b, &ph) {
                    return Some(Err(named(e, ci, cj)));
                }
                found.hits.extend(ph.hits.iter().map(|h| hit(a, b, h)));
                found
                    .overlaps
                    .extend(ph.overlaps.into_iter().map(|o| overlap(a, b, o)));
            }
            if found.hits.is_empty() && found.overlaps.is_empty() {
                return None;
            }
            let found = settle(tidy(found), curves[ci], curves[cj]);
            if found.hits.is_empty() && found.overlaps.is_empty() {
                return None;
            }
            // In the curves' own order.
            Some(Ok(if ci < cj {
                (
                    ci,
                    cj,
                    PairIntersections {
                        i: ci,
                        j: cj,
                        found,
                    },
                )
            } else {
                let found = swapped(&found);
                (
                    cj,
                    ci,
                    PairIntersections {
                        i: cj,
                        j: ci,
                        found,
                    },
                )
            }))
        })
        .collect::<Result<_, _>>()?;
    // Every member of two groups meets as their first curves do.
    let members = |c: usize| -> &[usize] {
        groups
            .iter()
            .find(|g| g.curves[0] == c)
            .map_or(std::slice::from_ref(&first[c]), |g| g.curves.as_slice())
    };
    let mut out: Vec<PairIntersections> = Vec::with_capacity(results.len());
    for (ci, cj, p) in results {
        let (mi, mj) = if groups.is_empty() {
            (std::slice::from_ref(&ci), std::slice::from_ref(&cj))
        } else {
            (members(ci), members(cj))
        };
        for &i in mi {
            for &j in mj {
                out.push(if i < j {
                    PairIntersections {
                        i,
                        j,
                        found: p.found.clone(),
                    }
                } else {
                    PairIntersections {
                        i: j,
                        j: i,
                        found: swapped(&p.found),
                    }
                });
            }
        }
    }
    out.par_sort_unstable_by_key(|p| (p.i, p.j));
    Ok(AllIntersections {
        pairs: out,
        copies: groups,
    })
}

/// A pair's refusal, naming the two curves (in the caller's indices, the smaller
/// first, its parameters in the same order).
fn named(e: AnalysisError, ci: usize, cj: usize) -> AnalysisError {
    match e {
        AnalysisError::Crowded { s, t, leaves, .. } => {
            let (pair, s, t) = if ci < cj {
                ((ci, cj), s, t)
            } else {
                ((cj, ci), t, s)
            };
            AnalysisError::Crowded {
                pair: Some(pair),
                s,
                t,
                leaves,
            }
        }
        other => other,
    }
}

/// The Morton code of `(x, y)` (16 bits each): their bits interleaved, an order in which
/// near points are mostly near.
fn morton(x: u32, y: u32) -> u32 {
    let spread = |v: u32| {
        let mut v = v & 0xffff;
        v = (v | (v << 8)) & 0x00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333;
        (v | (v << 1)) & 0x5555_5555
    };
    spread(x) | (spread(y) << 1)
}

/// One segment's box on the grid.
#[derive(Debug, Clone, Copy)]
struct Item {
    lo: DVec2,
    hi: DVec2,
    curve: usize,
    piece: usize,
}

/// Intersections seen from the other curve: `s` and `t` exchanged, overlaps oriented by
/// the new first curve.
fn swapped(found: &Intersections) -> Intersections {
    let mut hits: Vec<super::Hit> = found
        .hits
        .iter()
        .map(|h| super::Hit {
            s: h.t,
            t: h.s,
            error_s: h.error_t,
            error_t: h.error_s,
            ..*h
        })
        .collect();
    hits.sort_by(|x, y| x.s.total_cmp(&y.s));
    let mut overlaps: Vec<super::Overlap> = found
        .overlaps
        .iter()
        .map(|o| {
            if o.t.0 <= o.t.1 {
                super::Overlap { s: o.t, t: o.s }
            } else {
                super::Overlap {
                    s: (o.t.1, o.t.0),
                    t: (o.s.1, o.s.0),
                }
            }
        })
        .collect();
    overlaps.sort_by(|x, y| x.s.0.total_cmp(&y.s.0));
    Intersections { hits, overlaps }
}

/// The groups of copies, and for each curve the first curve of its group (itself when it
/// has no copy).
fn copies(curves: &[&CurveAnalysis]) -> (Vec<Copies>, Vec<usize>) {
    let key = |c: &CurveAnalysis| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        c.domain().0.to_bits().hash(&mut h);
        c.domain().1.to_bits().hash(&mut h);
        for p in c.pieces() {
            for k in 0..2 {
                p.a(k).iter().for_each(|v| v.to_bits().hash(&mut h));
            }
            if let Some(w) = p.w() {
                w.iter().for_each(|v| v.to_bits().hash(&mut h));
            }
            p.t0.to_bits().hash(&mut h);
        }
        h.finish()
    };
    let same = |a: &CurveAnalysis, b: &CurveAnalysis| {
        a.domain() == b.domain()
            && a.pieces().len() == b.pieces().len()
            && a.pieces()
                .iter()
                .zip(b.pieces())
                .all(|(p, q)| same_piece(p, q))
    };
    // Curves by their key: equal keys side by side.
    let mut keyed: Vec<(u64, usize)> = curves
        .par_iter()
        .enumerate()
        .map(|(i, c)| (key(c), i))
        .collect();
    keyed.par_sort_unstable();
    let mut first: Vec<usize> = (0..curves.len()).collect();
    let mut groups: Vec<Copies> = Vec::new();
    for run in keyed.chunk_by(|x, y| x.0 == y.0).filter(|r| r.len() > 1) {
        // Within a run, split by exact equality (a hash collision is no copy).
        let mut rest: Vec<usize> = run.iter().map(|&(_, i)| i).collect();
        while let Some(&head) = rest.first() {
            let (group, others): (Vec<usize>, Vec<usize>) =
                rest.iter().partition(|&&i| same(curves[head], curves[i]));
            if group.len() > 1 {
                for &i in &group {
                    first[i] = head;
                }
                groups.push(Copies {
                    curves: group,
                    domain: curves[head].domain(),
                });
            }
            rest = others;
        }
    }
    groups.sort_by_key(|g| g.curves[0]);
    (groups, first)
}

/// Whether two segments are the same to the bit.
fn same_piece(p: &Piece, q: &Piece) -> bool {
    let bits = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    };
    p.t0.to_bits() == q.t0.to_bits()
        && p.t1.to_bits() == q.t1.to_bits()
        && (0..3).all(|k| bits(p.a(k), q.a(k)))
        && match (p.w(), q.w()) {
            (None, None) => true,
            (Some(a), Some(b)) => bits(a, b),
            _ => false,
        }
}

/// The pairs of boxes of different curves that overlap, `(curve, piece, curve, piece)`
/// with the first curve's index the smaller, each once.
fn box_pairs(items: &[Item]) -> Vec<(usize, usize, usize, usize)> {
    if items.len() < 2 {
        return Vec::new();
    }
    let overlap = |a: &Item, b: &Item| {
        a.curve != b.curve
            && a.lo.x <= b.hi.x
            && b.lo.x <= a.hi.x
            && a.lo.y <= b.hi.y
            && b.lo.y <= a.hi.y
    };
    let ordered = |a: &Item, b: &Item| {
        if a.curve < b.curve {
            (a.curve, a.piece, b.curve, b.piece)
        } else {
            (b.curve, b.piece, a.curve, a.piece)
        }
    };
    // The cell: the median of the boxes' larger sides (finite ones).
    let mut sides: Vec<f64> = items
        .iter()
        .map(|it| (it.hi - it.lo).max_element())
        .filter(|s| s.is_finite())
        .collect();
    let mid = sides.len() / 2;
    let cell = if sides.is_empty() {
        1.0
    } else {
        *sides.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    let lo = items.iter().fold(DVec2::INFINITY, |m, it| m.min(it.lo));
    let finite = cell.is_finite() && cell > 0.0 && lo.is_finite();
    let index = |x: f64, o: f64| ((x - o) / cell).floor() as i64;
    let (mut wide, mut narrow): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    for (k, it) in items.iter().enumerate() {
        let fits = finite
            && it.hi.is_finite()
            && index(it.hi.x, lo.x) - index(it.lo.x, lo.x) <= WIDE
            && index(it.hi.y, lo.y) - index(it.lo.y, lo.y) <= WIDE;
        if fits {
            narrow.push(k);
        } else {
            wide.push(k);
        }
    }
    // (cell, item) for every cell an item's box touches, sorted by cell.
    let mut cells: Vec<((i64, i64), u32)> = narrow
        .par_iter()
        .flat_map_iter(|&k| {
            let it = &items[k];
            let (x0, x1) = (index(it.lo.x, lo.x), index(it.hi.x, lo.x));
            let (y0, y1) = (index(it.lo.y, lo.y), index(it.hi.y, lo.y));
            (x0..=x1).flat_map(move |x| (y0..=y1).map(move |y| ((x, y), k as u32)))
        })
        .collect();
    cells.par_sort_unstable();
    let mut out: Vec<(usize, usize, usize, usize)> = cells
        .par_chunk_by(|p, q| p.0 == q.0)
        .flat_map_iter(|run| {
            let cell_of = run[0].0;
            let mut found = Vec::new();
            for (n, &(_, ka)) in run.iter().enumerate() {
                let a = &items[ka as usize];
                for &(_, kb) in &run[n + 1..] {
                    let b = &items[kb as usize];
                    if !overlap(a, b) {
                        continue;
                    }
                    // Reported in the cell of the common part's lower corner only.
                    let corner = a.lo.max(b.lo);
                    if (index(corner.x, lo.x), index(corner.y, lo.y)) == cell_of {
                        found.push(ordered(a, b));
                    }
                }
            }
            found
        })
        .collect();
    // Wide boxes against every box (a pair of two wide boxes once).
    let mut is_wide = vec![false; items.len()];
    for &k in &wide {
        is_wide[k] = true;
    }
    let is_wide = &is_wide;
    let extra: Vec<(usize, usize, usize, usize)> = wide
        .par_iter()
        .flat_map_iter(|&k| {
            let a = &items[k];
            items
                .iter()
                .enumerate()
                .filter(move |&(m, b)| (!is_wide[m] || m > k) && overlap(a, b))
                .map(move |(_, b)| ordered(a, b))
                .collect::<Vec<_>>()
        })
        .collect();
    out.extend(extra);
    out
}
