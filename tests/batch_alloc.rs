//! The batch solver allocates nothing in the steady state: a counting global allocator
//! (the one place the project uses `unsafe`, to implement `GlobalAlloc`) sees no
//! allocation during a second batch.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::DVec3;
use splinescope_core::rng::Rng;
use splinescope_core::solve::batch::{BatchResult, BatchSingleTarget};

struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator; the counter only
// observes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn batch_solves_allocate_nothing_in_the_steady_state() {
    let mut rng = Rng::new(4);
    let degree = 5;
    let curves = 20_000;
    let points: Vec<DVec3> = (0..curves * (degree + 1))
        .map(|_| DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), 0.0))
        .collect();
    let targets: Vec<DVec3> = (0..curves)
        .map(|_| DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), 0.0))
        .collect();
    let ts: Vec<f64> = (0..curves).map(|_| rng.range(0.1, 0.9)).collect();
    let batch = BatchSingleTarget::new(degree).expect("degree 5");
    let mut out = vec![DVec3::ZERO; points.len()];
    let mut results = vec![BatchResult::default(); curves];
    // Warm-up: starts the thread pool.
    batch.solve(&points, &targets, Some(&ts), &mut out, &mut results);
    batch.solve(&points, &targets, None, &mut out, &mut results);
    for projecting in [false, true] {
        ALLOCATIONS.store(0, Ordering::SeqCst);
        COUNTING.store(true, Ordering::SeqCst);
        batch.solve(
            &points,
            &targets,
            (!projecting).then_some(ts.as_slice()),
            &mut out,
            &mut results,
        );
        COUNTING.store(false, Ordering::SeqCst);
        assert_eq!(
            ALLOCATIONS.load(Ordering::SeqCst),
            0,
            "steady-state batch (projecting: {projecting}) allocated"
        );
    }
    // The last batch projected: a target whose nearest point is a fixed end is reported
    // unsolved (and its curve left as it was); every other one is met.
    for r in &results {
        if r.solved {
            assert!(r.residual < 1e-9, "{r:?}");
        } else {
            assert!(r.t_s == 0.0 || r.t_s == 1.0, "{r:?}");
        }
    }
    assert!(results.iter().filter(|r| r.solved).count() > curves / 2);
}
