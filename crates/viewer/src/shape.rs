//! What the viewer shows of the curves' shape beyond the curves: the curvature comb (`K`,
//! drawn by the GPU from the same segments it tessellates), the markers the analysis
//! finds — inflections and cusps, curvature extrema, intersections — recomputed off the
//! frame thread after an edit so a drag never waits for them, and the selected curve's
//! readouts (length, tight box, signed area when closed, counts).

use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::{Duration, Instant};

use splinescope_core::analysis::{CurveAnalysis, DEFAULT_ACCURACY};
use splinescope_core::geom::Aabb;
use splinescope_core::ops::{Offset, OffsetOptions, offset};

use splinescope_encoding::draw::MarkerKind;
use splinescope_scene::format::Scene;
use splinescope_scene::format::shape::{CombCap, CombScale, Marker, ShapeOptions, markers};

/// The panel's shape switches and the comb's scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeView {
    /// Curvature combs drawn (`K`, `view --comb`).
    pub comb: bool,
    /// Only the selected curve's comb.
    pub comb_selected_only: bool,
    /// The scale follows the view when the comb is turned on (the panel's "auto").
    pub comb_auto: bool,
    /// World length of a hair per unit of curvature.
    pub comb_scale: f64,
    /// The longest hair, a fraction of the view's height.
    pub comb_cap: CombCap,
    /// Inflection and cusp markers.
    pub inflections: bool,
    /// Curvature extremum markers.
    pub curvature_extrema: bool,
    /// Intersection markers (between curves and of a curve with itself).
    pub intersections: bool,
    /// Joint markers: kinks (G0) and curvature jumps (G1).
    pub joints: bool,
    /// The selected curve's tight bounding box.
    pub bbox: bool,
    /// The selected curve's offset drawn (recomputed off the frame thread after edits).
    pub offset: bool,
    /// The offset's signed distance (world units; > 0 to the left of the direction of
    /// travel, y up).
    pub offset_distance: f64,
}

impl Default for ShapeView {
    fn default() -> ShapeView {
        ShapeView {
            comb: false,
            comb_selected_only: false,
            comb_auto: true,
            comb_scale: 1.0,
            comb_cap: CombCap::default(),
            inflections: false,
            curvature_extrema: false,
            intersections: false,
            joints: false,
            bbox: false,
            offset: false,
            offset_distance: 0.0,
        }
    }
}

impl ShapeView {
    /// The markers asked for (the comb is the GPU's, not a marker).
    #[must_use]
    pub fn marker_options(&self) -> ShapeOptions {
        ShapeOptions {
            comb: None,
            comb_cap: self.comb_cap,
            inflections: self.inflections,
            curvature_extrema: self.curvature_extrema,
            intersections: self.intersections,
            joints: self.joints,
        }
    }

    /// Sets the automatic scale for `scene` seen `view_height` world units tall.
    pub fn fit_comb(&mut self, scene: &Scene, view_height: f64) {
        self.comb_scale = CombScale::Auto.resolve(scene, view_height);
        self.comb_auto = true;
    }

    /// Sets the cap typed by the user (a fraction of the view's height: a finite number
    /// above 0), else refused (the message names the value) and left as it was.
    ///
    /// # Errors
    /// The comb cap error, naming the value.
    pub fn set_comb_cap(&mut self, fraction: f64) -> Result<(), String> {
        self.comb_cap = CombCap::fraction(fraction).map_err(|e| e.to_string())?;
        Ok(())
    }

    /// Sets a scale typed or dragged by the user: a finite number above 0, else refused
    /// (the message names the value) and the scale is left as it was.
    ///
    /// # Errors
    /// The comb scale error, naming the value.
    pub fn set_comb_scale(&mut self, scale: f64) -> Result<(), String> {
        CombScale::fixed(scale).map_err(|e| e.to_string())?;
        self.comb_scale = scale;
        self.comb_auto = false;
        Ok(())
    }
}

/// The least time between two marker computations started by edits.
pub const MARKER_THROTTLE: Duration = Duration::from_millis(100);

/// One background computation at a time for what the frame shows: after an edit or a new
/// `key` it is due, it starts at most every [`MARKER_THROTTLE`], and the frame only polls.
#[derive(Debug)]
struct Job<K, T> {
    running: Option<Receiver<T>>,
    /// Asked for again (an edit or a new key) since the running or last computation began.
    dirty: bool,
    started: Option<Instant>,
    key: K,
}

impl<K: Default, T> Default for Job<K, T> {
    fn default() -> Self {
        Job {
            running: None,
            dirty: false,
            started: None,
            key: K::default(),
        }
    }
}

/// What a poll of a [`Job`] found.
enum Polled<T> {
    /// A computation is still running.
    Running,
    /// One finished with this.
    Done(T),
    /// None is running.
    Idle,
}

impl<K: PartialEq, T: Send + 'static> Job<K, T> {
    /// Notes an edit (`changed`) or a new `key`, and takes a finished computation's result.
    fn poll(&mut self, changed: bool, key: K) -> Polled<T> {
        if key != self.key {
            self.key = key;
            self.dirty = true;
        }
        self.dirty |= changed;
        let Some(rx) = &self.running else {
            return Polled::Idle;
        };
        match rx.try_recv() {
            Ok(found) => {
                self.running = None;
                Polled::Done(found)
            }
            Err(TryRecvError::Empty) => Polled::Running,
            Err(TryRecvError::Disconnected) => {
                self.running = None;
                Polled::Idle
            }
        }
    }

    /// Starts `work` on a thread when one is due (asked for, and past the throttle).
    fn start_if_due(&mut self, now: Instant, work: impl FnOnce() -> T + Send + 'static) {
        let due = self
            .started
            .is_none_or(|t| now.duration_since(t) >= MARKER_THROTTLE);
        if self.dirty && due {
            self.dirty = false;
            self.started = Some(now);
            let (tx, rx) = channel();
            std::thread::spawn(move || {
                let _ = tx.send(work());
            });
            self.running = Some(rx);
        }
    }

    /// Nothing is asked for: none is due.
    fn settle(&mut self) {
        self.dirty = false;
    }

    /// Whether a computation is running or due.
    fn busy(&self) -> bool {
        self.running.is_some() || self.dirty
    }
}

/// Markers computed on a worker thread: after an edit or a switch, at most one
/// computation runs at a time and one starts at most every [`MARKER_THROTTLE`]; the frame
/// only polls.
#[derive(Debug, Default)]
pub struct MarkerWorker {
    /// The latest markers.
    pub markers: Vec<Marker>,
    /// Whether `markers` changed since it was last taken ([`MarkerWorker::take_fresh`]).
    fresh: bool,
    job: Job<ShapeOptions, Vec<Marker>>,
}

impl MarkerWorker {
    /// After an edit (`changed`) or with new `options`: starts a computation when one is
    /// due, takes a finished one's result. With no marker asked for, the markers are
    /// cleared at once.
    pub fn poll(&mut self, scene: &Scene, changed: bool, options: ShapeOptions, now: Instant) {
        match self.job.poll(changed, options) {
            Polled::Running => return,
            Polled::Done(found) => {
                self.markers = found;
                self.fresh = true;
            }
            Polled::Idle => {}
        }
        if !options.any_marker() {
            if !self.markers.is_empty() {
                self.markers.clear();
                self.fresh = true;
            }
            self.job.settle();
            return;
        }
        let scene = scene.clone();
        self.job
            .start_if_due(now, move || markers(&scene, &options));
    }

    /// Whether a computation is running or due.
    #[must_use]
    pub fn busy(&self) -> bool {
        self.job.busy()
    }

    /// The markers when they changed since the last call.
    pub fn take_fresh(&mut self) -> Option<&[Marker]> {
        if std::mem::take(&mut self.fresh) {
            Some(&self.markers)
        } else {
            None
        }
    }

    /// Waits (up to `limit`) for the running computation: for tests and screenshots.
    pub fn wait(&mut self, scene: &Scene, limit: Duration) {
        let end = Instant::now() + limit;
        while self.busy() && Instant::now() < end {
            // Past the throttle, so that a due computation starts.
            self.poll(scene, false, self.job.key, Instant::now() + MARKER_THROTTLE);
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// An offset to compute: of which curve, how far, within what tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetRequest {
    /// The curve's index.
    pub curve: usize,
    /// The signed distance.
    pub distance: f64,
    /// The tolerance (world units).
    pub tolerance: f64,
}

impl OffsetRequest {
    /// The request for the selected curve at the panel's distance, drawn within a quarter
    /// pixel of a view `view_height` world units tall in `height_px` pixels (the tolerance
    /// rounded down to a power of two, so that a zoom recomputes it only now and then).
    #[must_use]
    pub fn for_view(
        shape: &ShapeView,
        selected: Option<usize>,
        view_height: f64,
        height_px: f64,
    ) -> Option<OffsetRequest> {
        let curve = selected.filter(|_| shape.offset && shape.offset_distance != 0.0)?;
        let px = view_height / height_px.max(1.0);
        let tolerance = 2f64.powf((0.25 * px).log2().floor());
        (tolerance.is_finite() && tolerance > 0.0).then_some(OffsetRequest {
            curve,
            distance: shape.offset_distance,
            tolerance,
        })
    }
}

/// The selected curve's offset computed on a worker thread, as the markers are.
#[derive(Debug, Default)]
pub struct OffsetWorker {
    /// The latest offset and the request it answers (an error's message when refused).
    pub latest: Option<(OffsetRequest, Result<Offset, String>)>,
    job: Job<Option<OffsetRequest>, (OffsetRequest, Result<Offset, String>)>,
}

impl OffsetWorker {
    /// After an edit (`changed`) or with a new `request`: starts a computation when one is
    /// due, takes a finished one's result; with no request, the offset is dropped.
    pub fn poll(
        &mut self,
        scene: &Scene,
        changed: bool,
        request: Option<OffsetRequest>,
        now: Instant,
    ) {
        match self.job.poll(changed, request) {
            Polled::Running => return,
            Polled::Done(found) => self.latest = Some(found),
            Polled::Idle => {}
        }
        let Some(request) = request else {
            self.latest = None;
            self.job.settle();
            return;
        };
        let Some(sc) = scene.curves.get(request.curve) else {
            self.latest = None;
            self.job.settle();
            return;
        };
        let curve = sc.curve.clone();
        self.job.start_if_due(now, move || {
            let found = offset(
                &curve,
                request.distance,
                request.tolerance,
                &OffsetOptions::default(),
            )
            .map_err(|e| e.to_string());
            (request, found)
        });
    }

    /// Whether a computation is running or due.
    #[must_use]
    pub fn busy(&self) -> bool {
        self.job.busy()
    }

    /// The offset to draw: the latest, when it is of the curve asked for now.
    #[must_use]
    pub fn current(&self) -> Option<&Result<Offset, String>> {
        let (req, found) = self.latest.as_ref()?;
        (Some(req.curve) == self.job.key.map(|r| r.curve)).then_some(found)
    }

    /// Waits (up to `limit`) for the running computation: for tests and screenshots.
    pub fn wait(&mut self, scene: &Scene, limit: Duration) {
        let end = Instant::now() + limit;
        while self.busy() && Instant::now() < end {
            self.poll(scene, false, self.job.key, Instant::now() + MARKER_THROTTLE);
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}

/// What the panel says about the selected curve's shape.
#[derive(Debug, Clone, PartialEq)]
pub struct Readouts {
    /// Its length, within [`DEFAULT_ACCURACY`]; `None` when the analysis refuses it.
    pub length: Option<f64>,
    /// Its tight axis-aligned box.
    pub bbox: Aabb,
    /// The signed area it encloses, when it is closed and planar.
    pub area: Option<f64>,
    /// Inflections (planar curves).
    pub inflections: Option<usize>,
    /// Intersections with other curves and itself, from the latest markers (`None` when
    /// intersection markers are off).
    pub intersections: Option<usize>,
}

impl Readouts {
    /// The readouts of curve `index` of `scene`; intersections counted in `markers`.
    #[must_use]
    pub fn of(scene: &Scene, index: usize, markers: Option<&[Marker]>) -> Option<Readouts> {
        let curve = &scene.curves.get(index)?.curve;
        let a = CurveAnalysis::new(curve);
        let (t0, t1) = a.domain();
        Some(Readouts {
            length: a.length(t0, t1, DEFAULT_ACCURACY).ok().map(|l| l.value),
            bbox: a.bounding_box(),
            area: if a.is_closed() {
                a.signed_area().ok()
            } else {
                None
            },
            inflections: a.inflections().ok().map(|v| v.len()),
            intersections: markers.map(|m| {
                m.iter()
                    .filter(|m| {
                        matches!(
                            m.kind,
                            MarkerKind::Intersection | MarkerKind::SelfIntersection
                        ) && (m.curve == index || m.other.is_some_and(|(o, _)| o == index))
                    })
                    .count()
            }),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use splinescope_core::geom::{Bezier, Curve, Nurbs};

    #[test]
    fn markers_arrive_from_the_worker_and_clear_when_switched_off() {
        let scene = Scene::of_curves([
            Curve::Bezier(Bezier::new(vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(1.0, -2.0, 0.0),
                DVec3::new(2.0, 0.0, 0.0),
            ])),
            Curve::Bezier(Bezier::new(vec![
                DVec3::new(-1.0, 0.0, 0.0),
                DVec3::new(3.0, 0.0, 0.0),
            ])),
        ]);
        let mut w = MarkerWorker::default();
        let on = ShapeOptions {
            comb: None,
            comb_cap: CombCap::default(),
            inflections: true,
            curvature_extrema: false,
            intersections: true,
            joints: false,
        };
        w.poll(&scene, true, on, Instant::now());
        assert!(w.busy());
        w.wait(&scene, Duration::from_secs(10));
        let found = w.take_fresh().expect("fresh markers").to_vec();
        assert_eq!(
            found
                .iter()
                .filter(|m| m.kind == MarkerKind::Inflection)
                .count(),
            1
        );
        assert_eq!(
            found
                .iter()
                .filter(|m| m.kind == MarkerKind::Intersection)
                .count(),
            3
        );
        assert!(w.take_fresh().is_none(), "taken once");
        let r = Readouts::of(&scene, 0, Some(&found)).expect("curve 0");
        assert_eq!((r.inflections, r.intersections), (Some(1), Some(3)));
        w.poll(&scene, false, ShapeOptions::default(), Instant::now());
        assert_eq!(w.take_fresh().map(<[Marker]>::len), Some(0));
    }

    #[test]
    fn the_offset_arrives_from_the_worker_follows_edits_and_goes_when_off() {
        let r = 1.5;
        let mut scene =
            Scene::of_curves([Curve::Nurbs(Nurbs::circle(DVec3::ZERO, r).expect("circle"))]);
        let shape = ShapeView {
            offset: true,
            offset_distance: 0.5,
            ..ShapeView::default()
        };
        let request = OffsetRequest::for_view(&shape, Some(0), 10.0, 1000.0).expect("asked");
        assert!(
            request.tolerance <= 0.25 * 10.0 / 1000.0 && request.tolerance > 0.125 * 10.0 / 1000.0
        );
        let radius_of = |w: &OffsetWorker| {
            let o = w.current().expect("an offset").as_ref().expect("computed");
            let path = &o.paths[0];
            path.segments()[0].points[0].length()
        };
        let mut w = OffsetWorker::default();
        w.poll(&scene, false, Some(request), Instant::now());
        w.wait(&scene, Duration::from_secs(10));
        // A counter-clockwise circle's left offset is inside it: radius r − d.
        assert!((radius_of(&w) - (r - 0.5)).abs() < 1e-9);
        // An edit (a bigger circle) is followed.
        scene.curves[0].curve = Curve::Nurbs(Nurbs::circle(DVec3::ZERO, 3.0).expect("circle"));
        w.poll(
            &scene,
            true,
            Some(request),
            Instant::now() + MARKER_THROTTLE,
        );
        w.wait(&scene, Duration::from_secs(10));
        assert!((radius_of(&w) - 2.5).abs() < 1e-9);
        // A refusal is kept as its message; off drops it.
        let spatial = Scene::of_curves([Curve::Bezier(Bezier::new(vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 1.0),
        ]))]);
        w.poll(
            &spatial,
            true,
            Some(request),
            Instant::now() + 2 * MARKER_THROTTLE,
        );
        w.wait(&spatial, Duration::from_secs(10));
        let message = w
            .current()
            .expect("answered")
            .as_ref()
            .expect_err("refused");
        assert!(message.contains("planar"), "{message}");
        w.poll(&spatial, false, None, Instant::now() + 3 * MARKER_THROTTLE);
        assert!(w.current().is_none() && w.latest.is_none());
        assert!(OffsetRequest::for_view(&ShapeView::default(), Some(0), 10.0, 1000.0).is_none());
    }

    #[test]
    fn a_circles_readouts_are_its_closed_forms() {
        let r = 1.5;
        let scene =
            Scene::of_curves([Curve::Nurbs(Nurbs::circle(DVec3::ZERO, r).expect("circle"))]);
        let out = Readouts::of(&scene, 0, None).expect("curve");
        let pi = std::f64::consts::PI;
        assert!((out.length.expect("length") - 2.0 * pi * r).abs() < 1e-9);
        assert!((out.area.expect("closed").abs() - pi * r * r).abs() < 1e-9);
        assert!((out.bbox.max.x - r).abs() < 1e-12 && (out.bbox.min.y + r).abs() < 1e-12);
        assert_eq!(out.inflections, Some(0));
        assert_eq!(out.intersections, None);
    }

    #[test]
    fn a_typed_scale_is_checked_and_auto_follows_the_view() {
        let mut s = ShapeView::default();
        assert!(s.set_comb_scale(-1.0).unwrap_err().contains("-1"));
        assert!(
            s.comb_auto && s.comb_scale == 1.0,
            "unchanged after a refusal"
        );
        s.set_comb_scale(0.25).expect("positive");
        assert!(!s.comb_auto && s.comb_scale == 0.25);
        let scene = Scene::of_curves([Curve::Nurbs(
            Nurbs::circle(DVec3::ZERO, 2.0).expect("circle"),
        )]);
        s.fit_comb(&scene, 10.0);
        // κ = 1/2 everywhere: the hair is the fraction of the view.
        assert!(s.comb_auto);
        assert!(
            (s.comb_scale * 0.5 - 10.0 * splinescope_core::analysis::comb::AUTO_COMB_FRACTION)
                .abs()
                < 1e-12
        );
    }
}
