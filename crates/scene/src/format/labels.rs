//! Where the curves' labels go, as the window, `render --labels` and `export --labels`
//! place them: a search over candidate positions, as map and plot labelers do. Each
//! label's candidates sit around points along its curve (the middle first), close beside
//! the point and then further out with a leader line back to it; a candidate is allowed
//! only inside the page and clear of every label placed before it (and of the legend), and
//! among those the one covering the fewest cells of ink (the curves' pixels) wins, then
//! the nearest. A label with no allowed candidate is hidden and counted — never drawn over
//! another. Given the choices of the last frame, a label keeps its place while that place
//! stays allowed and covers no more ink than the best, so labels do not jump while a point
//! is dragged.

use glam::DVec2;

/// The side of a cell of the ink grid, in pixels.
pub const INK_CELL: f64 = 4.0;

/// The gap between a label's box and its point, in pixels.
const GAP: f64 = 6.0;

/// Distances of the candidates with a leader line, in pixels beyond the gap.
const LEADER_REACH: [f64; 2] = [28.0, 56.0];

/// The parameters along a curve's domain (as fractions) whose points anchor its label's
/// candidates, in order of preference.
pub const ANCHORS: [f64; 9] = [0.5, 0.75, 0.25, 0.625, 0.375, 0.875, 0.125, 1.0, 0.0];

/// Which pixels the curves cover, on a grid of [`INK_CELL`]-pixel cells.
#[derive(Debug, Clone)]
pub struct Ink {
    cols: usize,
    rows: usize,
    cells: Vec<bool>,
}

impl Ink {
    /// An empty grid over a page of `size` pixels.
    #[must_use]
    pub fn new(size: DVec2) -> Ink {
        let cols = ((size.x / INK_CELL).ceil().max(1.0) as usize).min(4096);
        let rows = ((size.y / INK_CELL).ceil().max(1.0) as usize).min(4096);
        Ink {
            cols,
            rows,
            cells: vec![false; cols * rows],
        }
    }

    fn mark(&mut self, p: DVec2) {
        let (x, y) = (p.x / INK_CELL, p.y / INK_CELL);
        if x >= 0.0 && y >= 0.0 && (x as usize) < self.cols && (y as usize) < self.rows {
            self.cells[y as usize * self.cols + x as usize] = true;
        }
    }

    /// Marks the cells a polyline (pixel coordinates) passes through. Pieces wholly off
    /// the page, or not finite, mark nothing.
    pub fn add_polyline(&mut self, points: &[DVec2]) {
        for w in points.windows(2) {
            let (a, b) = (w[0], w[1]);
            if !(a.is_finite() && b.is_finite()) {
                continue;
            }
            let steps = ((b - a).length() / (0.5 * INK_CELL)).ceil().min(10_000.0) as usize;
            for k in 0..=steps {
                self.mark(a.lerp(b, k as f64 / steps.max(1) as f64));
            }
        }
        if let [p] = points {
            self.mark(*p);
        }
    }

    /// The cells of ink inside the box `[min, max]`.
    #[must_use]
    pub fn covered(&self, min: DVec2, max: DVec2) -> usize {
        let c0 = (min.x / INK_CELL).floor().max(0.0) as usize;
        let r0 = (min.y / INK_CELL).floor().max(0.0) as usize;
        let c1 = ((max.x / INK_CELL).ceil().max(0.0) as usize).min(self.cols);
        let r1 = ((max.y / INK_CELL).ceil().max(0.0) as usize).min(self.rows);
        let mut n = 0;
        for r in r0..r1 {
            n += self.cells[r * self.cols + c0.min(c1)..r * self.cols + c1]
                .iter()
                .filter(|c| **c)
                .count();
        }
        n
    }
}

/// One label to place: the points along its curve (pixels, in order of preference; those
/// off the page or not finite are skipped) and the size of its box.
#[derive(Debug, Clone)]
pub struct LabelRequest {
    /// Anchor points on the curve, preferred first.
    pub anchors: Vec<DVec2>,
    /// The box's width and height in pixels (the text and its margin).
    pub size: DVec2,
}

/// Which candidate a label took: its anchor and its position around it.
pub type Choice = (usize, usize);

/// A placed label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// The box's top-left corner.
    pub min: DVec2,
    /// The box's bottom-right corner.
    pub max: DVec2,
    /// A leader line from the curve's point to the box's nearest point, when the box
    /// stands off.
    pub leader: Option<(DVec2, DVec2)>,
    /// The candidate taken (give it back as `keep` next time).
    pub choice: Choice,
    /// Cells of ink the box covers.
    pub ink: usize,
}

/// The box of candidate `position` around `anchor` for a box of `size`, and whether it
/// stands off (a leader line).
fn candidate(anchor: DVec2, size: DVec2, position: usize) -> (DVec2, bool) {
    // Eight directions: NE, SE, NW, SW, E, W, N, S (y grows downwards).
    let dirs = [
        DVec2::new(1.0, -1.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(-1.0, -1.0),
        DVec2::new(-1.0, 1.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(-1.0, 0.0),
        DVec2::new(0.0, -1.0),
        DVec2::new(0.0, 1.0),
    ];
    let ring = position / dirs.len();
    let d = dirs[position % dirs.len()];
    let reach = GAP
        + if ring == 0 {
            0.0
        } else {
            LEADER_REACH[ring - 1]
        };
    // The box's corner or side nearest the anchor sits `reach` away along `d`.
    let near = anchor + d * reach;
    let min = DVec2::new(
        match d.x {
            x if x > 0.0 => near.x,
            x if x < 0.0 => near.x - size.x,
            _ => near.x - 0.5 * size.x,
        },
        match d.y {
            y if y > 0.0 => near.y,
            y if y < 0.0 => near.y - size.y,
            _ => near.y - 0.5 * size.y,
        },
    );
    (min, ring > 0)
}

/// Candidates per anchor: the close ring and the rings with a leader line.
const POSITIONS: usize = 8 * (1 + LEADER_REACH.len());

fn overlaps((a0, a1): (DVec2, DVec2), (b0, b1): (DVec2, DVec2)) -> bool {
    a0.x < b1.x && b0.x < a1.x && a0.y < b1.y && b0.y < a1.y
}

/// The point of the box `[min, max]` nearest `p`.
fn nearest_on_box(p: DVec2, min: DVec2, max: DVec2) -> DVec2 {
    p.clamp(min, max)
}

/// Places `labels` in order on a page `[0, size]` (a margin of 2 pixels kept), clear of
/// each other and of `blocked` boxes (a legend), over the curves' `ink`; `keep[i]` is the
/// choice label `i` took last time (see the module docs). `None` for a hidden label.
#[must_use]
pub fn place(
    labels: &[LabelRequest],
    ink: &Ink,
    size: DVec2,
    blocked: &[(DVec2, DVec2)],
    keep: &[Option<Choice>],
) -> Vec<Option<Placed>> {
    let margin = 2.0;
    let mut taken: Vec<(DVec2, DVec2)> = blocked.to_vec();
    let mut out = Vec::with_capacity(labels.len());
    for (i, label) in labels.iter().enumerate() {
        let allowed = |min: DVec2, taken: &[(DVec2, DVec2)]| {
            let max = min + label.size;
            let grown = (min - DVec2::splat(margin), max + DVec2::splat(margin));
            min.x >= margin
                && min.y >= margin
                && max.x <= size.x - margin
                && max.y <= size.y - margin
                && taken.iter().all(|t| !overlaps(grown, *t))
        };
        let evaluate = |(a, p): Choice, taken: &[(DVec2, DVec2)]| -> Option<(Placed, f64)> {
            let anchor = *label.anchors.get(a)?;
            if !anchor.is_finite() {
                return None;
            }
            let (min, stands_off) = candidate(anchor, label.size, p);
            if !allowed(min, taken) {
                return None;
            }
            let max = min + label.size;
            let covered = ink.covered(min, max);
            let leader = stands_off.then(|| (anchor, nearest_on_box(anchor, min, max)));
            // Ink first, then a leader's length, then the order of preference.
            let cost = covered as f64 * 1e4
                + leader.map_or(0.0, |(a, b)| 100.0 + (b - a).length())
                + a as f64 * 8.0
                + (p % 8) as f64;
            Some((
                Placed {
                    min,
                    max,
                    leader,
                    choice: (a, p),
                    ink: covered,
                },
                cost,
            ))
        };
        let mut best: Option<(Placed, f64)> = None;
        for a in 0..label.anchors.len() {
            // A place free of ink and without a leader beats every later anchor's.
            if best
                .as_ref()
                .is_some_and(|(b, _)| b.ink == 0 && b.leader.is_none())
            {
                break;
            }
            for p in 0..POSITIONS {
                if let Some((placed, cost)) = evaluate((a, p), &taken)
                    && best.as_ref().is_none_or(|(_, c)| cost < *c)
                {
                    best = Some((placed, cost));
                }
            }
        }
        // The last frame's place, while it is allowed and covers no more ink.
        if let (Some(Some(choice)), Some((b, _))) = (keep.get(i), &best)
            && let Some((kept, _)) = evaluate(*choice, &taken)
            && kept.ink <= b.ink
        {
            best = Some((kept, 0.0));
        }
        match best {
            Some((placed, _)) => {
                taken.push((placed.min, placed.max));
                if let Some((a, b)) = placed.leader {
                    // The leader's own path is kept clear too (a thin box along it).
                    let (lo, hi) = (a.min(b), a.max(b));
                    if (hi - lo).min_element() < 3.0 {
                        taken.push((lo - DVec2::splat(1.0), hi + DVec2::splat(1.0)));
                    }
                }
                out.push(Some(placed));
            }
            None => out.push(None),
        }
    }
    out
}

/// What a picture says of `hidden` labels: `None` when none is, else "1 label hidden" or
/// "N labels hidden".
#[must_use]
pub fn hidden_note(hidden: usize) -> Option<String> {
    match hidden {
        0 => None,
        1 => Some("1 label hidden".to_owned()),
        n => Some(format!("{n} labels hidden")),
    }
}

/// Where a box of `size` goes in a page of `page` pixels: the corner (8 pixels in) whose
/// box covers the fewest cells of `ink` — the top right first on a tie.
#[must_use]
pub fn corner(ink: &Ink, page: DVec2, size: DVec2) -> DVec2 {
    let m = 8.0;
    let corners = [
        DVec2::new(page.x - m - size.x, m),
        DVec2::new(m, m),
        DVec2::new(page.x - m - size.x, page.y - m - size.y),
        DVec2::new(m, page.y - m - size.y),
    ];
    let mut best = corners[0].max(DVec2::ZERO);
    let mut least = usize::MAX;
    for c in corners {
        let c = c.max(DVec2::ZERO);
        let n = ink.covered(c, c + size);
        if n < least {
            least = n;
            best = c;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boxes_overlap(placed: &[Option<Placed>]) -> bool {
        let p: Vec<&Placed> = placed.iter().flatten().collect();
        p.iter().enumerate().any(|(i, a)| {
            p[i + 1..]
                .iter()
                .any(|b| overlaps((a.min, a.max), (b.min, b.max)))
        })
    }

    #[test]
    fn crowded_labels_never_overlap_and_the_rest_are_hidden() {
        let size = DVec2::new(200.0, 100.0);
        let ink = Ink::new(size);
        // 40 labels all anchored at the page's centre: a few fit, the rest are hidden.
        let labels: Vec<LabelRequest> = (0..40)
            .map(|_| LabelRequest {
                anchors: vec![DVec2::new(100.0, 50.0)],
                size: DVec2::new(60.0, 14.0),
            })
            .collect();
        let placed = place(&labels, &ink, size, &[], &[]);
        let shown = placed.iter().flatten().count();
        assert!((4..40).contains(&shown), "{shown} shown");
        assert!(!boxes_overlap(&placed));
        for p in placed.iter().flatten() {
            assert!(p.min.x >= 2.0 && p.min.y >= 2.0 && p.max.x <= 198.0 && p.max.y <= 98.0);
        }
    }

    #[test]
    fn a_label_avoids_the_ink_when_a_free_spot_exists_and_keeps_its_place() {
        let size = DVec2::new(300.0, 200.0);
        let mut ink = Ink::new(size);
        // A horizontal line through the anchor and a vertical one: the close candidates
        // NE, SE, NW, SW are free of them; the box must not cover a cell of either.
        ink.add_polyline(&[DVec2::new(0.0, 100.0), DVec2::new(300.0, 100.0)]);
        ink.add_polyline(&[DVec2::new(150.0, 0.0), DVec2::new(150.0, 200.0)]);
        let label = LabelRequest {
            anchors: vec![DVec2::new(150.0, 100.0)],
            size: DVec2::new(50.0, 14.0),
        };
        let placed = place(std::slice::from_ref(&label), &ink, size, &[], &[]);
        let p = placed[0].expect("placed");
        assert_eq!(p.ink, 0, "{p:?}");
        assert_eq!(ink.covered(p.min, p.max), 0);
        // Kept where it was while still allowed (here: the south-west spot, also free).
        let keep = [Some((0, 3))];
        let again = place(std::slice::from_ref(&label), &ink, size, &[], &keep);
        assert_eq!(again[0].expect("placed").choice, (0, 3));
        // A blocked place is left.
        let sw = again[0].expect("placed");
        let moved = place(&[label], &ink, size, &[(sw.min, sw.max)], &keep);
        assert_ne!(moved[0].expect("placed").choice, (0, 3));
    }

    #[test]
    fn a_legend_goes_to_the_emptiest_corner() {
        let size = DVec2::new(300.0, 200.0);
        let mut ink = Ink::new(size);
        // Ink in the top right and bottom left: the top left is chosen.
        ink.add_polyline(&[DVec2::new(220.0, 5.0), DVec2::new(295.0, 60.0)]);
        ink.add_polyline(&[DVec2::new(5.0, 150.0), DVec2::new(80.0, 195.0)]);
        ink.add_polyline(&[DVec2::new(220.0, 150.0), DVec2::new(295.0, 195.0)]);
        let at = corner(&ink, size, DVec2::new(80.0, 50.0));
        assert_eq!(at, DVec2::new(8.0, 8.0));
    }
}
